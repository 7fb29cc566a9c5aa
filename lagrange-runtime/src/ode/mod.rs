//! Integrators for the second-order system q̇ = v, v̇ = a(t, q, v).
//!
//! The state is the pair (q, v) of `SVector<T, N>`: a `2N` vector cannot be named
//! with const generics on stable Rust, so Runge–Kutta stages are pairs too. All
//! stages live on the stack; an integration allocates only the growing
//! [`Trajectory`].
//!
//! - [`Rk4`]: classic fixed-step Runge–Kutta of order 4.
//! - [`Dopri5`]: Dormand–Prince 5(4) with Hairer's step-size control, stiffness
//!   test and Shampine's dense output of order 4.
//! - [`Dop853`]: Dormand–Prince 8(5,3), the same control with its own error
//!   estimate and a 7th-order dense output, for tight tolerances.
//! - [`Radau5`]: Radau IIA of order 5, implicit, for stiff systems.
//! - [`Gauss`]: Gauss–Legendre collocation in canonical (q, P), symplectic.
//! - [`StormerVerlet`]: velocity Verlet with a fixed step, symplectic.
//! - [`Rattle`](crate::Rattle): RATTLE for [`Constrained`](crate::Constrained) systems with
//!   holonomic constraints (its own entry point: it needs Φ, not only a).
//!
//! DOPRI5 and DOP853 run in one loop, `explicit`, as Hairer's two codes share
//! theirs: step-size control, first step, stiffness test, dense output,
//! recording and failure; each method file holds its tableau, its stages, its
//! error estimate and its continuous extension. Every run records through
//! `run::Run`, which returns the partial trajectory with a failure.
//!
//! New integrators implement [`Integrator`]; a new explicit embedded method
//! implements `explicit::EmbeddedMethod`.

mod canonical;
mod dense;
mod dop853;
mod dopri5;
mod explicit;
mod gauss;
mod mechanical;
mod moreau;
mod radau5;
mod record;
mod rk4;
mod run;
mod settings;
mod trajectory;
mod verlet;

pub use dense::DenseSegment;
pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use gauss::Gauss;
pub use mechanical::Mechanical;
pub use moreau::MoreauJean;
pub(crate) use moreau::midpoint_segment;
pub use radau5::Radau5;
pub use record::{Continuation, Record};
pub use rk4::Rk4;
pub(crate) use run::{Run, fixed_steps};
pub use trajectory::Trajectory;
pub use verlet::StormerVerlet;
pub(crate) use verlet::fixed_step_count;

use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation};
use nalgebra::{SMatrix, SVector};

/// The right-hand side of a second-order system q̈ = a(t, q, q̇).
///
/// Implemented by [`Dynamics`](crate::Dynamics); tests and users can implement it
/// directly for any second-order ODE.
pub trait SecondOrder<T: Real, const N: usize, const Q: usize = N> {
    /// Where unit quaternions sit in q (see [`crate::numeric::orientation`]):
    /// none unless overridden, and then Q = N. With them, q̇ is not v but
    /// [`rate`](Self::rate), every integrator steps the quaternions in
    /// R⁴ and normalises them after each step, and a trajectory's dense
    /// output is normalised where it is read.
    const ORIENTATIONS: &'static [Orientation] = &[];

    /// The acceleration a(t, q, v).
    ///
    /// # Errors
    /// Whatever the right-hand side cannot evaluate: a singular mass matrix, a
    /// non-finite state.
    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>;

    /// q̇ at (q, v): v itself for ordinary coordinates, ½ q ⊗ (0, ω) for a
    /// quaternion.
    fn rate(&self, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, Q> {
        const {
            assert!(
                orientation::fits(Self::ORIENTATIONS, Q, N),
                "ORIENTATIONS does not fit: nq must be nv + 1 per orientation, each quaternion's four slots in q after the coordinates before it, its ω at the same place in v"
            )
        };
        let mut out = SVector::<T, Q>::zeros();
        if Self::ORIENTATIONS.is_empty() {
            out.as_mut_slice().copy_from_slice(v.as_slice());
        } else {
            orientation::rate(
                Self::ORIENTATIONS,
                q.as_slice(),
                v.as_slice(),
                out.as_mut_slice(),
            );
        }
        out
    }

    /// q ⊕ δ: q moved by the tangent vector δ, an orientation turned by the
    /// rotation vector δ in body axes (q ⊗ exp(δ)); q + δ without orientations.
    fn advance(&self, q: &SVector<T, Q>, delta: &SVector<T, N>) -> SVector<T, Q> {
        orientation::plus(Self::ORIENTATIONS, q, delta)
    }

    /// A quantity recorded at every accepted step as an accuracy diagnostic (the
    /// energy or Jacobi integral). Zero unless overridden.
    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        let _ = (t, q, v);
        T::zero()
    }

