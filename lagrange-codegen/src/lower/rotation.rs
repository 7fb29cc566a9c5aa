//! Rotations R(q,t) of rigid bodies and their angular velocities.
//!
//! A rotation is written as a product of factors: `rot_x(a)`, `rot_y(a)`,
//! `rot_z(a)`, `euler_zxz(a, b, c)` (= rot_z(a)·rot_x(b)·rot_z(c), Suslov's
//! precession–nutation–spin), `euler_zyx(a, b, c)` (= rot_z(a)·rot_y(b)·rot_x(c),
//! yaw–pitch–roll) or an explicit 3×3 matrix `[[..], [..], [..]]`. R maps body
//! coordinates to world coordinates.
//!
//! The body-frame angular velocity ω = vee(Rᵀ Ṙ) is composed factor by factor,
//! ω(R₁R₂) = R₂ᵀ ω(R₁) + ω(R₂), with ω(rot_axis(a)) = ȧ e_axis, and the world-frame
//! one likewise, Ω(R₁R₂) = Ω(R₁) + R₁ Ω(R₂). This gives the
//! compact textbook forms (e.g. p = ψ̇ sinθ sinφ + θ̇ cosφ for z-x-z) directly,
//! instead of a product of nine-term sums that would have to be simplified back
//! with sin² + cos² = 1. Only an explicit matrix factor goes through Rᵀ Ṙ.

use lagrange_symbolic::Expr as Sym;
use syn::{BinOp, Expr};

use crate::lower::{Lowerer, Mode};
use crate::lowered::Factor;
use crate::mat3::{
    Mat3, mat_mul, mat_vec, quaternion_matrix, second_order_turn, skew, transpose, vee,
};

/// A lowered rotation: the matrix and the angular velocity in body and world axes.
pub struct Rotation {
    /// R, body → world.
    pub matrix: Mat3,
    /// The angular velocity in body axes.
    pub omega_body: [Sym; 3],
    /// The angular velocity in world axes.
    pub omega_world: [Sym; 3],
    /// The elementary factors (axis, angle) in order, when every factor is one
    /// (an explicit matrix has none): the joints of a kinematic tree.
    pub factors: Option<Vec<Factor>>,
}

const FORMS: &str = "rot_x(a), rot_y(a), rot_z(a), euler_zxz(a, b, c), euler_zyx(a, b, c) or a 3×3 matrix [[..], [..], [..]]";

