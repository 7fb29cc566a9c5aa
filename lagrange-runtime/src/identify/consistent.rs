//! Estimates constrained to physically consistent parameters: the full π
//! searched over the log-Cholesky parametrisation (every θ a real body),
//! by Levenberg–Marquardt on the weighted residual of τ.

use nalgebra::{DMatrix, DVector, SVector};

use super::base::BaseParameters;
use super::estimate::{Sample, check_data, weighted_full};
use super::pseudo_inertia::Parametrisation;
use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// The settings of [`identify_consistent`].
#[derive(Clone, Debug, PartialEq)]
pub struct Consistency {
    /// The weight of the pull toward the prior, relative to the data's
    /// mean curvature (the mean of the diagonal of the Gauss–Newton matrix
    /// at the prior). It has to choose among the π that fit equally well
    /// (the directions the data cannot see), and it biases the ones they
    /// can see, most in their weakest directions: measured from noise-free
    /// data, π_b off by 1e-5 (relative) on the UR5 at the default 1e-6 and
    /// 4e-9 at 1e-10, by 1.3e-3 on a planar 2R arm at 1e-6. Smaller is less
    /// bias but, where the data push a body toward the boundary of
    /// consistency, slower convergence: the optimum recedes toward a flat
    /// body at infinite θ (the tests' light forearm converges in 443
    /// iterations at 1e-6, not in 2000 at 1e-8).
    pub regularisation: f64,
    /// Levenberg–Marquardt iterations at most.
    pub iterations: usize,
    /// Converged when a step lowers the cost by less than this fraction of
    /// it. Where the data pull a body toward the boundary of consistency
    /// (an inertia they would have negative), the cost keeps falling ever
    /// more slowly as the body flattens: this says when the rest is not
    /// worth having.
    pub tolerance: f64,
}

impl Default for Consistency {
    fn default() -> Self {
        Consistency {
            regularisation: 1e-6,
            iterations: 2000,
            tolerance: 1e-8,
        }
    }
}

/// A physically consistent estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct ConsistentEstimate {
    /// The full π, each body's block with a positive definite
    /// pseudo-inertia, each point mass positive.
    pub parameters: DVector<f64>,
    /// Its base parameters, π_b = K π.
    pub base: DVector<f64>,
    /// The weighted residual's root mean square, as [`super::Estimate`]'s.
    pub residual: f64,
    /// Levenberg–Marquardt iterations made.
    pub iterations: usize,
}

/// π from `samples`, physically consistent, by weighted least squares with
/// each body's ten parameters written through the log-Cholesky
/// parametrisation of its pseudo-inertia (Rucker and Wensing 2022) and each
/// point mass as m = e^θ, so that every iterate is a real body, minimising
///
/// ‖W π(θ) − τ/σ‖² + λ ‖θ − θ_prior‖²,
///
/// W the full regressor stacked and weighted as [`super::identify`] weights
/// it. The second term is needed because W has a null space (what the base
/// parameters leave out): there the data say nothing and the estimate stays
/// near the prior. It is a plain Euclidean distance in θ: smooth, its
/// Hessian the identity (so that the Levenberg–Marquardt matrix is positive
/// definite along the null space), and in θ a body's scale is its log mass
/// and log lengths, so that the pull is relative; the entropic divergence
/// of Lee, Wensing and Park (2020) is coordinate free but needs its own
/// Hessian, and at a weight this small the choice only picks among equal
/// fits. The Jacobian is analytic: ∂π/∂θ through J = U Uᵀ.
///
/// The model passed supplies only the regressor; `prior` is the π to stay
/// near (a CAD model's, or `sys.inertial_parameters()`), and must be
/// physically consistent, but for bodies whose ten parameters are all zero
/// (a URDF frame without `<inertial>`, a tool frame): those stay massless.
///
/// # Errors
/// [`IdentifyError::Inconsistent`] for a prior that is not physically
/// consistent (naming the body); [`IdentifyError::NotConverged`] with the
/// best iterate when the iterations run out; the data errors of
/// [`super::identify`] (noise levels, NaN in a sample, lengths); and
/// [`IdentifyError::Setting`] for a regularisation that is not positive and
/// finite.
pub fn identify_consistent<S, const N: usize, const Q: usize>(
    sys: &S,
    base: &BaseParameters,
    samples: &[Sample<N, Q>],
    noise: &SVector<f64, N>,
    prior: &DVector<f64>,
    settings: &Consistency,
) -> Result<ConsistentEstimate, IdentifyError>
where
    S: Lagrangian<f64, N, Q>,
{
    check_data(samples, noise)?;
    let lambda = settings.regularisation;
    if !(lambda.is_finite() && lambda > 0.0) {
        return Err(IdentifyError::Setting {
            setting: "regularisation",
            value: lambda,
            reason: "the pull toward the prior must be positive and finite (1e-6 by default)",
        });
    }
    if !(settings.tolerance.is_finite() && settings.tolerance >= 0.0) {
        return Err(IdentifyError::Setting {
            setting: "tolerance",
            value: settings.tolerance,
            reason: "the relative decrease of the cost that ends the iteration must be finite \
                     and not negative (1e-8 by default)",
        });
    }
    let names = S::REGRESSOR_PARAMETERS;
    if prior.len() != names.len() {
        return Err(IdentifyError::Lengths {
            what: "the prior π",
            got: prior.len(),
            expected: names.len(),
        });
    }
    if let Some((index, &value)) = prior.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(IdentifyError::NotFiniteValue {
            what: "the prior π",
            index,
            value,
        });
    }
    let (parametrisation, start) = Parametrisation::at(names, prior, "the prior π")?;
    let (w, y) = weighted_full(sys, samples, noise)?;
    let problem = Problem::compressed(&w, &y, parametrisation, start);
    let fit = problem.levenberg_marquardt(lambda, settings);
    let (pi, _) = problem.parametrisation.pi_and_jacobian(&fit.theta);
    let residual = (problem.data_cost(&pi) / (y.len().max(1) as f64)).sqrt();
    if !fit.converged {
        return Err(IdentifyError::NotConverged {
            iterations: fit.iterations,
            residual,
            best: pi,
        });
    }
    Ok(ConsistentEstimate {
        base: base.of_parameters(&pi)?,
        parameters: pi,
        residual,
        iterations: fit.iterations,
    })
}

