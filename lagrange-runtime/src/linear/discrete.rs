//! Discrete time, for controllers that act at samples
//! ([`Simulation::sampled`](crate::Simulation::sampled)): the exact
//! zero-order-hold discretisation of ẋ = A x + B u over one sample period h,
//!
//! ```text
//! x_{k+1} = A_d x_k + B_d u_k,   exp(h [[A, B], [0, 0]]) = [[A_d, B_d], [0, I]]
//! ```
//!
//! (Van Loan's block exponential, by nalgebra's scaling-and-squaring Padé
//! `exp`), and the discrete LQR: the gain K = (R + B_dᵀ P B_d)⁻¹ B_dᵀ P A_d
//! minimising Σ x_kᵀ Q x_k + u_kᵀ R u_k, with P the stabilising solution of
//! the discrete algebraic Riccati equation
//!
//! ```text
//! P = AᵀPA − AᵀPB (R + BᵀPB)⁻¹ BᵀPA + Q
//! ```
//!
//! by the structure-preserving doubling algorithm (Chu, Fan and Lin 2005),
//! which converges quadratically to it wherever (A, B) is stabilisable and
//! (Q, A) detectable. Both are checked against SciPy (`cont2discrete` with
//! `method = "zoh"`, `solve_discrete_are`), with the script that printed the
//! reference values in `lagrange-bench/peer/scipy_discrete.py`.

use super::Linear;
use super::lqr::{Lqr, RICCATI_TOLERANCE, check_problem, pbh};
use crate::error::{Error, LinearError, SettingsError};
use nalgebra::{Complex, DMatrix};

/// A discrete-time linear model x_{k+1} = A_d x_k + B_d u_k: a [`Linear`]
/// model sampled every `period` seconds with its inputs held in between
/// (zero-order hold). Built by [`Linear::discretize`].
#[derive(Clone, Debug, PartialEq)]
pub struct Discrete {
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    period: f64,
    states: Vec<String>,
    inputs: Vec<String>,
}

impl Linear {
    /// The exact zero-order-hold discretisation of this model over one
    /// sample of `period` seconds (see [`zero_order_hold`]); the states and
    /// inputs keep their names.
    ///
    /// ```
    /// use lagrange_runtime::linear::Linear;
    /// use nalgebra::DMatrix;
    ///
    /// // A double integrator: x = (position, velocity), u a force on unit mass.
    /// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    /// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    /// let model = Linear::new(a, b, &["x", "x'"], &["u"], 1)?;
    /// let sampled = model.discretize(0.1)?;
    /// // A_d = [[1, h], [0, 1]], B_d = [h²/2, h].
    /// assert!((sampled.a()[(0, 1)] - 0.1).abs() < 1e-15);
    /// assert!((sampled.b()[(0, 0)] - 0.005).abs() < 1e-15);
    /// // The discrete LQR gain for u_k = −K x_k at 10 Hz.
    /// let q = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 0.5]);
    /// let r = DMatrix::from_element(1, 1, 0.2);
    /// let design = sampled.lqr(&q, &r)?;
    /// assert!(design.closed_loop.iter().all(|z| z.norm() < 1.0));
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`zero_order_hold`].
    pub fn discretize(&self, period: f64) -> Result<Discrete, Error> {
        let (a, b) = zero_order_hold(self.a(), self.b(), period)?;
        Ok(Discrete {
            a,
            b,
            period,
            states: self.states().to_vec(),
            inputs: self.inputs().to_vec(),
        })
    }
}

