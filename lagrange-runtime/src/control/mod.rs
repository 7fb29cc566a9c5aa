//! Driving a system with inputs: feedback controllers, sampled (zero-order
//! hold) controllers and open-loop signals, in all three forward dynamics.
//!
//! A [`Driven`] system has P named inputs u; they add the generalized forces
//! ΔQ(q, q̇, u, t) = [`Driven::input_forces`] to Q − h and never touch M, h or
//! the constraints. The pieces:
//!
//! - [`Forcing`]: any generalized force ΔQ(t, q, q̇) added to Q − h by
//!   [`Dynamics`](crate::Dynamics), [`ConstrainedDynamics`](crate::ConstrainedDynamics)
//!   (before the saddle-point solve) and [`ReducedDynamics`](crate::ReducedDynamics)
//!   (as F* += Wᵀ ΔQ). Each of them has a defaulted type parameter
//!   `F = `[`NoForcing`](crate::NoForcing) and a `with_forcing` method: `Dynamics::new(&sys)` is
//!   unforced as before, and the `if F::ACTIVE` branch that adds ΔQ is removed at
//!   compile time when there is no forcing.
//! - [`InputSource`]: where u comes from. [`Feedback`] (u = k(t, q, q̇), evaluated
//!   inside the right-hand side at every stage), [`Sampled`] (u_k = k(t_k, q_k, q̇_k)
//!   at t_k = t₀ + k h, held in between), [`OpenLoop`] (u(t)) and [`InputTable`]
//!   (breakpoints with linear interpolation or zero-order hold).
//! - [`InputForces`]: a source and a driven system as a [`Forcing`]; it checks
//!   every input and reports NaN or ∞ as [`Error::NonFiniteInput`] naming the
//!   input, never as a NaN force.
//! - A [`Simulation`](crate::Simulation) given a source by
//!   [`feedback`](crate::Simulation::feedback), [`sampled`](crate::Simulation::sampled),
//!   [`open_loop`](crate::Simulation::open_loop) or
//!   [`control`](crate::Simulation::control) runs every form
//!   (`run`, `run_constrained`, `run_reduced`, `run_atlas`) with the simulation's checks,
//!   drift control and [`event`](crate::Simulation::event)s, and returns a
//!   [`ControlRun`](crate::ControlRun): the trajectory, the inputs at every stored point, a CSV
//!   writer.
//!
//! ```
//! # use lagrange_runtime::{Dopri5, Driven, Lagrangian, Simulation};
//! # use nalgebra::{Matrix1, Vector1};
//! # struct Cart;
//! # impl Lagrangian<f64, 1> for Cart {
//! #     const COORDINATES: [&'static str; 1] = ["x"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, _: &Vector1<f64>, _: f64) -> f64 { 0.0 }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 { self.kinetic_energy(q, v, t) }
//! # }
//! # impl Driven<f64, 1, 1> for Cart {
//! #     const INPUTS: [&'static str; 1] = ["force"];
//! #     fn input_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, u: &Vector1<f64>, _: f64) -> Vector1<f64> { *u }
//! #     fn input_jacobians(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: &Vector1<f64>, _: f64)
//! #         -> (Matrix1<f64>, Matrix1<f64>, Matrix1<f64>) {
//! #         (Matrix1::identity(), Matrix1::zeros(), Matrix1::zeros())
//! #     }
//! # }
//! let (cart, kp, kd) = (Cart, 4.0, 4.0); // a free cart of unit mass
//! let run = Simulation::new(&cart)
//!     .integrator(Dopri5::tol(1e-10))
//!     .feedback(|_, q, v| [-kp * q[0] - kd * v[0]])   // [T; P]: a wrong length does not compile
//!     .run([1.0], [0.0], 0.0..5.0)?;
//! run.save_csv(std::env::temp_dir().join("cart.csv"))?; // t,x,dot_x,force,integral,residuals
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! # Design
//!
//! **Why a restart at every sample.** A zero-order-hold input jumps at the
//! sample instants. An integrator stepping across a jump loses its order (a
//! Runge–Kutta stage sees the new value for part of a step), an adaptive one
//! wastes rejected steps locating it, and a stage evaluated exactly at the
//! instant would see the wrong value. So the run is cut at every sample instant
//! t_k = t₀ + k h (computed from k, not accumulated): the controller is called
//! once with the state reached there, the input is held constant for the whole
//! piece, and the integrator starts afresh to t_{k+1}, as it does after an event
//! action. The pieces are concatenated into one trajectory (the restart point is
//! recorded once) and their work statistics summed. Inside a piece the
//! dynamics are smooth, so the integrator keeps its full order: with a
//! piecewise-constant input the sampled states match the exact discrete-time
//! propagation to round-off. Tables restart the same way at their breakpoints
//! (a linear table's kinks, a hold table's jumps). Because the controller is
//! called exactly once per sample, in time order, a [`Sampled`] controller may
//! keep state (`FnMut`: an integrator of the error, a filter).
//!
//! **Cost.** Continuous feedback and open-loop signals cost one call of the
//! source per right-hand-side evaluation plus one per stored point (to record
//! it), and allocate nothing per call: the inputs live on the stack
//! (`SVector<T, P>`), and only the recorded inputs (one `Vec`) are added to the
//! run's allocations. A sampled run pays one integrator start per sample (for
//! DOPRI5 a starting-step estimate, two evaluations; for RK4 one) and the
//! allocations of one trajectory piece per sample. The integrator's step budget
//! and the event budget apply per piece.
//!
//! **Forced Jacobians.** The state dependence of a forcing (a feedback law) is
//! unknown to the runtime, so forced dynamics offer no analytic Jacobian and the
//! implicit integrators fall back to finite differences, which see the forcing
//! correctly.
//!
//! **What is recorded.** [`ControlRun::inputs`](crate::ControlRun::inputs) holds one u per stored point of
//! the trajectory. For continuous sources it is the source evaluated at the
//! stored time and state (after an event action, the state after it). For
//! held sources ([`Sampled`], hold tables) it is the value in force on the step
//! that ends at that point, except at a sample instant, where it is the new
//! sample taken there: u_k at t_k, including t₀ and the end time when the end
//! time is a sample instant.

