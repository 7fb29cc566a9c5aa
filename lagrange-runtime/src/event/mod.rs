//! Events: zero crossings of user functions g(t, q, v) during an integration,
//! located on the dense output, optionally changing the state (an impact law)
//! or ending the run.
//!
//! ```
//! # use lagrange_runtime::{Dopri5, Event, Lagrangian, Simulation};
//! # use nalgebra::{Matrix1, Vector1};
//! # struct Ball;
//! # impl Lagrangian<f64, 1> for Ball {
//! #     const COORDINATES: [&'static str; 1] = ["z"];
//! #     const RHEONOMIC: bool = false;
//! #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
//! #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
//! #     fn generalized_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-9.81) }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
//! #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 9.81 * q[0] }
//! #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! # }
//! let (ball, e) = (Ball, 0.9); // z'' = −g above a floor at z = 0
//! let run = Simulation::new(&ball)
//!     .integrator(Dopri5::tol(1e-10))
//!     .event(
//!         Event::new(|_, q, _| q[0])                  // height above the floor
//!             .falling()
//!             .action(move |_, _, v| *v *= -e),       // restitution
//!     )
//!     .run([1.0], [0.0], 0.0..5.0)?;
//! for o in &run.occurrences { println!("{} {}", o.t, o.v[0]); }
//! assert!((run.occurrences[0].t - (2.0 / 9.81_f64).sqrt()).abs() < 1e-9);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! # Design
//!
//! The integrators know nothing about events beyond one hook,
//! [`SecondOrder::after_step`]: after every accepted step they hand it the step's
//! dense output and may be told to stop there. The event layer wraps the
//! system in an observer that implements the hook:
//!
//! 1. **Detection.** Each event function is compared at the start of the step
//!    (the value kept from the previous step), at the dense-output midpoint and
//!    at the end. The midpoint catches a pair of crossings inside one step (a
//!    grazing double root) that the end values alone would cancel; crossings
//!    closer together than half a step can still be missed, as with any
//!    sampling scheme (limit the step size with the integrator's `hmax` if the
//!    event function oscillates faster than the steps).
//! 2. **Location.** A sign change is located by Brent's method on the dense
//!    output, to about 4 ε relative in t; the event time is the end of Brent's
//!    final bracket on the *old* side of the crossing, so that a state cut there
//!    has not yet crossed (a point inside a cavity stays inside).
//! 3. **Non-stopping events** (no action, not terminal) are only recorded; the
//!    integrator runs on undisturbed, so counting crossings costs nothing but
//!    the function evaluations.
//! 4. **Stopping events** (with an action, or terminal) end the integrator's run
//!    at the step holding the earliest one. The driver cuts that step at the
//!    event time (the step's polynomial is kept, only its end moves), applies
//!    the action, projects the state onto the constraints if the system has any
//!    ([`SecondOrder::project`]), and — unless the event is terminal — starts the
//!    integrator afresh from the new state to the original end time. The pieces
//!    are concatenated into one [`Trajectory`].
//! 5. **Restart events** ([`Event::restart`]) stop the same way but land just
//!    past the surface and keep the state: paired with a switch in the
//!    equations of motion (a `sign`, an `if`, a `min` on the same function)
//!    they make every step lie on one side of it.
//!
//! Restarting rather than resuming is deliberate: a state jump invalidates what
//! a method carries between steps (DOPRI5's FSAL stage, the step-size history,
//! the implicit methods' Jacobian), and every integrator already knows how to
//! start cleanly, so each of them supports events with a two-line change and
//! no per-method state surgery. The cost is one starting-step estimate per
//! impact.
//!
//! Stopping at the step rather than integrating in chunks and searching
//! afterwards matters for impacts: past the event the free motion may leave the
//! admissible region (through a wall, into a chart singularity), where the
//! right-hand side is meaningless or fails.
//!
//! After an action the trajectory is right-continuous: the point recorded at
//! the event time is the state *after* the action, while the dense-output
//! segment ending there interpolates the motion before it; the state before is
//! kept in the [`Occurrence`]. At the restart the fired event's function is
//! taken to have its pre-crossing sign, so the event cannot fire again at the
//! same instant; if the action does not resolve the event (the state still
//! crosses at once) the run stops with [`Error::EventsAccumulate`] instead of
//! looping, and accumulating impacts (Zeno behaviour) end with
//! [`Error::TooManyEvents`] or [`Error::EventsAccumulate`].
//!
//! The observer allocates nothing per step beyond appending occurrences; the
//! event functions and actions are boxed closures, called through one
//! indirection.
//!
//! [`SecondOrder::after_step`]: crate::ode::SecondOrder::after_step
//! [`SecondOrder::project`]: crate::ode::SecondOrder::project

