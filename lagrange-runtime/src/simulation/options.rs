//! The options of a run that change what it returns: events and an input
//! source. Each is a slot of [`Simulation`]'s type, empty by default
//! ([`NoEvents`], [`Unforced`]); filling one changes the run's result (see
//! [`Runs`](super::Runs)), so the slots are types, not fields to check.

use super::Simulation;
use crate::control::{Feedback, InputSource, IntoInput, OpenLoop, Sampled, Saturated};
use crate::event::{Event, Events};
use crate::numeric::Real;
use crate::system::{Driven, Lagrangian};
use nalgebra::SVector;
use std::marker::PhantomData;

/// The event slot of a [`Simulation`] with no events (the default).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoEvents;

/// The input slot of a [`Simulation`] with no input source (the default).
#[derive(Clone, Copy, Debug, Default)]
pub struct Unforced;

/// The input slot of a [`Simulation`] driven by the source `C`, for a system
/// with N velocities, P inputs and Q coordinates (named here so that the
/// source's closures take their argument types from the system).
#[derive(Clone, Copy, Debug)]
pub struct Control<C, T, const N: usize, const P: usize, const Q: usize> {
    pub(crate) source: C,
    types: PhantomData<fn() -> T>,
}

/// The former builder of a run with events, now a [`Simulation`] whose event
/// slot is filled: `Simulation::event` returns this type, and its methods are
/// `Simulation`'s.
#[deprecated(
    since = "0.1.0",
    note = "one builder: use `Simulation<'a, S, I, Unforced, Events<'e, T, N, Q>>` (what `Simulation::event` returns); see the CHANGELOG"
)]
pub type EventSimulation<'a, 'e, S, I, T, const N: usize, const Q: usize = N> =
    Simulation<'a, S, I, Unforced, Events<'e, T, N, Q>>;

/// The former builder of a driven run, now a [`Simulation`] whose input slot
/// is filled (and, as the old builder always had, an event list).
#[deprecated(
    since = "0.1.0",
    note = "one builder: use `Simulation<'a, S, I, Control<C, T, N, P, Q>, E>` (what `Simulation::feedback`, `sampled`, `open_loop` and `control` return); see the CHANGELOG"
)]
pub type ControlledSimulation<
    'a,
    'e,
    S,
    I,
    C,
    T,
    const N: usize,
    const P: usize,
    const Q: usize = N,
> = Simulation<'a, S, I, Control<C, T, N, P, Q>, Events<'e, T, N, Q>>;