mod held;
mod saturation;
mod state_feedback;
mod table;

pub(crate) use held::HeldForces;
pub(crate) use saturation::stretches;
pub use saturation::{Saturated, Saturation};
pub use state_feedback::StateFeedback;
pub use table::{InputTable, Interpolation};

use crate::error::SettingsError;
use crate::error::{Error, check_finite_inputs};
use crate::mechanics::Forcing;
use crate::numeric::Real;
use crate::system::Driven;
use nalgebra::SVector;
use std::cell::RefCell;
use std::fmt;

/// A value a controller may return for P inputs: `[T; P]` or `SVector<T, P>`.
///
/// P is fixed by the system's [`Driven`] implementation, so a controller that
/// returns the wrong number of inputs is a compile error, not a run-time one.
#[diagnostic::on_unimplemented(
    message = "a controller must return the system's {P} input(s), as `[T; {P}]` or `SVector<T, {P}>`; this one returns `{Self}`",
    label = "returns `{Self}`, expected {P} input(s)",
    note = "the inputs are the ones declared in `inputs(...)`, in that order"
)]
pub trait IntoInput<T, const P: usize> {
    /// The inputs as a vector.
    fn into_input(self) -> SVector<T, P>;
}

impl<T: Real, const P: usize> IntoInput<T, P> for [T; P] {
    #[inline]
    fn into_input(self) -> SVector<T, P> {
        SVector::from(self)
    }
}

impl<T: Real, const P: usize> IntoInput<T, P> for SVector<T, P> {
    #[inline]
    fn into_input(self) -> SVector<T, P> {
        self
    }
}

/// Where the P inputs of a driven system come from during a run.
///
/// Besides the value, a source says when the run must restart
/// ([`next_break`](Self::next_break): sample instants, table breakpoints) and
/// whether its value is held between those instants
/// ([`held`](Self::held): zero-order hold); see the [module docs](self).
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a source of this system's inputs: the system declares {P} input(s) in `inputs(..)`, with {N} velocities and {Q} configuration entries",
    label = "this must give {P} input(s)",
    note = "an `InputTable` needs one column per declared input ({P}); a controller built by hand (`Feedback`, `Sampled`, `OpenLoop`) must return {P} value(s) and read q of {Q} and v of {N} entries"
)]
pub trait InputSource<T: Real, const N: usize, const P: usize, const Q: usize = N> {
    /// The inputs at (t, q, q̇) (q of Q entries: with free orientations it
    /// holds their quaternions). For a held source, called once per break,
    /// with the state reached there.
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P>;

    /// The first instant strictly after `after` at which the run must restart,
    /// `start` being the run's initial time; `None` if there is none. The
    /// default has none.
    fn next_break(&self, start: T, after: T) -> Option<T> {
        let _ = (start, after);
        None
    }

    /// Whether the input is held constant between breaks at its value at the
    /// break that starts the piece (zero-order hold). The default is `false`:
    /// the source is evaluated at every stage.
    fn held(&self) -> bool {
        false
    }

    /// How many breaks fall in (start, end], when the source knows it without
    /// enumerating them: the run refuses, before any work, more breaks than
    /// its step budget. The default does not know (`None`).
    fn breaks_within(&self, start: T, end: T) -> Option<f64> {
        let _ = (start, end);
        None
    }

