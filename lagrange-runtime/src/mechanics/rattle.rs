//! RATTLE: the symmetric, symplectic extension of Störmer–Verlet to holonomic
//! constraints (Andersen 1983; Hairer, Lubich, Wanner, *Geometric Numerical
//! Integration*, §VII.1.4).
//!
//! ```text
//! v½   = vₙ + h/2 · M⁻¹ (F(qₙ, vₙ) + Φ_q(qₙ)ᵀ λ)
//! qₙ₊₁ = qₙ + h v½                      with λ such that Φ(qₙ₊₁, tₙ₊₁) = 0
//! vₙ₊₁ = v½ + h/2 · M⁻¹ (F(qₙ₊₁, v½) + Φ_q(qₙ₊₁)ᵀ μ)
//!                                       with μ such that Φ_q vₙ₊₁ + Φ_t = 0
//! ```
//!
//! With free orientations (Q ≠ N) the drift is qₙ₊₁ = qₙ ⊕ h v½ (each
//! quaternion turned by exp(h ω½)) and the end kick is implicit in vₙ₊₁
//! (see [`Rattle::integrate`]).
//!
//! F = Q − h is the right-hand side without constraint forces. λ solves a
//! nonlinear system of K equations (Newton with the exact Jacobian
//! Φ_q(qₙ₊₁) M⁻¹ Φ_q(qₙ)ᵀ, iterated to round-off); μ a linear one. Both
//! constraint levels therefore hold to round-off at every step, without any
//! projection or stabilisation, and the method is time-reversible and
//! symplectic on the constraint manifold, so its energy error stays bounded
//! (O(h²)) over long runs instead of drifting.
//!
//! Why a dedicated entry point rather than an [`Integrator`](super::Integrator):
//! the method needs the constraints themselves (Φ and Φ_q separately, not only
//! the accelerations a [`SecondOrder`](super::SecondOrder) system provides), so
//! it takes a [`Constrained`] system directly. A `Simulation` given the study's
//! [`Method::Rattle`](crate::study::Method::Rattle) calls it in the multiplier
//! form, which is how a work-precision study sweeps it.
//!
//! **Assumptions**, checked where they can be: a constant mass matrix (checked
//! at every step; a configuration-dependent M brings Coriolis terms that this
//! splitting does not treat symplectically — use a Hamiltonian formulation),
//! holonomic constraints only (checked: the nonholonomic rows have no position
//! level). With velocity-dependent forces (damping) the method still runs,
//! evaluating F at v½ for the end of the step as Störmer–Verlet does, but is
//! no longer symplectic.

use crate::error::SettingsError;
use crate::error::{Error, Failure, to_vec, unit_quaternions};
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::mechanics::dynamics::DEFAULT_SINGULAR_TOLERANCE;
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation;
use crate::ode::{Continuation, Record, Trajectory};
use crate::ode::{DenseSegment, Pair, Sample, Stats, check_problem, fixed_step_count};
use crate::ode::{Run, fixed_steps};
use crate::system::Constrained;
use nalgebra::{SMatrix, SVector};

