//! Physical validity of masses and inertias: a mass is non-negative; principal
//! moments are non-negative and satisfy the triangle inequalities
//! (A + B ≥ C, ...); a full tensor's second-moment matrix tr(I)/2·E − I is
//! positive semidefinite (which implies both for its principal moments). Zero
//! is allowed: a massless point, a slender rod's axis, a thin plate's
//! A + B = C. Values given by literals are checked here, with the error at the
//! literal; values computed from parameters are recorded as
//! [`PhysicalCheck`]s for the generated `check_parameters`, which applies the
//! same rules (`lagrange_runtime::physical`) before a run.
//!
//! A Rayleigh dissipation function with literal coefficients must be positive
//! semidefinite in the velocities (a negative damping coefficient feeds energy
//! in); one whose coefficients are parameters or depend on the state (a van
//! der Pol term) is left alone, so a deliberately self-exciting model stays
//! possible.

use lagrange_symbolic::Expr as Sym;
use syn::Expr;

use crate::ast::Body;
use crate::lower::Lowerer;
use crate::lowered::{Factor, PhysicalCheck, Skeleton, SpinModel};
use crate::mat3::Mat3;

/// Relative round-off allowed on the inequalities, as at run time.
const ROUND_OFF: f64 = 1e-12;

/// The value of an expression that depends on nothing (literals, `pi`).
fn value(lw: &Lowerer, e: Sym) -> Option<f64> {
    lw.ctx
        .free_symbols(e)
        .is_empty()
        .then(|| lw.ctx.eval(e, &|_| f64::NAN))
}

/// The mass of a point or body (`what` is "point `p`" or "body `b`"), checked
/// now if it is a constant, else recorded.
pub fn mass(lw: &Lowerer, name: &str, what: &str, syntax: &Expr, m: Sym) -> Option<PhysicalCheck> {
    let Some(v) = value(lw, m) else {
        return Some(PhysicalCheck::Mass(name.to_string(), m));
    };
    if v < 0.0 {
        lw.cx.error_spanned_by(
            syntax,
            format!("{what}: mass = {v} must be non-negative (zero is allowed: a massless point)"),
        );
    }
    None
}

/// A joint's damping, armature or rotor inertia (`what`) on `coordinate`,
/// which must be ≥ 0: checked now if it is a constant (the error at
/// `syntax`), else recorded for `check_parameters`.
pub fn joint(
    lw: &Lowerer,
    coordinate: &str,
    what: &'static str,
    syntax: &Expr,
    v: Sym,
) -> Option<PhysicalCheck> {
    let Some(x) = value(lw, v) else {
        return Some(PhysicalCheck::Joint(coordinate.to_string(), what, v));
    };
    if x < 0.0 {
        lw.cx.error_spanned_by(
            syntax,
            format!(
                "joint `{coordinate}`: {what} = {x}: a joint's {what} is ≥ 0 (a negative one feeds energy in)"
            ),
        );
    }
    None
}

/// A joint's gear ratio on `coordinate`, which must be > 0 (0 would cut
/// the motor off): checked now if it is a constant (the error at
/// `syntax`), else recorded for `check_parameters`.
pub fn gear(lw: &Lowerer, coordinate: &str, syntax: &Expr, v: Sym) -> Option<PhysicalCheck> {
    let Some(x) = value(lw, v) else {
        return Some(PhysicalCheck::Gear(coordinate.to_string(), v));
    };
    if x <= 0.0 {
        lw.cx.error_spanned_by(
            syntax,
            format!(
                "joint `{coordinate}`: gear = {x}: a gear ratio is > 0 (motor turns per joint turn)"
            ),
        );
    }
    None
}

/// How a body's inertia is given and used.
#[derive(Copy, Clone)]
pub struct Shape {
    /// Given about the point `about`, moved to the centre of mass.
    pub moved: bool,
    /// The body turns about all three of its axes (no component of its
    /// angular velocity is identically zero). A body that does not, such as a
    /// planar one (`rot_z` only), is written with the moments it uses,
    /// `[0, 0, Iz]`: the triangle inequalities then do not apply, as the
    /// equations never read the moments they would constrain.
    pub spatial: bool,
}

