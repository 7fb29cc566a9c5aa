//! Conditionals in the description language, `if a > b { x } else { y }`:
//! comparisons `>`, `<`, `>=`, `<=` joined by `&&`, `||` and `!`, and `else if`
//! chains, lowered to the engine's one piecewise node
//! `select(test, x, y)` = if test > 0 { x } else { y }.

use syn::{BinOp, Expr, UnOp};

use crate::lower::{Lowerer, Mode};
use lagrange_symbolic::Expr as Sym;

/// A lowered condition.
enum Cond {
    /// d > 0, or with `negated` its negation (d ≤ 0).
    Test {
        d: Sym,
        negated: bool,
    },
    And(Box<Cond>, Box<Cond>),
    Or(Box<Cond>, Box<Cond>),
    Not(Box<Cond>),
}

impl Lowerer<'_> {
    /// `if cond { then } else { otherwise }`, differentiated branch by branch.
    pub(crate) fn conditional(&mut self, i: &syn::ExprIf, mode: Mode) -> Option<Sym> {
        let cond = self.condition(&i.cond, mode);
        let then = self.block(&i.then_branch, mode);
        let otherwise = match &i.else_branch {
            Some((_, e)) => match &**e {
                Expr::Block(b) => self.block(&b.block, mode),
                other => self.expr(other, mode),
            },
            None => {
                self.cx.error_spanned_by(
                    i.if_token,
                    "an `if` in an expression needs an `else` branch: `if a > b { x } else { y }`",
                );
                None
            }
        };
        let cond = cond?;
        let then = then?;
        let otherwise = otherwise?;
        Some(self.branch(&cond, then, otherwise))
    }

    /// The value `then` where `cond` holds, `otherwise` elsewhere.
    fn branch(&mut self, cond: &Cond, then: Sym, otherwise: Sym) -> Sym {
        match cond {
            Cond::Test { d, negated: false } => self.ctx.select(*d, then, otherwise),
            Cond::Test { d, negated: true } => self.ctx.select(*d, otherwise, then),
            Cond::Not(c) => self.branch(c, otherwise, then),
            Cond::And(a, b) => {
                let inner = self.branch(b, then, otherwise);
                self.branch(a, inner, otherwise)
            }
            Cond::Or(a, b) => {
                let inner = self.branch(b, then, otherwise);
                self.branch(a, then, inner)
            }
        }
    }

    /// A condition: a comparison, or several joined by `&&`, `||`, `!`.
    /// Equality is refused: floats are never compared exactly.
    fn condition(&mut self, cond: &Expr, mode: Mode) -> Option<Cond> {
        match cond {
            Expr::Paren(p) => self.condition(&p.expr, mode),
            Expr::Unary(u) if matches!(u.op, UnOp::Not(_)) => {
                Some(Cond::Not(Box::new(self.condition(&u.expr, mode)?)))
            }
            Expr::Binary(b) if matches!(b.op, BinOp::And(_) | BinOp::Or(_)) => {
                let l = self.condition(&b.left, mode);
                let r = self.condition(&b.right, mode);
                let l = Box::new(l?);
                let r = Box::new(r?);
                Some(match b.op {
                    BinOp::And(_) => Cond::And(l, r),
                    _ => Cond::Or(l, r),
                })
            }
            Expr::Binary(b) => self.comparison(b, mode),
            _ => {
                self.cx.error_spanned_by(
                    cond,
                    "the condition must compare two expressions with `>`, `<`, `>=` or `<=` (joined by `&&`, `||`, `!`), e.g. `if dot(x) > 0 { .. } else { .. }`",
                );
                None
            }
        }
    }

    /// `a > b` is (a − b) > 0 and `a < b` is (b − a) > 0; `a >= b` is "not
    /// b > a", `a <= b` "not a > b".
    fn comparison(&mut self, b: &syn::ExprBinary, mode: Mode) -> Option<Cond> {
        let negated = match b.op {
            BinOp::Gt(_) | BinOp::Lt(_) => false,
            BinOp::Ge(_) | BinOp::Le(_) => true,
            BinOp::Eq(_) | BinOp::Ne(_) => {
                self.cx.error_spanned_by(
                    b.op,
                    "`==` and `!=` compare floats exactly, which a state never meets reliably; use `>`, `<`, `>=` or `<=`",
                );
                return None;
            }
            _ => {
                self.cx.error_spanned_by(
                    b.op,
                    "the condition must compare two expressions with `>`, `<`, `>=` or `<=` (joined by `&&`, `||`, `!`)",
                );
                return None;
            }
        };
        let l = self.expr(&b.left, mode);
        let r = self.expr(&b.right, mode);
        let l = l?;
        let r = r?;
        let left_larger_is_positive = matches!(b.op, BinOp::Gt(_) | BinOp::Le(_));
        let d = if left_larger_is_positive {
            self.ctx.sub(l, r)
        } else {
            self.ctx.sub(r, l)
        };
        if self.ctx.free_symbols(d).is_empty() {
            let holds = (self.ctx.eval(d, &|_| f64::NAN) > 0.0) != negated;
            self.cx.error_spanned_by(
                b,
                format!(
                    "`{}` compares constants: it is always {holds}, so the `if` always takes its {} branch; compare an expression of the state, time or parameters, or write that branch alone",
                    quote::ToTokens::to_token_stream(b),
                    if holds { "first" } else { "`else`" },
                ),
            );
            return None;
        }
        Some(Cond::Test { d, negated })
    }

    /// `{ expr }`: a block holding one expression.
    fn block(&mut self, block: &syn::Block, mode: Mode) -> Option<Sym> {
        match block.stmts.as_slice() {
            [syn::Stmt::Expr(e, None)] => self.expr(e, mode),
            _ => {
                self.cx.error_spanned_by(
                    block,
                    "a branch holds one expression, without `let` or `;`: `{ x }`",
                );
                None
            }
        }
    }
}