    /// Checks the source's settings before a run.
    ///
    /// # Errors
    /// [`Error::Settings`] naming the bad setting.
    fn check(&self) -> Result<(), Error> {
        Ok(())
    }

    /// The bounds (lower, upper) its inputs are clamped into, for a source
    /// that saturates ([`Saturated`]); `None` (the default) otherwise.
    fn bounds(&self) -> Option<([f64; P], [f64; P])> {
        None
    }

    /// Each input's joint (its index in v) and no-load speed, for a source
    /// whose bounds narrow with speed ([`Saturated::with_speeds`]); `None`
    /// (the default) otherwise.
    fn speed_limits(&self) -> Option<([usize; P], [f64; P])> {
        None
    }

    /// `u` kept within what the actuators can give at (t, q, v): applied to
    /// a held value at every evaluation, since a motor's torque–speed line
    /// holds between samples too. The default keeps `u`.
    fn limit(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>, u: SVector<T, P>) -> SVector<T, P> {
        let _ = (t, q, v);
        u
    }
}

impl<T: Real, const N: usize, const P: usize, const Q: usize, C: InputSource<T, N, P, Q> + ?Sized>
    InputSource<T, N, P, Q> for &C
{
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        (**self).input(t, q, v)
    }
    fn next_break(&self, start: T, after: T) -> Option<T> {
        (**self).next_break(start, after)
    }
    fn held(&self) -> bool {
        (**self).held()
    }
    fn breaks_within(&self, start: T, end: T) -> Option<f64> {
        (**self).breaks_within(start, end)
    }
    fn check(&self) -> Result<(), Error> {
        (**self).check()
    }
    fn bounds(&self) -> Option<([f64; P], [f64; P])> {
        (**self).bounds()
    }
    fn speed_limits(&self) -> Option<([usize; P], [f64; P])> {
        (**self).speed_limits()
    }
    fn limit(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>, u: SVector<T, P>) -> SVector<T, P> {
        (**self).limit(t, q, v, u)
    }
}

/// Continuous feedback u = k(t, q, q̇), evaluated inside the right-hand side at
/// every stage of the integrator. Built by
/// [`Simulation::feedback`](crate::Simulation::feedback) or [`Feedback::new`].
#[derive(Clone, Copy)]
pub struct Feedback<F>(F);

impl<F> Feedback<F> {
    /// The feedback law `k(t, q, q̇)`, returning `[T; P]` or `SVector<T, P>`.
    pub fn new(k: F) -> Self {
        Self(k)
    }
}

impl<F> fmt::Debug for Feedback<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Feedback(..)")
    }
}

impl<T, F, U, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for Feedback<F>
where
    T: Real,
    F: Fn(T, &SVector<T, Q>, &SVector<T, N>) -> U,
    U: IntoInput<T, P>,
{
    #[inline]
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        (self.0)(t, q, v).into_input()
    }
}

/// An open-loop signal u(t). Built by
/// [`Simulation::open_loop`](crate::Simulation::open_loop) or [`OpenLoop::new`].
#[derive(Clone, Copy)]
pub struct OpenLoop<F>(F);

impl<F> OpenLoop<F> {
    /// The signal `u(t)`, returning `[T; P]` or `SVector<T, P>`.
    pub fn new(u: F) -> Self {
        Self(u)
    }
}

impl<F> fmt::Debug for OpenLoop<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("OpenLoop(..)")
    }
}

impl<T, F, U, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for OpenLoop<F>
where
    T: Real,
    F: Fn(T) -> U,
    U: IntoInput<T, P>,
{
    #[inline]
    fn input(&self, t: T, _: &SVector<T, Q>, _: &SVector<T, N>) -> SVector<T, P> {
        (self.0)(t).into_input()
    }
}

/// A sampled controller with zero-order hold: u_k = k(t_k, q_k, q̇_k) at the
/// sample instants t_k = t₀ + k h of a run starting at t₀, held constant on
/// [t_k, t_{k+1}). Built by [`Simulation::sampled`](crate::Simulation::sampled)
/// or [`Sampled::new`].
///
/// The controller is called exactly once per sample instant, in time order,
/// never inside the integrator's stages, so it may keep state (`FnMut`).
pub struct Sampled<F> {
    period: f64,
    controller: RefCell<F>,
}

impl<F> Sampled<F> {
    /// The controller `k(t, q, q̇)` sampled every `period` (checked when a run
    /// starts: it must be positive and finite).
    pub fn new(period: f64, controller: F) -> Self {
        Self {
            period,
            controller: RefCell::new(controller),
        }
    }

    /// The sampling period h.
    pub fn period(&self) -> f64 {
        self.period
    }
}

impl<F> fmt::Debug for Sampled<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sampled")
            .field("period", &self.period)
            .finish_non_exhaustive()
    }
}