mod driver;
mod limits;
mod view;
mod watch;

pub(crate) use driver::within_budget;
pub use driver::{DEFAULT_MAX_EVENTS, Events};
pub use limits::LimitPolicy;
pub(crate) use limits::{Limited, watched};
pub(crate) use view::{BackFn, ViewFn};

use crate::error::{Error, Progress, to_vec};
use crate::numeric::Real;
use crate::ode::Trajectory;
use nalgebra::SVector;
use std::fmt;

/// Which sign changes of an event function count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Direction {
    /// From negative to positive.
    Rising,
    /// From positive to negative.
    Falling,
    /// Either way (the default).
    #[default]
    Both,
}

impl Direction {
    /// Whether a crossing that starts from a value of sign `before` counts.
    fn admits<T: Real>(self, before: T) -> bool {
        match self {
            Direction::Rising => before < T::zero(),
            Direction::Falling => before > T::zero(),
            Direction::Both => true,
        }
    }
}

type EventFn<'a, T, const N: usize, const Q: usize> =
    Box<dyn Fn(T, &SVector<T, Q>, &SVector<T, N>) -> T + 'a>;
type ActionFn<'a, T, const N: usize, const Q: usize> =
    Box<dyn Fn(T, &mut SVector<T, Q>, &mut SVector<T, N>) + 'a>;
type TestFn<'a, T, const N: usize, const Q: usize> =
    Box<dyn Fn(T, &SVector<T, Q>, &SVector<T, N>) -> bool + 'a>;

/// When an occurrence ends the run.
enum Terminal<'a, T, const N: usize, const Q: usize> {
    Never,
    Always,
    /// When the test holds for the state after the action.
    If(TestFn<'a, T, N, Q>),
}

/// An event: the zero crossings of g(t, q, v) in a [`Direction`], optionally
/// with an action that maps the state at the crossing to a new one (an impact
/// law), optionally terminal (the run ends there).
///
/// ```
/// use lagrange_runtime::Event;
/// use nalgebra::SVector;
/// let e = 0.8;
/// let floor = Event::new(|_t, q: &SVector<f64, 1>, _v: &SVector<f64, 1>| q[0])
///     .falling()
///     .named("floor")
///     .action(move |_t, _q, v| *v *= -e);
/// assert_eq!(floor.name(), "floor");
/// ```
pub struct Event<'a, T: Real, const N: usize, const Q: usize = N> {
    name: Option<String>,
    g: EventFn<'a, T, N, Q>,
    direction: Direction,
    terminal: Terminal<'a, T, N, Q>,
    action: Option<ActionFn<'a, T, N, Q>>,
    restart: bool,
}

impl<T: Real, const N: usize, const Q: usize> fmt::Debug for Event<'_, T, N, Q> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Event")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .field(
                "terminal",
                &match self.terminal {
                    Terminal::Never => "never",
                    Terminal::Always => "always",
                    Terminal::If(_) => "if",
                },
            )
            .field("action", &self.action.is_some())
            .field("restart", &self.restart)
            .finish()
    }
}

