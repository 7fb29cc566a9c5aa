//! Parameter hoisting: the subexpressions of a set of outputs that depend on
//! parameters only (composite masses, products of lengths, inertia sums) split
//! off, so generated code computes them once per parameter set instead of once
//! per call.
//!
//! Sums and products are flattened, so a parameter-only part is often not a
//! node of its own: `2·m₁·l₁·cos q₁` is one product. Its parameter-only factors
//! (with the constants among them) are grouped into one hoisted term, and the
//! same for the terms of a sum; a whole node that depends on parameters only is
//! hoisted as it is. Bare parameters and constants stay where they are: reading
//! them costs what reading a hoisted value costs.

use std::collections::HashMap;

use crate::context::Context;
use crate::node::{Expr, Node, SymbolKind};

/// Outputs rewritten over hoisted terms.
pub struct Hoisted {
    /// The parameter-only terms, each a function of the parameters alone.
    pub terms: Vec<Expr>,
    /// The free symbols that stand for the terms in `outputs` (same order).
    pub symbols: Vec<Expr>,
    /// The outputs with every hoisted term replaced by its symbol.
    pub outputs: Vec<Expr>,
}

/// The terms found so far and the rewrites done.
struct Pass<'a> {
    prefix: &'a str,
    memo: HashMap<Expr, Expr>,
    index: HashMap<Expr, usize>,
    terms: Vec<Expr>,
    symbols: Vec<Expr>,
}

impl Context {
    /// Splits the parameter-only subexpressions off `outputs`; the stand-in
    /// symbols are free symbols named `{prefix}{k}`.
    pub fn hoist(&mut self, outputs: &[Expr], prefix: &str) -> Hoisted {
        let mut pass = Pass {
            prefix,
            memo: HashMap::new(),
            index: HashMap::new(),
            terms: Vec::new(),
            symbols: Vec::new(),
        };
        let outputs = outputs.iter().map(|&e| pass.rewrite(self, e)).collect();
        Hoisted {
            terms: pass.terms,
            symbols: pass.symbols,
            outputs,
        }
    }

    /// Whether `e` has symbols and they are all parameters.
    fn parametric(&self, e: Expr) -> bool {
        let free = self.free_slice(e);
        !free.is_empty()
            && free
                .iter()
                .all(|&s| matches!(self.symbol_kind(s), SymbolKind::Parameter(_)))
    }
}

impl Pass<'_> {
    fn term(&mut self, ctx: &mut Context, e: Expr) -> Expr {
        if let Some(&k) = self.index.get(&e) {
            return self.symbols[k];
        }
        let k = self.terms.len();
        let s = ctx.free_symbol(&format!("{}{k}", self.prefix));
        self.index.insert(e, k);
        self.terms.push(e);
        self.symbols.push(s);
        s
    }

    fn rewrite(&mut self, ctx: &mut Context, e: Expr) -> Expr {
        if let Some(&r) = self.memo.get(&e) {
            return r;
        }
        let r = match ctx.node(e).clone() {
            Node::Const(_) | Node::Float(_) | Node::Sym(_) => e,
            _ if ctx.parametric(e) => self.term(ctx, e),
            Node::Add(ts) => self.group(ctx, &ts, true),
            Node::Mul(fs) => self.group(ctx, &fs, false),
            _ => ctx.rebuild(e, |cx, c| self.rewrite(cx, c)),
        };
        self.memo.insert(e, r);
        r
    }

    /// A sum or product: its parameter-only operands (and constants, when there
    /// is a parameter among them) as one hoisted term, the rest rewritten.
    fn group(&mut self, ctx: &mut Context, operands: &[Expr], sum: bool) -> Expr {
        let (fixed, rest): (Vec<Expr>, Vec<Expr>) = operands
            .iter()
            .partition(|&&x| ctx.parametric(x) || ctx.is_constant(x));
        let mut out: Vec<Expr> = rest.iter().map(|&x| self.rewrite(ctx, x)).collect();
        let has_parameter = fixed.iter().any(|&x| ctx.parametric(x));
        let single_atom = fixed.len() == 1 && ctx.as_symbol(fixed[0]).is_some();
        if has_parameter && !single_atom {
            let combined = if sum {
                ctx.sum(&fixed)
            } else {
                ctx.product(&fixed)
            };
            let s = self.term(ctx, combined);
            out.push(s);
        } else {
            out.extend(fixed);
        }
        if sum {
            ctx.sum(&out)
        } else {
            ctx.product(&out)
        }
    }
}
