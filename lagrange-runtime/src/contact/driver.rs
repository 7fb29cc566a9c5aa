//! The run from event to event: each stretch integrated with its contacts'
//! modes fixed and the events that end it watched on the dense output; at
//! each event the impacts and the new modes.

use super::compliant::Compliant;
use super::form::{ContactForm, Mode, has_tangent};
use super::run::{ChangeKind, ContactChange, ContactRun, ContactSettings};
use crate::error::{ContactError, ContactFault, Error, Failure, SettingsError};
use crate::event::{Event, Events};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::ode::{Continuation, Integrator, MoreauJean, Sample, Trajectory};
use crate::ode::{check_orientations, check_problem};
use crate::system::{ContactLaw, ContactRows, Contacts};
use nalgebra::SVector;
use std::ops::Range;

/// What the zero of a stretch's event means.
#[derive(Clone, Copy, Debug)]
enum Watched {
    Touches(usize),
    LiftsOff(usize),
    Stops(usize),
    Slips(usize),
}

/// What an event imposes on the next choice of modes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Forced {
    Nothing,
    Open(usize),
    Slide(usize),
}

/// A contact run in progress: the system, its laws and what has been
/// computed so far.
pub(super) struct Driver<'s, S, T: Real, const N: usize, const Q: usize = N, F = NoForcing> {
    pub(super) system: &'s S,
    /// The inputs' forces, where a source drives the run.
    pub(super) forcing: &'s F,
    pub(super) laws: Vec<ContactLaw>,
    pub(super) settings: ContactSettings,
    pub(super) singular: T,
    pub(super) trajectory: Option<Trajectory<T, N, Q>>,
    pub(super) changes: Vec<ContactChange<T>>,
    pub(super) phases: Vec<(T, Vec<Mode<T>>)>,
}

/// Runs `system` with its contacts from (q0, v0) over `span`, driven by
/// `forcing`'s forces ([`NoForcing`] for none).
/// `refused` is an error found before the run (an input source it cannot
/// take), returned with the initial state alone.
pub(crate) fn run_contacts<S, I, T, F, const N: usize, const Q: usize>(
    (system, forcing, refused): (&S, &F, Result<(), Error>),
    integrator: &I,
    (settings, compliant): (ContactSettings, Option<Compliant>),
    singular: T,
    (q0, v0, span): (SVector<T, Q>, SVector<T, N>, Range<T>),
) -> Result<ContactRun<T, N, Q>, Failure<ContactRun<T, N, Q>>>
where
    S: Contacts<T, N, Q>,
    I: Integrator,
    T: Real,
    F: Forcing<T, N, Q>,
{
    let mut driver = Driver {
        system,
        forcing,
        laws: system.contact_laws(),
        settings,
        singular,
        trajectory: None,
        changes: Vec::new(),
        phases: Vec::new(),
    };
    let stepping = integrator
        .as_any()
        .and_then(|a| a.downcast_ref::<MoreauJean>());
    let outcome = refused
        .and_then(|()| forcing.take_sample(span.start, &q0, &v0))
        .and_then(|()| match (compliant, stepping) {
            (Some(model), _) => driver.comply(&model, integrator, (q0, v0), span.clone()),
            (None, Some(scheme)) => driver.step_through(scheme, q0, v0, span.clone()),
            (None, None) => driver.drive(integrator, q0, v0, span.clone()),
        });
    let trajectory = match driver.trajectory.take() {
        Some(t) => t,
        None => {
            let form = driver.form(vec![Mode::Open; driver.laws.len()]);
            Trajectory::start(span.start, q0, v0, Sample::of(&form, span.start, &q0, &v0))
        }
    };
    let run = ContactRun {
        trajectory,
        changes: driver.changes,
        phases: driver.phases,
        singular,
        stick_speed: T::lit(settings.stick_speed),
        compliant,
    };
    match outcome {
        Ok(()) => Ok(run),
        Err(error) => Err(Failure::new(error, run)),
    }
}

