//! Constraints kept with multipliers: forward dynamics from the saddle-point
//! system, drift control, and consistent initial conditions.
//!
//! A [`Constrained`] system's equations M q̈ + h = Q + Gᵀ ν, G q̈ = γ are an index-1
//! DAE once differentiated to the acceleration level. Integrating them as an ODE
//! keeps G q̈ = γ exactly but lets Φ = 0 and G q̇ + g = 0 drift with the
//! integration error; [`Drift`] chooses what to do about it.
//!
//! A pendulum as a point (x, y) on a rod x² + y² = l², written by hand:
//!
//! ```
//! use lagrange_runtime::{Constrained, ConstrainedDynamics, Dopri5, Drift, Lagrangian, Simulation};
//! use nalgebra::{Matrix1x2, Matrix2, Vector1, Vector2};
//!
//! struct Bob { g: f64 }
//! impl Lagrangian<f64, 2> for Bob {
//!     const COORDINATES: [&'static str; 2] = ["x", "y"];
//!     const RHEONOMIC: bool = false;
//!     fn mass_matrix(&self, _: &Vector2<f64>, _: f64) -> Matrix2<f64> { Matrix2::identity() }
//!     fn bias(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::zeros() }
//!     fn generalized_forces(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> {
//!         Vector2::new(0.0, -self.g)
//!     }
//!     fn mass_matrix_and_rhs(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64)
//!         -> (Matrix2<f64>, Vector2<f64>) {
//!         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//!     }
//!     fn kinetic_energy(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> f64 { 0.5 * v.norm_squared() }
//!     fn potential_energy(&self, q: &Vector2<f64>, _: f64) -> f64 { self.g * q[1] }
//!     fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
//!         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//!     }
//! }
//! impl Constrained<f64, 2, 1> for Bob {
//!     const CONSTRAINTS: [&'static str; 1] = ["rod"];
//!     const HOLONOMIC: usize = 1;
//!     fn constraint_positions(&self, q: &Vector2<f64>, _: f64) -> Vector1<f64> {
//!         Vector1::new(q.norm_squared() - 1.0)
//!     }
//!     fn constraint_jacobian(&self, q: &Vector2<f64>, _: f64) -> (Matrix1x2<f64>, Vector1<f64>) {
//!         (Matrix1x2::new(2.0 * q[0], 2.0 * q[1]), Vector1::zeros())
//!     }
//!     fn constraint_rhs(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> Vector1<f64> {
//!         Vector1::new(-2.0 * v.norm_squared()) // γ = −Ġ q̇
//!     }
//!     fn constrained_system(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64)
//!         -> (Matrix2<f64>, Vector2<f64>, Matrix1x2<f64>, Vector1<f64>) {
//!         let (m, f) = self.mass_matrix_and_rhs(q, v, t);
//!         (m, f, self.constraint_jacobian(q, t).0, self.constraint_rhs(q, v, t))
//!     }
//! }
//!
//! let sys = Bob { g: 9.81 };
//! let (q0, v0) = (Vector2::new(0.6, -0.8), Vector2::new(0.0, 0.0));
//! let traj = Simulation::new(&sys)
//!     .integrator(Dopri5::tol(1e-10))
//!     .drift(Drift::projection())
//!     .run_constrained(q0, v0, 0.0..10.0)?;
//! let [phi, vel] = traj.max_residuals();
//! assert!(phi < 1e-12 && vel < 1e-12);
//! assert!(traj.integral_drift() < 1e-8);
//!
//! // Multipliers and reactions at the lowest point, moving at 2 m/s: the rod
//! // carries m (v²/l + g) = 4 + 9.81.
//! let sol = ConstrainedDynamics::new(&sys)
//!     .solve(0.0, &Vector2::new(0.0, -1.0), &Vector2::new(2.0, 0.0))?;
//! assert!((sol.reactions[1] - 13.81).abs() < 1e-12);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! The range-space solve shared by the dynamics and the projections is
//! `numeric::saddle` (layer 0); here:
//!
//! - `projection`: Gauss–Newton onto Φ = 0 and the velocity correction;
//! - `consistency`: residuals, the initial-condition check and its repair.

