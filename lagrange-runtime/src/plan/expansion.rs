//! One step of the backward pass in matrices: Q's quadratic model from the
//! cost's, the step's Jacobians and the value function after the step, and
//! the value function before it from the step's feedback.
//!
//! The Jacobians come in two forms (`StepJacobian`). Any step gives F_x and
//! F_u dense. A semi-implicit Euler step in the plane gives the one stage's
//! q̈ derivatives instead, A = [A_q A_v] (N × 2N) and A_u (N × P), with
//!
//! ```text
//! F_x = P + B A,   F_u = B A_u,   B = [h² I; h I],   P = [[I, h I], [0, I]],
//! ```
//!
//! and every product by P or B is a sum of blocks. With V = V_xx,
//! C = Bᵀ V B (N × N) and G = Bᵀ V P (N × 2N), both sums of V's blocks,
//!
//! ```text
//! F_xᵀ V F_x = Pᵀ V P + Aᵀ E + Eᵀ A,   E = G + ½ C A,
//! F_uᵀ V F_x = A_uᵀ (G + C A),          F_uᵀ V F_u = A_uᵀ C A_u,
//! ```
//!
//! so that the products are C A (N × N × 2N), Aᵀ E (2N × N × 2N),
//! A_uᵀ (G + C A) (P × N × 2N), C A_u (N × N × P) and A_uᵀ (C A_u)
//! (P × N × P): 10 N³ multiply–adds a step for an arm of N joints driven at
//! each (3,430 for seven), where F_x and F_u formed would take 26 N³. Q_xx is held as l_xx + Pᵀ V P + 2 Aᵀ E, whose symmetric part
//! is Q_xx: the value function reads only that part.

use super::cost::CostModel;
use crate::mechanics::InputDerivatives;
use crate::numeric::products::{gemm, gemv};
use nalgebra::{DMatrix, DVector};

/// ∂F/∂x and ∂F/∂u of one step, each with its transpose (the products
/// compute A B only; the transposes are taken once a linearisation, not
/// once a backward pass).
pub(super) enum StepJacobian {
    /// Any step: F_x (2N × 2N) and F_u (2N × P).
    Dense {
        fx: DMatrix<f64>,
        fu: DMatrix<f64>,
        fx_t: DMatrix<f64>,
        fu_t: DMatrix<f64>,
    },
    /// Semi-implicit Euler in the plane (see the module notes).
    Euler {
        h: f64,
        a: DMatrix<f64>,
        au: DMatrix<f64>,
        a_t: DMatrix<f64>,
        au_t: DMatrix<f64>,
    },
}

impl StepJacobian {
    pub(super) fn dense(fx: DMatrix<f64>, fu: DMatrix<f64>) -> Self {
        let (fx_t, fu_t) = (fx.transpose(), fu.transpose());
        Self::Dense { fx, fu, fx_t, fu_t }
    }

    /// Euler's form written over `self` in place where it already is one
    /// (the Jacobians of the last iteration's plan), with no allocation.
    pub(super) fn set_euler<const N: usize, const P: usize>(
        &mut self,
        step: f64,
        d: &InputDerivatives<f64, N, P>,
    ) {
        let Self::Euler {
            h,
            a,
            au,
            a_t,
            au_t,
        } = self
        else {
            *self = Self::euler(step, d);
            return;
        };
        *h = step;
        a.fixed_view_mut::<N, N>(0, 0).copy_from(&d.dq);
        a.fixed_view_mut::<N, N>(0, N).copy_from(&d.dv);
        au.fixed_view_mut::<N, P>(0, 0).copy_from(&d.du);
        a.transpose_to(a_t);
        au.transpose_to(au_t);
    }

    /// Euler's form of a stage's derivatives (see the module notes).
    pub(super) fn euler<const N: usize, const P: usize>(
        h: f64,
        d: &InputDerivatives<f64, N, P>,
    ) -> Self {
        let mut form = Self::Euler {
            h,
            a: DMatrix::zeros(N, 2 * N),
            au: DMatrix::zeros(N, P),
            a_t: DMatrix::zeros(2 * N, N),
            au_t: DMatrix::zeros(P, N),
        };
        form.set_euler(h, d);
        form
    }
}

