//! Events: zero crossings of user functions g(t, q, v) during an integration,
//! located on the dense output, optionally changing the state (an impact law)
//! or ending the run.
//!
//! ```text
//! let bounce = Event::new(|_, q, _| q[0])            // height above the floor
//!     .falling()
//!     .action(move |_, _, v| *v *= -e);              // restitution
//! let run = Simulation::new(&ball).integrator(Dopri5::tol(1e-10))
//!     .event(bounce)
//!     .run([1.0], [0.0], 0.0..10.0)?;
//! for o in &run.occurrences { println!("{} {}", o.t, o.v[0]); }
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

use crate::error::{Error, Failure, to_vec};
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::numeric::root::brent_bracket;
use crate::ode::Trajectory;
use crate::ode::{DenseSegment, Integrator, Mechanical, Sample, SecondOrder, check_problem};
use nalgebra::{SMatrix, SVector};
use std::cell::RefCell;
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

type EventFn<'a, T, const N: usize> = Box<dyn Fn(T, &SVector<T, N>, &SVector<T, N>) -> T + 'a>;
type ActionFn<'a, T, const N: usize> = Box<dyn Fn(T, &mut SVector<T, N>, &mut SVector<T, N>) + 'a>;
type TestFn<'a, T, const N: usize> = Box<dyn Fn(T, &SVector<T, N>, &SVector<T, N>) -> bool + 'a>;

/// When an occurrence ends the run.
enum Terminal<'a, T, const N: usize> {
    Never,
    Always,
    /// When the test holds for the state after the action.
    If(TestFn<'a, T, N>),
}

/// An event: the zero crossings of g(t, q, v) in a [`Direction`], optionally
/// with an action that maps the state at the crossing to a new one (an impact
/// law), optionally terminal (the run ends there).
///
/// ```
/// use lagrange_runtime::Event;
/// use nalgebra::SVector;
/// let e = 0.8;
/// let floor = Event::new(|_t, q: &SVector<f64, 1>, _v| q[0])
///     .falling()
///     .named("floor")
///     .action(move |_t, _q, v| *v *= -e);
/// assert_eq!(floor.name(), "floor");
/// ```
pub struct Event<'a, T: Real, const N: usize> {
    name: Option<String>,
    g: EventFn<'a, T, N>,
    direction: Direction,
    terminal: Terminal<'a, T, N>,
    action: Option<ActionFn<'a, T, N>>,
    restart: bool,
}

impl<T: Real, const N: usize> fmt::Debug for Event<'_, T, N> {
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

impl<'a, T: Real, const N: usize> Event<'a, T, N> {
    /// An event on the zero crossings of `g(t, q, v)` in both directions, not
    /// terminal, without action: it is only recorded.
    pub fn new(g: impl Fn(T, &SVector<T, N>, &SVector<T, N>) -> T + 'a) -> Self {
        Self {
            name: None,
            g: Box::new(g),
            direction: Direction::Both,
            terminal: Terminal::Never,
            action: None,
            restart: false,
        }
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
        test: impl Fn(T, &SVector<T, N>, &SVector<T, N>) -> bool + 'a,
    ) -> Self {
        self.terminal = Terminal::If(Box::new(test));
        self
    }