mod consistency;
mod projection;

pub use consistency::{check_consistency, project_consistent};

use crate::error::SettingsError;
use crate::error::{Error, check_tolerance, to_vec};
use crate::mechanics::dynamics::{DEFAULT_SINGULAR_TOLERANCE, all_finite, on_sphere};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation::Orientation;
use crate::numeric::saddle::{Dependent, Schur, range_space};
use crate::ode::SecondOrder;
use crate::system::Constrained;
use nalgebra::SVector;

/// Default threshold on the pivot ratio of G M⁻¹ Gᵀ below which constraint rows
/// are reported as redundant.
pub const DEFAULT_REDUNDANT_TOLERANCE: f64 = 1e-12;
/// Default tolerance of the initial-condition check on max |Φ| and max |G q̇ + g|.
pub const DEFAULT_CONSISTENCY_TOLERANCE: f64 = 1e-10;
/// Default tolerance of the projection onto Φ = 0 (and of the velocity correction).
pub const DEFAULT_PROJECTION_TOLERANCE: f64 = 1e-12;
/// Default limit on Gauss–Newton iterations of the projection.
pub const DEFAULT_PROJECTION_ITERATIONS: usize = 10;

/// What to do about constraint drift, the slow violation of Φ = 0 and G q̇ + g = 0
/// by the integration error (only G q̈ = γ is imposed).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Drift {
    /// Nothing: the residuals grow with the integration error (linearly in Φ̇,
    /// and Φ quadratically in time). Fine for short runs at tight tolerances.
    #[default]
    None,
    /// Baumgarte stabilisation: γ ← γ − 2α (G q̇ + g) − β² Φ (the Φ term on the
    /// holonomic rows only), which turns the drift into a damped oscillation
    /// ë + 2α ė + β² e = 0. Cheap, but α and β need tuning to the time scales of
    /// the system (α = β = a few times its highest frequency is a common start) and
    /// the residuals stay of the order of the integration error.
    Baumgarte {
        /// Damping of the velocity-level residual (1/time).
        alpha: f64,
        /// Stiffness of the position-level residual (1/time).
        beta: f64,
    },
    /// Projection after every accepted step: Gauss–Newton onto Φ(q, t) = 0 in the
    /// metric of M, then the M-weighted velocity correction onto G q̇ + g = 0. Keeps
    /// the residuals at `tol` or below (round-off in practice).
    Projection {
        /// Absolute tolerance on max |Φ| and on max |G q̇ + g|; must be above the
        /// round-off level of Φ.
        tol: f64,
        /// Gauss–Newton iterations allowed per projection (quadratic convergence:
        /// 2–3 are typical after a step).
        max_iter: usize,
    },
}

impl Drift {
    /// [`Drift::Projection`] with the default tolerance (1e-12) and iteration limit
    /// (10).
    pub fn projection() -> Self {
        Drift::Projection {
            tol: DEFAULT_PROJECTION_TOLERANCE,
            max_iter: DEFAULT_PROJECTION_ITERATIONS,
        }
    }

    /// The projection settings this choice implies: its own for
    /// [`Drift::Projection`], the defaults otherwise (used to repair initial
    /// conditions).
    pub fn projection_settings(&self) -> (f64, usize) {
        match *self {
            Drift::Projection { tol, max_iter } => (tol, max_iter),
            _ => (DEFAULT_PROJECTION_TOLERANCE, DEFAULT_PROJECTION_ITERATIONS),
        }
    }

