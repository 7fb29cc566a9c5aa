//! Configuration spaces with free rotations: where unit quaternions sit in q,
//! and the maps between q, its rate and the tangent space.
//!
//! A free orientation (a free body's, or a spherical joint's) is stored as a
//! unit quaternion `(w, x, y, z)`, scalar first, that turns body axes into the
//! parent's (the world's for a free body): p_parent = R(q) p_body. Its
//! velocity is the angular velocity ω in **body axes**, three numbers, so the
//! configuration has four numbers where the velocity has three and
//! nq = nv + (number of orientations). Every other coordinate is an ordinary
//! one, its velocity its rate.
//!
//! Why a quaternion: it is the smallest representation without a singular
//! set (any three numbers have one, by the hairy ball theorem for SO(3)'s
//! charts), its kinematics q̇ = ½ q ⊗ (0, ω) is polynomial, and its only
//! constraint, |q| = 1, is a quadratic invariant that every Runge–Kutta
//! method applied to q̇ = ½ q ⊗ (0, ω) keeps to its own order, so that
//! normalising after each step (a projection onto the invariant) keeps the
//! method's order (Hairer, Lubich and Wanner, *Geometric Numerical
//! Integration*, §IV.4). Pinocchio stores `(x, y, z, w)`; MuJoCo and Drake
//! store `(w, x, y, z)` as here.
//!
//! The layout is a list of [`Orientation`]s in increasing order; the ordinary
//! coordinates fill the other slots, in order, in q and v alike.

use crate::numeric::Real;
use crate::numeric::func::{cos, sin, sqrt};

/// Where one unit quaternion sits in q (four slots from `q`, order w, x, y,
/// z) and its body-axis angular velocity in v (three slots from `v`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Orientation {
    /// The index of the quaternion's w in q.
    pub q: usize,
    /// The index of ωx in v.
    pub v: usize,
}

/// How far below this a quaternion's norm may be from 1 in an initial state
/// and still be normalised silently; beyond it the state is refused.
pub const UNIT_TOLERANCE: f64 = 1e-6;

/// The slots of q and v in step: `Ordinary(i, j)` for a coordinate q_i with
/// rate v_j, `Rotation(o)` for an orientation.
pub(crate) enum Slot {
    Ordinary(usize, usize),
    Rotation(Orientation),
}

/// Walks the layout: every slot of q and v exactly once, in order.
pub(crate) fn slots(layout: &[Orientation], nq: usize) -> impl Iterator<Item = Slot> + '_ {
    let mut i = 0;
    let mut j = 0;
    let mut k = 0;
    std::iter::from_fn(move || {
        if i >= nq {
            return None;
        }
        if let Some(&o) = layout.get(k).filter(|o| o.q == i) {
            (i, j, k) = (i + 4, j + 3, k + 1);
            return Some(Slot::Rotation(o));
        }
        (i, j) = (i + 1, j + 1);
        Some(Slot::Ordinary(i - 1, j - 1))
    })
}

/// Whether `layout` fits a configuration of `nq` numbers with `nv`
/// velocities: orientations in order, not overlapping, each one's velocity
/// slot where the ordinary coordinates before it put it. A `const fn`: a
/// system's `ORIENTATIONS` is checked at compile time.
pub const fn fits(layout: &[Orientation], nq: usize, nv: usize) -> bool {
    if nq != nv + layout.len() {
        return false;
    }
    let mut k = 0;
    let mut before = 0;
    while k < layout.len() {
        let o = layout[k];
        if o.q < before || o.q + 4 > nq || o.q < k || o.v != o.q - k {
            return false;
        }
        before = o.q + 4;
        k += 1;
    }
    true
}

/// q̇ from (q, v): the rate of every ordinary coordinate is its velocity, and
/// a quaternion's is ½ q ⊗ (0, ω).
pub fn rate<T: Real>(layout: &[Orientation], q: &[T], v: &[T], out: &mut [T]) {
    for s in slots(layout, q.len()) {
        match s {
            Slot::Ordinary(i, j) => out[i] = v[j],
            Slot::Rotation(o) => {
                let d = quaternion_rate(quaternion(q, o.q), [v[o.v], v[o.v + 1], v[o.v + 2]]);
                out[o.q..o.q + 4].copy_from_slice(&d);
            }
        }
    }
}

