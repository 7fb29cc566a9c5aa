//! Euler-angle charts of SO(3) and the maps between them: what the atlas
//! ([`crate::atlas`]) needs to carry an orientation from the user's chart to a
//! second one and back, exactly.
//!
//! A chart is a sequence of body axes (a, b, c), b ≠ a and b ≠ c (z-x-z,
//! z-y-x, ...), optionally after a constant offset C: R = C · R_a(α) R_b(β)
//! R_c(γ). The body angular velocity ω = E(α, β, γ) (α̇, β̇, γ̇) does not see C.
//!
//! Its singular set is where the body's c axis, seen through Cᵀ, lies along
//! e_a: then α and γ turn about one line and E drops rank. The conditioning
//! s = |(Cᵀ R e_c)⊥e_a| is |sin β| for a proper sequence (a = c) and |cos β|
//! for a Tait–Bryan one. The atlas's second chart takes C = R_b(π/2), which
//! moves e_a to an axis perpendicular to it, so the two singular sets are
//! disjoint: with x = R e_c·e_a and y = R e_c·C e_a, x² + y² ≤ 1 gives
//! s₁² + s₂² ≥ 1, and wherever one chart is poor the other is good.

use super::Real;
use super::func::{abs, atan2, cos, sin, sqrt};
use nalgebra::{Matrix3, Vector3};

/// One Euler-angle chart: the axes (0 = x, 1 = y, 2 = z) and whether the
/// offset C = R_b(π/2) comes first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EulerChart {
    /// The three rotation axes in order (0 = x, 1 = y, 2 = z).
    pub axes: [usize; 3],
    /// Whether the constant offset C = R_b(π/2) precedes the three
    /// rotations (the second chart of an atlas).
    pub offset: bool,
}

impl EulerChart {
    /// The user's chart of `axes`, or `None` if they are not an Euler
    /// sequence (the middle axis must differ from both ends).
    pub fn new(axes: [usize; 3]) -> Option<Self> {
        let [a, b, c] = axes;
        (a < 3 && b < 3 && c < 3 && a != b && b != c).then_some(Self {
            axes,
            offset: false,
        })
    }

    /// The same sequence after the offset: the chart whose singular set is
    /// disjoint from this one's.
    pub fn second(self) -> Self {
        Self {
            offset: !self.offset,
            ..self
        }
    }

    /// The offset C: R_b(π/2) (its entries are exactly 0 and ±1), or I.
    pub fn offset_matrix<T: Real>(&self) -> Matrix3<T> {
        if self.offset {
            elementary_cs(self.axes[1], T::zero(), T::one())
        } else {
            Matrix3::identity()
        }
    }

    /// R = C · R_a(α) R_b(β) R_c(γ).
    pub fn matrix<T: Real>(&self, angles: [T; 3]) -> Matrix3<T> {
        let [a, b, c] = self.axes;
        self.offset_matrix::<T>()
            * elementary(a, angles[0])
            * elementary(b, angles[1])
            * elementary(c, angles[2])
    }

    /// E with ω (body axes) = E · (α̇, β̇, γ̇): its columns are the three axes,
    /// each seen in the body.
    pub fn rates<T: Real>(&self, angles: [T; 3]) -> Matrix3<T> {
        let [a, b, c] = self.axes;
        let rc_t = elementary(c, angles[2]).transpose();
        let u1 = rc_t * elementary(b, angles[1]).transpose() * unit(a);
        let u2 = rc_t * unit(b);
        Matrix3::from_columns(&[u1, u2, unit(c)])
    }

    /// Ė · (α̇, β̇, γ̇): ω̇ = E q̈ + this.
    pub fn rate_bias<T: Real>(&self, angles: [T; 3], rates: [T; 3]) -> Vector3<T> {
        let [a, b, c] = self.axes;
        let [da, db, dc] = rates;
        let rc_t = elementary(c, angles[2]).transpose();
        let p = elementary(b, angles[1]).transpose() * unit(a);
        let u1 = rc_t * p;
        let u2 = rc_t * unit(b);
        let ec = unit::<T>(c);
        let du1 = rc_t * (unit::<T>(b).cross(&p) * -db) - ec.cross(&u1) * dc;
        let du2 = -ec.cross(&u2) * dc;
        du1 * da + du2 * db
    }