/// The products one step of the backward pass writes, allocated once a
/// pass and overwritten step by step (`numeric::products` writes in place).
pub(super) struct Expansion {
    /// V_xx F_x in the dense form; V_xx P in Euler's.
    vxx_fx: DMatrix<f64>,
    /// V_xx F_u in the dense form.
    vxx_fu: DMatrix<f64>,
    /// Euler's form: Bᵀ V_xx, G = (Bᵀ V_xx) P (then G + C A),
    /// C = (Bᵀ V_xx) B, C A (then E), C A_u.
    b_vxx: DMatrix<f64>,
    g: DMatrix<f64>,
    c: DMatrix<f64>,
    ca: DMatrix<f64>,
    cau: DMatrix<f64>,
    /// Bᵀ V_x, and μ's N × 2N factor Bᵀ P + (h⁴ + h²) A.
    b_vx: DVector<f64>,
    b_fx: DMatrix<f64>,
    qx: DVector<f64>,
    pub(super) qu: DVector<f64>,
    qxx: DMatrix<f64>,
    quu: DMatrix<f64>,
    qux: DMatrix<f64>,
    /// Q̃_uu and Q̃_ux, regularised.
    pub(super) reg_uu: DMatrix<f64>,
    pub(super) reg_ux: DMatrix<f64>,
    gain_t: DMatrix<f64>,
    qux_t: DMatrix<f64>,
    /// C = ½ Q_uu K + Q_ux, and E = Kᵀ C (then ½ Q_xx + E in place).
    closed: DMatrix<f64>,
    kt_closed: DMatrix<f64>,
    /// Q_uu k + Q_u.
    pub(super) step_change: DVector<f64>,
}

impl Expansion {
    pub(super) fn new(n2: usize, p: usize) -> Self {
        let n = n2 / 2;
        let (square, tall, wide) = (
            DMatrix::zeros(n2, n2),
            DMatrix::zeros(n2, p),
            DMatrix::zeros(p, n2),
        );
        Expansion {
            vxx_fx: square.clone(),
            vxx_fu: tall.clone(),
            b_vxx: DMatrix::zeros(n, n2),
            g: DMatrix::zeros(n, n2),
            c: DMatrix::zeros(n, n),
            ca: DMatrix::zeros(n, n2),
            cau: DMatrix::zeros(n, p),
            b_vx: DVector::zeros(n),
            b_fx: DMatrix::zeros(n, n2),
            qx: DVector::zeros(n2),
            qu: DVector::zeros(p),
            qxx: square.clone(),
            kt_closed: square,
            quu: DMatrix::zeros(p, p),
            qux: wide.clone(),
            reg_uu: DMatrix::zeros(p, p),
            reg_ux: wide.clone(),
            gain_t: tall.clone(),
            qux_t: tall,
            closed: wide,
            step_change: DVector::zeros(p),
        }
    }

    /// Q's derivatives at a step from the cost's model, the step's
    /// Jacobians and the value function (V_x, V_xx) after it; the
    /// regularised Q̃_uu = Q_uu + μ F_uᵀF_u and Q̃_ux = Q_ux + μ F_uᵀF_x
    /// (Tassa, Erez and Todorov 2012: V_xx + μI, which keeps the new states
    /// near the nominal's).
    pub(super) fn expand(
        &mut self,
        l: &CostModel,
        jacobian: &StepJacobian,
        (vx, vxx): (&DVector<f64>, &DMatrix<f64>),
        mu: f64,
    ) {
        self.qx.as_mut_slice().copy_from_slice(l.lx.as_slice());
        self.qu.as_mut_slice().copy_from_slice(l.lu.as_slice());
        self.qxx.as_mut_slice().copy_from_slice(l.lxx.as_slice());
        self.quu.as_mut_slice().copy_from_slice(l.luu.as_slice());
        self.qux.as_mut_slice().copy_from_slice(l.lux.as_slice());
        match jacobian {
            StepJacobian::Dense { fx, fu, fx_t, fu_t } => {
                self.dense(fx, fu, (fx_t, fu_t), (vx, vxx));
            }
            StepJacobian::Euler {
                h,
                a,
                au,
                a_t,
                au_t,
            } => self.euler(*h, (a, au), (a_t, au_t), (vx, vxx)),
        }
        self.reg_uu
            .as_mut_slice()
            .copy_from_slice(self.quu.as_slice());
        self.reg_ux
            .as_mut_slice()
            .copy_from_slice(self.qux.as_slice());
        if mu == 0.0 {
            return;
        }
        match jacobian {
            StepJacobian::Dense { fx, fu, fu_t, .. } => {
                gemm(&mut self.reg_uu, mu, fu_t, fu, 1.0);
                gemm(&mut self.reg_ux, mu, fu_t, fx, 1.0);
            }
            StepJacobian::Euler { h, a, au, au_t, .. } => {
                self.euler_regularisation(*h, (a, au), au_t, mu);
            }
        }
    }