/// q ⊕ δ: an ordinary coordinate moves by its δ, an orientation turns by the
/// rotation vector δ in body axes (q ⊗ exp(δ)): Pinocchio's `integrate`.
pub fn integrate<T: Real>(layout: &[Orientation], q: &[T], delta: &[T], out: &mut [T]) {
    for s in slots(layout, q.len()) {
        match s {
            Slot::Ordinary(i, j) => out[i] = q[i] + delta[j],
            Slot::Rotation(o) => {
                let turn = exp([delta[o.v], delta[o.v + 1], delta[o.v + 2]]);
                out[o.q..o.q + 4].copy_from_slice(&multiply(quaternion(q, o.q), turn));
            }
        }
    }
}

/// q ⊕ δ as a vector: [`integrate`] of a configuration of Q numbers by a
/// tangent vector of N.
pub(crate) fn plus<T: Real, const N: usize, const Q: usize>(
    layout: &[Orientation],
    q: &nalgebra::SVector<T, Q>,
    delta: &nalgebra::SVector<T, N>,
) -> nalgebra::SVector<T, Q> {
    let mut out = nalgebra::SVector::<T, Q>::zeros();
    integrate(layout, q.as_slice(), delta.as_slice(), out.as_mut_slice());
    out
}

/// δ with q0 ⊕ δ = q1: the tangent vector from q0 to q1, an orientation's the
/// rotation vector of q0⁻¹ ⊗ q1 (the shorter way round): Pinocchio's
/// `difference`.
pub fn difference<T: Real>(layout: &[Orientation], q0: &[T], q1: &[T], out: &mut [T]) {
    for s in slots(layout, q0.len()) {
        match s {
            Slot::Ordinary(i, j) => out[j] = q1[i] - q0[i],
            Slot::Rotation(o) => {
                let [w, x, y, z] = quaternion(q0, o.q);
                let relative = multiply([w, -x, -y, -z], quaternion(q1, o.q));
                out[o.v..o.v + 3].copy_from_slice(&log(relative));
            }
        }
    }
}

/// The largest | |q_k| − 1 | over the orientations: zero without any.
pub fn unit_error<T: Real>(layout: &[Orientation], q: &[T]) -> T {
    layout.iter().fold(T::zero(), |worst, o| {
        let e = (norm(quaternion(q, o.q)) - T::one()).abs();
        if e > worst || e.partial_cmp(&e).is_none() {
            e
        } else {
            worst
        }
    })
}

/// The first orientation whose quaternion is not a rotation (not finite, or
/// its norm further than [`UNIT_TOLERANCE`] from 1), with that norm.
pub fn first_off_unit<T: Real>(layout: &[Orientation], q: &[T]) -> Option<(Orientation, f64)> {
    layout.iter().find_map(|&o| {
        let n = norm(quaternion(q, o.q)).to_f64();
        let unit = (n - 1.0).abs() <= UNIT_TOLERANCE;
        (!unit).then_some((o, n))
    })
}

/// Scales every quaternion to unit norm, in place.
pub fn normalise<T: Real>(layout: &[Orientation], q: &mut [T]) {
    for o in layout {
        let n = norm(quaternion(q, o.q));
        for x in &mut q[o.q..o.q + 4] {
            *x /= n;
        }
    }
}

/// The quaternion at slot `at` of q.
pub fn quaternion<T: Real>(q: &[T], at: usize) -> [T; 4] {
    [q[at], q[at + 1], q[at + 2], q[at + 3]]
}

/// The Euclidean norm of a quaternion.
pub fn norm<T: Real>([w, x, y, z]: [T; 4]) -> T {
    sqrt(w * w + x * x + y * y + z * z)
}

/// ½ q ⊗ (0, ω).
pub(crate) fn quaternion_rate<T: Real>([w, x, y, z]: [T; 4], [a, b, c]: [T; 3]) -> [T; 4] {
    let h = T::lit(0.5);
    [
        -h * (x * a + y * b + z * c),
        h * (w * a + y * c - z * b),
        h * (w * b + z * a - x * c),
        h * (w * c + x * b - y * a),
    ]
}

/// The Hamilton product p ⊗ q.
pub fn multiply<T: Real>([a, b, c, d]: [T; 4], [w, x, y, z]: [T; 4]) -> [T; 4] {
    [
        a * w - b * x - c * y - d * z,
        a * x + b * w + c * z - d * y,
        a * y - b * z + c * w + d * x,
        a * z + b * y - c * x + d * w,
    ]
}