    /// How far R is from this chart's singular set: |(Cᵀ R e_c)⊥e_a|, in
    /// [0, 1]; E's smallest singular value shrinks with it.
    pub fn conditioning<T: Real>(&self, r: &Matrix3<T>) -> T {
        let [a, _, c] = self.axes;
        let v = self.offset_matrix::<T>().transpose() * r.column(c);
        let (i, j) = others(a);
        sqrt(v[i] * v[i] + v[j] * v[j])
    }

    /// [`conditioning`](Self::conditioning) of this chart's own R(angles),
    /// from the middle angle alone: |sin β| for a proper sequence, |cos β|
    /// for Tait–Bryan.
    pub fn own_conditioning<T: Real>(&self, angles: [T; 3]) -> T {
        let [a, _, c] = self.axes;
        abs(if a == c {
            sin(angles[1])
        } else {
            cos(angles[1])
        })
    }

    /// The angles of R in this chart: of the two solutions (and their 2π
    /// shifts), the one nearest `near`, or the principal one (β in [0, π] for
    /// a proper sequence, [−π/2, π/2] for Tait–Bryan) without it. On the
    /// singular set α is taken from `near` (or 0) and γ carries the rest.
    pub fn angles<T: Real>(&self, r: &Matrix3<T>, near: Option<[T; 3]>) -> [T; 3] {
        let [a, b, c] = self.axes;
        let rp = self.offset_matrix::<T>().transpose() * r;
        let v: Vector3<T> = rp.column(c).into();
        let (i, j) = others(a);
        let across = sqrt(v[i] * v[i] + v[j] * v[j]);
        let principal = if a == c {
            atan2(across, v[a])
        } else {
            // e_a · (e_b × e_c) = ±1: R_b(β) e_c = cos β e_c + sin β e_b × e_c.
            let sigma = unit::<T>(a).dot(&unit::<T>(b).cross(&unit(c)));
            atan2(sigma * v[a], across)
        };
        let other = if a == c {
            -principal
        } else {
            T::lit(std::f64::consts::PI) - principal
        };
        let solve = |beta: T| {
            let u = elementary(b, beta) * unit::<T>(c);
            let alpha = if across < T::lit(1e-12) {
                near.map_or(T::zero(), |n| n[0])
            } else {
                // The turn about e_a that takes u's part across e_a to v's.
                let ua = Vector3::new(u[i], u[j], T::zero());
                let va = Vector3::new(v[i], v[j], T::zero());
                atan2(ua.cross(&va)[2], ua.dot(&va))
            };
            let rest = elementary(b, beta).transpose() * elementary(a, alpha).transpose() * rp;
            let (k, l) = others(c);
            [alpha, beta, atan2(rest[(l, k)], rest[(k, k)])]
        };
        let candidates = [solve(principal), solve(other)];
        match near {
            None => candidates[0],
            Some(n) => {
                let shifted = candidates.map(|x| [0, 1, 2].map(|k| wrap_near(x[k], n[k])));
                let distance = |x: &[T; 3]| (0..3).fold(T::zero(), |s, k| s + abs(x[k] - n[k]));
                if distance(&shifted[1]) < distance(&shifted[0]) {
                    shifted[1]
                } else {
                    shifted[0]
                }
            }
        }
    }
}

/// x shifted by a multiple of 2π to lie within π of `near`.
fn wrap_near<T: Real>(x: T, near: T) -> T {
    let two_pi = T::lit(std::f64::consts::TAU);
    x - two_pi * nalgebra::ComplexField::round((x - near) / two_pi)
}

