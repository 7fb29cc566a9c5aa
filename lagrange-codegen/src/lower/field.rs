//! Field accesses: `self.m`, a point's or body's coordinates `P.x` and their
//! velocities, a body's angular velocity `B.omega_x` and axes `B.axis_x.y`.

use lagrange_symbolic::Expr as Sym;
use syn::{Expr, Ident};

use super::{Binding, CartesianRef, Lowerer, Mode};

impl Lowerer<'_> {
    /// `self.m` (the parameter `m`), `P.x` (a coordinate of a point or body centre),
    /// `B.omega_x` / `B.omega_1` (world / body components of a body's angular velocity).
    pub(super) fn field(&mut self, f: &syn::ExprField, mode: Mode) -> Option<Sym> {
        if let Expr::Field(inner) = &*f.base {
            return self.axis_component(inner, &f.member, mode);
        }
        let base = match &*f.base {
            Expr::Path(p) => p.path.get_ident(),
            _ => None,
        };
        let (Some(base), syn::Member::Named(member)) = (base, &f.member) else {
            self.cx.error_spanned_by(
                f,
                "only `self.<parameter>`, `<point>.x` and `<body>.omega_x` field accesses are supported",
            );
            return None;
        };
        if base == "self" {
            return self.self_field(member);
        }
        let Some(frame) = self.frame_of(base) else {
            let kind = match self.scope.get(&base.to_string()) {
                None => None,
                Some(Binding::Failed) => return None,
                Some(Binding::Coordinate(_)) => Some("a coordinate"),
                Some(Binding::Parameter(_)) => Some("a parameter"),
                Some(Binding::Input(_)) => Some("an input"),
                Some(Binding::Orientation(_)) => Some("an orientation"),
                // Not a frame: `frame_of` found none.
                Some(_) => Some("a definition"),
            };
            let msg = match kind {
                Some("an orientation") => orientation_field(base, &f.member),
                Some(kind) => format!(
                    "`{base}` is {kind}, a number: only points and bodies have coordinates `.x`, `.y`, `.z`; write `{base}` itself"
                ),
                None => format!(
                    "unknown point or body `{base}`; declare it with `point({base}, ...)` or `body({base}, ...)`"
                ),
            };
            self.cx.error_at(base.span(), msg);
            return None;
        };
        let m = member.to_string();
        if let Some(c) = component(&m) {
            return self.coordinate_of(frame, c, false, base, member, mode);
        }
        let omega = match m.as_str() {
            "omega_x" => Some((0, 0)),
            "omega_y" => Some((0, 1)),
            "omega_z" => Some((0, 2)),
            "omega_1" => Some((1, 0)),
            "omega_2" => Some((1, 1)),
            "omega_3" => Some((1, 2)),
            _ => None,
        };
        let Some((which, c)) = omega else {
            self.cx.error_at(
                member.span(),
                format!("`{base}.{m}`: expected a coordinate `x`, `y`, `z`, or for a body `omega_x`/`omega_y`/`omega_z` (world frame), `omega_1`/`omega_2`/`omega_3` (body frame) or an axis component `axis_x.x` … `axis_z.z`"),
            );
            return None;
        };
        let Some(w) = self.frames[frame].omega else {
            self.cx.error_at(
                member.span(),
                format!("`{base}` is a point; only bodies have an angular velocity"),
            );
            return None;
        };
        if mode != Mode::State {
            self.cx.error_at(
                member.span(),
                format!(
                    "the angular velocity `{base}.{m}` cannot appear in {}",
                    self.describe(mode)
                ),
            );
            return None;
        }
        Some(w[which][c])
    }

    /// `B.axis_x.y`: a world component of one of a body's unit axes, that is
    /// an entry of its rotation matrix (R_ij = `B.axis_<j>.<i>`).
    fn axis_component(
        &mut self,
        inner: &syn::ExprField,
        member: &syn::Member,
        mode: Mode,
    ) -> Option<Sym> {
        let usage = "write `<body>.axis_x.x` (… `axis_z.z`): the world components of a body's axes";
        let base = match &*inner.base {
            Expr::Path(p) => p.path.get_ident(),
            _ => None,
        };
        let axis = match &inner.member {
            syn::Member::Named(m) => ["axis_x", "axis_y", "axis_z"].iter().position(|a| m == a),
            syn::Member::Unnamed(_) => None,
        };
        let component = match member {
            syn::Member::Named(m) => component(&m.to_string()),
            syn::Member::Unnamed(_) => None,
        };
        let (Some(base), Some(axis), Some(c)) = (base, axis, component) else {
            self.cx
                .error_spanned_by(inner, format!("unsupported field access: {usage}"));
            return None;
        };
        let Some(frame) = self.frame_of(base) else {
            self.cx.error_at(
                base.span(),
                format!("unknown body `{base}`; declare it with `body({base}, ...)`"),
            );
            return None;
        };
        let Some(r) = self.frames[frame].axes else {
            self.cx.error_at(
                base.span(),
                format!("`{base}` is a point; only bodies have axes"),
            );
            return None;
        };
        if mode == Mode::Constant {
            self.cx.error_spanned_by(
                inner,
                format!(
                    "a body's axes depend on the configuration and cannot appear in {}",
                    self.describe(mode)
                ),
            );
            return None;
        }
        Some(r[c][axis])
    }

    /// A Cartesian coordinate (or, with `velocity`, its rate) of a frame: the
    /// expression itself, or a recorded free symbol while lowering a constraint.
    pub(super) fn coordinate_of(
        &mut self,
        frame: usize,
        c: usize,
        velocity: bool,
        base: &Ident,
        member: &Ident,
        mode: Mode,
    ) -> Option<Sym> {
        let f = &self.frames[frame];
        if c >= f.position.len() {
            self.cx.error_at(
                member.span(),
                format!("`{base}.{member}`: the scene is planar, `{base}` has only `x` and `y`"),
            );
            return None;
        }
        if mode == Mode::Constant {
            self.cx.error_at(
                base.span(),
                format!(
                    "{} must be constant: it cannot depend on the position of `{base}`",
                    self.describe(mode)
                ),
            );
            return None;
        }
        if velocity && mode != Mode::State {
            self.cx.error_at(
                base.span(),
                format!(
                    "velocity `dot({base}.{member})` cannot appear in {}",
                    self.describe(mode)
                ),
            );
            return None;
        }
        let x = f.position[c];
        let value = if velocity {
            self.ctx.time_derivative(x)
        } else {
            x
        };
        let name = if velocity {
            format!("dot({base}.{member})")
        } else {
            format!("{base}.{member}")
        };
        match &mut self.cartesian {
            None => Some(value),
            Some(refs) => {
                let symbol = self.ctx.free_symbol(&name);
                if !refs.iter().any(|r| r.symbol == symbol) {
                    refs.push(CartesianRef {
                        symbol,
                        frame,
                        component: c,
                        velocity,
                    });
                }
                Some(symbol)
            }
        }
    }

    /// `self.m` is accepted as a spelling of the parameter `m`.
    fn self_field(&mut self, name: &Ident) -> Option<Sym> {
        match self.scope.get(&name.to_string()) {
            Some(Binding::Parameter(p)) => Some(*p),
            _ => {
                self.cx.error_at(
                    name.span(),
                    format!("`self.{name}` is not a parameter field of the struct"),
                );
                None
            }
        }
    }
}

/// `x`, `y`, `z` → 0, 1, 2.
pub(super) fn component(name: &str) -> Option<usize> {
    match name {
        "x" => Some(0),
        "y" => Some(1),
        "z" => Some(2),
        _ => None,
    }
}

/// `turn.wx` in an expression: the angular velocity has that name in the
/// runtime, and is read in expressions from a body the orientation turns.
fn orientation_field(base: &Ident, member: &syn::Member) -> String {
    let member = quote::ToTokens::to_token_stream(member);
    format!(
        "`{base}.{member}` is not read in expressions: `{base}` is an orientation, and its \
         angular velocity (`{base}.wx`, `{base}.wy`, `{base}.wz` in body axes, as `VELOCITIES` \
         and the tables name it) is read from a body it turns, `<body>.omega_1`, `omega_2`, \
         `omega_3` (body axes) or `omega_x`, `omega_y`, `omega_z` (world axes)"
    )
}