impl Lowerer<'_> {
    /// Lowers a rotation expression; errors point at the offending factor.
    pub fn rotation(&mut self, e: &Expr) -> Option<Rotation> {
        let mut factors = Vec::new();
        flatten_product(e, &mut factors);
        let mut acc: Option<Rotation> = None;
        let mut ok = true;
        for f in factors {
            let Some(r) = self.factor(f) else {
                ok = false;
                continue;
            };
            acc = Some(match acc {
                None => r,
                Some(a) => self.compose(a, r),
            });
        }
        if ok { acc } else { None }
    }

    fn factor(&mut self, e: &Expr) -> Option<Rotation> {
        match e {
            Expr::Paren(p) => self.rotation(&p.expr),
            Expr::Group(g) => self.rotation(&g.expr),
            Expr::Call(c) => {
                let name = match &*c.func {
                    Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                    _ => None,
                };
                let (axes, arity): (&[usize], usize) = match name.as_deref() {
                    Some("rot_x") => (&[0], 1),
                    Some("rot_y") => (&[1], 1),
                    Some("rot_z") => (&[2], 1),
                    Some("euler_zxz") => (&[2, 0, 2], 3),
                    Some("euler_zyx") => (&[2, 1, 0], 3),
                    _ => {
                        self.cx.error_spanned_by(
                            &c.func,
                            format!("not a rotation; a rotation is a product of {FORMS}"),
                        );
                        return None;
                    }
                };
                if c.args.len() != arity {
                    self.cx.error_spanned_by(
                        c,
                        format!(
                            "`{}` takes {arity} angle{}",
                            name.unwrap_or_default(),
                            if arity == 1 { "" } else { "s" }
                        ),
                    );
                    return None;
                }
                let angles: Vec<Option<Sym>> = c
                    .args
                    .iter()
                    .map(|a| self.expr(a, Mode::Configuration))
                    .collect();
                let angles: Vec<Sym> = angles.into_iter().collect::<Option<_>>()?;
                let mut acc: Option<Rotation> = None;
                for (&axis, &angle) in axes.iter().zip(&angles) {
                    let r = self.elementary(axis, angle);
                    acc = Some(match acc {
                        None => r,
                        Some(a) => self.compose(a, r),
                    });
                }
                acc
            }
            Expr::Array(rows) => self.explicit(e, rows),
            Expr::Path(p) if self.orientation_named(p).is_some() => {
                let k = self.orientation_named(p)?;
                Some(self.free_orientation(k))
            }
            _ => {
                self.cx
                    .error_spanned_by(e, format!("not a rotation; expected a product of {FORMS}"));
                None
            }
        }
    }

    /// The orientation a path names, if it names one.
    fn orientation_named(&self, p: &syn::ExprPath) -> Option<usize> {
        self.orientation_index(&p.path.get_ident()?.to_string())
    }

    /// A free orientation in the chart that moves with it: R₀·R(θ) with
    /// R(θ) = I + [θ]× + ½[θ]×², the exponential map to the second order that
    /// Lagrange's equations at θ = 0 read (first derivatives of T and V,
    /// second of the constraints), and ω = θ̇ + ½ θ̇ × θ, vee(Rᵀ Ṙ) to the first
    /// order. R₀ is the quaternion's rotation matrix.
    fn free_orientation(&mut self, k: usize) -> Rotation {
        let theta = self.orientations[k].theta;
        let r0 = quaternion_matrix(&mut self.ctx, self.orientations[k].quaternion);
        let local = second_order_turn(&mut self.ctx, theta);
        let matrix = mat_mul(&mut self.ctx, &r0, &local);
        let rates = theta.map(|x| self.ctx.time_derivative(x));
        // θ̇ × θ = [θ̇]× θ.
        let rate_skew = skew(&mut self.ctx, rates);
        let turn = mat_vec(&mut self.ctx, &rate_skew, theta);
        let half = self.ctx.rational(1, 2);
        let omega_body = [0, 1, 2].map(|i| {
            let h = self.ctx.mul(half, turn[i]);
            self.ctx.add(rates[i], h)
        });
        let omega_world = mat_vec(&mut self.ctx, &matrix, omega_body);
        let quaternion = self.orientations[k].quaternion;
        Rotation {
            matrix,
            omega_body,
            omega_world,
            factors: Some(vec![Factor::Free { theta, quaternion }]),
        }
    }

    /// rot_axis(a) and ω = ȧ e_axis.
    fn elementary(&mut self, axis: usize, angle: Sym) -> Rotation {
        let zero = self.ctx.zero();
        let one = self.ctx.one();
        let (c, s) = crate::mat3::cos_sin(&mut self.ctx, angle);
        let ms = self.ctx.neg(s);
        let i = (axis + 1) % 3;
        let j = (axis + 2) % 3;
        let mut m = [[zero; 3]; 3];
        m[axis][axis] = one;
        m[i][i] = c;
        m[j][j] = c;
        m[i][j] = ms;
        m[j][i] = s;
        let rate = self.ctx.time_derivative(angle);
        let mut w = [zero; 3];
        w[axis] = rate;
        Rotation {
            matrix: m,
            omega_body: w,
            omega_world: w,
            factors: Some(vec![Factor::Turn(axis, angle)]),
        }
    }

    /// `[[..], [..], [..]]`, with ω = vee(Rᵀ Ṙ) taken as the skew part (exact for
    /// a rotation, and robust to an Rᵀ Ṙ that simplification leaves not quite skew).
    fn explicit(&mut self, e: &Expr, rows: &syn::ExprArray) -> Option<Rotation> {
        let shape_ok = rows.elems.len() == 3
            && rows
                .elems
                .iter()
                .all(|r| matches!(r, Expr::Array(a) if a.elems.len() == 3));
        if !shape_ok {
            let shape: Vec<String> = rows
                .elems
                .iter()
                .map(|r| match r {
                    Expr::Array(a) => a.elems.len().to_string(),
                    _ => "1".to_string(),
                })
                .collect();
            self.cx.error_spanned_by(
                e,
                format!(
                    "a rotation matrix must be 3×3, found {} row{} of lengths [{}]",
                    rows.elems.len(),
                    if rows.elems.len() == 1 { "" } else { "s" },
                    shape.join(", ")
                ),
            );
            return None;
        }
        let zero = self.ctx.zero();
        let mut m = [[zero; 3]; 3];
        let mut ok = true;
        for (i, row) in rows.elems.iter().enumerate() {
            let Expr::Array(row) = row else { continue };
            for (j, x) in row.elems.iter().enumerate() {
                match self.expr(x, Mode::Configuration) {
                    Some(v) => m[i][j] = v,
                    None => ok = false,
                }
            }
        }
        if !ok {
            return None;
        }
        let md = m.map(|row| row.map(|x| self.ctx.time_derivative(x)));
        let body = mat_mul(&mut self.ctx, &transpose(&m), &md);
        let world = mat_mul(&mut self.ctx, &md, &transpose(&m));
        Some(Rotation {
            matrix: m,
            omega_body: vee(&mut self.ctx, &body),
            omega_world: vee(&mut self.ctx, &world),
            factors: None,
        })
    }

    /// R₁R₂ with ω = R₂ᵀ ω₁ + ω₂ and Ω = Ω₁ + R₁ Ω₂.
    fn compose(&mut self, a: Rotation, b: Rotation) -> Rotation {
        let matrix = mat_mul(&mut self.ctx, &a.matrix, &b.matrix);
        let rotated = mat_vec(&mut self.ctx, &transpose(&b.matrix), a.omega_body);
        let omega_body = [0, 1, 2].map(|k| self.ctx.add(rotated[k], b.omega_body[k]));
        let carried = mat_vec(&mut self.ctx, &a.matrix, b.omega_world);
        let omega_world = [0, 1, 2].map(|k| self.ctx.add(a.omega_world[k], carried[k]));
        let factors = match (a.factors, b.factors) {
            (Some(mut x), Some(y)) => {
                x.extend(y);
                Some(x)
            }
            _ => None,
        };
        Rotation {
            matrix,
            omega_body,
            omega_world,
            factors,
        }
    }
}

/// `A * B * C` → [A, B, C] (left to right, the order the factors apply in).
fn flatten_product<'e>(e: &'e Expr, out: &mut Vec<&'e Expr>) {
    match e {
        Expr::Binary(b) if matches!(b.op, BinOp::Mul(_)) => {
            flatten_product(&b.left, out);
            flatten_product(&b.right, out);
        }
        _ => out.push(e),
    }
}