/// A body's inertia about its centre of mass: checked now if its entries are
/// constants, else recorded; left alone when the body says so (read by
/// `urdf(.., inertia = as_written)`).
pub fn inertia(lw: &Lowerer, b: &Body, i: &Mat3, shape: Shape) -> Option<PhysicalCheck> {
    if b.inertia_unchecked {
        return None;
    }
    let syntax = b.inertia.as_ref()?;
    let Expr::Array(list) = syntax else {
        return None;
    };
    let name = b.name.to_string();
    let principal = list.elems.len() == 3 && !shape.moved;
    let entries = [i[0][0], i[1][1], i[2][2], i[0][1], i[0][2], i[1][2]];
    let names = if principal {
        ["A", "B", "C"]
    } else {
        ["Ixx", "Iyy", "Izz"]
    };
    let values: Option<Vec<f64>> = entries.iter().map(|&e| value(lw, e)).collect();
    let Some(v) = values else {
        let diagonal = [entries[0], entries[1], entries[2]];
        return Some(match (shape.spatial, principal) {
            (false, _) => PhysicalCheck::Moments(name, names, diagonal),
            (true, true) => PhysicalCheck::Principal(name, diagonal),
            (true, false) => PhysicalCheck::Tensor(name, entries),
        });
    };
    let moved = shape.moved;
    for k in 0..3 {
        if v[k] < 0.0 {
            let what = if principal {
                "principal moment"
            } else {
                "moment"
            };
            let (at, moved_note): (&dyn quote::ToTokens, &str) = if moved {
                (
                    syntax,
                    " once moved from `about` to the centre of mass (I_com = I_about − m(|d|²E − d dᵀ))",
                )
            } else {
                (&list.elems[k], "")
            };
            lw.cx.error_spanned_by(
                at,
                format!(
                    "body `{name}`: {what} {} = {}{moved_note} must be non-negative (a moment of \
                     inertia is ∫ r² dm about an axis; zero is allowed, as for a slender rod's axis)",
                    names[k], v[k]
                ),
            );
            return None;
        }
    }
    if !shape.spatial {
        return None;
    }
    if principal {
        triangle(lw, &name, &list.elems, [v[0], v[1], v[2]]);
    } else if !crate::mat3::second_moments_psd(&v, ROUND_OFF) {
        let whose = if moved {
            "its inertia moved from `about` to the centre of mass (parallel-axis theorem, \
             I_com = I_about − m(|d|²E − d dᵀ))"
        } else {
            "its inertia tensor"
        };
        lw.cx.error_spanned_by(
            syntax,
            format!(
                "body `{name}`: {whose} is that of no rigid body: the second-moment matrix \
                 tr(I)/2·E − I is not positive semidefinite (a principal moment is negative \
                 or exceeds the sum of the other two); check the products' sign \
                 (I_xy = -∫xy dm) and sizes"
            ),
        );
    }
    None
}

/// A body that a free orientation turns alone (no other body has that
/// orientation among its factors, and no point mass sits on it) is a free
/// body: its inertia about the centre of mass must be positive definite, or
/// M is singular at every state. Literal entries are checked here, the error
/// at the inertia; a zero moment from parameters makes a run's first step
/// `Error::SingularMassMatrix`. A body with others hanging on its orientation
/// is left alone: their masses may make M regular.
pub fn free_bodies(lw: &Lowerer, bodies: &[Body], skeleton: &Skeleton, spins: &[SpinModel]) {
    let free = |f: &&Factor| matches!(f, Factor::Free { .. });
    let turning: Vec<Vec<Factor>> = skeleton
        .bodies
        .iter()
        .map(|b| b.factors.iter().flatten().filter(free).copied().collect())
        .collect();
    for (i, own) in turning.iter().enumerate() {
        let Some(&last) = own.last() else { continue };
        let alone = turning.iter().filter(|t| t.contains(&last)).count() == 1;
        let on_it = skeleton
            .masses
            .iter()
            .flatten()
            .filter(|(b, _)| *b == i)
            .count();
        let values: Option<Vec<f64>> = spins[i]
            .inertia
            .iter()
            .flatten()
            .map(|&e| value(lw, e))
            .collect();
        let (Some(v), true, 1) = (values, alone, on_it) else {
            continue;
        };
        let body = bodies.iter().find(|b| b.name == spins[i].name);
        let Some(syntax) = body.and_then(|b| b.inertia.as_ref()) else {
            continue;
        };
        if !positive_definite(&v) {
            lw.cx.error_spanned_by(
                syntax,
                format!(
                    "body `{}`: a free orientation turns it and nothing else, so its inertia \
                     about the centre of mass must be positive definite (every principal moment \
                     above zero); with this one the mass matrix is singular at every state: \
                     give each moment a positive value (a thin rod's axial moment is small, not \
                     zero)",
                    spins[i].name
                ),
            );
        }
    }
}

/// Whether the symmetric 3×3 matrix `v` (row-major) is positive definite:
/// its leading principal minors above round-off.
fn positive_definite(v: &[f64]) -> bool {
    let m = |r: usize, c: usize| v[3 * r + c];
    let scale = (m(0, 0) + m(1, 1) + m(2, 2)).abs();
    let d1 = m(0, 0);
    let d2 = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
    let d3 = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
        - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
        + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
    d1 > ROUND_OFF * scale
        && d2 > ROUND_OFF * scale * scale
        && d3 > ROUND_OFF * scale * scale * scale
}