/// An event slot: adding an event fills it.
pub trait EventSlot<'e, T: Real, const N: usize, const Q: usize> {
    /// The events with `event` added last.
    fn with(self, event: Event<'e, T, N, Q>) -> Events<'e, T, N, Q>;
    /// Calls `f` with the events (none for [`NoEvents`]).
    fn read<R>(&self, f: impl FnOnce(&Events<'e, T, N, Q>) -> R) -> R;
}

impl<'e, T: Real, const N: usize, const Q: usize> EventSlot<'e, T, N, Q> for NoEvents {
    fn with(self, event: Event<'e, T, N, Q>) -> Events<'e, T, N, Q> {
        Events::new().with(event)
    }
    fn read<R>(&self, f: impl FnOnce(&Events<'e, T, N, Q>) -> R) -> R {
        f(&Events::new())
    }
}

impl<'e, T: Real, const N: usize, const Q: usize> EventSlot<'e, T, N, Q> for Events<'e, T, N, Q> {
    fn with(self, event: Event<'e, T, N, Q>) -> Events<'e, T, N, Q> {
        Events::with(self, event)
    }
    fn read<R>(&self, f: impl FnOnce(&Events<'e, T, N, Q>) -> R) -> R {
        f(self)
    }
}

impl<'a, S, I, C, E> Simulation<'a, S, I, C, E> {
    /// Watches `event` during the run; call it again for more. Occurrences
    /// name events by the order they were added, from 0. The run then
    /// returns an [`EventRun`](crate::EventRun), the trajectory and the
    /// occurrences (or, with an input source, a [`ControlRun`](super::ControlRun)
    /// that holds them). See [`crate::event`] for how events are detected,
    /// located and acted on.
    ///
    /// The event's scalar and dimension are the system's, so the closures
    /// need no annotation to index the state (`q[0]`, `v[1]`); one that
    /// calls a method on a component (`q[1].cos()`) needs its scalar named
    /// once, see [`Event::new`].
    ///
    /// ```
    /// # use lagrange_runtime::{Event, SecondOrder, Lagrangian, Simulation, Dopri5};
    /// # use nalgebra::{SMatrix, SVector, Vector1, Matrix1};
    /// # struct Fall;
    /// # impl Lagrangian<f64, 1> for Fall {
    /// #     const COORDINATES: [&'static str; 1] = ["z"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-9.81) }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
    /// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 9.81 * q[0] }
    /// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
    /// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    /// #     }
    /// # }
    /// // A ball dropped from 1 m bounces with restitution 0.9 (coming to rest
    /// // at 8.6 s); the apexes are where v falls through zero.
    /// let run = Simulation::new(&Fall)
    ///     .integrator(Dopri5::tol(1e-10))
    ///     .event(Event::new(|_, q, _| q[0]).falling().action(|_, _, v| *v *= -0.9))
    ///     .event(Event::new(|_, _, v| v[0]).falling())
    ///     .run([1.0], [0.0], 0.0..5.0)?;
    /// let bounces = run.times(0);
    /// assert!((bounces[0] - (2.0f64 / 9.81).sqrt()).abs() < 1e-12);
    /// assert_eq!(run.times(1).len(), bounces.len());
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    pub fn event<'e, T: Real, const N: usize, const Q: usize>(
        self,
        event: Event<'e, T, N, Q>,
    ) -> Simulation<'a, S, I, C, Events<'e, T, N, Q>>
    where
        S: Lagrangian<T, N, Q>,
        E: EventSlot<'e, T, N, Q>,
    {
        Simulation {
            system: self.system,
            integrator: self.integrator,
            settings: self.settings,
            control: self.control,
            events: self.events.with(event),
        }
    }

    /// Watches the events of `events` (replacing any added before), in
    /// their order. An empty list gives the run the type it has with events
    /// (an [`EventRun`](crate::EventRun), or for a controlled run the same
    /// [`ControlRun`](super::ControlRun)), so that events can be added to it
    /// conditionally:
    ///
    /// ```
    /// # use lagrange_runtime::{Event, Events, Lagrangian, Simulation};
    /// # use nalgebra::{Matrix1, Vector1};
    /// # struct Fall;
    /// # impl Lagrangian<f64, 1> for Fall {
    /// #     const COORDINATES: [&'static str; 1] = ["z"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-9.81) }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
    /// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 9.81 * q[0] }
    /// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
    /// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    /// #     }
    /// # }
    /// let bounce = true;
    /// let mut sim = Simulation::new(&Fall).events(Events::new());
    /// if bounce {
    ///     sim = sim.event(Event::new(|_, q, _| q[0]).falling().action(|_, _, v| *v *= -0.9));
    /// }
    /// let run = sim.run([1.0], [0.0], 0.0..1.0)?;
    /// assert_eq!(run.times(0).len(), 1);
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    pub fn events<'e, T: Real, const N: usize, const Q: usize>(
        self,
        events: Events<'e, T, N, Q>,
    ) -> Simulation<'a, S, I, C, Events<'e, T, N, Q>>
    where
        S: Lagrangian<T, N, Q>,
    {
        Simulation {
            system: self.system,
            integrator: self.integrator,
            settings: self.settings,
            control: self.control,
            events,
        }
    }
}

impl<'e, S, I, C, T: Real, const N: usize, const Q: usize>
    Simulation<'_, S, I, C, Events<'e, T, N, Q>>
{
    /// Sets how many events may stop and restart the integration (default
    /// [`DEFAULT_MAX_EVENTS`](crate::event::DEFAULT_MAX_EVENTS)); with a held
    /// input source the budget applies per sample interval; the atlas's runs
    /// do not apply it (their chart switches restart the integration too).
    pub fn max_events(mut self, n: usize) -> Self {
        self.events = self.events.max_events(n);
        self
    }
}

impl<'a, S, I, E> Simulation<'a, S, I, Unforced, E> {
    /// Drives the system with continuous feedback u = `k(t, q, q̇)`, evaluated
    /// inside the right-hand side at every stage. `k` returns `[T; P]` or
    /// `SVector<T, P>` with P the number of the system's
    /// [inputs](Driven::INPUTS): returning another number of inputs does not
    /// compile. `k` must be a pure function of its arguments (the integrator
    /// calls it at trial states, several times per step).
    ///
    /// ```
    /// # use lagrange_runtime::{Driven, Dopri5, Lagrangian, Simulation};
    /// # use nalgebra::{Matrix1, SMatrix, Vector1};
    /// # struct Cart;
    /// # impl Lagrangian<f64, 1> for Cart {
    /// #     const COORDINATES: [&'static str; 1] = ["x"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
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
    /// // A unit mass under critically damped PD control: x = (1 + t) e^{−t}.
    /// let run = Simulation::new(&Cart)
    ///     .integrator(Dopri5::tol(1e-12))
    ///     .feedback(|_, q, v| [-q[0] - 2.0 * v[0]])
    ///     .run([1.0], [0.0], 0.0..3.0)?;
    /// let (x, _) = run.trajectory().final_state();
    /// assert!((x[0] - 4.0 * (-3.0f64).exp()).abs() < 1e-10);
    /// assert_eq!(run.inputs()[0][0], -1.0); // u at t = 0
    /// let mut csv = Vec::new();
    /// run.write_csv(&mut csv)?;
    /// assert!(String::from_utf8(csv).unwrap().starts_with("t,x,dot_x,force,integral,"));
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    pub fn feedback<T, F, U, const N: usize, const P: usize, const Q: usize>(
        self,
        k: F,
    ) -> Simulation<'a, S, I, Control<Feedback<F>, T, N, P, Q>, E>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        F: Fn(T, &SVector<T, Q>, &SVector<T, N>) -> U,
        U: IntoInput<T, P>,
    {
        self.control(Feedback::new(k))
    }

    /// Drives the system with a sampled controller and zero-order hold: u_k =
    /// `k(t_k, q_k, q̇_k)` at t_k = t₀ + k·`period`, held until the next sample;
    /// the integrator restarts at every sample instant (see the
    /// [module docs](crate::control)). `k` may keep state between samples
    /// (`FnMut`): it is called once per sample, in time order. A period that is
    /// not positive and finite makes the run fail with
    /// [`Error::Settings`](crate::Error::Settings).
    pub fn sampled<T, F, U, const N: usize, const P: usize, const Q: usize>(
        self,
        period: f64,
        k: F,
    ) -> Simulation<'a, S, I, Control<Sampled<F>, T, N, P, Q>, E>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        F: FnMut(T, &SVector<T, Q>, &SVector<T, N>) -> U,
        U: IntoInput<T, P>,
    {
        self.control(Sampled::new(period, k))
    }

    /// Drives the system with an open-loop signal u(t), evaluated at every
    /// stage; `u` returns `[T; P]` or `SVector<T, P>`.
    pub fn open_loop<T, F, U, const N: usize, const P: usize, const Q: usize>(
        self,
        u: F,
    ) -> Simulation<'a, S, I, Control<OpenLoop<F>, T, N, P, Q>, E>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        F: Fn(T) -> U,
        U: IntoInput<T, P>,
    {
        self.control(OpenLoop::new(u))
    }

    /// Drives the system from any [`InputSource`]: an
    /// [`InputTable`](crate::InputTable), or a [`Feedback`], [`Sampled`] or
    /// [`OpenLoop`] built beforehand (the methods above build those with
    /// the closure's argument types inferred from the system).
    pub fn control<T, C, const N: usize, const P: usize, const Q: usize>(
        self,
        source: C,
    ) -> Simulation<'a, S, I, Control<C, T, N, P, Q>, E>
    where
        T: Real,
        S: Lagrangian<T, N, Q> + Driven<T, N, P, Q>,
        C: InputSource<T, N, P, Q>,
    {
        Simulation {
            system: self.system,
            integrator: self.integrator,
            settings: self.settings,
            control: Control {
                source,
                types: PhantomData,
            },
            events: self.events,
        }
    }
}

impl<'a, S, I, C, T, E, const N: usize, const P: usize, const Q: usize>
    Simulation<'a, S, I, Control<C, T, N, P, Q>, E>
{
    /// The input source.
    pub fn source(&self) -> &C {
        &self.control.source
    }

    /// Keeps each input within [lower, upper] whatever the source asks (an
    /// actuator's effort limits: a URDF robot's `JOINT_EFFORTS`, mapped to
    /// its inputs): the run integrates the clamped inputs, records them,
    /// and [`ControlRun::saturations`](crate::ControlRun::saturations) says
    /// where an input was held at a limit. An infinite bound is none; a
    /// NaN bound or lower > upper fails the run with
    /// [`Error::Settings`](crate::Error::Settings).
    pub fn input_limits(
        self,
        lower: [f64; P],
        upper: [f64; P],
    ) -> Simulation<'a, S, I, Control<Saturated<C, P>, T, N, P, Q>, E> {
        Simulation {
            system: self.system,
            integrator: self.integrator,
            settings: self.settings,
            control: Control {
                source: Saturated::new(self.control.source, lower, upper),
                types: PhantomData,
            },
            events: self.events,
        }
    }
}

impl<'a, S, I, C, T, E, const N: usize, const P: usize, const Q: usize>
    Simulation<'a, S, I, Control<Saturated<C, P>, T, N, P, Q>, E>
{
    /// Narrows each input's effort limits with its motor's speed (after
    /// [`input_limits`](Self::input_limits)): input k drives the joint
    /// whose velocity is `v[joints[k]]`, and at speed w a bound that
    /// pushes along the motion shrinks to bound · max(0, 1 − |w|/`no_load[k]`),
    /// the linear torque–speed line of a DC motor (full torque at stall,
    /// none at the no-load speed), while a bound against the motion stays
    /// whole. The line holds at every evaluation, between a sampled
    /// controller's samples too; [`ControlRun::saturations`] reads the
    /// narrowed bounds. A URDF robot's `<limit velocity>` is
    /// `JOINT_VELOCITIES`, a no-load speed to map as the efforts are. A
    /// motor behind a gear (`joint(q, motor = u, gear = n)`) turns n times
    /// faster than its joint: give its no-load speed divided by n. A
    /// no-load speed that is not positive fails the run with
    /// [`Error::Settings`](crate::Error::Settings); ∞ is none.
    ///
    /// [`ControlRun::saturations`]: crate::ControlRun::saturations
    pub fn speed_limits(self, joints: [usize; P], no_load: [f64; P]) -> Self {
        Simulation {
            system: self.system,
            integrator: self.integrator,
            settings: self.settings,
            control: Control {
                source: self.control.source.with_speeds(joints, no_load),
                types: PhantomData,
            },
            events: self.events,
        }
    }
}

/// The deprecated names are the builder's types (a program naming them keeps
/// compiling): these functions compile only if each alias is that type.
#[cfg(test)]
#[allow(deprecated, dead_code)]
mod former_names {
    use super::*;

    fn event_simulation<'a, 'e, S, I, T: Real, const N: usize, const Q: usize>(
        s: Simulation<'a, S, I, Unforced, Events<'e, T, N, Q>>,
    ) -> EventSimulation<'a, 'e, S, I, T, N, Q> {
        s
    }

    fn controlled_simulation<'a, 'e, S, I, C, T: Real, const N: usize, const P: usize>(
        s: Simulation<'a, S, I, Control<C, T, N, P, N>, Events<'e, T, N, N>>,
    ) -> ControlledSimulation<'a, 'e, S, I, C, T, N, P> {
        s
    }
}