impl<T, F, U, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q> for Sampled<F>
where
    T: Real,
    F: FnMut(T, &SVector<T, Q>, &SVector<T, N>) -> U,
    U: IntoInput<T, P>,
{
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        (self.controller.borrow_mut())(t, q, v).into_input()
    }

    /// t₀ + k h for the smallest k with t₀ + k h > `after`.
    fn next_break(&self, start: T, after: T) -> Option<T> {
        let h = T::lit(self.period);
        let mut k = ((after - start) / h).to_f64().floor().max(0.0);
        while start + h * T::lit(k) <= after {
            k += 1.0;
        }
        Some(start + h * T::lit(k))
    }

    fn held(&self) -> bool {
        true
    }

    fn breaks_within(&self, start: T, end: T) -> Option<f64> {
        Some(((end - start).to_f64() / self.period).floor().max(0.0))
    }

    fn check(&self) -> Result<(), Error> {
        let h = self.period;
        if !(h.is_finite() && h > 0.0) {
            return Err(SettingsError::Value {
                owner: "sampled",
                setting: "sampling period",
                value: h,
                requirement: "positive and finite".into(),
            }
            .into());
        }
        Ok(())
    }
}

/// The generalized forces of a [`Driven`] system's inputs taken from a source:
/// ΔQ = [`Driven::input_forces`](q, q̇, u(t, q, q̇), t), a [`Forcing`] for the
/// dynamics.
///
/// ```
/// # use lagrange_runtime::{Driven, Dynamics, Feedback, InputForces, Lagrangian};
/// # use nalgebra::{Matrix1, SMatrix, Vector1};
/// # struct Cart;
/// # impl Lagrangian<f64, 1> for Cart {
/// #     const COORDINATES: [&'static str; 1] = ["x"];
/// #     const RHEONOMIC: bool = false;
/// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(2.0) }
/// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
/// #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
/// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
/// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
/// #     }
/// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { v[0] * v[0] }
/// #     fn potential_energy(&self, _: &Vector1<f64>, _: f64) -> f64 { 0.0 }
/// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 { self.kinetic_energy(q, v, t) }
/// # }
/// # impl Driven<f64, 1, 1> for Cart {
/// #     const INPUTS: [&'static str; 1] = ["force"];
/// #     fn input_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, u: &Vector1<f64>, _: f64) -> Vector1<f64> { *u }
/// #     fn input_jacobians(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: &Vector1<f64>, _: f64)
/// #         -> (SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>) {
/// #         (SMatrix::identity(), SMatrix::zeros(), SMatrix::zeros())
/// #     }
/// # }
/// // A cart of mass 2 pushed by u = −4 x.
/// let k = |_t: f64, q: &Vector1<f64>, _v: &Vector1<f64>| [-4.0 * q[0]];
/// let dynamics = Dynamics::new(&Cart).with_forcing(InputForces::new(&Cart, Feedback::new(k)));
/// let a = dynamics.acceleration(0.0, &Vector1::new(0.5), &Vector1::new(0.0))?;
/// assert!((a[0] + 1.0).abs() < 1e-15);
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
pub struct InputForces<'s, S, C, const P: usize> {
    system: &'s S,
    source: C,
}

impl<'s, S, C, const P: usize> InputForces<'s, S, C, P> {
    /// The forces of `system`'s inputs taken from `source`.
    pub fn new(system: &'s S, source: C) -> Self {
        Self { system, source }
    }

    /// The source.
    pub fn source(&self) -> &C {
        &self.source
    }
}

impl<S, C: Clone, const P: usize> Clone for InputForces<'_, S, C, P> {
    fn clone(&self) -> Self {
        Self {
            system: self.system,
            source: self.source.clone(),
        }
    }
}
impl<S, C: Copy, const P: usize> Copy for InputForces<'_, S, C, P> {}

impl<S, C: fmt::Debug, const P: usize> fmt::Debug for InputForces<'_, S, C, P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("InputForces")
            .field("source", &self.source)
            .finish_non_exhaustive()
    }
}

impl<S, C, T, const N: usize, const P: usize, const Q: usize> Forcing<T, N, Q>
    for InputForces<'_, S, C, P>
where
    S: Driven<T, N, P, Q>,
    C: InputSource<T, N, P, Q>,
    T: Real,
{
    #[inline]
    fn force(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        let u = self.source.input(t, q, v);
        check_input::<S, T, N, P, Q>(t, q, v, &u)?;
        Ok(self.system.input_forces(q, v, &u, t))
    }
}

/// [`Error::NonFiniteInput`] for the first non-finite input, if any.
pub(crate) fn check_input<
    S: Driven<T, N, P, Q>,
    T: Real,
    const N: usize,
    const P: usize,
    const Q: usize,
>(
    t: T,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
    u: &SVector<T, P>,
) -> Result<(), Error> {
    check_finite_inputs(&S::INPUTS, t, q, v, u)
}