/// A + B ≥ C and its rotations, the error at the moment that is too large.
fn triangle(
    lw: &Lowerer,
    name: &str,
    elems: &syn::punctuated::Punctuated<Expr, syn::Token![,]>,
    m: [f64; 3],
) {
    let names = ["A", "B", "C"];
    let tol = ROUND_OFF * (m[0] + m[1] + m[2]);
    for k in 0..3 {
        let i = (k + 1) % 3;
        let j = (k + 2) % 3;
        if m[i] + m[j] < m[k] - tol {
            let a = names[i];
            let b = names[j];
            let c = names[k];
            lw.cx.error_spanned_by(
                &elems[k],
                format!(
                    "body `{name}`: principal moments {a} = {}, {b} = {}, {c} = {} break the \
                     triangle inequality {a} + {b} >= {c}: no rigid body has them (the moment \
                     about one axis is at most the sum of the other two)",
                    m[i], m[j], m[k]
                ),
            );
            return;
        }
    }
}

/// D(q, q̇) with a constant numeric Hessian in the velocities (literal damping
/// coefficients) must be positive semidefinite: the error at the dissipation
/// names the first velocity where a pivot of ∂²D/∂q̇² is negative.
pub fn dissipation(lw: &mut Lowerer, syntax: &Expr, d: Sym, coordinates: &[syn::Ident]) {
    let qd = lw.ctx.velocities();
    let mut h = vec![vec![0.0; qd.len()]; qd.len()];
    for (i, &vi) in qd.iter().enumerate() {
        let di = lw.ctx.diff(d, vi);
        for (j, &vj) in qd.iter().enumerate() {
            let dij = lw.ctx.diff(di, vj);
            let dij = lw.ctx.simplify(dij);
            match value(lw, dij) {
                Some(v) => h[i][j] = v,
                None => return,
            }
        }
    }
    let Some(k) = negative_pivot(h) else {
        return;
    };
    let q = coordinates
        .get(k)
        .map(ToString::to_string)
        .unwrap_or_default();
    lw.cx.error_spanned_by(
        syntax,
        format!(
            "a Rayleigh dissipation function is >= 0 for all velocities, but this one's \
             ∂²D/∂q̇² is not positive semidefinite (a negative pivot at `dot({q})`): its \
             damping feeds energy in instead of taking it out; write damping as \
             `c * pow(dot({q}), 2) / 2` with c >= 0, or, if a self-exciting term is intended, \
             make its coefficient a parameter"
        ),
    );
}

/// The index of the first negative pivot of a symmetric matrix in Cholesky
/// with diagonal pivoting (largest remaining diagonal first), or `None` when
/// it is positive semidefinite to round-off.
fn negative_pivot(mut a: Vec<Vec<f64>>) -> Option<usize> {
    let n = a.len();
    let scale = (0..n).map(|i| a[i][i].abs()).fold(0.0, f64::max);
    let tol = ROUND_OFF * scale.max(f64::MIN_POSITIVE);
    let mut left: Vec<usize> = (0..n).collect();
    while !left.is_empty() {
        let (at, &p) = left
            .iter()
            .enumerate()
            .max_by(|x, y| a[*x.1][*x.1].total_cmp(&a[*y.1][*y.1]))?;
        let pivot = a[p][p];
        if pivot <= tol {
            // The rest must vanish: a negative diagonal, or an off-diagonal
            // entry beside a zero diagonal, makes the matrix indefinite.
            let bad = left
                .iter()
                .find(|&&i| a[i][i] < -tol || left.iter().any(|&j| j != i && a[i][j].abs() > tol));
            return bad.copied();
        }
        left.remove(at);
        for &i in &left {
            for &j in &left {
                a[i][j] -= a[i][p] * a[p][j] / pivot;
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pivots_find_indefinite_damping() {
        assert_eq!(negative_pivot(vec![vec![1.0, 0.0], vec![0.0, 0.0]]), None);
        // Singular but semidefinite: one damper on x − y.
        assert_eq!(negative_pivot(vec![vec![1.0, -1.0], vec![-1.0, 1.0]]), None);
        assert_eq!(negative_pivot(vec![vec![-0.3]]), Some(0));
        // A zero diagonal beside a coupling, and a coupling too strong.
        assert!(negative_pivot(vec![vec![0.0, 1.0], vec![1.0, 0.0]]).is_some());
        assert!(negative_pivot(vec![vec![2.0, 3.0], vec![3.0, 2.0]]).is_some());
    }

    #[test]
    fn second_moments() {
        let second_moments_psd = |v: &[f64]| crate::mat3::second_moments_psd(v, ROUND_OFF);
        // A slender rod along (1, −1, 0)/√2: I = E − u uᵀ, on the boundary.
        assert!(second_moments_psd(&[0.5, 0.5, 1.0, 0.5, 0.0, 0.0]));
        assert!(second_moments_psd(&[1.0, 1.0, 2.0, 0.0, 0.0, 0.0]));
        assert!(!second_moments_psd(&[1.0, 1.0, 3.0, 0.0, 0.0, 0.0]));
        assert!(!second_moments_psd(&[1.0, 1.0, 1.0, 2.0, 0.0, 0.0]));
        // Positive definite, yet no body: principal moments 1, 1, 2.5.
        assert!(!second_moments_psd(&[1.0, 1.0, 2.5, 0.0, 0.0, 0.0]));
    }
}