    /// Checks the parameters: finite and non-negative α, β; positive finite tol
    /// and at least one iteration.
    ///
    /// # Errors
    /// [`Error::Settings`] naming the bad parameter.
    pub fn check(&self) -> Result<(), Error> {
        let value = |setting, value, requirement: &str| SettingsError::Value {
            owner: "drift",
            setting,
            value,
            requirement: requirement.into(),
        };
        let bad = match *self {
            Drift::None => None,
            Drift::Baumgarte { alpha, beta } => {
                [("Baumgarte alpha", alpha), ("Baumgarte beta", beta)]
                    .into_iter()
                    .find(|&(_, x)| !(x.is_finite() && x >= 0.0))
                    .map(|(n, x)| value(n, x, "non-negative and finite"))
            }
            Drift::Projection { tol, .. } if !(tol.is_finite() && tol > 0.0) => {
                Some(value("projection tol", tol, "positive and finite"))
            }
            Drift::Projection { max_iter: 0, .. } => Some(SettingsError::ZeroCount {
                owner: "drift",
                setting: "projection max_iter",
            }),
            Drift::Projection { .. } => None,
        };
        bad.map_or(Ok(()), |e| Err(e.into()))
    }
}

/// Accelerations, multipliers and generalized reactions at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<T: Real, const N: usize, const K: usize> {
    /// q̈.
    pub accelerations: SVector<T, N>,
    /// ν = [λ; μ], one per constraint row (minimum-norm if the rows are redundant
    /// and least squares was enabled).
    pub multipliers: SVector<T, K>,
    /// The generalized constraint forces Gᵀ ν, so that M q̈ + h = Q + Gᵀ ν.
    pub reactions: SVector<T, N>,
}

/// The forward dynamics of a [`Constrained`] system (K constraint rows), as a
/// right-hand side for the integrators.
///
/// ```text
/// [ M  Gᵀ ] [ q̈ ]   [ Q − h ]
/// [ G  0  ] [ −ν ] = [   γ   ]
/// ```
///
/// solved by the range-space method: Cholesky of M (pivot-ratio check as in
/// [`Dynamics`](crate::Dynamics)), then a pivoted Cholesky of the Schur complement
/// G M⁻¹ Gᵀ, whose pivot ratio detects redundant constraints. Everything lives on
/// the stack; nothing is allocated per evaluation except an error.
///
/// `F` is an extra generalized force ΔQ(t, q, q̇) added to Q − h before the
/// solve (see [`Dynamics`](crate::Dynamics) and
/// [`with_forcing`](Self::with_forcing)); the default [`NoForcing`] adds nothing.
#[derive(Debug)]
pub struct ConstrainedDynamics<'a, S, T, const K: usize, F = NoForcing> {
    system: &'a S,
    singular_tolerance: T,
    redundant_tolerance: T,
    least_squares: bool,
    drift: Drift,
    forcing: F,
    /// The system's parameter-only terms, if computed once for the run.
    terms: &'a [T],
}

// Manual impls: derive would demand `S: Clone`, but only a reference is held.
impl<S, T: Copy, const K: usize, F: Copy> Clone for ConstrainedDynamics<'_, S, T, K, F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, T: Copy, const K: usize, F: Copy> Copy for ConstrainedDynamics<'_, S, T, K, F> {}

impl<'a, S, T: Real, const K: usize> ConstrainedDynamics<'a, S, T, K> {
    /// Dynamics of `system` with the default tolerances, no least squares,
    /// [`Drift::None`] and no forcing.
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            singular_tolerance: T::lit(DEFAULT_SINGULAR_TOLERANCE),
            redundant_tolerance: T::lit(DEFAULT_REDUNDANT_TOLERANCE),
            least_squares: false,
            drift: Drift::None,
            forcing: NoForcing,
            terms: &[],
        }
    }
}