/// RATTLE with a fixed step `h` for [`Constrained`] systems with a constant
/// mass matrix and holonomic constraints.
///
/// A pendulum in Cartesian coordinates (unit mass on a unit rod, written by
/// hand here; the derive writes the same traits): RATTLE keeps the bob on its
/// rod to round-off over a thousand steps.
///
/// ```
/// # use lagrange_runtime::{Constrained, Lagrangian, Rattle};
/// # use nalgebra::{Matrix1x2, Matrix2, Vector1, Vector2};
/// # struct Bob;
/// # impl Lagrangian<f64, 2> for Bob {
/// #     const COORDINATES: [&'static str; 2] = ["x", "y"];
/// #     const RHEONOMIC: bool = false;
/// #     const CONSTRAINED: bool = true;
/// #     fn visit_form<F: lagrange_runtime::FormVisitor<f64, 2, Self>>(&self, f: F) -> F::Output {
/// #         f.multipliers::<1>(self)
/// #     }
/// #     fn mass_matrix(&self, _: &Vector2<f64>, _: f64) -> Matrix2<f64> { Matrix2::identity() }
/// #     fn bias(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::zeros() }
/// #     fn generalized_forces(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::new(0.0, -9.81) }
/// #     fn mass_matrix_and_rhs(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> (Matrix2<f64>, Vector2<f64>) {
/// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
/// #     }
/// #     fn kinetic_energy(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> f64 { 0.5 * v.norm_squared() }
/// #     fn potential_energy(&self, q: &Vector2<f64>, _: f64) -> f64 { 9.81 * q[1] }
/// #     fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
/// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
/// #     }
/// #     fn rhs_jacobians(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: &Vector2<f64>, _: f64)
/// #         -> Option<(Matrix2<f64>, Matrix2<f64>)> { Some((Matrix2::zeros(), Matrix2::zeros())) }
/// # }
/// # impl Constrained<f64, 2, 1> for Bob {
/// #     const CONSTRAINTS: [&'static str; 1] = ["rod"];
/// #     const HOLONOMIC: usize = 1;
/// #     fn constraint_positions(&self, q: &Vector2<f64>, _: f64) -> Vector1<f64> { Vector1::new(q.norm_squared() - 1.0) }
/// #     fn constraint_jacobian(&self, q: &Vector2<f64>, _: f64) -> (Matrix1x2<f64>, Vector1<f64>) {
/// #         (Matrix1x2::new(2.0 * q[0], 2.0 * q[1]), Vector1::zeros())
/// #     }
/// #     fn constraint_rhs(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> Vector1<f64> { Vector1::new(-2.0 * v.norm_squared()) }
/// #     fn constrained_system(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64)
/// #         -> (Matrix2<f64>, Vector2<f64>, Matrix1x2<f64>, Vector1<f64>) {
/// #         let (m, f) = self.mass_matrix_and_rhs(q, v, t);
/// #         (m, f, self.constraint_jacobian(q, t).0, self.constraint_rhs(q, v, t))
/// #     }
/// #     fn constraint_derivatives(&self, _: &Vector2<f64>, v: &Vector2<f64>, a: &Vector2<f64>, nu: &Vector1<f64>, _: f64)
/// #         -> Option<(Matrix2<f64>, Matrix1x2<f64>, Matrix1x2<f64>, Matrix1x2<f64>)> {
/// #         Some((Matrix2::identity() * (2.0 * nu[0]), -2.0 * a.transpose(), -4.0 * v.transpose(), 2.0 * v.transpose()))
/// #     }
/// # }
/// let (q0, v0) = (Vector2::new(0.3_f64.sin(), -0.3_f64.cos()), Vector2::zeros());
/// let traj = Rattle::step(1e-2).integrate(&Bob, 0.0, 10.0, q0, v0)?;
/// assert!(traj.max_residuals()[0] < 1e-13);
/// # Ok::<(), lagrange_runtime::Failure<lagrange_runtime::Trajectory<f64, 2>>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rattle {
    h: f64,
    max_steps: usize,
    max_iterations: usize,
    consistency_tolerance: f64,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Rattle {
    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// RATTLE with step size `h`.
    pub fn step(h: f64) -> Self {
        Self {
            record: Record::Steps,
            h,
            max_steps: 10_000_000,
            max_iterations: 20,
            consistency_tolerance: crate::mechanics::constraint::DEFAULT_CONSISTENCY_TOLERANCE,
        }
    }

    /// Refuses spans that need more than `n` steps (default 10⁷), before starting.
    pub fn max_steps(mut self, n: usize) -> Self {
        self.max_steps = n;
        self
    }

    /// Newton iterations allowed for λ per step (default 20; it converges
    /// quadratically, typically in 3–4).
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// Tolerance of the check that the initial state satisfies the
    /// constraints at both levels (default 1e-10).
    pub fn consistency_tolerance(mut self, tol: f64) -> Self {
        self.consistency_tolerance = tol;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> f64 {
        self.h
    }

    /// The step budget set by [`max_steps`](Self::max_steps).
    pub fn step_budget(&self) -> usize {
        self.max_steps
    }

    /// Integrates `system` from the consistent state (q0, v0) at t0 to t1.
    ///
    /// With free orientations (Q ≠ N: q holds unit quaternions, v the
    /// body-axis angular velocities) the drift is q ⊕ h v½ (each quaternion
    /// turned by exp(h ω½)), λ is found by Newton through the exponential's
    /// right Jacobian, and the end kick is solved for vₙ₊₁ by fixed-point
    /// iteration, F(qₙ₊₁, vₙ₊₁) (the gyroscopic terms ω × Iω make F depend on
    /// ω, and the explicit F(qₙ₊₁, v½) would leave the method first order):
    /// the step is the symmetric composition of an explicit and an implicit
    /// half kick around the drift, second order, both constraint levels held
    /// to round-off. The mass matrix in ω must still be constant (a body's
    /// inertia in body axes is; its centre of mass must be its reference
    /// point).
    ///
    /// # Errors
    /// [`Error::Settings`] for a bad step, span or initial state, a
    /// system with nonholonomic rows, or a mass matrix that changes along the
    /// motion; [`Error::InconsistentInitialConditions`];
    /// [`Error::NonUnitQuaternion`]; [`Error::SingularMassMatrix`];
    /// [`Error::RedundantConstraints`] when Φ_q M⁻¹ Φ_qᵀ is singular;
    /// [`Error::NewtonFailure`] when λ (or, with orientations, vₙ₊₁) does not
    /// converge (the step is too large); [`Error::NonFiniteState`].
    #[allow(clippy::type_complexity)]
    pub fn integrate<S, T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        system: &S,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>
    where
        S: Constrained<T, N, K, Q>,
    {
        let dynamics = ConstrainedDynamics::<S, T, K>::new(system);
        let sample = Sample::of(&dynamics, t0, &q0, &v0);
        let mut run = Run::start(self.record, Continuation::start(t0), t0, q0, v0, sample);
        // Everything computed before a failure goes back with it.
        let outcome = self.run(system, &dynamics, (t0, t1), (q0, v0), &mut run);
        run.finish(outcome)
    }

    /// Checks the settings, the problem and the initial state, then takes the
    /// fixed steps.
    fn run<S, T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        system: &S,
        dynamics: &ConstrainedDynamics<S, T, K>,
        (t0, t1): (T, T),
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        self.record.check_span(t0, t1, Q + N)?;
        check_problem(t0, t1, &q0, &v0)?;
        let n = fixed_step_count("RATTLE", self.h, self.max_steps, t0, t1)?;
        self.check_settings::<S, T, N, K, Q>()?;
        let q0 = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q0)?;
        dynamics.check_consistency(t0, &q0, &v0, T::lit(self.consistency_tolerance))?;
        let m0 = system.mass_matrix(&q0, t0);
        // The constant mass matrix, factorised and judged as the dynamics do.
        let tolerance = T::lit(DEFAULT_SINGULAR_TOLERANCE);
        let chol = Cholesky::new(m0, tolerance).map_err(|ratio| {
            Error::singular_mass(t0, &q0, ratio, &m0, (&S::VELOCITIES, S::ATLAS))
        })?;
        run.traj.reserve(n);
        let h = T::lit(self.h);
        let mut q = q0;
        let mut v = v0;
        let (_, mut f) = system.mass_matrix_and_rhs(&q, &v, t0);
        run.stats.evaluations += 1;
        // Φ_q at the current point: computed once, at the end of the step that
        // reaches it.
        let (mut g_n, _) = system.constraint_jacobian(&q, t0);
        for (t, t_next) in fixed_steps(t0, t1, h, n) {
            let (q_next, v_next, g_next, segment) = self.advance(
                system,
                (&m0, &chol),
                (t, t_next),
                (&q, &v, &f),
                &g_n,
                &mut run.stats,
            )?;
            run.push(dynamics, segment, q_next, v_next);
            run.stats.accepted += 1;
            // F at the end of the step with the final velocity: the next
            // step's first kick.
            f = system.mass_matrix_and_rhs(&q_next, &v_next, t_next).1;
            run.stats.evaluations += 1;
            (q, v, g_n) = (q_next, v_next, g_next);
        }
        Ok(())
    }

    /// Nonholonomic rows, Newton iterations and the consistency tolerance.
    fn check_settings<S, T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
    ) -> Result<(), Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        if S::HOLONOMIC != K {
            return Err(SettingsError::Unsupported {
                owner: "RATTLE",
                needs: "holonomic constraints only".into(),
                remedy: format!(
                    "{} of the {K} constraints ({:?}) are nonholonomic; choose another integrator",
                    K - S::HOLONOMIC,
                    &S::CONSTRAINTS[S::HOLONOMIC..]
                ),
            }
            .into());
        }
        if self.max_iterations == 0 {
            let setting = "max_iterations";
            return Err(SettingsError::ZeroCount {
                owner: "RATTLE",
                setting,
            }
            .into());
        }
        let tol = self.consistency_tolerance;
        if !(tol.is_finite() && tol > 0.0) {
            return Err(SettingsError::Value {
                owner: "RATTLE",
                setting: "consistency tolerance",
                value: tol,
                requirement: "positive and finite".into(),
            }
            .into());
        }
        Ok(())
    }

    /// One RATTLE step from (q, v) at t, with F = `f` and Φ_q = `g_n` there, to
    /// t_next: the new state, Φ_q there, and the step's dense output (the cubic
    /// Hermite interpolant with the constrained accelerations at both ends).
    #[allow(clippy::type_complexity)]
    fn advance<S, T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        system: &S,
        (m0, chol): (&SMatrix<T, N, N>, &Cholesky<T, N>),
        (t, t_next): (T, T),
        (q, v, f): (&SVector<T, Q>, &SVector<T, N>, &SVector<T, N>),
        g_n: &SMatrix<T, K, N>,
        stats: &mut Stats,
    ) -> Result<
        (
            SVector<T, Q>,
            SVector<T, N>,
            SMatrix<T, K, N>,
            DenseSegment<T, N, Q>,
        ),
        Error,
    >
    where
        S: Constrained<T, N, K, Q>,
    {
        let half = T::lit(0.5);
        let hk = t_next - t;
        // M⁻¹ Φ_q(qₙ)ᵀ, one column per constraint.
        let minv_gt = chol.solve_columns(g_n.transpose());
        // Position step: qₙ ⊕ (δ̂ + M⁻¹ Φ_q(qₙ)ᵀ Λ) with Λ = h²/2 λ.
        let a_free = chol.solve(*f);
        let drift = v * hk + a_free * (half * hk * hk);
        let ((q_next, delta), lambda) =
            self.solve_positions(system, (t, hk, t_next), q, &drift, &minv_gt)?;
        let v_half = delta / hk;
        // The constraint force over the first half step, as an acceleration.
        let a_start = a_free + minv_gt * (lambda * (T::lit(2.0) / (hk * hk)));
        let (m_next, f_half) = system.mass_matrix_and_rhs(&q_next, &v_half, t_next);
        stats.evaluations += 1;
        check_constant_mass(m0, &m_next, t_next, &q_next)?;
        let (v_next, a_end, g_next) = self.end_kick(
            system,
            chol,
            (t_next, hk),
            (&q_next, &v_half, f_half),
            stats,
        )?;
        if !(all_finite(&q_next) && all_finite(&v_next)) {
            return Err(Error::non_finite(t_next, &q_next, &v_next));
        }
        let rate = |q: &SVector<T, Q>, v: &SVector<T, N>| {
            let mut out = SVector::<T, Q>::zeros();
            orientation::rate(
                S::ORIENTATIONS,
                q.as_slice(),
                v.as_slice(),
                out.as_mut_slice(),
            );
            out
        };
        let segment = DenseSegment::hermite(
            t,
            t_next,
            &Pair::new(*q, *v),
            &Pair::new(rate(q, v), a_start),
            &Pair::new(q_next, v_next),
            &Pair::new(rate(&q_next, &v_next), a_end),
        );
        Ok((q_next, v_next, g_next, segment))
    }

    /// The second half kick at qₙ₊₁: vₙ₊₁ = v½ + h/2 M⁻¹(F + Gᵀ μ) with μ
    /// such that G vₙ₊₁ + g = 0 (linear in Μ = h/2 μ), F = `f_half` at v½;
    /// with orientations F is re-evaluated at vₙ₊₁ until vₙ₊₁ stops moving
    /// (fixed-point iteration; [`Error::NewtonFailure`] if it does not
    /// settle within the iteration limit). Returns vₙ₊₁, the constrained
    /// acceleration there and Φ_q(qₙ₊₁).
    #[allow(clippy::type_complexity)]
    fn end_kick<S, T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        system: &S,
        chol: &Cholesky<T, N>,
        (t_next, hk): (T, T),
        (q_next, v_half, f_half): (&SVector<T, Q>, &SVector<T, N>, SVector<T, N>),
        stats: &mut Stats,
    ) -> Result<(SVector<T, N>, SVector<T, N>, SMatrix<T, K, N>), Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        let half = T::lit(0.5);
        let (g_next, g_t) = system.constraint_jacobian(q_next, t_next);
        let minv_gt_next = chol.solve_columns(g_next.transpose());
        let schur = g_next * minv_gt_next;
        let eps = T::default_epsilon();
        let mut f = f_half;
        let mut previous = T::max_value().unwrap_or(T::one() / eps);
        for _ in 0..self.max_iterations {
            let a_free_next = chol.solve(f);
            let v_hat = v_half + a_free_next * (half * hk);
            let rhs = -(g_next * v_hat + g_t);
            let mu = solve_square(schur, &rhs)
                .ok_or_else(|| redundant::<S, T, N, K, Q>(t_next, q_next))?;
            let v_next = v_hat + minv_gt_next * mu;
            let a_end = a_free_next + minv_gt_next * (mu * (T::lit(2.0) / hk));
            if S::ORIENTATIONS.is_empty() {
                return Ok((v_next, a_end, g_next));
            }
            let f_next = system.mass_matrix_and_rhs(q_next, &v_next, t_next).1;
            stats.evaluations += 1;
            let size = chol.solve(f_next - f).amax() * half * hk / (T::one() + v_next.amax());
            f = f_next;
            if size <= T::lit(4.0) * eps || (size >= previous && size <= T::lit(1e3) * eps) {
                return Ok((v_next, a_end, g_next));
            }
            previous = size;
        }
        Err(Error::NewtonFailure {
            t: t_next.to_f64(),
            h: hk.to_f64(),
            iterations: self.max_iterations,
        })
    }

    /// Newton on Φ(qₙ ⊕ δ(Λ), t₁) = 0, δ(Λ) = δ̂ + M⁻¹Gₙᵀ Λ, with the exact
    /// Jacobian Φ_q(q(Λ)) J_r(δ) M⁻¹ Gₙᵀ (J_r the exponential's right
    /// Jacobian on each orientation's three entries, the identity
    /// elsewhere); returns (q(Λ), δ(Λ)) and Λ. Stops when the correction no
    /// longer shrinks at round-off level.
    #[allow(clippy::type_complexity)]
    fn solve_positions<S, T: Real, const N: usize, const K: usize, const Q: usize>(
        &self,
        system: &S,
        (t, h, t1): (T, T, T),
        q_n: &SVector<T, Q>,
        drift: &SVector<T, N>,
        minv_gt: &SMatrix<T, N, K>,
    ) -> Result<((SVector<T, Q>, SVector<T, N>), SVector<T, K>), Error>
    where
        S: Constrained<T, N, K, Q>,
    {
        let eps = T::default_epsilon();
        let mut lambda = SVector::<T, K>::zeros();
        let mut delta = *drift;
        let mut q = orientation::plus(S::ORIENTATIONS, q_n, &delta);
        let mut previous = T::max_value().unwrap_or(T::one() / eps);
        for _ in 0..self.max_iterations {
            let phi = system.constraint_positions(&q, t1);
            let (g, _) = system.constraint_jacobian(&q, t1);
            let along = through_exp::<S, T, N, K, Q>(&delta, minv_gt);
            let step = solve_square(g * along, &(-phi))
                .ok_or_else(|| redundant::<S, T, N, K, Q>(t1, &q))?;
            lambda += step;
            delta = drift + minv_gt * lambda;
            q = orientation::plus(S::ORIENTATIONS, q_n, &delta);
            let size = (minv_gt * step).amax() / (T::one() + q.amax());
            if !size.is_finite() {
                break;
            }
            // Converged: the last correction moved q by round-off only, or
            // stopped shrinking there.
            if size <= T::lit(4.0) * eps || (size >= previous && size <= T::lit(1e3) * eps) {
                return Ok(((q, delta), lambda));
            }
            previous = size;
        }
        Err(Error::NewtonFailure {
            t: t.to_f64(),
            h: h.to_f64(),
            iterations: self.max_iterations,
        })
    }
}