impl Discrete {
    /// A_d (states × states).
    pub fn a(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// B_d (states × inputs).
    pub fn b(&self) -> &DMatrix<f64> {
        &self.b
    }

    /// The sample period h, seconds.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// The states' names, as the continuous model's.
    pub fn states(&self) -> &[String] {
        &self.states
    }

    /// The inputs' names, as the continuous model's.
    pub fn inputs(&self) -> &[String] {
        &self.inputs
    }

    /// The discrete LQR design for (A_d, B_d); see [`dlqr`].
    ///
    /// # Errors
    /// As [`dlqr`].
    pub fn lqr(&self, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr, Error> {
        dlqr(&self.a, &self.b, q, r)
    }
}

/// (A_d, B_d) of the exact zero-order-hold discretisation of ẋ = A x + B u
/// over `period`: the blocks of exp(h [[A, B], [0, 0]]).
///
/// # Errors
/// [`Error::Settings`] for a period that is not positive and finite, for
/// sizes that disagree or entries that are not finite, and for a model so
/// fast for the period that exp(A h) overflows.
pub fn zero_order_hold(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    period: f64,
) -> Result<(DMatrix<f64>, DMatrix<f64>), Error> {
    if !(period.is_finite() && period > 0.0) {
        return Err(SettingsError::Value {
            owner: "zero-order hold",
            setting: "period",
            value: period,
            requirement: "positive and finite (seconds)".into(),
        }
        .into());
    }
    let (n, m) = (a.nrows(), b.ncols());
    let finite = |x: &DMatrix<f64>| x.iter().all(|v| v.is_finite());
    for (name, x, rows, cols) in [("A", a, n, n), ("B", b, n, m)] {
        if x.shape() != (rows, cols) || !finite(x) {
            return Err(SettingsError::Shape {
                owner: "zero-order hold",
                name,
                expected: (rows, cols),
                got: x.shape(),
                finite: finite(x),
                meaning: "",
            }
            .into());
        }
    }
    let mut block = DMatrix::zeros(n + m, n + m);
    block.view_mut((0, 0), (n, n)).copy_from(&(a * period));
    block.view_mut((0, n), (n, m)).copy_from(&(b * period));
    let e = if n + m == 0 { block } else { block.exp() };
    if !finite(&e) {
        return Err(SettingsError::Value {
            owner: "zero-order hold",
            setting: "period",
            value: period,
            requirement: format!(
                "short enough that exp(A h) is finite (‖A‖ = {:e})",
                a.norm()
            ),
        }
        .into());
    }
    Ok((
        e.view((0, 0), (n, n)).into_owned(),
        e.view((0, n), (n, m)).into_owned(),
    ))
}

/// The infinite-horizon discrete LQR gain minimising Σ x_kᵀQx_k + u_kᵀRu_k
/// for x_{k+1} = A x_k + B u_k: K = (R + BᵀPB)⁻¹ BᵀPA (inputs × states, the
/// law u_k = −K x_k) with P the stabilising solution of the discrete
/// algebraic Riccati equation, by the doubling algorithm (see the module
/// notes). The returned [`Lqr`]'s `residual` is the DARE's relative residual
/// ‖AᵀPA − P − AᵀPB(R + BᵀPB)⁻¹BᵀPA + Q‖_F / (‖Q‖_F + ‖P‖_F + ‖AᵀPA‖_F),
/// `closed_loop` the eigenvalues of A − BK sorted by decreasing modulus
/// (each inside the unit circle), `iterations` the doubling steps and
/// `newton_steps` zero.
///
/// # Errors
/// [`Error::Settings`] for inconsistent sizes, non-finite entries, Q not
/// symmetric positive semidefinite or R not symmetric positive definite;
/// [`LinearError::NotStabilisable`] if the PBH test finds an uncontrollable
/// mode with |λ| ≥ 1 or the closed loop has an eigenvalue on or outside the
/// unit circle (its `ratio` is then that modulus); [`LinearError::Riccati`]
/// if the doubling does not converge in 100 steps or the residual exceeds
/// [`RICCATI_TOLERANCE`].
pub fn dlqr(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<Lqr, Error> {
    let n = a.nrows();
    let r_chol = check_problem(a, b, q, r)?;
    if n == 0 {
        return Ok(Lqr {
            gain: DMatrix::zeros(b.ncols(), 0),
            riccati: DMatrix::zeros(0, 0),
            residual: 0.0,
            closed_loop: vec![],
            iterations: 0,
            newton_steps: 0,
        });
    }
    let scale = 1.0 + a.amax();
    pbh(a, b, |z| z.norm() >= 1.0 - 1e-9 * scale)?;
    let g = b * r_chol.solve(&b.transpose());
    let (p, iterations) = doubling(a, &g, q)?;
    let residual = dare_residual(a, b, q, r, &p);
    if !(residual <= RICCATI_TOLERANCE) {
        return Err(LinearError::Riccati {
            reason: "residual of the discrete Riccati equation above the acceptance tolerance"
                .into(),
            residual,
        }
        .into());
    }
    let btp = b.transpose() * &p;
    let gain = (r + &btp * b)
        .cholesky()
        .ok_or_else(|| riccati_failed("R + BᵀPB is not positive definite", residual))?
        .solve(&(btp * a));
    let closed_loop = inside_unit_circle(&(a - b * &gain))?;
    Ok(Lqr {
        gain,
        riccati: p,
        residual,
        closed_loop,
        iterations,
        newton_steps: 0,
    })
}

/// The stabilising DARE solution by doubling: with A₀ = A, G₀ = B R⁻¹ Bᵀ,
/// H₀ = Q and W = I + G_k H_k,
/// A_{k+1} = A_k W⁻¹ A_k, G_{k+1} = G_k + A_k W⁻¹ G_k A_kᵀ,
/// H_{k+1} = H_k + A_kᵀ H_k W⁻¹ A_k; H_k → P quadratically (A_k → 0).
/// Returns P and the steps taken.
fn doubling(
    a: &DMatrix<f64>,
    g: &DMatrix<f64>,
    q: &DMatrix<f64>,
) -> Result<(DMatrix<f64>, usize), Error> {
    let n = a.nrows();
    let (mut ak, mut gk, mut hk) = (a.clone(), g.clone(), q.clone());
    for k in 1..=100 {
        let w = (DMatrix::identity(n, n) + &gk * &hk).lu();
        let (Some(w_a), Some(w_g)) = (w.solve(&ak), w.solve(&gk)) else {
            return Err(riccati_failed(
                "I + G H became singular in the doubling iteration",
                f64::NAN,
            ));
        };
        let h_next = &hk + ak.transpose() * &hk * &w_a;
        let g_next = &gk + &ak * w_g * ak.transpose();
        ak = &ak * w_a;
        let change = (&h_next - &hk).norm() / h_next.norm().max(f64::MIN_POSITIVE);
        hk = (&h_next + h_next.transpose()) * 0.5;
        gk = (&g_next + g_next.transpose()) * 0.5;
        if !change.is_finite() {
            break;
        }
        if change <= 1e-15 * n as f64 || ak.amax() <= f64::EPSILON * (1.0 + hk.amax()) {
            return Ok((hk, k));
        }
    }
    Err(riccati_failed(
        "the doubling iteration did not converge in 100 steps ((A, B) not stabilisable \
         or (Q, A) not detectable: an eigenvalue of the closed loop on the unit circle)",
        f64::NAN,
    ))
}

/// The relative residual of the discrete algebraic Riccati equation at P.
fn dare_residual(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
    p: &DMatrix<f64>,
) -> f64 {
    let atpa = a.transpose() * p * a;
    let btpa = b.transpose() * p * a;
    let Some(chol) = (r + b.transpose() * p * b).cholesky() else {
        return f64::INFINITY;
    };
    let res = &atpa - p - btpa.transpose() * chol.solve(&btpa) + q;
    let scale = q.norm() + p.norm() + atpa.norm();
    if scale > 0.0 {
        res.norm() / scale
    } else {
        res.norm()
    }
}

/// The closed loop's eigenvalues by decreasing modulus;
/// [`LinearError::NotStabilisable`] unless each is inside the unit circle.
fn inside_unit_circle(closed: &DMatrix<f64>) -> Result<Vec<Complex<f64>>, Error> {
    let mut ev: Vec<Complex<f64>> = closed.complex_eigenvalues().iter().copied().collect();
    ev.sort_by(|x, y| y.norm().total_cmp(&x.norm()).then(y.im.total_cmp(&x.im)));
    if let Some(z) = ev.first().filter(|z| !(z.norm() < 1.0)) {
        return Err(LinearError::NotStabilisable {
            re: z.re,
            im: z.im,
            ratio: z.norm(),
        }
        .into());
    }
    Ok(ev)
}

fn riccati_failed(reason: &str, residual: f64) -> Error {
    LinearError::Riccati {
        reason: reason.into(),
        residual,
    }
    .into()
}

#[cfg(test)]
#[path = "discrete_tests.rs"]
mod tests;
