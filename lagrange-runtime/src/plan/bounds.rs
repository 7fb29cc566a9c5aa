//! Bounds on the state as a penalty: a cost term, not a constraint.

use super::cost::{Cost, CostModel};
use nalgebra::SVector;

/// ½ w Σᵢ (max(0, xᵢ − upperᵢ)² + max(0, lowerᵢ − xᵢ)²) on x = (q, v): box
/// bounds on the configuration and velocities **as a quadratic penalty**,
/// zero inside the box. DDP handles it as any cost term, so the bounds hold
/// only approximately: a bound is overshot by about the pull of the rest of
/// the cost divided by `weight` (raise the weight to tighten it, at the
/// price of a stiffer problem). It is neither a hard constraint nor an
/// augmented Lagrangian. Add it with
/// [`running_cost`](super::OptimalControl::running_cost) (every step) or
/// [`final_cost`](super::OptimalControl::final_cost) (the last state; with
/// equal bounds there it is a terminal equality as a penalty). The model's
/// Hessian is exact: w on the entries outside the box.
#[derive(Clone, Debug, PartialEq)]
pub struct StateBounds<const N: usize> {
    lower: (SVector<f64, N>, SVector<f64, N>),
    upper: (SVector<f64, N>, SVector<f64, N>),
    weight: f64,
}

impl<const N: usize> StateBounds<N> {
    /// Bounds on q and v (±∞ for none) with the penalty's weight w.
    pub fn new(
        lower: (SVector<f64, N>, SVector<f64, N>),
        upper: (SVector<f64, N>, SVector<f64, N>),
        weight: f64,
    ) -> Self {
        Self {
            lower,
            upper,
            weight,
        }
    }

    /// Each entry's excess beyond its box (signed: positive above, negative
    /// below, zero inside), q's entries then v's.
    fn excess(&self, q: &SVector<f64, N>, v: &SVector<f64, N>) -> Vec<f64> {
        let over = |x: f64, lo: f64, hi: f64| {
            if x > hi {
                x - hi
            } else if x < lo {
                x - lo
            } else {
                0.0
            }
        };
        let qs = (0..N).map(|i| over(q[i], self.lower.0[i], self.upper.0[i]));
        let vs = (0..N).map(|i| over(v[i], self.lower.1[i], self.upper.1[i]));
        qs.chain(vs).collect()
    }
}

impl<const N: usize, const P: usize> Cost<N, P> for StateBounds<N> {
    fn value(
        &self,
        _: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        _: Option<&SVector<f64, P>>,
    ) -> f64 {
        let e = self.excess(q, v);
        0.5 * self.weight * e.iter().map(|x| x * x).sum::<f64>()
    }

    fn model(
        &self,
        t: f64,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> CostModel {
        let mut m = CostModel::zero(2 * N, usize::from(u.is_some()) * P);
        m.value = Cost::<N, P>::value(self, t, q, v, u);
        for (i, e) in self.excess(q, v).into_iter().enumerate() {
            if e != 0.0 {
                m.lx[i] = self.weight * e;
                m.lxx[(i, i)] = self.weight;
            }
        }
        m
    }
}