/// J_r(δ) x: each orientation's three rows of `x` turned by the right
/// Jacobian of exp at its δ, the others as they are.
fn through_exp<S, T: Real, const N: usize, const K: usize, const Q: usize>(
    delta: &SVector<T, N>,
    x: &SMatrix<T, N, K>,
) -> SMatrix<T, N, K>
where
    S: Constrained<T, N, K, Q>,
{
    let mut out = *x;
    for o in S::ORIENTATIONS {
        let jr = orientation::right_jacobian([delta[o.v], delta[o.v + 1], delta[o.v + 2]]);
        for c in 0..K {
            for (i, row) in jr.iter().enumerate() {
                out[(o.v + i, c)] = (0..3).fold(T::zero(), |s, k| s + row[k] * x[(o.v + k, c)]);
            }
        }
    }
    out
}

fn all_finite<T: Real, const N: usize>(x: &SVector<T, N>) -> bool {
    x.iter().all(|c| c.is_finite())
}

/// Solves the K×K system a x = b by Gaussian elimination with partial
/// pivoting on the stack (nalgebra's LU needs a type-level dimension that a
/// generic `const K` cannot name); `None` if `a` is singular.
fn solve_square<T: Real, const K: usize>(
    mut a: SMatrix<T, K, K>,
    b: &SVector<T, K>,
) -> Option<SVector<T, K>> {
    let mut x = *b;
    for col in 0..K {
        let pivot = (col..K).max_by(|&i, &j| {
            a[(i, col)]
                .abs()
                .partial_cmp(&a[(j, col)].abs())
                .unwrap_or(std::cmp::Ordering::Equal)
        })?;
        if a[(pivot, col)] == T::zero() || !a[(pivot, col)].is_finite() {
            return None;
        }
        a.swap_rows(pivot, col);
        x.swap_rows(pivot, col);
        for row in col + 1..K {
            let factor = a[(row, col)] / a[(col, col)];
            for c in col..K {
                let sub = factor * a[(col, c)];
                a[(row, c)] -= sub;
            }
            let sub = factor * x[col];
            x[row] -= sub;
        }
    }
    for row in (0..K).rev() {
        let mut s = x[row];
        for c in row + 1..K {
            s -= a[(row, c)] * x[c];
        }
        x[row] = s / a[(row, row)];
    }
    x.iter().all(|c| c.is_finite()).then_some(x)
}

