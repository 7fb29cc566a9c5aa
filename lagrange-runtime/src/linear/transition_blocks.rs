//! A symmetric (2N + P)-square matrix over (q, v, u) in N × N, N × P and
//! P × P blocks on the stack (three `chain::Band`s of rows), and its
//! congruence by a stage's tangent W = ∂(q_s, v_s, u)/∂(q, v, u), whose
//! rows are `chain::Rows` and whose input rows are [0 0 I]: the step
//! curvature's Σ_s W_sᵀ G_s W_s without a dynamically sized product (at
//! 5 × 5 those cost more in dispatch than in arithmetic).

use super::chain::{Band, Rows};
use nalgebra::{DMatrix, SMatrix};

impl<const R: usize, const N: usize, const P: usize> Band<R, N, P> {
    /// This band times W (columns (q, v, u) of the step's unknowns), given
    /// its blocks on the stage's q rows (`rq`), v rows (`rv`) and input rows
    /// (`ru`, multiplying W's identity).
    fn times(
        rq: &SMatrix<f64, R, N>,
        rv: &SMatrix<f64, R, N>,
        ru: &SMatrix<f64, R, P>,
        (tq, tv): (&Rows<N, P>, &Rows<N, P>),
    ) -> Self {
        Self {
            q: rq * tq.q + rv * tv.q,
            v: rq * tq.v + rv * tv.v,
            u: rq * tq.u + rv * tv.u + ru,
        }
    }
}

/// The three bands of rows q, v and u.
#[derive(Clone, Copy)]
pub(super) struct Square<const N: usize, const P: usize> {
    pub(super) q: Band<N, N, P>,
    pub(super) v: Band<N, N, P>,
    pub(super) u: Band<P, N, P>,
}

impl<const N: usize, const P: usize> Square<N, P> {
    pub(super) fn zero() -> Self {
        Self {
            q: Band::zero(),
            v: Band::zero(),
            u: Band::zero(),
        }
    }

    /// Column j of the whole (j < N on q, then v, then u) from its three
    /// pieces, on rows q, v and u.
    pub(super) fn set_column(
        &mut self,
        j: usize,
        (on_q, on_v, on_u): (
            &SMatrix<f64, N, 1>,
            &SMatrix<f64, N, 1>,
            &SMatrix<f64, P, 1>,
        ),
    ) {
        macro_rules! put {
            ($field:ident, $col:expr) => {{
                self.q.$field.set_column($col, on_q);
                self.v.$field.set_column($col, on_v);
                self.u.$field.set_column($col, on_u);
            }};
        }
        match j {
            j if j < N => put!(q, j),
            j if j < 2 * N => put!(v, j - N),
            j => put!(u, j - 2 * N),
        }
    }

    /// The input columns from the input rows (the matrix being symmetric),
    /// with no input–input block: where q̈ is affine in u.
    pub(super) fn mirror_inputs(&mut self) {
        self.q.u = self.u.q.transpose();
        self.v.u = self.u.v.transpose();
        self.u.u = SMatrix::zeros();
    }

    /// self += Wᵀ g W, W the stage's tangent (rows tq of q_s, tv of v_s).
    pub(super) fn add_congruence(&mut self, g: &Self, (tq, tv): (&Rows<N, P>, &Rows<N, P>)) {
        let t = (tq, tv);
        let gw_q = Band::times(&g.q.q, &g.q.v, &g.q.u, t);
        let gw_v = Band::times(&g.v.q, &g.v.v, &g.v.u, t);
        let gw_u = Band::times(&g.u.q, &g.u.v, &g.u.u, t);
        // Wᵀ's row band c' is [T_q.c'ᵀ  T_v.c'ᵀ  (I where c' = u)].
        macro_rules! add {
            ($band:expr, $tq:expr, $tv:expr) => {{
                $band.q += $tq.tr_mul(&gw_q.q) + $tv.tr_mul(&gw_v.q);
                $band.v += $tq.tr_mul(&gw_q.v) + $tv.tr_mul(&gw_v.v);
                $band.u += $tq.tr_mul(&gw_q.u) + $tv.tr_mul(&gw_v.u);
            }};
        }
        add!(self.q, tq.q, tv.q);
        add!(self.v, tq.v, tv.v);
        add!(self.u, tq.u, tv.u);
        self.u.q += gw_u.q;
        self.u.v += gw_u.v;
        self.u.u += gw_u.u;
    }

    /// The matrix, symmetrised: (M + Mᵀ)/2.
    pub(super) fn symmetric(&self) -> DMatrix<f64> {
        let width = 2 * N + P;
        let mut m = DMatrix::zeros(width, width);
        for (r, band) in [(0, &self.q), (N, &self.v)] {
            m.fixed_view_mut::<N, N>(r, 0).copy_from(&band.q);
            m.fixed_view_mut::<N, N>(r, N).copy_from(&band.v);
            m.fixed_view_mut::<N, P>(r, 2 * N).copy_from(&band.u);
        }
        m.fixed_view_mut::<P, N>(2 * N, 0).copy_from(&self.u.q);
        m.fixed_view_mut::<P, N>(2 * N, N).copy_from(&self.u.v);
        m.fixed_view_mut::<P, P>(2 * N, 2 * N).copy_from(&self.u.u);
        for j in 0..width {
            for i in 0..j {
                let mean = 0.5 * (m[(i, j)] + m[(j, i)]);
                (m[(i, j)], m[(j, i)]) = (mean, mean);
            }
        }
        m
    }
}