    /// Constraint residuals recorded at every accepted step: the largest position
    /// residual |Φ(q,t)|∞ and the largest velocity residual |G q̇ + g|∞. Zero for an
    /// unconstrained system.
    fn residuals(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> [T; 2] {
        let _ = (t, q, v);
        [T::zero(); 2]
    }

    /// Called by every integrator after each accepted step: may move the state back
    /// onto a manifold (projection onto the constraints, or recomputing dependent
    /// velocities in a reduced nonholonomic form). Returns whether the state was
    /// changed, so that integrators that reuse the last stage (FSAL) re-evaluate it.
    ///
    /// # Errors
    /// A projection that does not converge, or a right-hand side failure.
    fn project(&self, t: T, q: &mut SVector<T, Q>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        let _ = (t, q, v);
        Ok(false)
    }

    /// Called by every integrator after each accepted step, once
    /// [`project`](Self::project) has run: `segment` is the step's dense output and
    /// (q, v) the state recorded at its end. Returning `Ok(true)` ends the
    /// integration after this step, so the trajectory ends at `segment.end()`
    /// instead of the requested end time; an error aborts the run. The default
    /// never stops.
    ///
    /// This is the event layer's hook ([`Events`](crate::Events)): it watches the
    /// event functions on each step and stops the integrator at the first step
    /// that holds an event which changes the state or ends the run. A hook rather
    /// than chunked re-integration, because the integrator must not step past an
    /// impact: beyond it the state may be meaningless (outside a wall, past a
    /// chart singularity).
    ///
    /// # Errors
    /// Whatever the observer cannot evaluate (a non-finite event function).
    fn after_step(
        &self,
        segment: &DenseSegment<T, N, Q>,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<bool, Error> {
        let _ = (segment, q, v);
        Ok(false)
    }

    /// The same system in Hamilton's form, if it has one: what the symplectic
    /// [`Gauss`] integrator needs. `None` unless overridden;
    /// [`Dynamics`](crate::Dynamics) returns itself.
    fn mechanical(&self) -> Option<&dyn Mechanical<T, N, Q>> {
        None
    }

    /// The Jacobian blocks (∂a/∂q, ∂a/∂v) at (t, q, v), if the system can compute
    /// them; `None` (the default) makes the implicit integrators use finite
    /// differences.
    #[allow(clippy::type_complexity)]
    fn jacobian(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Option<Result<(SMatrix<T, N, Q>, SMatrix<T, N, N>), Error>> {
        let _ = (t, q, v);
        None
    }
}

/// What a trajectory records at each point besides the state.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Sample<T> {
    /// The conserved quantity ([`SecondOrder::integral`]).
    pub integral: T,
    /// Position and velocity constraint residuals ([`SecondOrder::residuals`]).
    pub residuals: [T; 2],
    /// The largest | |q_k| − 1 | over the orientation quaternions (zero
    /// without any): round-off, since every integrator normalises them.
    pub unit_error: T,
}

impl<T: Real> Sample<T> {
    /// Samples `rhs` at (t, q, v).
    pub fn of<const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        rhs: &F,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Self {
        Self {
            integral: rhs.integral(t, q, v),
            residuals: rhs.residuals(t, q, v),
            unit_error: orientation::unit_error(F::ORIENTATIONS, q.as_slice()),
        }
    }
}

/// A method that integrates a [`SecondOrder`] system over a time span.
///
/// The integrator's settings are plain `f64`s (a tolerance needs no more), converted
/// to the system's scalar when a run starts.
pub trait Integrator {
    /// Integrates from (t0, q0, v0) to t1 > t0 and records the accepted steps
    /// as the integrator's [`Record`] says.
    ///
    /// # Errors
    /// A [`Failure`] holding the error and the trajectory up to the last
    /// accepted step (at least the initial state). The error is
    /// [`Error::Settings`] for invalid settings (a recording that would
    /// exceed [`Record::MAX_POINTS`] among them), a span that is empty,
    /// reversed or not finite, or a non-finite initial state; any error of the
    /// right-hand side; [`Error::StepSizeUnderflow`] and [`Error::TooManySteps`] for
    /// adaptive methods.
    fn integrate<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>> {
        self.continue_run(rhs, Continuation::start(t0), t0, t1, q0, v0)
    }

    /// [`integrate`](Self::integrate) as the next piece of a run whose
    /// recording stands at `from` (the [`Trajectory::continuation`] of the run
    /// so far): the drivers of events and controlled runs integrate piece by
    /// piece this way, so that the pieces record as one run.
    ///
    /// # Errors
    /// As [`integrate`](Self::integrate).
    fn continue_run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        from: Continuation<T>,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>>;

    /// The step budget of one run (`.max_steps(n)`): a run made of pieces
    /// spends it across all of them.
    fn max_steps(&self) -> usize;

    /// The integrator as a value a run can inspect, for a method that is not
    /// only an integrator of accelerations: the study's `Method` holds RATTLE,
    /// which a run of a constrained system hands the constraints themselves.
    /// `None` (the default) for a method that only integrates a
    /// [`SecondOrder`] problem, as every method of this module does.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        None
    }
}

/// Work done by one integration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Stats {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps (all of them, including those before the first acceptance,
    /// which Hairer's DOPRI5 does not count).
    pub rejected: usize,
    /// Evaluations of the right-hand side (accelerations), including those spent
    /// on finite-difference Jacobians.
    pub evaluations: usize,
    /// Jacobian evaluations (analytic or by finite differences) of the implicit
    /// methods; zero for explicit ones.
    pub jacobians: usize,
    /// LU factorisations of the implicit methods' iteration matrices (a complex
    /// factorisation counts as one); zero for explicit ones.
    pub factorizations: usize,
    /// Wall-clock time of the integration, measured around the whole run
    /// (trajectory recording included); zero on targets without a clock
    /// (`wasm32-unknown-unknown`), where everything else runs the same.
    pub wall_time: std::time::Duration,
}

