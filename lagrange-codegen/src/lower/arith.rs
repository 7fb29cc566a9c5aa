//! Literals and binary operators, with the precedence trap of `^` reported.

use lagrange_symbolic::{Context, Expr as Sym};
use syn::{BinOp, Expr, Lit};

use super::{Lowerer, Mode};

impl Lowerer<'_> {
    pub(super) fn literal(&mut self, lit: &Lit) -> Option<Sym> {
        match lit {
            Lit::Int(i) => match i.base10_parse::<i64>() {
                Ok(v) => Some(self.ctx.int(v)),
                Err(e) => {
                    self.cx.syn_error(e);
                    None
                }
            },
            Lit::Float(f) => {
                if let Some(e) = decimal(&mut self.ctx, f.base10_digits()) {
                    return Some(e);
                }
                let v = f.base10_parse::<f64>().unwrap_or(f64::NAN);
                match unrepresentable(v, f.base10_digits()) {
                    Some(why) => {
                        self.cx.error_spanned_by(f, why);
                        None
                    }
                    None => Some(self.ctx.float(v)),
                }
            }
            other => {
                self.cx.error_spanned_by(other, "expected a number");
                None
            }
        }
    }

    pub(super) fn binary(&mut self, b: &syn::ExprBinary, mode: Mode) -> Option<Sym> {
        if let BinOp::BitXor(_) = &b.op {
            // `^` binds looser than + - * / in Rust: `a + b^2` parses as `(a + b)^2`
            // and `x^2 + y` as `x^(2 + y)`. Rather than silently compute the wrong
            // power, insist on parentheses when an operand is itself an operation.
            for side in [&*b.left, &*b.right] {
                if matches!(side, Expr::Binary(_)) {
                    self.cx.error_spanned_by(
                        side,
                        format!(
                            "`^` binds looser than `+ - * /` in Rust, so this operand of `^` would be `{}`; add parentheses, e.g. `a + (b^2)`, or write `pow(b, 2)`",
                            quote::ToTokens::to_token_stream(side)
                        ),
                    );
                    return None;
                }
            }
        }
        let l = self.expr(&b.left, mode);
        let r = self.expr(&b.right, mode);
        let l = l?;
        let r = r?;
        match &b.op {
            BinOp::Add(_) => Some(self.ctx.add(l, r)),
            BinOp::Sub(_) => Some(self.ctx.sub(l, r)),
            BinOp::Mul(_) => Some(self.ctx.mul(l, r)),
            BinOp::Div(_) if self.ctx.is_zero(r) => {
                // The engine would fold `m / 0` to an infinity and the equations
                // would carry it silently.
                self.cx.error_spanned_by(
                    &b.right,
                    format!(
                        "division by zero: `{}` is the constant 0",
                        quote::ToTokens::to_token_stream(&*b.right)
                    ),
                );
                None
            }
            BinOp::Div(_) => Some(self.ctx.div(l, r)),
            BinOp::BitXor(_) => {
                let p = self.ctx.pow(l, r);
                self.finite_constant(p, b, "`^`")
            }
            _ => {
                self.cx.error_spanned_by(
                    b.op,
                    "unsupported operator in #[lagrange] expressions; use + - * / and ^ (power)",
                );
                None
            }
        }
    }
}

/// A decimal literal as an exact rational: `9.81` → 981/100, `1e-3` → 1/1000.
/// Exactness matters: `0.1 * 10` must fold to 1, not to 1.0000000000000002.
/// Why a float literal that is not an exact small decimal cannot stand for
/// its value in f64: it overflows to an infinity (`1e400`) or underflows to
/// zero (`1e-400`), either of which the equations would carry silently.
fn unrepresentable(v: f64, digits: &str) -> Option<String> {
    let nonzero = digits
        .split(['e', 'E'])
        .next()
        .is_some_and(|m| m.chars().any(|c| c.is_ascii_digit() && c != '0'));
    if !v.is_finite() {
        Some(format!(
            "`{digits}` is beyond f64's range (it would be an infinity); the largest finite value is about 1.8e308: write the quantity in other units"
        ))
    } else if v == 0.0 && nonzero {
        Some(format!(
            "`{digits}` is below f64's smallest value (it would be 0); the smallest is about 4.9e-324: write the quantity in other units"
        ))
    } else {
        None
    }
}

fn decimal(ctx: &mut Context, digits: &str) -> Option<Sym> {
    let (mantissa, exp) = match digits.find(['e', 'E']) {
        Some(i) => (&digits[..i], digits[i + 1..].parse::<i32>().ok()?),
        None => (digits, 0),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all: String = format!("{int_part}{frac_part}");
    let mut num: i64 = all.parse().ok()?;
    let mut scale = exp - frac_part.len() as i32;
    let mut den: i64 = 1;
    while scale > 0 {
        num = num.checked_mul(10)?;
        scale -= 1;
    }
    while scale < 0 {
        den = den.checked_mul(10)?;
        scale += 1;
    }
    Some(ctx.rational(num, den))
}
