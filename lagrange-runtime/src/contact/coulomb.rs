//! One step's impulse problem of the time-stepping scheme: Newton's law at
//! the velocity level and Coulomb's isotropic cone on the impulses of the
//! contacts closed at the step's midpoint, solved by nonsmooth Gauss–Seidel
//! (Jean and Moreau) with an exact solution of each contact's own problem.
//!
//! For contact i with rows H_i (its normal, then the tangents it rubs
//! along), the local velocities after the step are U_i = H_i v₁ (plus
//! e·min(uₙ, 0) on the normal, Newton's law: Uₙ ≥ 0 means uₙ⁺ ≥ −e uₙ
//! for an approaching contact) and
//! v₁ = v_free + Σ_j M⁻¹ H_jᵀ P_j. Each contact's impulse P_i = (Pₙ, P_t)
//! must satisfy Coulomb's law in its velocity form: apart (P = 0, Uₙ ≥ 0),
//! sticking (U = 0, |P_t| ≤ μ Pₙ) or sliding (Uₙ = 0, P_t = −μ Pₙ s with the
//! slip U_t = α s, α ≥ 0, |s| = 1). Gauss–Seidel solves each contact's
//! problem exactly with the others' impulses held, updates v₁, and sweeps
//! until no update moves a contact's velocities by more than the tolerance.

use crate::numeric::Real;
use nalgebra::SVector;

/// How a contact's impulse satisfies Coulomb's law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Branch<T> {
    /// No impulse: the contact opens.
    Apart,
    /// No slip after the step (for a contact without friction: in force).
    Sticking,
    /// Slipping along the unit direction `s` of its tangent rows.
    Sliding { s: [T; 2] },
}

/// One closed contact in the step's problem.
pub(super) struct Local<T: Real, const N: usize> {
    /// The contact's index among the system's laws.
    pub contact: usize,
    /// Its normal row, then the tangent rows it rubs along (none without
    /// friction), and which of the two tangents each is.
    pub rows: Vec<SVector<T, N>>,
    pub tangents: Vec<usize>,
    /// M⁻¹ rowᵀ for each row.
    pub responses: Vec<SVector<T, N>>,
    /// The block H_i M⁻¹ H_iᵀ.
    pub block: [[T; 3]; 3],
    /// e·min(uₙ, 0), added to the normal velocity (Newton's law).
    pub bias: T,
    pub friction: T,
    /// Dry friction's fixed bound on the impulse (its force bound times the
    /// step), where the rows are its tangents only, with no normal; `None`
    /// for a unilateral contact.
    pub bound: Option<T>,
    /// The impulse so far (normal, tangents), and how it stands.
    pub impulse: [T; 3],
    pub branch: Branch<T>,
}

impl<T: Real, const N: usize> Local<T, N> {
    /// A contact with its rows and responses; the block is computed here.
    pub fn new(
        contact: usize,
        (rows, tangents): (Vec<SVector<T, N>>, Vec<usize>),
        responses: Vec<SVector<T, N>>,
        bias: T,
        friction: T,
    ) -> Self {
        let mut block = [[T::zero(); 3]; 3];
        for (a, row) in rows.iter().enumerate() {
            for (b, response) in responses.iter().enumerate() {
                block[a][b] = row.dot(response);
            }
        }
        Self {
            contact,
            rows,
            tangents,
            responses,
            block,
            bias,
            friction,
            bound: None,
            impulse: [T::zero(); 3],
            branch: Branch::Apart,
        }
    }

    fn size(&self) -> usize {
        self.rows.len()
    }

    /// v += M⁻¹ H_iᵀ dp.
    fn apply(&self, v: &mut SVector<T, N>, dp: &[T; 3]) {
        for (response, d) in self.responses.iter().zip(dp) {
            *v += response * *d;
        }
    }
}