/// e ∈ [0, 1] and μ ≥ 0, finite.
fn check_laws(laws: &[ContactLaw]) -> Result<(), Error> {
    for law in laws {
        let name = law.name;
        if !(0.0..=1.0).contains(&law.restitution) {
            return Err(SettingsError::Value {
                owner: "contact law",
                setting: "restitution",
                value: law.restitution,
                requirement: format!("in [0, 1] (contact `{name}`)"),
            }
            .into());
        }
        let dry = law.is_dry_friction();
        if !(law.friction.is_finite() && (law.friction > 0.0 || !dry && law.friction == 0.0)) {
            let requirement = match dry {
                true => format!("positive and finite: dry friction's bound (contact `{name}`)"),
                false => format!("non-negative and finite (contact `{name}`)"),
            };
            return Err(SettingsError::Value {
                owner: "contact law",
                setting: "friction",
                value: law.friction,
                requirement,
            }
            .into());
        }
    }
    Ok(())
}

impl<'s, S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>
    Driver<'s, S, T, N, Q, F>
{
    pub(super) fn form(&self, modes: Vec<Mode<T>>) -> ContactForm<'_, S, T, F> {
        ContactForm {
            system: self.system,
            forcing: self.forcing,
            laws: &self.laws,
            modes,
            singular: self.singular,
            stick_speed: T::lit(self.settings.stick_speed),
        }
    }

    /// What every contact run checks before its first step: the span and
    /// the state (its quaternions unit), the settings, the laws and their
    /// listing.
    pub(super) fn check_start(
        &self,
        (t0, t1): (T, T),
        q0: &SVector<T, Q>,
        v0: &SVector<T, N>,
    ) -> Result<(), Error> {
        check_problem(t0, t1, q0, v0)?;
        check_orientations(&self.form(Vec::new()), q0)?;
        self.settings.check()?;
        check_laws(&self.laws)?;
        self.check_listed(t0, q0)
    }

    /// The laws' names are `CONTACTS`, in order.
    fn check_listed(&self, t0: T, q0: &SVector<T, Q>) -> Result<(), Error> {
        let laws: Vec<&'static str> = self.laws.iter().map(|l| l.name).collect();
        if laws == S::CONTACTS {
            return Ok(());
        }
        let differs = (0..laws.len().max(S::CONTACTS.len()))
            .find(|&k| laws.get(k) != S::CONTACTS.get(k))
            .unwrap_or(0);
        let named = laws.get(differs).or(S::CONTACTS.get(differs));
        Err(ContactError {
            contact: named.map_or_else(String::new, |n| (*n).to_owned()),
            t: t0.to_f64(),
            q: q0.iter().map(|x| x.to_f64()).collect(),
            fault: ContactFault::NotListed {
                listed: S::CONTACTS,
            },
        }
        .into())
    }

    fn join(&mut self, piece: Trajectory<T, N, Q>) {
        match &mut self.trajectory {
            Some(whole) => {
                whole.append(piece);
            }
            None => self.trajectory = Some(piece),
        }
    }

    /// The stretches from event to event, to the end of the span.
    fn drive<I: Integrator>(
        &mut self,
        integrator: &I,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<(), Error> {
        let (t0, t1) = (span.start, span.end);
        self.check_start((t0, t1), &q0, &v0)?;
        let (mut t, mut q, mut v) = (t0, q0, v0);
        let start = self.starting_modes(t, &q, &v)?;
        let mut modes = self.settle(t, &q, &mut v, &start, Forced::Nothing)?;
        let stalled_within = T::lit(64.0) * T::default_epsilon() * (abs(t0) + abs(t1));
        let (mut count, mut stalled) = (0usize, 0usize);
        loop {
            self.phases.push((t, modes.clone()));
            // A held input's next sample ends the stretch too.
            let sample = self.forcing.next_sample(t0, t).filter(|&b| b < t1);
            let stop = self.stretch(integrator, &modes, (t0, t, sample.unwrap_or(t1)), q, v)?;
            let Some((watched, (ts, qs, vs))) = stop else {
                let Some(b) = sample else { return Ok(()) };
                (t, q, v) = self.resample(b, (q, v))?;
                modes = self.settle(t, &q, &mut v, &modes, Forced::Nothing)?;
                continue;
            };
            count += 1;
            stalled = if ts - t <= stalled_within {
                stalled + 1
            } else {
                0
            };
            let name = self.laws[watched.contact()].name;
            if count > self.settings.max_changes {
                return Err(Error::TooManyEvents {
                    t: ts.to_f64(),
                    event: name.to_string(),
                    max_events: self.settings.max_changes,
                });
            }
            if stalled >= 8 {
                return Err(Error::EventsAccumulate {
                    t: ts.to_f64(),
                    event: name.to_string(),
                    count: stalled,
                });
            }
            crate::event::within_budget(self.trajectory.as_ref(), integrator.max_steps(), ts)?;
            (t, q, v) = (ts, qs, vs);
            if t1 - t <= stalled_within {
                return Ok(());
            }
            let forced = match watched {
                Watched::Touches(_) | Watched::Stops(_) => Forced::Nothing,
                Watched::LiftsOff(i) => Forced::Open(i),
                Watched::Slips(i) => Forced::Slide(i),
            };
            if let Watched::LiftsOff(i) = watched {
                self.record(t, i, ChangeKind::LiftsOff);
            }
            modes = self.settle(t, &q, &mut v, &modes, forced)?;
        }
    }

    /// The state at the end of the motion so far (`start` if none was
    /// made), at the sample instant `b`, with the held input's sample taken
    /// there.
    fn resample(
        &mut self,
        b: T,
        start: (SVector<T, Q>, SVector<T, N>),
    ) -> Result<(T, SVector<T, Q>, SVector<T, N>), Error> {
        let (q, v) = self
            .trajectory
            .as_ref()
            .map_or(start, Trajectory::final_state);
        self.forcing.take_sample(b, &q, &v)?;
        Ok((b, q, v))
    }

    /// One stretch with `modes`, from (q, v) at t to t1 or to the first
    /// event; joins its motion and returns the event and the state there
    /// (`None` at the end of the span).
    #[allow(clippy::type_complexity)]
    fn stretch<I: Integrator>(
        &mut self,
        integrator: &I,
        modes: &[Mode<T>],
        (t0, t, t1): (T, T, T),
        q: SVector<T, Q>,
        v: SVector<T, N>,
    ) -> Result<Option<(Watched, (T, SVector<T, Q>, SVector<T, N>))>, Error> {
        let form = self.form(modes.to_vec());
        let tolerance = T::lit(self.settings.gap_tolerance);
        let (watched, events) = watch(&form, (t, &q, &v), tolerance)?;
        let from = self
            .trajectory
            .as_ref()
            .map_or(Continuation::start(t0), Trajectory::continuation);
        let piece = events.continue_run(integrator, (&form, &[]), from, t, t1, q, v);
        drop(events);
        let piece = match piece {
            Ok(piece) => piece,
            Err(failure) => {
                self.join(failure.partial.trajectory);
                return Err(failure.error);
            }
        };
        self.join(piece.trajectory);
        Ok(piece
            .terminated_by
            .zip(piece.occurrences.last())
            .map(|(k, o)| (watched[k], (o.t, o.q, o.v))))
    }

    pub(super) fn record(&mut self, t: T, contact: usize, kind: ChangeKind<T>) {
        self.changes.push(ContactChange { t, contact, kind });
    }
}