    /// At each occurrence, `action(t, &mut q, &mut v)` replaces the state, and
    /// the integration restarts from it.
    pub fn action(
        mut self,
        action: impl Fn(T, &mut SVector<T, N>, &mut SVector<T, N>) + 'a,
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
    fn ends(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> bool {
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
    fn value(&self, index: usize, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> Result<T, Error> {
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
pub struct Occurrence<T: Real, const N: usize> {
    /// Which event, by its position in the order the events were added.
    pub event: usize,
    /// When.
    pub t: T,
    /// Coordinates at the event, before any action.
    pub q: SVector<T, N>,
    /// Velocities at the event, before any action.
    pub v: SVector<T, N>,
    /// Coordinates after the event's action (= `q` without one).
    pub q_after: SVector<T, N>,
    /// Velocities after the event's action (= `v` without one).
    pub v_after: SVector<T, N>,
}

/// The result of a run with events.
#[derive(Clone, Debug)]
pub struct EventRun<T: Real, const N: usize> {
    /// The motion, concatenated across the restarts at actions (see the module
    /// docs for what is recorded at an action).
    pub trajectory: Trajectory<T, N>,
    /// All occurrences, in time order.
    pub occurrences: Vec<Occurrence<T, N>>,
    /// The terminal event that ended the run, if one did.
    pub terminated_by: Option<usize>,
}

impl<T: Real, const N: usize> EventRun<T, N> {
    /// A run that stopped before its first step: the initial state, no
    /// occurrences.
    pub(crate) fn unstarted(trajectory: Trajectory<T, N>) -> Self {
        Self {
            trajectory,
            occurrences: Vec::new(),
            terminated_by: None,
        }
    }

    /// The occurrences of event `event`, in time order.
    pub fn of(&self, event: usize) -> impl Iterator<Item = &Occurrence<T, N>> {
        self.occurrences.iter().filter(move |o| o.event == event)
    }

    /// The times of event `event`, in increasing order.
    pub fn times(&self, event: usize) -> Vec<T> {
        self.of(event).map(|o| o.t).collect()
    }
}

/// A list of events and the budget of restarts, ready to drive any
/// [`Integrator`] on any [`SecondOrder`] system ([`Simulation::event`] builds
/// one for a [`Lagrangian`](crate::Lagrangian) system).
///
/// [`Simulation::event`]: crate::Simulation::event
#[derive(Debug)]
pub struct Events<'a, T: Real, const N: usize> {
    events: Vec<Event<'a, T, N>>,
    max_events: usize,
}

impl<T: Real, const N: usize> Default for Events<'_, T, N> {
    fn default() -> Self {
        Self::new()
    }
}

/// Default budget of events that stop the integration (actions and the
/// terminal one).
pub const DEFAULT_MAX_EVENTS: usize = 10_000;

impl<'a, T: Real, const N: usize> Events<'a, T, N> {
    /// No events yet; budget [`DEFAULT_MAX_EVENTS`].
    pub fn new() -> Self {
        Self {
            events: Vec::new(),
            max_events: DEFAULT_MAX_EVENTS,
        }
    }

    /// Adds an event; its index in occurrences is the number added before it.
    pub fn with(mut self, event: Event<'a, T, N>) -> Self {
        self.events.push(event);
        self
    }

    /// Sets how many events may stop and restart the integration before the
    /// run ends with [`Error::TooManyEvents`] (default [`DEFAULT_MAX_EVENTS`]).
    pub fn max_events(mut self, n: usize) -> Self {
        self.max_events = n;
        self
    }

    /// The events, in order.
    pub fn events(&self) -> &[Event<'a, T, N>] {
        &self.events
    }

    /// Integrates `rhs` with `integrator` from (q0, v0) at t0 to t1 (or to a
    /// terminal event), watching the events.
    ///
    /// A crossing exactly at t0 (g(t0) = 0) is not an event: the sign is taken
    /// from the first step.
    ///
    /// # Errors
    /// [`Error::InvalidSettings`] for a zero event budget or a bad span or
    /// initial state; [`Error::EventFunction`] if an event function is not
    /// finite; [`Error::NonFiniteState`] if an action produces a non-finite
    /// state; [`Error::TooManyEvents`], [`Error::EventsAccumulate`]; whatever
    /// the integrator and the system report.
    pub fn integrate<I: Integrator, F: SecondOrder<T, N>>(
        &self,
        integrator: &I,
        rhs: &F,
        t0: T,
        t1: T,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
    ) -> Result<EventRun<T, N>, Failure<EventRun<T, N>>> {
        let started = crate::numeric::clock::Stopwatch::start();
        let watch = Watch {
            rhs,
            events: &self.events,
            state: RefCell::new(WatchState {
                last: Vec::with_capacity(self.events.len()),
                fired: None,
                found: Vec::new(),
                stop: None,
            }),
        };
        let mut trajectory: Option<Trajectory<T, N>> = None;
        let mut terminated_by = None;
        // Everything computed before a failure (the pieces so far, the failed
        // piece's accepted steps, the occurrences) goes back with it.
        let outcome = (|| -> Result<(), Error> {
            check_problem(t0, t1, &q0, &v0)?;
            if self.max_events == 0 {
                return Err(Error::InvalidSettings(
                    "events: max_events must be positive".into(),
                ));
            }
            watch.reset(t0, &q0, &v0, None)?;
            // Two restarts closer than this are "no progress".
            let eps = T::default_epsilon();
            let stalled_within = T::lit(64.0) * eps * (abs(t0) + abs(t1));
            let (mut t, mut q, mut v) = (t0, q0, v0);
            let (mut restarts, mut stalled) = (0usize, 0usize);
            loop {
                let mut piece = match integrator.integrate(&watch, t, t1, q, v) {
                    Ok(piece) => piece,
                    Err(failure) => {
                        join(&mut trajectory, *failure.partial);
                        return Err(failure.error);
                    }
                };
                let Some(stop) = watch.state.borrow_mut().stop.take() else {
                    join(&mut trajectory, piece);
                    break;
                };
                let event = &self.events[stop.event];
                let (mut qa, mut va) = (stop.q, stop.v);
                if let Some(action) = &event.action {
                    action(stop.t, &mut qa, &mut va);
                    if !qa.iter().chain(va.iter()).all(|x| x.is_finite()) {
                        join(&mut trajectory, piece);
                        return Err(Error::non_finite(stop.t, &qa, &va));
                    }
                    rhs.project(stop.t, &mut qa, &mut va)?;
                }
                piece.truncate_last(stop.t, qa, va, Sample::of(rhs, stop.t, &qa, &va));
                join(&mut trajectory, piece);
                watch.state.borrow_mut().found.push(Occurrence {
                    event: stop.event,
                    t: stop.t,
                    q: stop.q,
                    v: stop.v,
                    q_after: qa,
                    v_after: va,
                });
                if event.ends(stop.t, &qa, &va) {
                    terminated_by = Some(stop.event);
                    break;
                }
                restarts += 1;
                if restarts > self.max_events {
                    return Err(Error::TooManyEvents {
                        t: stop.t.to_f64(),
                        event: event.label(stop.event),
                        max_events: self.max_events,
                    });
                }
                stalled = if stop.t - t <= stalled_within {
                    stalled + 1
                } else {
                    0
                };
                if stalled >= 3 {
                    return Err(Error::EventsAccumulate {
                        t: stop.t.to_f64(),
                        event: event.label(stop.event),
                        count: stalled,
                    });
                }
                // An event on the end time (up to round-off) leaves nothing to
                // integrate: a restart would only fail on a vanishing step.
                if t1 - stop.t <= stalled_within {
                    break;
                }
                // Past the surface the fired event's sign is already the new one.
                let fired = (!event.lands_past()).then_some((stop.event, stop.before));
                watch.reset(stop.t, &qa, &va, fired)?;
                (t, q, v) = (stop.t, qa, va);
            }
            Ok(())
        })();
        let mut trajectory = trajectory
            .unwrap_or_else(|| Trajectory::start(t0, q0, v0, Sample::of(rhs, t0, &q0, &v0)));
        let mut stats = *trajectory.stats();
        stats.wall_time = started.elapsed();
        trajectory.set_stats(stats);
        let run = EventRun {
            trajectory,
            occurrences: watch.state.into_inner().found,
            terminated_by,
        };
        match outcome {
            Ok(()) => Ok(run),
            Err(error) => Err(Failure::new(error, run)),
        }
    }
}

fn join<T: Real, const N: usize>(whole: &mut Option<Trajectory<T, N>>, piece: Trajectory<T, N>) {
    match whole {
        Some(w) => w.append(piece),
        None => *whole = Some(piece),
    }
}

/// The event occurrence that ends an integrator's run.
#[derive(Clone, Copy)]
struct Stop<T: Real, const N: usize> {
    event: usize,
    t: T,
    q: SVector<T, N>,
    v: SVector<T, N>,
    /// The event function's value on the old side of the crossing.
    before: T,
}

struct WatchState<T: Real, const N: usize> {
    /// Each event function at the last recorded state; zero means "sign not
    /// known yet" (exactly zero there), and the next sample sets it.
    last: Vec<T>,
    /// The event that fired at the start of this integrator run, until its
    /// first step is checked: its start value is the forced pre-crossing sign.
    fired: Option<usize>,
    found: Vec<Occurrence<T, N>>,
    stop: Option<Stop<T, N>>,
}

/// The system seen through the event observer: everything is delegated, and
/// [`after_step`](SecondOrder::after_step) watches the events.
struct Watch<'w, 'e, F, T: Real, const N: usize> {
    rhs: &'w F,
    events: &'w [Event<'e, T, N>],
    state: RefCell<WatchState<T, N>>,
}

impl<F: SecondOrder<T, N>, T: Real, const N: usize> Watch<'_, '_, F, T, N> {
    /// Samples every event function at the start of a run. After an action,
    /// the fired event keeps the sign it had before the crossing (its value at
    /// the cut is zero up to round-off, on either side), so it does not fire
    /// again at once.
    fn reset(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
        fired: Option<(usize, T)>,
    ) -> Result<(), Error> {
        let mut st = self.state.borrow_mut();
        st.last.clear();
        st.fired = fired.map(|(k, _)| k);
        for (i, event) in self.events.iter().enumerate() {
            let mut g = event.value(i, t, q, v)?;
            if let Some((k, before)) = fired
                && k == i
                && !same_sign(g, before)
            {
                g = if before > T::zero() {
                    T::lit(f64::MIN_POSITIVE)
                } else {
                    -T::lit(f64::MIN_POSITIVE)
                };
            }
            st.last.push(g);
        }
        Ok(())
    }
}

/// Whether a and b are both positive or both negative (zero matches nothing).
fn same_sign<T: Real>(a: T, b: T) -> bool {
    (a > T::zero() && b > T::zero()) || (a < T::zero() && b < T::zero())
}

/// The crossings of one event inside one step: up to two, one per half step.
/// `samples` are (t, g) at the start, the midpoint and the end.
///
/// `fired`: the event fired at the start of the step (the restart point) and
/// its start value is only the sign it had before. Right after that root the
/// function is below its round-off level, and a bracket reaching down to the
/// start would find noise there instead of a genuine second crossing (a small
/// bounce inside the first half step). So the left end is moved to the
/// furthest point start + (mid − start)/2^k where the function shows the old
/// sign; if there is none, the action did not resolve the event and the
/// crossing is reported right after the start (the driver then stops with
/// [`Error::EventsAccumulate`]).
fn crossings<T: Real, const N: usize>(
    event: &Event<'_, T, N>,
    segment: &DenseSegment<T, N>,
    samples: [(T, T); 3],
    fired: bool,
) -> [Option<(T, T)>; 2] {
    let on_segment = |s: T| {
        let (q, v) = segment.eval(s);
        (event.g)(s, &q, &v)
    };
    let mut out = [None; 2];
    for (k, pair) in samples.windows(2).enumerate() {
        let ((mut ta, mut ga), (tb, gb)) = (pair[0], pair[1]);
        // A zero start has no sign: the later sample sets it, no crossing.
        if ga == T::zero() || same_sign(ga, gb) || !event.direction.admits(ga) {
            continue;
        }
        if fired && k == 0 {
            let before = ga;
            let mut offset = (tb - ta) * T::lit(0.5);
            let mut found = false;
            for _ in 0..60 {
                let s = ta + offset;
                if s <= ta {
                    break;
                }
                let gs = on_segment(s);
                if same_sign(gs, before) {
                    (ta, ga, found) = (s, gs, true);
                    break;
                }
                offset *= T::lit(0.5);
            }
            if !found {
                out[k] = Some((ta + offset.max(T::default_epsilon() * abs(ta)), before));
                continue;
            }
        }
        let t = if gb == T::zero() {
            tb
        } else {
            let (b, fb, c, fc) = brent_bracket(on_segment, ta, tb, ga, gb);
            // The end of the final bracket on the old side of the crossing,
            // or on the new side for a restart.
            if event.lands_past() {
                if same_sign(fb, ga) { c } else { b }
            } else if same_sign(fb, ga) || fb == T::zero() || !same_sign(fc, ga) {
                b
            } else {
                c
            }
        };
        out[k] = Some((t, ga));
    }
    out
}

impl<F: SecondOrder<T, N>, T: Real, const N: usize> SecondOrder<T, N> for Watch<'_, '_, F, T, N> {
    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        self.rhs.acceleration(t, q, v)
    }

    fn integral(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> T {
        self.rhs.integral(t, q, v)
    }

    fn residuals(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> [T; 2] {
        self.rhs.residuals(t, q, v)
    }

    fn project(&self, t: T, q: &mut SVector<T, N>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        self.rhs.project(t, q, v)
    }

    fn mechanical(&self) -> Option<&dyn Mechanical<T, N>> {
        self.rhs.mechanical()
    }

    fn jacobian(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Option<Result<(SMatrix<T, N, N>, SMatrix<T, N, N>), Error>> {
        self.rhs.jacobian(t, q, v)
    }

    fn after_step(
        &self,
        segment: &DenseSegment<T, N>,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<bool, Error> {
        // The wrapped system's own observer first (an event layer inside
        // another): if it alone stops, the run ends there, before t1.
        let inner_stop = self.rhs.after_step(segment, q, v)?;
        if self.events.is_empty() {
            return Ok(inner_stop);
        }
        let mut guard = self.state.borrow_mut();
        let st = &mut *guard;
        let (ta, tb) = (segment.start(), segment.end());
        let tm = ta + (tb - ta) * T::lit(0.5);
        let (qm, vm) = segment.eval(tm);
        let first_new = st.found.len();
        let fired = st.fired.take();
        let mut stop: Option<Stop<T, N>> = None;
        for (i, event) in self.events.iter().enumerate() {
            let gm = event.value(i, tm, &qm, &vm)?;
            let gb = event.value(i, tb, q, v)?;
            let samples = [(ta, st.last[i]), (tm, gm), (tb, gb)];
            st.last[i] = gb;
            let fresh = fired == Some(i);
            for (t, before) in crossings(event, segment, samples, fresh)
                .into_iter()
                .flatten()
            {
                let (qc, vc) = if t == tb { (*q, *v) } else { segment.eval(t) };
                if event.stops() {
                    // Only the first crossing of a stopping event matters.
                    if stop.is_none_or(|s| t < s.t) {
                        stop = Some(Stop {
                            event: i,
                            t,
                            q: qc,
                            v: vc,
                            before,
                        });
                    }
                    break;
                }
                st.found.push(Occurrence {
                    event: i,
                    t,
                    q: qc,
                    v: vc,
                    q_after: qc,
                    v_after: vc,
                });
            }
        }
        if let Some(s) = &stop {
            // Crossings after the stop belong to a motion that will not happen.
            let mut k = first_new;
            while k < st.found.len() {
                if st.found[k].t > s.t {
                    st.found.swap_remove(k);
                } else {
                    k += 1;
                }
            }
        }
        st.found[first_new..]
            .sort_by(|a, b| a.t.partial_cmp(&b.t).unwrap_or(std::cmp::Ordering::Equal));
        st.stop = stop;
        Ok(stop.is_some() || inner_stop)
    }
}
