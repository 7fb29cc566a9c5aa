//! Function and method calls onto the engine's functions, and `dot(...)`, the
//! time derivative of a position.

use lagrange_symbolic::{Expr as Sym, Func};
use quote::ToTokens;
use syn::{Expr, Ident};

use super::field::component;
use super::{Binding, FUNCTIONS, Lowerer, Mode};

impl Lowerer<'_> {
    pub(super) fn call(&mut self, c: &syn::ExprCall, mode: Mode) -> Option<Sym> {
        let Expr::Path(p) = &*c.func else {
            return self.unsupported(&c.func, "calling this");
        };
        let Some(fname) = p.path.get_ident() else {
            return self.unsupported(&c.func, "a path call");
        };
        let args: Vec<&Expr> = c.args.iter().collect();
        let name = fname.to_string();
        if name == "dot" {
            return self.velocity(fname, &args, mode);
        }
        let Some(arity) = arity(&name) else {
            self.cx.error_at(
                fname.span(),
                format!("unsupported function `{name}`; supported: {FUNCTIONS}"),
            );
            return None;
        };
        if args.len() != arity {
            self.cx.error_spanned_by(
                c,
                format!(
                    "`{name}` takes {arity} argument{}, found {}",
                    if arity == 1 { "" } else { "s" },
                    args.len()
                ),
            );
            return None;
        }
        let lowered: Vec<Option<Sym>> = args.iter().map(|a| self.expr(a, mode)).collect();
        let lowered: Vec<Sym> = lowered.into_iter().collect::<Option<_>>()?;
        self.checked_apply(&name, &lowered, c)
    }

    /// [`apply`](Self::apply), refusing literal arguments that make the call
    /// meaningless: reversed or equal `clamp` bounds (the result would be a
    /// constant), and constants outside a function's domain (`sqrt(-1)`,
    /// `ln(0)`: NaN or an infinity in the equations). The error is at the call.
    fn checked_apply(&mut self, name: &str, a: &[Sym], call: &dyn ToTokens) -> Option<Sym> {
        if name == "clamp"
            && let (Some(lo), Some(hi)) = (self.ctx.as_f64(a[1]), self.ctx.as_f64(a[2]))
            && lo >= hi
        {
            let why = if lo == hi {
                format!(
                    "its bounds are equal, so it is the constant {hi}; write the constant, or distinct bounds"
                )
            } else {
                format!(
                    "its lower bound {lo} is above its upper bound {hi}, so it is the constant {hi} whatever its argument; swap the bounds"
                )
            };
            self.cx
                .error_spanned_by(call, format!("`clamp(x, lo, hi)` needs lo < hi: {why}"));
            return None;
        }
        let result = self.apply(name, a);
        self.finite_constant(result, call, &format!("`{name}`"))
    }

    /// `result`, unless it is a constant that is not a finite number (a
    /// function of constants outside its domain): then an error at `at`.
    pub(super) fn finite_constant(
        &mut self,
        result: Sym,
        at: &dyn ToTokens,
        what: &str,
    ) -> Option<Sym> {
        if self.ctx.free_symbols(result).is_empty() {
            let value = self.ctx.eval(result, &|_| f64::NAN);
            if !value.is_finite() {
                self.cx.error_spanned_by(
                    at,
                    format!(
                        "{what} of these constants is {value}, not a finite number: an argument lies outside the function's domain (`sqrt` needs x >= 0, `ln` x > 0, `asin` and `acos` -1 <= x <= 1, a power of 0 a positive exponent)"
                    ),
                );
                return None;
            }
        }
        Some(result)
    }

    /// `x.sin()`, `x.powi(2)`, `y.atan2(x)`: Rust method spelling of the same functions.
    pub(super) fn method(&mut self, m: &syn::ExprMethodCall, mode: Mode) -> Option<Sym> {
        let name = m.method.to_string();
        let Some(arity) = arity(&name) else {
            self.cx.error_at(
                m.method.span(),
                format!("unsupported function `{name}`; supported: {FUNCTIONS}"),
            );
            return None;
        };
        if m.args.len() + 1 != arity {
            self.cx.error_spanned_by(
                m,
                format!(
                    "`.{name}()` takes {} argument{}",
                    arity - 1,
                    if arity == 2 { "" } else { "s" }
                ),
            );
            return None;
        }
        let recv = self.expr(&m.receiver, mode);
        let rest: Vec<Option<Sym>> = m.args.iter().map(|a| self.expr(a, mode)).collect();
        let mut all = vec![recv?];
        for r in rest {
            all.push(r?);
        }
        self.checked_apply(&name, &all, m)
    }

    fn apply(&mut self, name: &str, a: &[Sym]) -> Sym {
        let f = match name {
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "asin" => Func::Asin,
            "acos" => Func::Acos,
            "atan" => Func::Atan,
            "sinh" => Func::Sinh,
            "cosh" => Func::Cosh,
            "tanh" => Func::Tanh,
            "exp" => Func::Exp,
            "ln" | "log" => Func::Ln,
            "sqrt" => Func::Sqrt,
            "abs" => Func::Abs,
            "atan2" => return self.ctx.atan2(a[0], a[1]),
            "sign" => return self.ctx.sign(a[0]),
            "min" => return self.ctx.min(a[0], a[1]),
            "max" => return self.ctx.max(a[0], a[1]),
            "clamp" => {
                let low = self.ctx.max(a[0], a[1]);
                return self.ctx.min(low, a[2]);
            }
            // pow, powi, powf
            _ => return self.ctx.pow(a[0], a[1]),
        };
        self.ctx.func(f, a[0])
    }

    /// `dot(q)`: the generalized velocity of coordinate `q`.
    fn velocity(&mut self, fname: &Ident, args: &[&Expr], mode: Mode) -> Option<Sym> {
        if let [Expr::Field(f)] = args
            && let Expr::Path(p) = &*f.base
            && let Some(base) = p.path.get_ident()
            && let syn::Member::Named(member) = &f.member
            && let Some(frame) = self.frame_of(base)
            && let Some(c) = component(&member.to_string())
        {
            return self.coordinate_of(frame, c, true, base, member, mode);
        }
        let target = match args {
            [Expr::Path(p)] => p.path.get_ident(),
            _ => None,
        };
        let Some(target) = target else {
            self.cx.error_at(
                fname.span(),
                "`dot(...)` takes one coordinate name, e.g. `dot(theta)`",
            );
            return None;
        };
        let binding = self.scope.get(&target.to_string()).copied();
        let Some(Binding::Coordinate(q)) = binding else {
            if let Some(why) = not_a_coordinate(target, binding) {
                self.cx
                    .error_at(target.span(), format!("`dot({target})`: {why}"));
            }
            return None;
        };
        if mode != Mode::State {
            self.cx.error_at(
                fname.span().join(target.span()).unwrap_or(fname.span()),
                format!("velocity `dot({target})` cannot appear in {}: it must depend on coordinates, parameters and `t` only", self.describe(mode)),
            );
            return None;
        }
        self.ctx.velocity(q)
    }
}