    /// Q_x += F_xᵀV_x, Q_u += F_uᵀV_x, Q_xx += F_xᵀV_xx F_x,
    /// Q_uu += F_uᵀV_xx F_u, Q_ux += F_uᵀV_xx F_x.
    fn dense(
        &mut self,
        fx: &DMatrix<f64>,
        fu: &DMatrix<f64>,
        (fx_t, fu_t): (&DMatrix<f64>, &DMatrix<f64>),
        (vx, vxx): (&DVector<f64>, &DMatrix<f64>),
    ) {
        gemm(&mut self.vxx_fx, 1.0, vxx, fx, 0.0);
        gemm(&mut self.vxx_fu, 1.0, vxx, fu, 0.0);
        gemv(&mut self.qx, 1.0, fx_t, vx, 1.0);
        gemv(&mut self.qu, 1.0, fu_t, vx, 1.0);
        gemm(&mut self.qxx, 1.0, fx_t, &self.vxx_fx, 1.0);
        gemm(&mut self.quu, 1.0, fu_t, &self.vxx_fu, 1.0);
        gemm(&mut self.qux, 1.0, fu_t, &self.vxx_fx, 1.0);
    }

    /// The same sums with F_x = P + B A and F_u = B A_u (see the module
    /// notes; Q_xx by its symmetric part).
    fn euler(
        &mut self,
        h: f64,
        (a, au): (&DMatrix<f64>, &DMatrix<f64>),
        (a_t, au_t): (&DMatrix<f64>, &DMatrix<f64>),
        (vx, vxx): (&DVector<f64>, &DMatrix<f64>),
    ) {
        let (n, n2) = (a.nrows(), a.ncols());
        // Q_x += Pᵀ V_x + Aᵀ (Bᵀ V_x), Q_u += A_uᵀ (Bᵀ V_x).
        add_p_t(self.qx.as_mut_slice(), vx.as_slice(), n2, h);
        rows_b(self.b_vx.as_mut_slice(), vx.as_slice(), n, h);
        gemv(&mut self.qx, 1.0, a_t, &self.b_vx, 1.0);
        gemv(&mut self.qu, 1.0, au_t, &self.b_vx, 1.0);
        // G = (Bᵀ V) P, C = (Bᵀ V) B; Q_xx += Pᵀ (V P).
        rows_b(self.b_vxx.as_mut_slice(), vxx.as_slice(), n, h);
        times_p(&mut self.g, &self.b_vxx, h);
        columns_b(&mut self.c, &self.b_vxx, h);
        times_p(&mut self.vxx_fx, vxx, h);
        add_p_t(self.qxx.as_mut_slice(), self.vxx_fx.as_slice(), n2, h);
        // C A; G + C A for Q_ux; E = (G + C A) − ½ C A for Q_xx += 2 Aᵀ E.
        gemm(&mut self.ca, 1.0, &self.c, a, 0.0);
        let ca = self.ca.as_mut_slice().iter_mut();
        ca.zip(self.g.as_mut_slice()).for_each(|(ca, g)| {
            *g += *ca;
            *ca = *g - 0.5 * *ca;
        });
        gemm(&mut self.qux, 1.0, au_t, &self.g, 1.0);
        gemm(&mut self.qxx, 2.0, a_t, &self.ca, 1.0);
        // Q_uu += A_uᵀ (C A_u).
        gemm(&mut self.cau, 1.0, &self.c, au, 0.0);
        gemm(&mut self.quu, 1.0, au_t, &self.cau, 1.0);
    }

