//! Linear-quadratic regulator: the continuous-time algebraic Riccati equation
//!
//! ```text
//! AᵀP + PA − P B R⁻¹ Bᵀ P + Q = 0
//! ```
//!
//! by the matrix sign function of the Hamiltonian `H = [[A, −S], [−Q, −Aᵀ]]`,
//! S = B R⁻¹ Bᵀ (Roberts 1971; Byers 1987 determinant scaling): the stable
//! invariant subspace of H is the null space of sign(H) + I and equals the range
//! of [I; P], so P solves the overdetermined [W₁₂; W₂₂ + I] P = −[W₁₁ + I; W₂₁]
//! (least squares by SVD). Up to three Newton (Kleinman) steps, each a Lyapunov
//! equation solved through its Kronecker form for n ≤ 30, then polish P to
//! round-off. No maintained Rust crate solves the CARE on nalgebra 0.35, hence
//! this implementation.

use super::{Linear, LinearError};
use crate::error::Error;
use crate::error::SettingsError;
use nalgebra::{Complex, DMatrix};

/// Largest relative residual accepted for the Riccati solution.
pub const RICCATI_TOLERANCE: f64 = 1e-8;

/// An LQR design: the gain, the Riccati solution and the checks made on them.
#[derive(Clone, Debug, PartialEq)]
pub struct Lqr {
    /// K = R⁻¹ Bᵀ P (inputs × states): the control law u = −K x.
    pub gain: DMatrix<f64>,
    /// P, the stabilising solution of the Riccati equation (symmetric).
    pub riccati: DMatrix<f64>,
    /// ‖AᵀP + PA − PSP + Q‖_F / (‖Q‖_F + 2‖AᵀP‖_F + ‖PSP‖_F).
    pub residual: f64,
    /// Eigenvalues of A − BK, sorted by decreasing real part.
    pub closed_loop: Vec<Complex<f64>>,
    /// Sign-function iterations done.
    pub iterations: usize,
    /// Newton refinement steps accepted.
    pub newton_steps: usize,
}

impl Linear {
    /// The LQR design for this model's (A, B); see [`lqr`].
    ///
    /// # Errors
    /// As [`lqr`].
    pub fn lqr(&self, q: &DMatrix<f64>, r: &DMatrix<f64>) -> Result<Lqr, Error> {
        lqr(self.a(), self.b(), q, r)
    }
}

/// The infinite-horizon LQR gain minimising ∫ xᵀQx + uᵀRu dt for ẋ = Ax + Bu:
/// K = R⁻¹BᵀP with P the stabilising solution of the algebraic Riccati equation
/// (see the module notes for the method). The residual is computed and reported;
/// A − BK is checked to be Hurwitz.
///
/// # Errors
/// [`Error::Settings`] for inconsistent sizes, non-finite entries, Q not
/// symmetric positive semidefinite or R not symmetric positive definite;
/// [`LinearError::NotStabilisable`] if the PBH test finds an uncontrollable mode
/// with Re λ ≥ 0 or the closed loop is not Hurwitz; [`LinearError::Riccati`] if
/// the sign iteration fails (eigenvalues of H on the imaginary axis: (Q, A) not
/// detectable, or not stabilisable) or the residual exceeds
/// [`RICCATI_TOLERANCE`].
pub fn lqr(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<Lqr, Error> {
    let n = a.nrows();
    let m = b.ncols();
    let r_chol = check_problem(a, b, q, r)?;
    if n == 0 {
        return Ok(Lqr {
            gain: DMatrix::zeros(m, 0),
            riccati: DMatrix::zeros(0, 0),
            residual: 0.0,
            closed_loop: vec![],
            iterations: 0,
            newton_steps: 0,
        });
    }
    let scale = 1.0 + a.amax();
    pbh(a, b, |z| z.re >= -1e-9 * scale)?;
    let s = b * r_chol.solve(&b.transpose());
    let (w, iterations) = sign(hamiltonian(a, &s, q))?;
    let p = stable_graph(&w, n)?;
    let (p, res, newton_steps) = refine(a, &s, q, p);
    if !(res <= RICCATI_TOLERANCE) {
        return Err(LinearError::Riccati {
            reason: "residual above the acceptance tolerance".into(),
            residual: res,
        }
        .into());
    }
    let gain = r_chol.solve(&(b.transpose() * &p));
    let closed_loop = closed_loop(&(a - b * &gain))?;
    Ok(Lqr {
        gain,
        riccati: p,
        residual: res,
        closed_loop,
        iterations,
        newton_steps,
    })
}

/// Checks the sizes, finiteness and definiteness of the design problem;
/// returns R's Cholesky factor.
pub(super) fn check_problem(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    q: &DMatrix<f64>,
    r: &DMatrix<f64>,
) -> Result<nalgebra::Cholesky<f64, nalgebra::Dyn>, Error> {
    let n = a.nrows();
    let m = b.ncols();
    if m == 0 {
        return Err(SettingsError::Unsupported {
            owner: "LQR",
            needs: "a model with inputs".into(),
            remedy: "this one has no inputs (B has no columns), so there is no control to \
                     design; declare them with `inputs(...)` in the description and use them \
                     in a force, or linearise a model that has them"
                .into(),
        }
        .into());
    }
    let shape = |name: &'static str, x: &DMatrix<f64>, rows: usize, cols: usize| {
        let finite = x.iter().all(|v| v.is_finite());
        if x.nrows() != rows || x.ncols() != cols || !finite {
            Err(SettingsError::Shape {
                owner: "LQR",
                name,
                expected: (rows, cols),
                got: x.shape(),
                finite,
                meaning: "",
            })
        } else {
            Ok(())
        }
    };
    shape("A", a, n, n)?;
    shape("B", b, n, m)?;
    shape("Q", q, n, n)?;
    shape("R", r, m, m)?;
    let symmetric = |x: &DMatrix<f64>| (x - x.transpose()).amax() <= 1e-12 * x.amax();
    if !symmetric(q) || !symmetric(r) {
        return Err(lqr_weights("Q and R must be symmetric"));
    }
    if n > 0 && q.clone().symmetric_eigenvalues().min() < -1e-12 * q.amax().max(1.0) {
        return Err(lqr_weights("Q must be positive semidefinite"));
    }
    nalgebra::Cholesky::new(r.clone()).ok_or_else(|| lqr_weights("R must be positive definite"))
}