/// Sweeps Gauss–Seidel over `locals`, starting from their impulses (already
/// applied to `v`), until a whole sweep moves no contact's velocities by
/// more than `tolerance`: `Ok(sweeps)`, or `Err(change)` of the last sweep
/// after `most` of them, or `Err(NaN)` when a contact's problem has no
/// solution.
///
/// The test is on the velocities, not the impulses: where contacts are
/// dependent (two corners of a box flat on the floor share its weight and
/// its friction along one row) the rigid problem leaves some combination of
/// the impulses undetermined, and Gauss–Seidel may drift along it, slowly
/// and without moving anything.
pub(super) fn gauss_seidel<T: Real, const N: usize>(
    locals: &mut [Local<T, N>],
    v: &mut SVector<T, N>,
    most: usize,
    tolerance: T,
) -> Result<usize, T> {
    let mut change = T::zero();
    for sweep in 1..=most {
        let start = *v;
        for c in locals.iter_mut() {
            let d = c.size();
            let mut free = [T::zero(); 3];
            for (a, (f, row)) in free.iter_mut().zip(&c.rows).enumerate() {
                let held: T = (0..d).fold(T::zero(), |s, b| s + c.block[a][b] * c.impulse[b]);
                *f = row.dot(v) - held;
            }
            free[0] += c.bias;
            let solved = match c.bound {
                Some(bound) => bounded(&c.block, d, free, bound),
                None => coulomb(&c.block, d, free, c.friction),
            };
            let (p, branch) = solved.ok_or(T::lit(f64::NAN))?;
            let dp = [
                p[0] - c.impulse[0],
                p[1] - c.impulse[1],
                p[2] - c.impulse[2],
            ];
            c.apply(v, &dp);
            c.impulse = p;
            c.branch = branch;
        }
        let moved = *v - start;
        change = locals.iter().fold(T::zero(), |m, c| {
            c.rows.iter().fold(m, |m, row| m.max(row.dot(&moved).abs()))
        });
        if change <= tolerance {
            return Ok(sweep);
        }
    }
    Err(change)
}

/// One contact's problem: the impulse P with U = W P + r satisfying
/// Coulomb's law, for the `d` × `d` block W (d = 1: normal only), the
/// velocities r without its impulse and friction μ; `None` when there is
/// none (a block that is not positive along the normal). Where several
/// answers exist, the first of apart, sticking, sliding is taken.
pub(super) fn coulomb<T: Real>(
    w: &[[T; 3]; 3],
    d: usize,
    r: [T; 3],
    mu: T,
) -> Option<([T; 3], Branch<T>)> {
    let zero = T::zero();
    if r[0] >= zero {
        return Some(([zero; 3], Branch::Apart));
    }
    if w[0][0] <= zero {
        return None;
    }
    if d == 1 || mu == zero {
        return Some(([-r[0] / w[0][0], zero, zero], Branch::Sticking));
    }
    if let Some(p) = stick(w, d, r)
        && p[0] >= zero
        && (p[1] * p[1] + p[2] * p[2]).sqrt() <= mu * p[0] * T::lit(1.0 + 1e-12)
    {
        return Some((p, Branch::Sticking));
    }
    let slide = |s: [T; 2]| sliding(w, d, r, mu, s);
    if d == 2 {
        return [T::one(), -T::one()].into_iter().find_map(|s| {
            let (p, _, _, speed) = slide([s, zero])?;
            (speed >= zero).then_some((p, Branch::Sliding { s: [s, zero] }))
        });
    }
    slide_in_plane(&slide)
}

/// Dry friction's problem: the impulse P on its `d` tangent rows (no
/// normal) with U = W P + r, sticking (U = 0) while |P| ≤ `bound`, sliding
/// otherwise (P = −bound s, U = α s with α ≥ 0). `None` when W is not
/// positive along the slip.
pub(super) fn bounded<T: Real>(
    w: &[[T; 3]; 3],
    d: usize,
    r: [T; 3],
    bound: T,
) -> Option<([T; 3], Branch<T>)> {
    let zero = T::zero();
    let p = match d {
        1 => (w[0][0] > zero).then(|| [-r[0] / w[0][0], zero, zero])?,
        _ => stick(w, d, r)?,
    };
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() <= bound {
        return Some((p, Branch::Sticking));
    }
    let slide = |s: [T; 2]| {
        let p = [-bound * s[0], -bound * s[1], zero];
        let mut u = [zero; 2];
        for (a, x) in u.iter_mut().enumerate().take(d) {
            *x = (0..d).fold(r[a], |acc, b| acc + w[a][b] * p[b]);
        }
        let cross = u[0] * s[1] - u[1] * s[0];
        let speed = u[0] * s[0] + u[1] * s[1];
        Some((p, u, cross, speed))
    };
    if d == 1 {
        let s = [r[0].signum(), zero];
        return Some((slide(s)?.0, Branch::Sliding { s }));
    }
    slide_in_plane(&slide)
}

