//! The chain rule through a step's stages in N × N blocks on the stack: a
//! stage's state derivative has the rows of q and the rows of v, each over
//! (dq, dv, du), and f = (v, q̈) has ∂f/∂x = [[0, I], [A_q, A_v]] and
//! ∂f/∂u = [[0], [A_u]], whose zero and identity blocks are never
//! multiplied.

use crate::mechanics::InputDerivatives;
use nalgebra::{DMatrix, SMatrix};

/// R rows of a derivative over (dq, dv, du).
#[derive(Clone, Copy)]
pub(super) struct Band<const R: usize, const N: usize, const P: usize> {
    pub(super) q: SMatrix<f64, R, N>,
    pub(super) v: SMatrix<f64, R, N>,
    pub(super) u: SMatrix<f64, R, P>,
}

/// N rows: a stage's q or v over (dq, dv, du).
pub(super) type Rows<const N: usize, const P: usize> = Band<N, N, P>;

impl<const R: usize, const N: usize, const P: usize> Band<R, N, P> {
    /// No dependence at all.
    pub(super) fn zero() -> Self {
        Self {
            q: SMatrix::zeros(),
            v: SMatrix::zeros(),
            u: SMatrix::zeros(),
        }
    }

    /// self + c · other.
    pub(super) fn plus(&self, c: f64, other: &Self) -> Self {
        Self {
            q: self.q + other.q * c,
            v: self.v + other.v * c,
            u: self.u + other.u * c,
        }
    }
}

impl<const N: usize, const P: usize> Rows<N, P> {
    /// The rows of dq (`position`) or of dv in dx itself.
    pub(super) fn identity(position: bool) -> Self {
        let (i, z) = (SMatrix::identity(), SMatrix::zeros());
        let (q, v) = if position { (i, z) } else { (z, i) };
        Self {
            q,
            v,
            u: SMatrix::zeros(),
        }
    }
}

/// d(q̈) = A_q dq_s + A_v dv_s + A_u du at a stage whose state has the
/// derivative (dq_s, dv_s).
pub(super) fn acceleration_rows<const N: usize, const P: usize>(
    d: &InputDerivatives<f64, N, P>,
    dq: &Rows<N, P>,
    dv: &Rows<N, P>,
) -> Rows<N, P> {
    Rows {
        q: d.dq * dq.q + d.dv * dv.q,
        v: d.dq * dq.v + d.dv * dv.v,
        u: d.dq * dq.u + d.dv * dv.u + d.du,
    }
}

/// (∂x⁺/∂x, ∂x⁺/∂u) from the rows of dq⁺ and dv⁺.
pub(super) fn assemble<const N: usize, const P: usize>(
    dq: &Rows<N, P>,
    dv: &Rows<N, P>,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let mut dx = DMatrix::zeros(2 * N, 2 * N);
    let mut du = DMatrix::zeros(2 * N, P);
    for (r, rows) in [(0, dq), (N, dv)] {
        dx.fixed_view_mut::<N, N>(r, 0).copy_from(&rows.q);
        dx.fixed_view_mut::<N, N>(r, N).copy_from(&rows.v);
        du.fixed_view_mut::<N, P>(r, 0).copy_from(&rows.u);
    }
    (dx, du)
}

/// RK4: stage i's state is x + c_i h k_{i−1}, so its derivative is
/// dx + c_i h dk_{i−1}, with dk = (dv_s, dq̈); dx⁺ = dx + h/6 Σ w_i dk_i.
pub(super) fn rk4<const N: usize, const P: usize>(
    stages: &[InputDerivatives<f64, N, P>; 4],
    nodes: [f64; 4],
    weights: [f64; 4],
    h: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (x_q, x_v) = (Rows::identity(true), Rows::identity(false));
    let (mut sum_q, mut sum_v) = (Rows::<N, P>::identity(true), Rows::identity(false));
    let mut previous: Option<(Rows<N, P>, Rows<N, P>)> = None;
    for ((d, c), w) in stages.iter().zip(nodes).zip(weights) {
        let (s_q, s_v) = match &previous {
            None => (x_q, x_v),
            Some((k_q, k_v)) => (x_q.plus(c * h, k_q), x_v.plus(c * h, k_v)),
        };
        let k = (s_v, acceleration_rows(d, &s_q, &s_v));
        sum_q = sum_q.plus(w * h / 6.0, &k.0);
        sum_v = sum_v.plus(w * h / 6.0, &k.1);
        previous = Some(k);
    }
    assemble(&sum_q, &sum_v)
}

/// Semi-implicit Euler: dv⁺ = dv + h dq̈, dq⁺ = dq + h dv⁺.
pub(super) fn semi_implicit<const N: usize, const P: usize>(
    d: &InputDerivatives<f64, N, P>,
    h: f64,
) -> (DMatrix<f64>, DMatrix<f64>) {
    // dq̈ = A_q dq + A_v dv + A_u du at the step's start: its rows are the
    // derivatives themselves, with nothing to multiply.
    let accel = Rows {
        q: d.dq,
        v: d.dv,
        u: d.du,
    };
    let dv = Rows::identity(false).plus(h, &accel);
    let dq = Rows::identity(true).plus(h, &dv);
    assemble(&dq, &dv)
}