/// The unit quaternion of the rotation vector θ: (cos |θ|/2, sin(|θ|/2) θ/|θ|),
/// with the series near zero so that it is exact to round-off there.
pub fn exp<T: Real>(theta: [T; 3]) -> [T; 4] {
    let angle = sqrt(theta.iter().fold(T::zero(), |s, &x| s + x * x));
    let half = angle * T::lit(0.5);
    // sin(a/2)/a: its series 1/2 − a²/48 + a⁴/3840 is exact to round-off below 1e-3.
    let k = if angle < T::lit(1e-3) {
        let a2 = angle * angle;
        T::lit(0.5) - a2 / T::lit(48.0) + a2 * a2 / T::lit(3840.0)
    } else {
        sin(half) / angle
    };
    [cos(half), theta[0] * k, theta[1] * k, theta[2] * k]
}

/// The right Jacobian of the exponential map, exp(θ + dθ) = exp(θ) ⊗
/// exp(J_r(θ) dθ) to first order: J_r = I − (1 − cos a)/a² \[θ\]× +
/// (a − sin a)/a³ \[θ\]×² with a = |θ| (series below a = 1e-3), so that
/// ∂(q ⊕ δ)/∂δ reads J_r(δ) in the tangent space at q ⊕ δ.
pub fn right_jacobian<T: Real>(theta: [T; 3]) -> [[T; 3]; 3] {
    let a2 = theta.iter().fold(T::zero(), |s, &x| s + x * x);
    let a = sqrt(a2);
    let (first, second) = if a < T::lit(1e-3) {
        (
            T::lit(0.5) - a2 / T::lit(24.0) + a2 * a2 / T::lit(720.0),
            T::lit(1.0 / 6.0) - a2 / T::lit(120.0) + a2 * a2 / T::lit(5040.0),
        )
    } else {
        ((T::one() - cos(a)) / a2, (a - sin(a)) / (a2 * a))
    };
    let [x, y, z] = theta;
    let hat = [[T::zero(), -z, y], [z, T::zero(), -x], [-y, x, T::zero()]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let hat2 = (0..3).fold(T::zero(), |s, k| s + hat[i][k] * hat[k][j]);
            let identity = if i == j { T::one() } else { T::zero() };
            identity - first * hat[i][j] + second * hat2
        })
    })
}

/// The rotation vector of a unit quaternion, taking the shorter way (w ≥ 0).
pub fn log<T: Real>([w, x, y, z]: [T; 4]) -> [T; 3] {
    let s = if w < T::zero() { -T::one() } else { T::one() };
    let w = w * s;
    let x = x * s;
    let y = y * s;
    let z = z * s;
    let sin_half = sqrt(x * x + y * y + z * z);
    let angle = T::lit(2.0) * sin_half.atan2(w);
    // angle / sin(angle/2) → 2 as the angle → 0.
    let k = if sin_half < T::lit(1e-8) {
        T::lit(2.0) / w
    } else {
        angle / sin_half
    };
    [x * k, y * k, z * k]
}

/// R(q) for a unit quaternion, row by row: p_parent = R p_body.
pub fn rotation_matrix<T: Real>([w, x, y, z]: [T; 4]) -> [[T; 3]; 3] {
    let two = T::lit(2.0);
    let one = T::one();
    [
        [
            one - two * (y * y + z * z),
            two * (x * y - w * z),
            two * (x * z + w * y),
        ],
        [
            two * (x * y + w * z),
            one - two * (x * x + z * z),
            two * (y * z - w * x),
        ],
        [
            two * (x * z - w * y),
            two * (y * z + w * x),
            one - two * (x * x + y * y),
        ],
    ]
}