impl Stats {
    /// Adds the work of another run (the pieces of a run restarted at events).
    pub fn add(&mut self, other: &Stats) {
        self.accepted += other.accepted;
        self.rejected += other.rejected;
        self.evaluations += other.evaluations;
        self.jacobians += other.jacobians;
        self.factorizations += other.factorizations;
        self.wall_time += other.wall_time;
    }

    /// Attempted steps: accepted + rejected.
    pub fn steps(&self) -> usize {
        self.accepted + self.rejected
    }
}

/// A point of the phase space, or a derivative of one (then `q` holds q̇ = v and
/// `v` holds v̇ = a).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Pair<T: Real, const N: usize, const Q: usize = N> {
    pub q: SVector<T, Q>,
    pub v: SVector<T, N>,
}

impl<T: Real, const N: usize, const Q: usize> Pair<T, N, Q> {
    pub fn new(q: SVector<T, Q>, v: SVector<T, N>) -> Self {
        Self { q, v }
    }

    pub fn zeros() -> Self {
        Self::new(SVector::zeros(), SVector::zeros())
    }

    /// The derivative (q̇, a(t, q, v)) of this state, q̇ = v for ordinary
    /// coordinates.
    pub fn derivative<F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        t: T,
        evaluations: &mut usize,
    ) -> Result<Self, Error> {
        *evaluations += 1;
        let a = rhs.acceleration(t, &self.q, &self.v)?;
        Ok(Self::new(rhs.rate(&self.q, &self.v), a))
    }

    /// self + h Σ_j c_j k_j, the Runge–Kutta stage combination.
    ///
    /// Written as plain loops over slices: the same expression with nalgebra
    /// operators builds a temporary per term, which dominates debug builds.
    #[inline]
    pub fn add_combination<const K: usize>(&self, h: T, c: [T; K], k: [&Self; K]) -> Self {
        let mut out = *self;
        combine(out.q.as_mut_slice(), h, &c, &k.map(|p| p.q.as_slice()));
        combine(out.v.as_mut_slice(), h, &c, &k.map(|p| p.v.as_slice()));
        out
    }

    /// h Σ_j c_j k_j.
    #[inline]
    pub fn combination<const K: usize>(h: T, c: [T; K], k: [&Self; K]) -> Self {
        Self::zeros().add_combination(h, c, k)
    }

    pub fn sub(&self, other: &Self) -> Self {
        Self::new(self.q - other.q, self.v - other.v)
    }

    pub fn scale(&self, s: T) -> Self {
        Self::new(self.q * s, self.v * s)
    }

    pub fn is_finite(&self) -> bool {
        self.q.iter().chain(self.v.iter()).all(|x| x.is_finite())
    }
}

#[inline]
fn combine<T: Real, const K: usize>(out: &mut [T], h: T, c: &[T; K], k: &[&[T]; K]) {
    for (i, o) in out.iter_mut().enumerate() {
        let mut s = T::zero();
        for j in 0..K {
            s += c[j] * k[j][i];
        }
        *o += h * s;
    }
}

/// What every integrator does after an accepted step: the quaternions back to
/// unit norm (the projection that keeps a Runge–Kutta method's order, since
/// the exact flow keeps |q| = 1 and the step leaves it only by its local
/// error), then the system's own [`project`](SecondOrder::project). Returns
/// what `project` returns: normalising moves the state by the local error
/// only, so a derivative kept from before it (FSAL) stays within that error.
///
/// # Errors
/// As [`project`](SecondOrder::project).
pub(crate) fn settle<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    t: T,
    q: &mut SVector<T, Q>,
    v: &mut SVector<T, N>,
) -> Result<bool, Error> {
    orientation::normalise(F::ORIENTATIONS, q.as_mut_slice());
    rhs.project(t, q, v)
}