impl<'a, S, T: Real, const K: usize, F> ConstrainedDynamics<'a, S, T, K, F> {
    /// The same dynamics with the generalized force `forcing` added to Q − h
    /// (replacing any forcing set before). Inputs never change M, h or the
    /// constraints, so drift control and projections are unaffected.
    pub fn with_forcing<G>(self, forcing: G) -> ConstrainedDynamics<'a, S, T, K, G> {
        ConstrainedDynamics {
            system: self.system,
            singular_tolerance: self.singular_tolerance,
            redundant_tolerance: self.redundant_tolerance,
            least_squares: self.least_squares,
            drift: self.drift,
            forcing,
            terms: self.terms,
        }
    }

    /// The same dynamics reading the system's parameter-only terms from `terms`
    /// (see [`Dynamics::with_parameter_terms`](crate::Dynamics::with_parameter_terms)).
    pub fn with_parameter_terms<'b>(self, terms: &'b [T]) -> ConstrainedDynamics<'b, S, T, K, F>
    where
        'a: 'b,
    {
        // Shortening the borrow is a coercion (the dynamics only hold
        // references), so the rest of the settings carry over as they are.
        let shorter: ConstrainedDynamics<'b, S, T, K, F> = self;
        ConstrainedDynamics { terms, ..shorter }
    }

    /// The forcing in use.
    pub fn forcing(&self) -> &F {
        &self.forcing
    }

    /// Sets the threshold on the mass matrix's pivot ratio (see
    /// [`Dynamics::with_singular_tolerance`](crate::Dynamics::with_singular_tolerance)).
    pub fn with_singular_tolerance(mut self, tolerance: T) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// Sets the threshold on the pivot ratio of G M⁻¹ Gᵀ below which constraint
    /// rows count as redundant (default 1e-12); a negative or non-finite one
    /// is refused ([`Error::Settings`]) at the first evaluation.
    pub fn with_redundant_tolerance(mut self, tolerance: T) -> Self {
        self.redundant_tolerance = tolerance;
        self
    }

    /// With `true`, redundant constraints are accepted and the multipliers are the
    /// minimum-norm ones (the accelerations are unique either way); with `false`
    /// (the default) they are an [`Error::RedundantConstraints`].
    pub fn least_squares(mut self, on: bool) -> Self {
        self.least_squares = on;
        self
    }

    /// Chooses the drift control.
    pub fn drift(mut self, drift: Drift) -> Self {
        self.drift = drift;
        self
    }

    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The drift control in use.
    pub fn drift_control(&self) -> Drift {
        self.drift
    }

    fn schur(&self) -> Schur<T> {
        Schur {
            tolerance: self.redundant_tolerance,
            least_squares: self.least_squares,
        }
    }

    /// Accelerations, multipliers and reactions at (t, q, v). With
    /// [`Drift::Baumgarte`] the accelerations include the stabilisation terms.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] if the state, the system's matrices or the result
    /// are not finite; [`Error::SingularMassMatrix`] if M is not positive definite
    /// or its pivot ratio is below the singular tolerance;
    /// [`Error::RedundantConstraints`] if rows of G are dependent and least squares
    /// is off; whatever the forcing reports (e.g. [`Error::NonFiniteInput`]).
    pub fn solve<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<Solution<T, N, K>, Error>
    where
        S: Constrained<T, N, K, Q>,
        F: Forcing<T, N, Q>,
    {
        if !(t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        // As in `Dynamics`: a stage off the unit sphere reads the rotation
        // it is closest to.
        let unit = on_sphere::<S, T, N, Q>(q);
        let q = &unit;
        check_tolerance(
            "ConstrainedDynamics",
            "singular tolerance",
            self.singular_tolerance.to_f64(),
        )?;
        check_tolerance(
            "ConstrainedDynamics",
            "redundant tolerance",
            self.redundant_tolerance.to_f64(),
        )?;
        let (m, mut f, g, mut gamma) = self.system.constrained_system_with(self.terms, q, v, t);
        if F::ACTIVE {
            f += self.forcing.force(t, q, v)?;
        }
        if let Drift::Baumgarte { alpha, beta } = self.drift {
            let (_, g0) = self.system.constraint_jacobian(q, t);
            let phi = self.system.constraint_positions(q, t);
            let velocity = g * v + g0;
            let two_alpha = T::lit(2.0 * alpha);
            let beta2 = T::lit(beta * beta);
            for i in 0..K {
                gamma[i] -= two_alpha * velocity[i];
                if i < holonomic::<S, T, N, K, Q>() {
                    gamma[i] -= beta2 * phi[i];
                }
            }
        }
        let finite = [m.as_slice(), f.as_slice(), g.as_slice(), gamma.as_slice()];
        if !finite.iter().all(|x| all_finite(x)) {
            return Err(Error::non_finite(t, q, v));
        }
        let chol = self.factor_mass_matrix(t, q, m)?;
        let (a, nu) = range_space(&chol, &g, K, f, &gamma, self.schur())
            .map_err(|d| redundant::<S, T, N, K, Q>(t, q, d))?;
        // Finite inputs with acceptable pivots can still overflow.
        if !(all_finite(a.as_slice()) && all_finite(nu.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Solution {
            accelerations: a,
            multipliers: nu,
            reactions: g.tr_mul(&nu),
        })
    }

    /// The generalized constraint forces Gᵀ ν at (t, q, v).
    ///
    /// # Errors
    /// As [`solve`](Self::solve).
    pub fn reactions<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Constrained<T, N, K, Q>,
        F: Forcing<T, N, Q>,
    {
        Ok(self.solve(t, q, v)?.reactions)
    }

    fn factor_mass_matrix<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        m: nalgebra::SMatrix<T, N, N>,
    ) -> Result<Cholesky<T, N>, Error>
    where
        S: crate::system::Lagrangian<T, N, Q>,
    {
        Cholesky::new(m, self.singular_tolerance)
            .map_err(|ratio| Error::singular_mass(t, q, ratio, &m, (&S::VELOCITIES, S::ATLAS)))
    }
}