/// The impulse that stops the contact: W P = −r (on the stack: this is
/// Gauss–Seidel's inner loop).
fn stick<T: Real>(w: &[[T; 3]; 3], d: usize, r: [T; 3]) -> Option<[T; 3]> {
    let p = if d == 2 {
        let m = nalgebra::Matrix2::from_fn(|a, b| w[a][b]);
        let x = m.lu().solve(&nalgebra::Vector2::new(-r[0], -r[1]))?;
        [x[0], x[1], T::zero()]
    } else {
        let m = nalgebra::Matrix3::from_fn(|a, b| w[a][b]);
        let x = m.lu().solve(&nalgebra::Vector3::new(-r[0], -r[1], -r[2]))?;
        [x[0], x[1], x[2]]
    };
    p.iter().all(|x| x.is_finite()).then_some(p)
}

/// The sliding impulse along the unit slip direction s: Pₙ from Uₙ = 0,
/// P_t = −μ Pₙ s; with the tangential velocity's cross product with s
/// (zero when they are parallel) and its component along s (the slip
/// speed, which must be ≥ 0). `None` when Pₙ would be negative or infinite.
#[allow(clippy::type_complexity)]
fn sliding<T: Real>(
    w: &[[T; 3]; 3],
    d: usize,
    r: [T; 3],
    mu: T,
    s: [T; 2],
) -> Option<([T; 3], [T; 2], T, T)> {
    let k = d - 1;
    let along = (0..k).fold(T::zero(), |acc, a| acc + w[0][1 + a] * s[a]);
    let den = w[0][0] - mu * along;
    if den <= T::zero() {
        return None;
    }
    let pn = -r[0] / den;
    let mut p = [pn, T::zero(), T::zero()];
    for a in 0..k {
        p[1 + a] = -mu * pn * s[a];
    }
    let mut u = [T::zero(); 2];
    for a in 0..k {
        u[a] = (0..d).fold(r[1 + a], |acc, b| acc + w[1 + a][b] * p[b]);
    }
    let cross = u[0] * s[1] - u[1] * s[0];
    let speed = u[0] * s[0] + u[1] * s[1];
    Some((p, u, cross, speed))
}

/// Samples of the slip's angle over the circle before refining a root.
const ANGLES: usize = 72;