/// Checks a start with orientations: each quaternion is a rotation (finite,
/// within
/// [`UNIT_TOLERANCE`](orientation::UNIT_TOLERANCE) of unit norm). The
/// simulation builders check and normalise before (naming the body); this
/// is the integrators' own check, for a [`SecondOrder`] used directly.
///
/// (The layout itself is checked at compile time, in [`SecondOrder::rate`].)
///
/// # Errors
/// [`Error::NonUnitQuaternion`] naming the quaternion by its place in q.
pub(crate) fn check_orientations<
    T: Real,
    const N: usize,
    const Q: usize,
    F: SecondOrder<T, N, Q>,
>(
    _: &F,
    q0: &SVector<T, Q>,
) -> Result<(), Error> {
    if let Some((o, norm)) = orientation::first_off_unit(F::ORIENTATIONS, q0.as_slice()) {
        return Err(Error::NonUnitQuaternion {
            orientation: format!("the quaternion at q[{}]", o.q),
            norm,
            tolerance: orientation::UNIT_TOLERANCE,
        });
    }
    Ok(())
}

/// Checks what every integrator needs: a finite, non-empty, forward time span and
/// a finite initial state.
pub fn check_problem<T: Real, const N: usize, const Q: usize>(
    t0: T,
    t1: T,
    q0: &SVector<T, Q>,
    v0: &SVector<T, N>,
) -> Result<(), Error> {
    if !(t0.is_finite() && t1.is_finite()) || t1 <= t0 {
        let start = t0.to_f64();
        let end = t1.to_f64();
        return Err(SettingsError::TimeSpan { start, end }.into());
    }
    if !Pair::new(*q0, *v0).is_finite() {
        let q = crate::error::to_vec(q0);
        let v = crate::error::to_vec(v0);
        return Err(SettingsError::InitialState { q, v }.into());
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod test_problems {
    //! Right-hand sides with known solutions, shared by the integrator tests.
    use super::*;

    /// q̈ = −ω² q: q = cos ωt, v = −ω sin ωt from (1, 0).
    pub struct Oscillator {
        pub omega: f64,
    }

    impl SecondOrder<f64, 1> for Oscillator {
        fn acceleration(
            &self,
            _t: f64,
            q: &SVector<f64, 1>,
            _v: &SVector<f64, 1>,
        ) -> Result<SVector<f64, 1>, Error> {
            Ok(q * -(self.omega * self.omega))
        }
        fn integral(&self, _t: f64, q: &SVector<f64, 1>, v: &SVector<f64, 1>) -> f64 {
            0.5 * (v[0] * v[0] + self.omega * self.omega * q[0] * q[0])
        }
    }

    impl Oscillator {
        pub fn exact(&self, t: f64) -> (f64, f64) {
            ((self.omega * t).cos(), -self.omega * (self.omega * t).sin())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combination_matches_operators() {
        let a = Pair::new(
            SVector::<f64, 2>::new(1.0, 2.0),
            SVector::<f64, 2>::new(3.0, 4.0),
        );
        let b = Pair::new(
            SVector::<f64, 2>::new(-1.0, 0.5),
            SVector::<f64, 2>::new(0.25, 8.0),
        );
        let y = a.add_combination(0.5, [2.0, -3.0], [&a, &b]);
        let q = a.q + (a.q * 2.0 + b.q * -3.0) * 0.5;
        let v = a.v + (a.v * 2.0 + b.v * -3.0) * 0.5;
        assert_eq!(y, Pair::new(q, v));
    }

    #[test]
    fn problem_checks() {
        let z = SVector::<f64, 1>::zeros();
        assert!(check_problem(0.0, 1.0, &z, &z).is_ok());
        for (t0, t1) in [
            (1.0, 1.0),
            (1.0, 0.0),
            (0.0, f64::INFINITY),
            (f64::NAN, 1.0),
        ] {
            assert!(matches!(
                check_problem(t0, t1, &z, &z),
                Err(Error::Settings(_))
            ));
        }
        let nan = SVector::<f64, 1>::new(f64::NAN);
        let e = check_problem(0.0, 1.0, &nan, &z).unwrap_err();
        assert!(e.to_string().contains("initial state"), "{e}");
    }
}

/// The failure of a run that stopped before its first step: the partial
/// result is the initial state alone.
pub(crate) fn failed_at_start<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    t0: T,
    q0: SVector<T, Q>,
    v0: SVector<T, N>,
    error: Error,
) -> Failure<Trajectory<T, N, Q>> {
    Failure::new(
        error,
        Trajectory::start(t0, q0, v0, Sample::of(rhs, t0, &q0, &v0)),
    )
}