impl<'a, T: Real, const N: usize, const Q: usize> Event<'a, T, N, Q> {
    /// An event on the zero crossings of `g(t, q, v)` in both directions, not
    /// terminal, without action: it is only recorded.
    ///
    /// `g` reads the configuration as the system holds it: with free
    /// orientations q has Q entries (each orientation's unit quaternion) and
    /// v has N (each orientation's body-axis ω), so `Event::new` fits every
    /// system, with or without orientations.
    ///
    /// Given to a simulation (`Simulation::new(&sys).event(Event::new(..))`),
    /// the event takes the system's scalar and dimension, so closures that
    /// index the state need no annotation: `|_, q, _| q[0] - 1.0`,
    /// `|_, _, v| v[0]`, `.action(|_, _, v| *v *= -0.9)`. Rust checks a
    /// closure's body where it is written, before it reaches the simulation,
    /// so a body that calls a method on a component (`q[1].cos()`,
    /// `q[0].abs()`) fails with "type annotations needed" (E0282). Name the
    /// scalar once, on the time, `|_: f64, q, _| q[1].cos()`; the compiler's
    /// suggestion points there too. An event built outside a simulation (a
    /// `let`, [`Events::with`]) has nothing to take its types from: annotate
    /// the state and the velocities, `|_, q: &SVector<f64, 2>, _: &SVector<f64, 2>|`
    /// (once the event reaches a simulation in the same function, the
    /// simulation fixes what is left unannotated).
    ///
    /// ```
    /// # use lagrange_runtime::{Dopri5, Event, Lagrangian, Simulation};
    /// # use nalgebra::{Matrix1, Vector1};
    /// # struct Pendulum;
    /// # impl Lagrangian<f64, 1> for Pendulum {
    /// #     const COORDINATES: [&'static str; 1] = ["theta"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::new(-q[0].sin()) }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
    /// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { -q[0].cos() }
    /// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
    /// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    /// #     }
    /// # }
    /// let run = Simulation::new(&Pendulum)
    ///     .integrator(Dopri5::tol(1e-10))
    ///     .event(Event::new(|_, _, v| v[0]).falling())          // no annotation
    ///     .event(Event::new(|_: f64, q, _| q[0].sin() - 0.5))   // the scalar, once
    ///     .run([1.0], [0.0], 0.0..10.0)?;
    /// assert!(!run.times(0).is_empty() && !run.times(1).is_empty());
    /// # Ok::<(), lagrange_runtime::Error>(())
    /// ```
    pub fn new(g: impl Fn(T, &SVector<T, Q>, &SVector<T, N>) -> T + 'a) -> Self {
        Event {
            name: None,
            g: Box::new(g),
            direction: Direction::Both,
            terminal: Terminal::Never,
            action: None,
            restart: false,
        }
    }