/// The two axes after `a` in cyclic order: (a + 1, a + 2) mod 3.
fn others(a: usize) -> (usize, usize) {
    ((a + 1) % 3, (a + 2) % 3)
}

fn unit<T: Real>(axis: usize) -> Vector3<T> {
    let mut e = Vector3::zeros();
    e[axis] = T::one();
    e
}

/// rot_axis(angle), right-handed.
pub fn elementary<T: Real>(axis: usize, angle: T) -> Matrix3<T> {
    elementary_cs(axis, cos(angle), sin(angle))
}

fn elementary_cs<T: Real>(axis: usize, c: T, s: T) -> Matrix3<T> {
    let (i, j) = others(axis);
    let mut m = Matrix3::identity();
    m[(i, i)] = c;
    m[(j, j)] = c;
    m[(i, j)] = -s;
    m[(j, i)] = s;
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    const SEQUENCES: [[usize; 3]; 12] = [
        [2, 0, 2],
        [2, 1, 2],
        [0, 1, 0],
        [0, 2, 0],
        [1, 0, 1],
        [1, 2, 1],
        [2, 1, 0],
        [2, 0, 1],
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
    ];
    const ANGLES: [[f64; 3]; 3] = [[0.3, 1.1, -2.0], [-2.9, 0.4, 0.7], [1.7, 2.6, 3.0]];

    fn charts() -> impl Iterator<Item = EulerChart> {
        SEQUENCES.iter().flat_map(|&s| {
            [
                EulerChart::new(s).unwrap(),
                EulerChart::new(s).unwrap().second(),
            ]
        })
    }

    #[test]
    fn angles_invert_the_matrix_in_every_chart() {
        for chart in charts() {
            for x in ANGLES {
                let r = chart.matrix(x);
                for near in [None, Some(x)] {
                    let y = chart.angles(&r, near);
                    assert!(
                        (chart.matrix(y) - r).norm() < 1e-14,
                        "{chart:?} {x:?} {y:?}"
                    );
                }
                let back = chart.angles(&r, Some(x));
                assert!((0..3).all(|k| (back[k] - x[k]).abs() < 1e-13), "{chart:?}");
            }
        }
    }

    #[test]
    fn rates_and_their_bias_match_finite_differences() {
        let x = [0.3, 1.1, -2.0];
        let dx = [0.7, -1.3, 0.4];
        let h = 1e-6;
        for chart in charts() {
            let at = |t: f64| [0, 1, 2].map(|k| x[k] + dx[k] * t);
            // ω = vee(Rᵀ Ṙ) by central differences.
            let omega = |t: f64| {
                let rd = (chart.matrix(at(t + h)) - chart.matrix(at(t - h))) / (2.0 * h);
                let w = chart.matrix(at(t)).transpose() * rd;
                Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)])
            };
            let e = chart.rates(x) * Vector3::from(dx);
            assert!((omega(0.0) - e).norm() < 1e-8, "{chart:?}");
            let de = (chart.rates(at(h)) - chart.rates(at(-h))) / (2.0 * h) * Vector3::from(dx);
            assert!((chart.rate_bias(x, dx) - de).norm() < 1e-8, "{chart:?}");
        }
    }

    #[test]
    fn the_two_singular_sets_are_disjoint() {
        for chart in charts() {
            for x in ANGLES {
                let r = chart.matrix(x);
                let s1 = chart.conditioning(&r);
                let s2 = chart.second().conditioning(&r);
                assert!(s1 * s1 + s2 * s2 >= 1.0 - 1e-14);
            }
            // On the first chart's singular set the second is at its best.
            let mut x = [0.4, 0.0, -0.9];
            if chart.axes[0] != chart.axes[2] {
                x[1] = std::f64::consts::FRAC_PI_2;
            }
            let r = chart.matrix(x);
            assert!(chart.conditioning(&r) < 1e-15);
            assert!((chart.second().conditioning(&r) - 1.0).abs() < 1e-15);
        }
    }
}