/// The unit quaternion (w ≥ 0) of a rotation matrix (nalgebra's
/// `UnitQuaternion::from_rotation_matrix`, sign fixed so that w ≥ 0).
pub fn from_rotation_matrix<T: Real>(r: &nalgebra::Matrix3<T>) -> [T; 4] {
    let rotation = nalgebra::Rotation3::from_matrix_unchecked(*r);
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&rotation);
    let s = if q.w < T::zero() { -T::one() } else { T::one() };
    [q.w * s, q.i * s, q.j * s, q.k * s]
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAYOUT: [Orientation; 1] = [Orientation { q: 1, v: 1 }];

    fn unit(q: [f64; 4]) -> [f64; 4] {
        let n = norm(q);
        q.map(|x| x / n)
    }

    #[test]
    fn layout_checks() {
        assert!(fits(&LAYOUT, 6, 5));
        assert!(!fits(&LAYOUT, 5, 5));
        assert!(!fits(&[Orientation { q: 1, v: 0 }], 6, 5));
        assert!(!fits(&[Orientation { q: 3, v: 3 }], 6, 5));
        let two = [Orientation { q: 0, v: 0 }, Orientation { q: 4, v: 3 }];
        assert!(fits(&two, 8, 6));
    }

    #[test]
    fn right_jacobian_is_the_derivative_of_exp() {
        for theta in [[0.3f64, -1.2, 0.7], [2e-4, -1e-4, 3e-4]] {
            let jr = right_jacobian(theta);
            let at = exp(theta);
            let inverse = [at[0], -at[1], -at[2], -at[3]];
            for j in 0..3 {
                let h = 1e-6;
                let mut plus = theta;
                let mut minus = theta;
                plus[j] += h;
                minus[j] -= h;
                let (p, m) = (
                    log(multiply(inverse, exp(plus))),
                    log(multiply(inverse, exp(minus))),
                );
                for i in 0..3 {
                    let d = (p[i] - m[i]) / (2.0 * h);
                    assert!(
                        (d - jr[i][j]).abs() < 1e-9,
                        "{theta:?} {i} {j}: {d} vs {}",
                        jr[i][j]
                    );
                }
            }
        }
    }

    #[test]
    fn exp_and_log_invert_each_other() {
        for theta in [[0.3f64, -1.2, 0.7], [1e-9, 2e-9, -1e-9], [0.0, 0.0, 3.0]] {
            let back = log(exp(theta));
            for k in 0..3 {
                assert!((back[k] - theta[k]).abs() < 1e-14, "{theta:?} -> {back:?}");
            }
        }
    }

    #[test]
    fn integrate_then_difference_is_the_tangent_step() {
        let q = [0.5, 0.1, -0.3, 0.8, 0.2, 2.0];
        let mut q = q;
        let u = unit(quaternion(&q, 1));
        q[1..5].copy_from_slice(&u);
        let delta = [0.25, 0.4, -0.2, 0.9, -1.5];
        let mut moved = [0.0; 6];
        integrate(&LAYOUT, &q, &delta, &mut moved);
        let mut back = [0.0; 5];
        difference(&LAYOUT, &q, &moved, &mut back);
        for k in 0..5 {
            assert!((back[k] - delta[k]).abs() < 1e-14, "{back:?}");
        }
        assert!(unit_error(&LAYOUT, &moved) < 1e-15);
    }

    #[test]
    fn rate_is_the_derivative_of_turning_at_omega() {
        // q(t) = q0 ⊗ exp(ω t): its derivative at 0 by central differences.
        let q0 = unit([0.3, -0.5, 0.2, 0.7]);
        let omega = [0.4, -1.1, 2.3];
        let at = |t: f64| multiply(q0, exp(omega.map(|w| w * t)));
        let h = 1e-6;
        let a = at(h);
        let b = at(-h);
        let d = quaternion_rate(q0, omega);
        for k in 0..4 {
            assert!(((a[k] - b[k]) / (2.0 * h) - d[k]).abs() < 1e-9);
        }
    }

    #[test]
    fn rotation_matrix_turns_body_axes_into_the_parent_s() {
        // A quarter turn about z takes the body's x axis to the world's y.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let r = rotation_matrix([h, 0.0, 0.0, h]);
        assert!((r[1][0] - 1.0).abs() < 1e-15 && r[0][0].abs() < 1e-15);
        let q = unit([0.3, -0.5, 0.2, 0.7]);
        let r = rotation_matrix(q);
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|k| r[k][i] * r[k][j]).sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((dot - expected).abs() < 1e-15);
            }
        }
    }
    #[test]
    fn from_rotation_matrix_inverts_rotation_matrix() {
        for q in [
            [0.3, -0.5, 0.2, 0.7],
            [0.0, 1.0, 0.0, 0.0],
            [0.01, 0.2, -0.9, 0.3],
            [1.0, 0.0, 0.0, 0.0],
        ] {
            let q = unit(q);
            let r = rotation_matrix(q);
            let back = from_rotation_matrix(&nalgebra::Matrix3::from_fn(|i, j| r[i][j]));
            let s = if q[0] < 0.0 { -1.0 } else { 1.0 };
            for k in 0..4 {
                assert!((back[k] - s * q[k]).abs() < 1e-15, "{q:?} -> {back:?}");
            }
        }
    }
}
