//! Dense output: a polynomial in θ = (t − t₀)/h over one accepted step.

use super::Pair;
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation};
use nalgebra::SVector;

/// The continuous extension of one accepted step [t₀, t₁], in Hairer's nested form
///
/// ```text
/// y(t₀ + θh) = r₁ + θ (r₂ + (1−θ) (r₃ + θ (r₄ + (1−θ) (r₅ + θ (r₆ + (1−θ) (r₇ + θ r₈))))))
/// ```
///
/// for both q and v. DOP853 fills r₅..r₈ (its 7th-order continuous extension);
/// DOPRI5 fills r₅ with Shampine's coefficients (a 4th-order interpolant, local
/// error O(h⁵)) and leaves r₆..r₈ = 0; the methods without an extension of their
/// own stop at r₄, the cubic Hermite interpolant through the values and
/// derivatives at both ends (local error O(h⁴), so 3rd order uniformly). Only the
/// coefficients in use are evaluated.
///
/// With the `serde` feature a segment saves its coefficients and where the
/// quaternions sit in q (normalised where it is read), so a saved run's
/// dense output reads back bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(into = "saved::Saved<T, N, Q>", try_from = "saved::Saved<T, N, Q>")
)]
pub struct DenseSegment<T: Real, const N: usize, const Q: usize = N> {
    t0: T,
    t1: T,
    h: T,
    r: [Pair<T, N, Q>; 8],
    /// How many of the r's are in use (4, 5 or 8).
    used: usize,
    /// The quaternions in q, normalised where the segment is read.
    orientations: &'static [Orientation],
}

impl<T: Real, const N: usize, const Q: usize> DenseSegment<T, N, Q> {
    /// A segment from its first K ≤ 8 coefficients. `h` is the step size the
    /// coefficients were computed with; `t1` the recorded end time (t₀ + h up to
    /// rounding).
    pub(crate) fn new<const K: usize>(
        t0: T,
        t1: T,
        h: T,
        coefficients: [Pair<T, N, Q>; K],
    ) -> Self {
        const { assert!(K >= 1 && K <= 8) };
        let mut r = [Pair::zeros(); 8];
        r[..K].copy_from_slice(&coefficients);
        Self {
            t0,
            t1,
            h,
            r,
            used: K,
            orientations: &[],
        }
    }

    /// The cubic Hermite interpolant from the states `y0`, `y1` and their
    /// derivatives `f0`, `f1` (derivative = (v, a)).
    pub(crate) fn hermite(
        t0: T,
        t1: T,
        y0: &Pair<T, N, Q>,
        f0: &Pair<T, N, Q>,
        y1: &Pair<T, N, Q>,
        f1: &Pair<T, N, Q>,
    ) -> Self {
        let h = t1 - t0;
        let (r1, r2, r3, r4) = Self::cubic_part(h, y0, f0, y1, f1);
        Self::new(t0, t1, h, [r1, r2, r3, r4])
    }

    /// r₁..r₄, shared by Hermite and DOPRI5: r₁ = y₀, r₂ = y₁ − y₀,
    /// r₃ = h f₀ − r₂, r₄ = r₂ − h f₁ − r₃.
    pub(crate) fn cubic_part(
        h: T,
        y0: &Pair<T, N, Q>,
        f0: &Pair<T, N, Q>,
        y1: &Pair<T, N, Q>,
        f1: &Pair<T, N, Q>,
    ) -> (Pair<T, N, Q>, Pair<T, N, Q>, Pair<T, N, Q>, Pair<T, N, Q>) {
        let r2 = y1.sub(y0);
        let r3 = f0.scale(h).sub(&r2);
        let r4 = r2.sub(&f1.scale(h)).sub(&r3);
        (*y0, r2, r3, r4)
    }

    /// The segment with the quaternions at `layout` normalised where it is
    /// read (an interpolant leaves the unit sphere by its own error).
    pub(crate) fn with_orientations(mut self, layout: &'static [Orientation]) -> Self {
        self.orientations = layout;
        self
    }