/// Why `dot(name)` has no meaning, for a name that is not a coordinate (`None`
/// for a failed definition, whose error is reported already).
fn not_a_coordinate(target: &Ident, binding: Option<Binding>) -> Option<String> {
    let Some(binding) = binding else {
        return Some(if target == "t" {
            "`t` is the time: its rate is 1".to_string()
        } else {
            format!("`{target}` is not a generalized coordinate")
        });
    };
    Some(match binding {
        Binding::Input(_) => format!(
            "`{target}` is an input, not a generalized coordinate: inputs are supplied at run \
             time without their time derivative, so `dot` cannot take one; if a force needs \
             the rate, declare it as an input of its own (`inputs({target}, {target}_rate)`) \
             and supply both"
        ),
        Binding::Parameter(_) => format!(
            "`{target}` is a parameter, constant in time: its rate is zero; remove the term"
        ),
        Binding::Definition { .. } => format!(
            "`{target}` is a definition; `dot` takes a coordinate (`dot(theta)`) or a point's \
             coordinate (`dot(P.x)`): write the definition's rate with the coordinates' rates"
        ),
        Binding::Frame(_) => format!(
            "`{target}` is a point or body; `dot` takes one of its coordinates, `dot({target}.x)`"
        ),
        Binding::Orientation(_) => format!(
            "`{target}` is an orientation; its rate is its angular velocity (`{target}.wx`, \
             `{target}.wy`, `{target}.wz` in body axes, as `VELOCITIES` and the tables name \
             it), which expressions read from a body it turns: `<body>.omega_1`, `omega_2`, \
             `omega_3` (body axes) or `omega_x`, `omega_y`, `omega_z` (world axes)"
        ),
        Binding::Failed | Binding::Coordinate(_) => return None,
    })
}

fn arity(name: &str) -> Option<usize> {
    Some(match name {
        "sin" | "cos" | "tan" | "asin" | "acos" | "atan" | "sinh" | "cosh" | "tanh" | "exp"
        | "ln" | "log" | "sqrt" | "abs" | "sign" => 1,
        "atan2" | "pow" | "powi" | "powf" | "min" | "max" => 2,
        "clamp" => 3,
        _ => return None,
    })
}