/// The number of holonomic rows, clamped to K so that a wrong constant cannot
/// index out of bounds.
fn holonomic<
    S: Constrained<T, N, K, Q>,
    T: Real,
    const N: usize,
    const K: usize,
    const Q: usize,
>() -> usize {
    S::HOLONOMIC.min(K)
}

/// The typed error for dependent rows, with coordinate and constraint names.
fn redundant<
    S: Constrained<T, N, K, Q>,
    T: Real,
    const N: usize,
    const K: usize,
    const Q: usize,
>(
    t: T,
    q: &SVector<T, Q>,
    d: Dependent<T>,
) -> Error {
    Error::RedundantConstraints {
        t: t.to_f64(),
        q: to_vec(q),
        coordinates: S::COORDINATES.to_vec(),
        ratio: d.ratio.to_f64(),
        dependent: d.rows.iter().map(|&i| S::CONSTRAINTS[i]).collect(),
    }
}

impl<S, T, F, const N: usize, const K: usize, const Q: usize> SecondOrder<T, N, Q>
    for ConstrainedDynamics<'_, S, T, K, F>
where
    S: Constrained<T, N, K, Q>,
    T: Real,
    F: Forcing<T, N, Q>,
{
    const ORIENTATIONS: &'static [Orientation] = S::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        Ok(self.solve(t, q, v)?.accelerations)
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.system.integral(&on_sphere::<S, T, N, Q>(q), v, t)
    }

    fn residuals(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> [T; 2] {
        ConstrainedDynamics::residuals(self, t, &on_sphere::<S, T, N, Q>(q), v)
    }

    fn project(&self, t: T, q: &mut SVector<T, Q>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        match self.drift {
            Drift::Projection { tol, max_iter } => {
                self.project_state(t, q, v, T::lit(tol), max_iter)
            }
            Drift::None | Drift::Baumgarte { .. } => Ok(false),
        }
    }
}