/// LQR weights that are not a cost.
fn lqr_weights(problem: &str) -> Error {
    let problem = problem.into();
    SettingsError::Data {
        owner: "LQR",
        problem,
    }
    .into()
}

/// The Hamiltonian matrix [[A, −S], [−Q, −Aᵀ]] with S = B R⁻¹ Bᵀ.
fn hamiltonian(a: &DMatrix<f64>, s: &DMatrix<f64>, q: &DMatrix<f64>) -> DMatrix<f64> {
    let n = a.nrows();
    let mut h = DMatrix::zeros(2 * n, 2 * n);
    h.view_mut((0, 0), (n, n)).copy_from(a);
    h.view_mut((0, n), (n, n)).copy_from(&-s);
    h.view_mut((n, 0), (n, n)).copy_from(&-q);
    h.view_mut((n, n), (n, n)).copy_from(&-a.transpose());
    h
}

/// P from the sign W of the Hamiltonian: the stable invariant subspace
/// (the kernel of W + I) written as the graph [I; P], by least squares on
/// [W₁₂; W₂₂ + I] P = −[W₁₁ + I; W₂₁], then symmetrised.
fn stable_graph(w: &DMatrix<f64>, n: usize) -> Result<DMatrix<f64>, Error> {
    let mut lhs = DMatrix::zeros(2 * n, n);
    lhs.view_mut((0, 0), (n, n))
        .copy_from(&w.view((0, n), (n, n)));
    lhs.view_mut((n, 0), (n, n))
        .copy_from(&(w.view((n, n), (n, n)) + DMatrix::identity(n, n)));
    let mut rhs = DMatrix::zeros(2 * n, n);
    rhs.view_mut((0, 0), (n, n))
        .copy_from(&-(w.view((0, 0), (n, n)) + DMatrix::identity(n, n)));
    rhs.view_mut((n, 0), (n, n))
        .copy_from(&-w.view((n, 0), (n, n)));
    let svd = lhs.svd(true, true);
    let sv = &svd.singular_values;
    if !(sv.min() > 1e-12 * sv.max()) {
        return Err(LinearError::Riccati {
            reason: "the stable invariant subspace of the Hamiltonian is not a graph [I; P] \
                     (no stabilising solution)"
                .into(),
            residual: f64::NAN,
        }
        .into());
    }
    let x = svd.solve(&rhs, 0.0).map_err(|e| LinearError::Riccati {
        reason: format!("least-squares solve failed: {e}"),
        residual: f64::NAN,
    })?;
    Ok((&x + x.transpose()) * 0.5)
}

/// Up to three Newton (Kleinman) steps on the Riccati equation, each kept only
/// if it lowers the residual (for n ≤ 30; larger systems keep the sign
/// iteration's P). Returns P, its relative residual and the steps kept.
fn refine(
    a: &DMatrix<f64>,
    s: &DMatrix<f64>,
    q: &DMatrix<f64>,
    mut p: DMatrix<f64>,
) -> (DMatrix<f64>, f64, usize) {
    let mut res = residual(a, s, q, &p);
    let mut steps = 0;
    if a.nrows() > 30 {
        return (p, res.1, steps);
    }
    for _ in 0..3 {
        if res.1 <= 4.0 * f64::EPSILON {
            break;
        }
        let ak = a - s * &p;
        let Some(dp) = lyapunov(&ak, &res.0) else {
            break;
        };
        let cand = &p + (&dp + dp.transpose()) * 0.5;
        let cres = residual(a, s, q, &cand);
        if !(cres.1 < res.1) {
            break;
        }
        p = cand;
        res = cres;
        steps += 1;
    }
    (p, res.1, steps)
}