/// The sliding answer with two tangents: the angle φ of s = (cos φ, sin φ)
/// at which the slip U_t is parallel to s and along it, bracketed on a grid
/// of angles and refined by bisection.
fn slide_in_plane<T: Real>(
    slide: &impl Fn([T; 2]) -> Option<([T; 3], [T; 2], T, T)>,
) -> Option<([T; 3], Branch<T>)> {
    let at = |phi: T| [phi.cos(), phi.sin()];
    let tau = T::lit(std::f64::consts::TAU);
    let angle = |k: usize| tau * T::lit(k as f64 / ANGLES as f64);
    for k in 0..ANGLES {
        let (a, b) = (angle(k), angle(k + 1));
        let (Some(fa), Some(fb)) = (slide(at(a)), slide(at(b))) else {
            continue;
        };
        if fa.2.signum() == fb.2.signum() && fa.2 != T::zero() {
            continue;
        }
        let (mut lo, mut hi, mut f_lo) = (a, b, fa.2);
        for _ in 0..80 {
            let mid = T::lit(0.5) * (lo + hi);
            let Some(fm) = slide(at(mid)) else { break };
            if fm.2 == T::zero() || fm.2.signum() == f_lo.signum() {
                (lo, f_lo) = (mid, fm.2);
            } else {
                hi = mid;
            }
            if hi - lo <= T::default_epsilon() * tau {
                break;
            }
        }
        let s = at(T::lit(0.5) * (lo + hi));
        if let Some((p, _, _, speed)) = slide(s)
            && speed >= T::zero()
        {
            return Some((p, Branch::Sliding { s }));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(w: [[f64; 3]; 3], d: usize, r: [f64; 3], mu: f64) -> ([f64; 3], Branch<f64>) {
        let (p, branch) = coulomb(&w, d, r, mu).expect("an answer");
        let u: Vec<f64> = (0..d)
            .map(|a| r[a] + (0..d).map(|b| w[a][b] * p[b]).sum::<f64>())
            .collect();
        let pt = (p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!(u[0] >= -1e-12 && p[0] >= 0.0, "{u:?} {p:?}");
        assert!((u[0] * p[0]).abs() < 1e-12, "complementarity {u:?} {p:?}");
        assert!(pt <= mu * p[0] * (1.0 + 1e-9) + 1e-15, "cone");
        if let Branch::Sliding { .. } = branch {
            // Maximal dissipation: P_t opposes the slip and is on the cone.
            let ut = [u[1], if d == 3 { u[2] } else { 0.0 }];
            let dot = ut[0] * p[1] + ut[1] * p[2];
            let slip = (ut[0] * ut[0] + ut[1] * ut[1]).sqrt();
            assert!(
                (dot + slip * pt).abs() < 1e-9 * (1.0 + slip * pt),
                "{ut:?} {p:?}"
            );
            assert!((pt - mu * p[0]).abs() < 1e-12);
        }
        (p, branch)
    }

    const W: [[f64; 3]; 3] = [[2.0, 0.3, -0.2], [0.3, 1.5, 0.1], [-0.2, 0.1, 1.2]];

    #[test]
    fn apart_when_the_free_motion_leaves() {
        let (p, b) = check(W, 3, [0.5, 1.0, -2.0], 0.4);
        assert_eq!((p, b), ([0.0; 3], Branch::Apart));
    }

    #[test]
    fn sticks_inside_the_cone() {
        let (_, b) = check(W, 3, [-1.0, 0.05, 0.02], 0.8);
        assert_eq!(b, Branch::Sticking);
    }

    #[test]
    fn slides_on_the_cone_against_the_slip() {
        let (_, b) = check(W, 3, [-1.0, 2.0, -1.5], 0.3);
        assert!(matches!(b, Branch::Sliding { .. }));
        let (_, b) = check(W, 2, [-1.0, 2.0, 0.0], 0.3);
        assert!(matches!(b, Branch::Sliding { .. }));
        let (_, b) = check(W, 2, [-1.0, -2.0, 0.0], 0.3);
        assert!(matches!(b, Branch::Sliding { .. }));
    }

    #[test]
    fn normal_only_without_friction() {
        let (p, b) = check(W, 1, [-1.0, 0.0, 0.0], 0.0);
        assert_eq!(b, Branch::Sticking);
        assert!((p[0] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn dry_friction_holds_within_its_bound_and_slides_on_it() {
        // One row: held while |r/w| ≤ bound, else the bound against r.
        let w: [[f64; 3]; 3] = [[2.0, 0.0, 0.0], [0.0; 3], [0.0; 3]];
        let (p, b) = bounded(&w, 1, [0.6, 0.0, 0.0], 0.5).unwrap();
        assert_eq!((p[0], b), (-0.3, Branch::Sticking));
        let (p, b) = bounded(&w, 1, [-1.4, 0.0, 0.0], 0.5).unwrap();
        assert_eq!((p[0], b), (0.5, Branch::Sliding { s: [-1.0, 0.0] }));
        // Two rows: on the disc's edge, the slip along the direction s
        // opposite to the impulse.
        let w2: [[f64; 3]; 3] = [[1.5, 0.1, 0.0], [0.1, 1.2, 0.0], [0.0; 3]];
        let r: [f64; 3] = [3.0, -2.0, 0.0];
        let (p, b) = bounded(&w2, 2, r, 0.4).unwrap();
        let Branch::Sliding { s } = b else {
            panic!("{b:?}")
        };
        assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 0.4).abs() < 1e-12);
        let u = [
            r[0] + w2[0][0] * p[0] + w2[0][1] * p[1],
            r[1] + w2[1][0] * p[0] + w2[1][1] * p[1],
        ];
        let speed = (u[0] * u[0] + u[1] * u[1]).sqrt();
        assert!((u[0] - speed * s[0]).abs() < 1e-9 && (u[1] - speed * s[1]).abs() < 1e-9);
    }

    #[test]
    fn random_problems_satisfy_coulomb() {
        // A fixed pseudo-random sequence of SPD blocks and velocities.
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..500 {
            let a = nalgebra::Matrix3::from_fn(|_, _| next());
            let w = a * a.transpose() + nalgebra::Matrix3::identity() * 0.5;
            let w = [0, 1, 2].map(|i| [0, 1, 2].map(|j| w[(i, j)]));
            let r = [next(), 2.0 * next(), 2.0 * next()];
            let mu = 0.05 + next().abs();
            check(w, 3, r, mu);
            check(w, 2, r, mu);
        }
    }
}