impl Watched {
    fn contact(self) -> usize {
        match self {
            Watched::Touches(i) | Watched::LiftsOff(i) | Watched::Stops(i) | Watched::Slips(i) => i,
        }
    }
}

/// The events that end a stretch in the form's modes, all terminal: an open
/// contact's gap, a closed one's normal force, a sliding one's slip along
/// the slip the start's direction makes there, a sticking one's margin to
/// the cone.
#[allow(clippy::type_complexity)]
fn watch<'f, S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>(
    form: &'f ContactForm<'_, S, T, F>,
    (t, q, v): (T, &SVector<T, Q>, &SVector<T, N>),
    tolerance: T,
) -> Result<(Vec<Watched>, Events<'f, T, N, Q>), Error> {
    let nan = T::lit(f64::NAN);
    let mut watched = Vec::new();
    let mut events = Events::new();
    for (i, mode) in form.modes.iter().enumerate() {
        let law = form.laws[i];
        let name = law.name;
        let mu = T::lit(law.friction);
        // Dry friction never lifts off: only its slip and margin are watched.
        let lifts = !law.is_dry_friction();
        let (what, event) = match *mode {
            Mode::Open => (
                Watched::Touches(i),
                touch(form, i, (t, q, v), tolerance).named(format!("{name} touches")),
            ),
            Mode::Sliding { hint } if mu > T::zero() && slips(&form.rows(i, t, q, v)?) => {
                let r = form.rows(i, t, q, v)?;
                let u = form.slip_direction(ContactForm::<S, T, F>::slip(&r, v), hint);
                if lifts {
                    watched.push(Watched::LiftsOff(i));
                    events = events.with(lift_off(form, i, name));
                }
                // The start's slip direction as a generalized velocity w,
                // whose slip T(q) w is compared with the slip along the way:
                // a contact's two tangents may come from a chart that
                // changes (two spheres'), and w, unlike u's components,
                // does not change with it.
                let w = r.tangents[0] * u[0] + r.tangents[1] * u[1];
                let stop = Event::new(move |t, q, v| {
                    form.rows(i, t, q, v).map_or(nan, |r| {
                        let s = ContactForm::<S, T, F>::slip(&r, v);
                        let along = ContactForm::<S, T, F>::slip(&r, &w);
                        along[0] * s[0] + along[1] * s[1]
                    })
                });
                (
                    Watched::Stops(i),
                    stop.named(format!("{name} stops slipping")),
                )
            }
            Mode::Sliding { .. } => (Watched::LiftsOff(i), lift_off(form, i, name)),
            Mode::Sticking => {
                if lifts {
                    watched.push(Watched::LiftsOff(i));
                    events = events.with(lift_off(form, i, name));
                }
                let margin = Event::new(move |t, q, v| {
                    form.solve(t, q, v).map_or(nan, |s| {
                        let f = s.tangential[i];
                        law.friction_bound(s.normal[i]) - (f[0] * f[0] + f[1] * f[1]).sqrt()
                    })
                });
                (Watched::Slips(i), margin.named(format!("{name} slips")))
            }
        };
        watched.push(what);
        events = events.with(event.falling().terminal());
    }
    Ok((watched, events))
}