/// The closed loop's eigenvalues, sorted by decreasing real part;
/// [`LinearError::NotStabilisable`] unless every one is in the left half-plane.
fn closed_loop(closed: &DMatrix<f64>) -> Result<Vec<Complex<f64>>, Error> {
    let mut ev: Vec<Complex<f64>> = closed.complex_eigenvalues().iter().copied().collect();
    ev.sort_by(|x, y| y.re.total_cmp(&x.re).then(y.im.total_cmp(&x.im)));
    if let Some(z) = ev.first().filter(|z| !(z.re < 0.0)) {
        return Err(LinearError::NotStabilisable {
            re: z.re,
            im: z.im,
            ratio: z.re,
        }
        .into());
    }
    Ok(ev)
}

/// The Riccati residual matrix and its relative size.
fn residual(
    a: &DMatrix<f64>,
    s: &DMatrix<f64>,
    q: &DMatrix<f64>,
    p: &DMatrix<f64>,
) -> (DMatrix<f64>, f64) {
    let atp = a.transpose() * p;
    let psp = p * s * p;
    let r = &atp + atp.transpose() - &psp + q;
    let scale = q.norm() + 2.0 * atp.norm() + psp.norm();
    let rel = if scale > 0.0 {
        r.norm() / scale
    } else {
        r.norm()
    };
    (r, rel)
}

/// PBH test: every eigenvalue λ of A that is `unstable` (continuous time:
/// Re λ ≥ −1e-9 (1 + ‖A‖); discrete: |λ| ≥ 1 − 1e-9 (1 + ‖A‖)) must keep
/// [A − λI, B] at full row rank.
pub(super) fn pbh(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    unstable: impl Fn(Complex<f64>) -> bool,
) -> Result<(), Error> {
    let n = a.nrows();
    for z in a.complex_eigenvalues().iter() {
        if !unstable(*z) {
            continue;
        }
        let mut mtx = DMatrix::<Complex<f64>>::zeros(n, n + b.ncols());
        for i in 0..n {
            for j in 0..n {
                mtx[(i, j)] = Complex::new(a[(i, j)], 0.0);
            }
            mtx[(i, i)] -= z;
            for j in 0..b.ncols() {
                mtx[(i, n + j)] = Complex::new(b[(i, j)], 0.0);
            }
        }
        let sv = mtx.singular_values();
        let ratio = sv.min() / sv.max();
        if !(ratio > 1e-9) {
            return Err(LinearError::NotStabilisable {
                re: z.re,
                im: z.im,
                ratio,
            }
            .into());
        }
    }
    Ok(())
}

/// The matrix sign function by the scaled Newton iteration
/// Z ← (Z/c + c Z⁻¹)/2, c = |det Z|^(1/n) while the change is large.
fn sign(mut z: DMatrix<f64>) -> Result<(DMatrix<f64>, usize), Error> {
    let n = z.nrows();
    let mut scaling = true;
    let mut finishing = false;
    for k in 1..=100 {
        let lu = z.clone().lu();
        let inv = lu.try_inverse().filter(|x| x.iter().all(|v| v.is_finite()));
        let Some(inv) = inv else {
            return Err(sign_failed(
                "the Hamiltonian has eigenvalues on the imaginary axis ((A, B) not \
                 stabilisable or (Q, A) not detectable)",
            ));
        };
        let c = if scaling {
            let log_det: f64 = lu.u().diagonal().iter().map(|d| d.abs().ln()).sum();
            (log_det / n as f64).exp()
        } else {
            1.0
        };
        let next = (&z / c + inv * c) * 0.5;
        let change = (&next - &z).norm() / next.norm();
        z = next;
        if change < 1e-2 {
            scaling = false;
        }
        // Quadratic convergence: one more step after a change of 1e-9 reaches
        // round-off.
        if finishing || change <= 1e-14 * (n as f64) {
            return Ok((z, k));
        }
        finishing = change <= 1e-9;
        if !change.is_finite() {
            break;
        }
    }
    Err(sign_failed(
        "the matrix sign iteration did not converge in 100 steps (eigenvalues of the \
         Hamiltonian on or near the imaginary axis)",
    ))
}

fn sign_failed(reason: &str) -> Error {
    LinearError::Riccati {
        reason: reason.into(),
        residual: f64::NAN,
    }
    .into()
}

/// X with Akᵀ X + X Ak = −R, through the Kronecker form
/// (I ⊗ Akᵀ + Akᵀ ⊗ I) vec X = −vec R (column-major vec).
fn lyapunov(ak: &DMatrix<f64>, r: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = ak.nrows();
    let at = ak.transpose();
    let id = DMatrix::<f64>::identity(n, n);
    let big = id.kronecker(&at) + at.kronecker(&id);
    let rhs = nalgebra::DVector::from_column_slice((-r).as_slice());
    let x = big.lu().solve(&rhs)?;
    Some(DMatrix::from_column_slice(n, n, x.as_slice()))
}