    /// Ends the segment at `t1` (inside the step): the polynomial is unchanged,
    /// only the recorded end moves, which is how a step is cut at an event.
    pub(crate) fn truncate(&mut self, t1: T) {
        debug_assert!(self.t0 <= t1 && t1 <= self.t1);
        self.t1 = t1;
    }

    /// Start of the step.
    pub fn start(&self) -> T {
        self.t0
    }

    /// End of the step.
    pub fn end(&self) -> T {
        self.t1
    }

    /// Whether `t` lies in [start, end].
    pub fn contains(&self, t: T) -> bool {
        self.t0 <= t && t <= self.t1
    }

    /// The interpolated (q, v) at `t` (meaningful for t in [start, end]).
    pub fn eval(&self, t: T) -> (SVector<T, Q>, SVector<T, N>) {
        let th = (t - self.t0) / self.h;
        let th1 = T::one() - th;
        let mut q = self.horner(th, th1, |p| &p.q);
        orientation::normalise(self.orientations, q.as_mut_slice());
        (q, self.horner(th, th1, |p| &p.v))
    }

    /// One part (q or v) of the nested polynomial, by Horner's rule from the
    /// innermost coefficient outwards; the factor in front of r_k (k ≥ 2,
    /// 1-based) is θ for even k and 1 − θ for odd k.
    fn horner<const M: usize>(
        &self,
        th: T,
        th1: T,
        part: impl Fn(&Pair<T, N, Q>) -> &SVector<T, M>,
    ) -> SVector<T, M> {
        let r = &self.r[..self.used];
        SVector::<T, M>::from_fn(|i, _| {
            let mut acc = T::zero();
            for (k, rk) in r.iter().enumerate().skip(1).rev() {
                let factor = if k % 2 == 1 { th } else { th1 };
                acc = factor * (part(rk)[i] + acc);
            }
            part(&r[0])[i] + acc
        })
    }
}

impl<T: Real, const N: usize> DenseSegment<T, N> {
    /// The cubic Hermite interpolant through (q0, v0) and (q1, v1) with the
    /// accelerations a0, a1 at the ends: the dense output of any one-step method
    /// that has no continuous extension of its own.
    #[allow(clippy::too_many_arguments)]
    pub fn cubic_hermite(
        t0: T,
        t1: T,
        (q0, v0, a0): (&SVector<T, N>, &SVector<T, N>, &SVector<T, N>),
        (q1, v1, a1): (&SVector<T, N>, &SVector<T, N>, &SVector<T, N>),
    ) -> Self {
        Self::hermite(
            t0,
            t1,
            &Pair::new(*q0, *v0),
            &Pair::new(*v0, *a0),
            &Pair::new(*q1, *v1),
            &Pair::new(*v1, *a1),
        )
    }
}

#[cfg(feature = "serde")]
mod saved;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_reproduces_cubics() {
        // q(t) = t³ − 2t, v = q̇ = 3t² − 2, a = 6t: q is cubic, so exact; v is
        // quadratic, also exact.
        let q = |t: f64| t * t * t - 2.0 * t;
        let v = |t: f64| 3.0 * t * t - 2.0;
        let a = |t: f64| 6.0 * t;
        let p = |x: f64| SVector::<f64, 1>::new(x);
        let t0 = 0.5;
        let t1 = 1.25;
        let y0 = Pair::new(p(q(t0)), p(v(t0)));
        let y1 = Pair::new(p(q(t1)), p(v(t1)));
        let f0 = Pair::new(p(v(t0)), p(a(t0)));
        let f1 = Pair::new(p(v(t1)), p(a(t1)));
        let s = DenseSegment::hermite(t0, t1, &y0, &f0, &y1, &f1);
        for i in 0..=10 {
            let t = t0 + (t1 - t0) * f64::from(i) / 10.0;
            let (qi, vi) = s.eval(t);
            assert!((qi[0] - q(t)).abs() < 1e-14, "{t}");
            assert!((vi[0] - v(t)).abs() < 1e-14, "{t}");
        }
        assert!(s.contains(t0) && s.contains(t1) && !s.contains(2.0));
        assert_eq!((s.start(), s.end()), (t0, t1));
    }
}