/// The event of an open contact's gap falling to zero. A contact that
/// leaves the surface at the start (a bounce) is watched through its gap
/// divided by the time since, φ(t)/(t − t₀), which starts at the normal
/// speed and falls through zero when the gap does: the gap itself starts at
/// zero, without a sign, and a bounce shorter than the integrator's step
/// would be missed.
fn touch<'f, S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>(
    form: &'f ContactForm<'_, S, T, F>,
    i: usize,
    (t0, q0, v0): (T, &SVector<T, Q>, &SVector<T, N>),
    tolerance: T,
) -> Event<'f, T, N, Q> {
    let nan = T::lit(f64::NAN);
    let leaving = form
        .rows(i, t0, q0, v0)
        .is_ok_and(|r| r.gap <= tolerance && r.normal.dot(v0) > T::zero());
    Event::new(move |t, q, v| {
        form.rows(i, t, q, v).map_or(nan, |r| match leaving {
            true if t > t0 => r.gap / (t - t0),
            true => r.normal.dot(v),
            false => form.approach(i, t, q, v).unwrap_or(r.gap),
        })
    })
}

/// Whether a contact can slip at all (it has a tangent row).
fn slips<T: Real, const N: usize>(rows: &ContactRows<T, N>) -> bool {
    rows.tangents.iter().any(has_tangent)
}

/// The event of a closed contact's normal force falling to zero.
fn lift_off<
    'f,
    S: Contacts<T, N, Q>,
    T: Real,
    F: Forcing<T, N, Q>,
    const N: usize,
    const Q: usize,
>(
    form: &'f ContactForm<'_, S, T, F>,
    i: usize,
    name: &str,
) -> Event<'f, T, N, Q> {
    let nan = T::lit(f64::NAN);
    Event::new(move |t, q, v| form.solve(t, q, v).map_or(nan, |s| s.normal[i]))
        .named(format!("{name} lifts off"))
        .falling()
        .terminal()
}