    /// Q̃_uu += μ (h⁴ + h²) A_uᵀ A_u and Q̃_ux += μ A_uᵀ (Bᵀ P + (h⁴ + h²) A),
    /// Bᵀ B being (h⁴ + h²) I and Bᵀ P = [h² I, (h³ + h) I].
    fn euler_regularisation(
        &mut self,
        h: f64,
        (a, au): (&DMatrix<f64>, &DMatrix<f64>),
        au_t: &DMatrix<f64>,
        mu: f64,
    ) {
        let (h2, n) = (h * h, a.nrows());
        let c = h2 * h2 + h2;
        gemm(&mut self.reg_uu, mu * c, au_t, au, 1.0);
        self.b_fx.copy_from(a);
        self.b_fx.scale_mut(c);
        for i in 0..n {
            self.b_fx[(i, i)] += h2;
            self.b_fx[(i, n + i)] += h2 * h + h;
        }
        gemm(&mut self.reg_ux, mu, au_t, &self.b_fx, 1.0);
    }

    /// The value function before the step from the true Q (so that it
    /// stays bounded as μ grows: with Q̃ in it, V_xx would lose μ F_xᵀ Π F_x
    /// a step, Π a projection, and raising μ would make matters worse):
    /// V_x = Q_x + Kᵀ(Q_uu k + Q_u) + Q_uxᵀ k and
    /// V_xx = Q_xx + Kᵀ Q_uu K + Kᵀ Q_ux + Q_uxᵀ K = Q_xx + E + Eᵀ with
    /// E = Kᵀ C, C = ½ Q_uu K + Q_ux (one product of 2N × P × 2N where the
    /// three terms apart take two), Q_xx by its symmetric part alone.
    pub(super) fn value(
        &mut self,
        gain: &DMatrix<f64>,
        kff: &DVector<f64>,
        (vx, vxx): (&mut DVector<f64>, &mut DMatrix<f64>),
    ) {
        self.step_change
            .as_mut_slice()
            .copy_from_slice(self.qu.as_slice());
        gemv(&mut self.step_change, 1.0, &self.quu, kff, 1.0);
        gain.transpose_to(&mut self.gain_t);
        self.qux.transpose_to(&mut self.qux_t);
        vx.as_mut_slice().copy_from_slice(self.qx.as_slice());
        gemv(vx, 1.0, &self.gain_t, &self.step_change, 1.0);
        gemv(vx, 1.0, &self.qux_t, kff, 1.0);
        self.closed
            .as_mut_slice()
            .copy_from_slice(self.qux.as_slice());
        gemm(&mut self.closed, 0.5, &self.quu, gain, 1.0);
        // V_xx = T + Tᵀ with T = ½ Q_xx + E: symmetric exactly (each pair
        // of entries the same two numbers added), and Q_xx entering by its
        // symmetric part alone.
        gemm(&mut self.kt_closed, 1.0, &self.gain_t, &self.closed, 0.0);
        let halves = self.kt_closed.as_mut_slice().iter_mut();
        halves
            .zip(self.qxx.as_slice())
            .for_each(|(e, q)| *e += 0.5 * q);
        self.kt_closed.transpose_to(vxx);
        let entries = vxx.as_mut_slice().iter_mut();
        entries
            .zip(self.kt_closed.as_slice())
            .for_each(|(v, t)| *v += t);
    }
}

/// out (N × c) = Bᵀ m = h² m_top + h m_bottom, for m (2N × c); both in
/// column-major storage (a vector is one column).
fn rows_b(out: &mut [f64], m: &[f64], n: usize, h: f64) {
    let h2 = h * h;
    for (o, c) in out.chunks_exact_mut(n).zip(m.chunks_exact(2 * n)) {
        let (top, bottom) = c.split_at(n);
        for ((o, t), b) in o.iter_mut().zip(top).zip(bottom) {
            *o = h2 * t + h * b;
        }
    }
}

/// out (r × N) = m B = h² m_left + h m_right, for m (r × 2N).
fn columns_b(out: &mut DMatrix<f64>, m: &DMatrix<f64>, h: f64) {
    let h2 = h * h;
    let (left, right) = m.as_slice().split_at(out.len());
    for ((o, l), r) in out.as_mut_slice().iter_mut().zip(left).zip(right) {
        *o = h2 * l + h * r;
    }
}

/// out = m P = [m_left, h m_left + m_right], for m (r × 2N).
fn times_p(out: &mut DMatrix<f64>, m: &DMatrix<f64>, h: f64) {
    let half = m.len() / 2;
    let (left, right) = m.as_slice().split_at(half);
    let (out_left, out_right) = out.as_mut_slice().split_at_mut(half);
    out_left.copy_from_slice(left);
    for ((o, l), r) in out_right.iter_mut().zip(left).zip(right) {
        *o = h * l + r;
    }
}