/// The least-squares problem in θ, its data ‖W π − y‖² kept as
/// ‖R π − z‖² + rest (W = Q R): the iterations then cost the parameters'
/// count, not the samples'.
struct Problem {
    r: DMatrix<f64>,
    z: DVector<f64>,
    rest: f64,
    parametrisation: Parametrisation,
    prior: DVector<f64>,
}

/// Where Levenberg–Marquardt stopped.
struct Fit {
    theta: DVector<f64>,
    iterations: usize,
    converged: bool,
}

impl Problem {
    fn compressed(
        w: &DMatrix<f64>,
        y: &DVector<f64>,
        parametrisation: Parametrisation,
        prior: DVector<f64>,
    ) -> Self {
        let (r, z) = if w.nrows() > w.ncols() {
            let qr = w.clone().qr();
            let z = qr.q().transpose() * y;
            (qr.r(), z)
        } else {
            (w.clone(), y.clone())
        };
        let rest = (y.norm_squared() - z.norm_squared()).max(0.0);
        Problem {
            r,
            z,
            rest,
            parametrisation,
            prior,
        }
    }

    /// ‖W π − y‖².
    fn data_cost(&self, pi: &DVector<f64>) -> f64 {
        (&self.r * pi - &self.z).norm_squared() + self.rest
    }

    /// The residual [R π(θ) − z; √λ (θ − θ_prior)] and its Jacobian.
    fn linearised(&self, theta: &DVector<f64>, lambda: f64) -> (DVector<f64>, DMatrix<f64>) {
        let (pi, dpi) = self.parametrisation.pi_and_jacobian(theta);
        let (m, n) = (self.r.nrows(), theta.len());
        let mut residual = DVector::zeros(m + n);
        residual.rows_mut(0, m).copy_from(&(&self.r * pi - &self.z));
        residual
            .rows_mut(m, n)
            .copy_from(&((theta - &self.prior) * lambda.sqrt()));
        let mut jac = DMatrix::zeros(m + n, n);
        jac.view_mut((0, 0), (m, n)).copy_from(&(&self.r * dpi));
        jac.view_mut((m, 0), (n, n)).fill_diagonal(lambda.sqrt());
        (residual, jac)
    }

    /// Levenberg–Marquardt with Nielsen's update of the damping μ, the
    /// pull λ relative to the data's mean curvature at the prior. Converged
    /// when a step no longer lowers the cost by more than the settings'
    /// tolerance of it, or the gradient vanishes to round-off.
    fn levenberg_marquardt(&self, relative: f64, settings: &Consistency) -> Fit {
        let mut theta = self.prior.clone();
        let (_, j0) = self.linearised(&theta, 0.0);
        let n = theta.len();
        let curvature = (j0.column_iter().map(|c| c.norm_squared()).sum::<f64>() / n.max(1) as f64)
            .max(f64::MIN_POSITIVE);
        let lambda = relative * curvature;
        let (mut r, mut jac) = self.linearised(&theta, lambda);
        let mut cost = r.norm_squared();
        let mut mu = 1e-3 * curvature;
        let mut nu = 2.0;
        for iteration in 1..=settings.iterations {
            let gradient = jac.transpose() * &r;
            if gradient.amax() <= 1e-15 * curvature * (1.0 + theta.amax()) {
                return Fit {
                    theta,
                    iterations: iteration - 1,
                    converged: true,
                };
            }
            let normal = jac.transpose() * &jac + DMatrix::identity(n, n) * mu;
            let Some(step) = normal.cholesky().map(|c| c.solve(&-&gradient)) else {
                (mu, nu) = (mu * nu, nu * 2.0);
                continue;
            };
            let trial = &theta + &step;
            let (r_trial, jac_trial) = self.linearised(&trial, lambda);
            let trial_cost = r_trial.norm_squared();
            // The decrease the linear model predicted: −2 gᵀs − sᵀJᵀJ s.
            let predicted = -(2.0 * gradient.dot(&step) + (&jac * &step).norm_squared());
            if trial_cost.is_finite() && trial_cost < cost {
                let ratio = (cost - trial_cost) / predicted.max(f64::MIN_POSITIVE);
                mu *= (1.0 - (2.0 * ratio - 1.0).powi(3)).max(1.0 / 3.0);
                nu = 2.0;
                let decrease = cost - trial_cost;
                (theta, r, jac, cost) = (trial, r_trial, jac_trial, trial_cost);
                if decrease <= settings.tolerance * cost {
                    return Fit {
                        theta,
                        iterations: iteration,
                        converged: true,
                    };
                }
            } else {
                (mu, nu) = (mu * nu, nu * 2.0);
                if step.amax() <= 1e-15 * (1.0 + theta.amax()) {
                    return Fit {
                        theta,
                        iterations: iteration,
                        converged: true,
                    };
                }
            }
        }
        Fit {
            theta,
            iterations: settings.iterations,
            converged: false,
        }
    }
}