/// Φ_q M⁻¹ Φ_qᵀ singular: the constraints are dependent at q.
fn redundant<S, T: Real, const N: usize, const K: usize, const Q: usize>(
    t: T,
    q: &SVector<T, Q>,
) -> Error
where
    S: Constrained<T, N, K, Q>,
{
    Error::RedundantConstraints {
        t: t.to_f64(),
        q: to_vec(q),
        coordinates: S::COORDINATES.to_vec(),
        ratio: 0.0,
        dependent: S::CONSTRAINTS.to_vec(),
    }
}

/// RATTLE's splitting assumes M constant; a change beyond round-off is an error.
fn check_constant_mass<T: Real, const N: usize, const Q: usize>(
    m0: &SMatrix<T, N, N>,
    m: &SMatrix<T, N, N>,
    t: T,
    q: &SVector<T, Q>,
) -> Result<(), Error> {
    let scale = m0.amax();
    let change = (m - m0).amax();
    if change <= T::lit(1e-12) * scale {
        return Ok(());
    }
    Err(SettingsError::Unsupported {
        owner: "RATTLE",
        needs: "a constant mass matrix".into(),
        remedy: format!(
            "M changed by {:e} (relative) at t = {}, q = {:?}; use a Cartesian model or \
             another integrator",
            (change / scale).to_f64(),
            t.to_f64(),
            to_vec(q)
        ),
    }
    .into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    #[test]
    fn elimination_with_pivoting() {
        // A zero leading entry needs the row swap.
        let a = Matrix3::new(0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0);
        let x = Vector3::new(1.0, -2.0, 0.5);
        let got = solve_square(a, &(a * x)).unwrap();
        assert!((got - x).amax() < 1e-15, "{got}");
        let singular = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
        assert!(solve_square(singular, &x).is_none());
    }
}