    /// The same as [`new`](Event::new), which takes q with its quaternions
    /// for every system.
    #[deprecated(
        note = "`Event::new` now reads q with its quaternions on systems with orientations; call it instead"
    )]
    pub fn with_orientations(g: impl Fn(T, &SVector<T, Q>, &SVector<T, N>) -> T + 'a) -> Self {
        Self::new(g)
    }

    /// Only crossings from negative to positive count.
    pub fn rising(self) -> Self {
        self.direction(Direction::Rising)
    }

    /// Only crossings from positive to negative count.
    pub fn falling(self) -> Self {
        self.direction(Direction::Falling)
    }

    /// Sets which crossings count.
    pub fn direction(mut self, direction: Direction) -> Self {
        self.direction = direction;
        self
    }

    /// The run ends at the first occurrence of this event (after its action, if
    /// it has one).
    pub fn terminal(mut self) -> Self {
        self.terminal = Terminal::Always;
        self
    }

    /// The run ends at an occurrence where `test(t, q, v)` holds for the state
    /// after the action (if any): e.g. an impact that leaves too little normal
    /// velocity to bounce again, so the caller can switch to a resting or
    /// sliding contact model. Replaces [`terminal`](Self::terminal).
    pub fn terminal_if(
        mut self,
        test: impl Fn(T, &SVector<T, Q>, &SVector<T, N>) -> bool + 'a,
    ) -> Self {
        self.terminal = Terminal::If(Box::new(test));
        self
    }

    /// At each occurrence, `action(t, &mut q, &mut v)` replaces the state, and
    /// the integration restarts from it.
    pub fn action(
        mut self,
        action: impl Fn(T, &mut SVector<T, Q>, &mut SVector<T, N>) + 'a,
    ) -> Self {
        self.action = Some(Box::new(action));
        self
    }

    /// At each crossing the step is cut and the integrator restarted there,
    /// from the state just past the surface, unchanged. This pairs the event
    /// with a switch in the equations of motion on the same function
    /// (`sign(g)`, `if g > 0 { .. }`, `min`, `max`, `clamp`, `abs` in a
    /// force or potential): no step then straddles the switch, so the
    /// integrator does not chatter or shrink its steps there, and each smooth
    /// piece is integrated on its own.
    ///
    /// The restart lands on the far side of the surface, so the event does
    /// not fire again at once. If the motion turns back at once (a sliding
    /// mode, such as a body that friction holds at rest) the crossings
    /// accumulate and the run ends with [`Error::EventsAccumulate`]: end the
    /// run there instead ([`terminal_if`](Self::terminal_if)) or hold the
    /// state with an [`action`](Self::action). With an action, the action
    /// takes over: it receives the state before the crossing, as for any
    /// impact law.
    pub fn restart(mut self) -> Self {
        self.restart = true;
        self
    }

    /// Names the event in error messages (by default `event #k`, k its
    /// position).
    pub fn named(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// The event's name, empty if it has none.
    pub fn name(&self) -> &str {
        self.name.as_deref().unwrap_or("")
    }

    /// The crossings this event counts.
    pub fn crossing_direction(&self) -> Direction {
        self.direction
    }

    /// Whether the event may end the run ([`terminal`](Self::terminal) or
    /// [`terminal_if`](Self::terminal_if)).
    pub fn is_terminal(&self) -> bool {
        !matches!(self.terminal, Terminal::Never)
    }

    /// Whether an occurrence stops the integrator (it has an action or may end
    /// the run).
    fn stops(&self) -> bool {
        self.is_terminal() || self.action.is_some() || self.restart
    }

    /// Whether the cut lands past the surface ([`restart`](Self::restart)
    /// without an action) rather than before it.
    fn lands_past(&self) -> bool {
        self.restart && self.action.is_none()
    }

    /// Whether the occurrence at t with the state (q, v) after the action ends the run.
    fn ends(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> bool {
        match &self.terminal {
            Terminal::Never => false,
            Terminal::Always => true,
            Terminal::If(test) => test(t, q, v),
        }
    }

    fn label(&self, index: usize) -> String {
        self.name
            .clone()
            .unwrap_or_else(|| format!("event #{index}"))
    }

    /// g(t, q, v), or [`Error::EventFunction`] if it is not finite.
    fn value(&self, index: usize, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<T, Error> {
        let g = (self.g)(t, q, v);
        if g.is_finite() {
            Ok(g)
        } else {
            Err(Error::EventFunction {
                event: self.label(index),
                t: t.to_f64(),
                q: to_vec(q),
                v: to_vec(v),
            })
        }
    }
}

/// One occurrence of an event.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Occurrence<T: Real, const N: usize, const Q: usize = N> {
    /// Which event, by its position in the order the events were added.
    pub event: usize,
    /// When.
    pub t: T,
    /// Coordinates at the event, before any action.
    pub q: SVector<T, Q>,
    /// Velocities at the event, before any action.
    pub v: SVector<T, N>,
    /// Coordinates after the event's action (= `q` without one).
    pub q_after: SVector<T, Q>,
    /// Velocities after the event's action (= `v` without one).
    pub v_after: SVector<T, N>,
}

/// The result of a run with events.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventRun<T: Real, const N: usize, const Q: usize = N> {
    /// The motion, concatenated across the restarts at actions (see the module
    /// docs for what is recorded at an action).
    pub trajectory: Trajectory<T, N, Q>,
    /// All occurrences, in time order.
    pub occurrences: Vec<Occurrence<T, N, Q>>,
    /// The terminal event that ended the run, if one did.
    pub terminated_by: Option<usize>,
}

impl<T: Real, const N: usize, const Q: usize> EventRun<T, N, Q> {
    /// A run that stopped before its first step: the initial state, no
    /// occurrences.
    pub(crate) fn unstarted(trajectory: Trajectory<T, N, Q>) -> Self {
        Self {
            trajectory,
            occurrences: Vec::new(),
            terminated_by: None,
        }
    }

    /// The occurrences of event `event`, in time order.
    pub fn of(&self, event: usize) -> impl Iterator<Item = &Occurrence<T, N, Q>> {
        self.occurrences.iter().filter(move |o| o.event == event)
    }

    /// The times of event `event`, in increasing order.
    pub fn times(&self, event: usize) -> Vec<T> {
        self.of(event).map(|o| o.t).collect()
    }
}

impl<T: Real, const N: usize, const Q: usize> Progress for EventRun<T, N, Q> {
    fn progress(&self) -> (usize, Option<f64>) {
        self.trajectory.progress()
    }
}