/// out += Pᵀ m = [m_top; h m_top + m_bottom], for m and out (2N × c) in
/// column-major storage (a vector is one column).
fn add_p_t(out: &mut [f64], m: &[f64], rows: usize, h: f64) {
    let n = rows / 2;
    for (o, c) in out.chunks_exact_mut(rows).zip(m.chunks_exact(rows)) {
        let (o_top, o_bottom) = o.split_at_mut(n);
        let (top, bottom) = c.split_at(n);
        for (o, t) in o_top.iter_mut().zip(top) {
            *o += t;
        }
        for ((o, t), b) in o_bottom.iter_mut().zip(top).zip(bottom) {
            *o += h * t + b;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{SMatrix, SVector};

    /// Euler's form multiplies by P + B A and B A_u without forming them:
    /// Q's model, the regularised blocks and the value function after a
    /// feedback agree with the dense form's, F_x and F_u formed, to round-off.
    #[test]
    fn euler_s_form_agrees_with_the_dense_one() {
        const N: usize = 3;
        const P: usize = 2;
        let mut uniform = crate::numeric::samples::uniform(7);
        let mut r = move || 2.0 * uniform();
        let h = 0.05;
        let d = InputDerivatives::<f64, N, P> {
            acceleration: SVector::zeros(),
            dq: SMatrix::from_fn(|_, _| 10.0 * r()),
            dv: SMatrix::from_fn(|_, _| r()),
            du: SMatrix::from_fn(|_, _| 3.0 * r()),
        };
        let (fx, fu) = formed(h, &d);
        let half = DMatrix::from_fn(2 * N, 2 * N, |_, _| r());
        let vxx = &half * half.transpose();
        let vx = DVector::from_fn(2 * N, |_, _| r());
        let l = CostModel {
            value: 0.0,
            lx: DVector::from_fn(2 * N, |_, _| r()),
            lu: DVector::from_fn(P, |_, _| r()),
            lxx: DMatrix::identity(2 * N, 2 * N),
            luu: DMatrix::identity(P, P) * 0.1,
            lux: DMatrix::from_fn(P, 2 * N, |_, _| r()),
        };
        let gain = DMatrix::from_fn(P, 2 * N, |_, _| r());
        let kff = DVector::from_fn(P, |_, _| r());
        let run = |jacobian: StepJacobian| {
            let mut e = Expansion::new(2 * N, P);
            e.expand(&l, &jacobian, (&vx, &vxx), 0.3);
            let (mut vx1, mut vxx1) = (DVector::zeros(2 * N), DMatrix::zeros(2 * N, 2 * N));
            e.value(&gain, &kff, (&mut vx1, &mut vxx1));
            let column = |x: DVector<f64>| DMatrix::from_column_slice(x.len(), 1, x.as_slice());
            // Euler's form holds Q_xx by its symmetric part.
            let qxx = (&e.qxx + e.qxx.transpose()) * 0.5;
            [e.qx, e.qu, vx1]
                .map(column)
                .into_iter()
                .chain([qxx, e.quu, e.qux, e.reg_uu, e.reg_ux, vxx1])
                .collect::<Vec<_>>()
        };
        let dense = run(StepJacobian::dense(fx, fu));
        let euler = run(StepJacobian::euler(h, &d));
        for (i, (a, b)) in dense.iter().zip(&euler).enumerate() {
            let scale = 1.0 + a.amax();
            assert!(
                (a - b).amax() < 1e-13 * scale,
                "product {i}: {a} against {b}"
            );
        }
    }

    /// F_x = P + B [A_q A_v] and F_u = B A_u as matrices.
    fn formed<const N: usize, const P: usize>(
        h: f64,
        d: &InputDerivatives<f64, N, P>,
    ) -> (DMatrix<f64>, DMatrix<f64>) {
        let mut b = DMatrix::zeros(2 * N, N);
        let mut p = DMatrix::identity(2 * N, 2 * N);
        for i in 0..N {
            b[(i, i)] = h * h;
            b[(N + i, i)] = h;
            p[(i, N + i)] = h;
        }
        let mut a = DMatrix::zeros(N, 2 * N);
        a.fixed_view_mut::<N, N>(0, 0).copy_from(&d.dq);
        a.fixed_view_mut::<N, N>(0, N).copy_from(&d.dv);
        let au = DMatrix::from_column_slice(N, P, d.du.as_slice());
        (p + &b * a, b * au)
    }
}
