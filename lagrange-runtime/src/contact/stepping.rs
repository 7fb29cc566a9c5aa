//! The time-stepping run ([`MoreauJean`]): fixed steps, each with one
//! impulse problem over the contacts closed at its midpoint, and the
//! changes of the contacts' modes read off the impulses step by step.

use super::coulomb::{Branch, Local, gauss_seidel};
use super::driver::Driver;
use super::form::{ContactForm, Mode, has_tangent};
use super::run::{ChangeKind, ContactState};
use crate::error::{ContactFault, Error};
use crate::mechanics::Forcing;
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::clock::Stopwatch;
use crate::ode::{Continuation, MoreauJean, Sample, Trajectory, fixed_steps};
use crate::ode::{SecondOrder, Stats, midpoint_segment};
use crate::system::Contacts;
use nalgebra::SVector;
use std::ops::Range;

/// One step's outcome per contact: its mode after the step and the normal
/// speed it had at the midpoint, before the impulse.
struct Outcome<T> {
    modes: Vec<Mode<T>>,
    approach: Vec<T>,
    /// The normal speed after the impulse along the midpoint's normal (the
    /// speed Newton's law sets), per contact.
    leaving: Vec<T>,
}

impl<S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>
    Driver<'_, S, T, N, Q, F>
{
    /// The fixed steps of `scheme` over `span`, recording the motion, the
    /// modes and their changes.
    pub(super) fn step_through(
        &mut self,
        scheme: &MoreauJean,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
        span: Range<T>,
    ) -> Result<(), Error> {
        let (t0, t1) = (span.start, span.end);
        self.check_start((t0, t1), &q0, &v0)?;
        scheme.recording().check_span(t0, t1, 2 * N)?;
        let n = scheme.steps(t0, t1)?;
        self.refuse_penetration(t0, &q0, &v0)?;
        let start = self.starting_modes(t0, &q0, &v0)?;
        let sample = Sample::of(&self.form(start.clone()), t0, &q0, &v0);
        let mut traj = Trajectory::start_recording(
            scheme.recording(),
            Continuation::start(t0),
            t0,
            q0,
            v0,
            sample,
        );
        traj.reserve(n);
        self.phases.push((t0, start.clone()));
        let started = Stopwatch::start();
        let mut stats = Stats::default();
        let (mut q, mut v, mut modes) = (q0, v0, start);
        let mut impulses: Vec<Option<[T; 3]>> = vec![None; self.laws.len()];
        let mut outcome = Ok(());
        let h = T::lit(scheme.step_size());
        let mut sample = self.forcing.next_sample(t0, t0);
        for (t, t_next) in fixed_steps(t0, t1, h, n) {
            // A held input is sampled at the step start nearest its instant.
            if let Some(b) = sample.filter(|&b| b <= t + T::lit(0.5) * h) {
                if let Err(error) = self.forcing.take_sample(t, &q, &v) {
                    outcome = Err(error);
                    break;
                }
                sample = self.forcing.next_sample(t0, b);
            }
            stats.evaluations += 1;
            match self.step(scheme, (t, t_next), (&q, &v), &mut impulses) {
                Ok((q_next, v_next, after)) => {
                    stats.accepted += 1;
                    let tm = T::lit(0.5) * (t + t_next);
                    let after = self.note_changes(tm, &modes, &after);
                    let form = self.form(after.clone());
                    let segment =
                        midpoint_segment(&form, (t, t_next), (&q, &v), (&q_next, &v_next));
                    traj.push_sampled(segment, q_next, v_next, |t, q, v| {
                        Sample::of(&form, t, q, v)
                    });
                    (q, v, modes) = (q_next, v_next, after);
                }
                Err(error) => {
                    outcome = Err(error);
                    break;
                }
            }
        }
        stats.wall_time = started.elapsed();
        traj.set_stats(stats);
        self.trajectory = Some(traj);
        outcome
    }

    /// A start below a surface beyond the gap tolerance is refused, as the
    /// event-driven run refuses it.
    fn refuse_penetration(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<(), Error> {
        let form = self.form(vec![Mode::Open; self.laws.len()]);
        let tolerance = T::lit(self.settings.gap_tolerance);
        for i in 0..self.laws.len() {
            let gap = form.rows(i, t, q, v)?.gap;
            if gap < -tolerance {
                let fault = ContactFault::Penetrates {
                    gap: gap.to_f64(),
                    tolerance: self.settings.gap_tolerance,
                };
                return Err(form.fault(i, t, q, fault));
            }
        }
        Ok(())
    }

    /// One step from (q, v) at t to t_next: the state after it and what
    /// the contacts did. `impulses` holds each contact's impulse of the
    /// step before (the warm start), and is updated.
    #[allow(clippy::type_complexity)]
    fn step(
        &self,
        scheme: &MoreauJean,
        (t, t_next): (T, T),
        (q, v): (&SVector<T, Q>, &SVector<T, N>),
        impulses: &mut [Option<[T; 3]>],
    ) -> Result<(SVector<T, Q>, SVector<T, N>, Outcome<T>), Error> {
        let h = t_next - t;
        let half = T::lit(0.5) * h;
        let tm = t + half;
        let form = self.form(vec![Mode::Open; self.laws.len()]);
        let mid = form.advance(q, &(v * half));
        let (m, rhs) = form.dynamics(tm, &mid, v)?;
        let chol = form.factor(tm, &mid, m)?;
        let mut next_v = v + chol.solve(rhs) * h;
        let (mut locals, approach) =
            self.closed(&form, (tm, &mid, v), (&chol, h), impulses, &mut next_v)?;
        let tolerance = T::lit(scheme.velocity_tolerance());
        if let Err(residual) =
            gauss_seidel(&mut locals, &mut next_v, scheme.max_sweeps(), tolerance)
        {
            let contact = locals.first().map_or(0, |c| c.contact);
            let fault = if !residual.is_finite() {
                ContactFault::NoImpulse
            } else {
                ContactFault::ImpulsesUnsettled {
                    sweeps: scheme.max_sweeps(),
                    change: residual.to_f64(),
                }
            };
            return Err(form.fault(contact, tm, &mid, fault));
        }
        let next_q = form.advance(&mid, &(next_v * half));
        if !(next_q.iter().chain(next_v.iter()).all(|x| x.is_finite())) {
            return Err(Error::non_finite(t_next, &next_q, &next_v));
        }
        let mut modes = vec![Mode::Open; self.laws.len()];
        let mut leaving = vec![T::zero(); self.laws.len()];
        for c in &locals {
            impulses[c.contact] = Some(c.impulse);
            modes[c.contact] = mode_of(c);
            if c.bound.is_none() {
                leaving[c.contact] = c.rows[0].dot(&next_v);
            }
        }
        let outcome = Outcome {
            modes,
            approach,
            leaving,
        };
        Ok((next_q, next_v, outcome))
    }

    /// The contacts closed at the midpoint (t, q, v) of a step h, each with
    /// its rows, responses M⁻¹ rowᵀ and Newton's bias e·min(uₙ, 0), warm-started from the
    /// step before's impulse (added to `next_v`); and every contact's
    /// normal speed there. An open contact forgets its impulse.
    #[allow(clippy::type_complexity)]
    fn closed(
        &self,
        form: &ContactForm<'_, S, T, F>,
        (t, q, v): (T, &SVector<T, Q>, &SVector<T, N>),
        (chol, h): (&Cholesky<T, N>, T),
        impulses: &mut [Option<[T; 3]>],
        next_v: &mut SVector<T, N>,
    ) -> Result<(Vec<Local<T, N>>, Vec<T>), Error> {
        let mut locals = Vec::new();
        let mut approach = vec![T::zero(); self.laws.len()];
        for (i, law) in self.laws.iter().enumerate() {
            let r = form.rows(i, t, q, v)?;
            approach[i] = r.normal.dot(v);
            if r.gap > T::lit(self.settings.gap_tolerance) {
                impulses[i] = None;
                continue;
            }
            let mu = T::lit(law.friction);
            let dry = law.is_dry_friction();
            // Dry friction has its tangents only, its impulse bounded by
            // the force bound times the step.
            let mut rows = if dry { Vec::new() } else { vec![r.normal] };
            let mut tangents = Vec::new();
            for (k, row) in r.tangents.iter().enumerate() {
                if mu > T::zero() && has_tangent(row) {
                    rows.push(*row);
                    tangents.push(k);
                }
            }
            if rows.is_empty() {
                continue;
            }
            let responses = rows.iter().map(|row| chol.solve(*row)).collect();
            // Newton's law for a contact that approaches; one that recedes
            // (or whose normal turned with the step, h J̇q̇) takes no
            // restitution, which would lift a pivoting corner by (1 + e) h J̇q̇.
            let bias = T::lit(law.restitution) * approach[i].min(T::zero());
            let mut local = Local::new(i, (rows, tangents), responses, bias, mu);
            local.bound = dry.then(|| mu * h);
            // Warm start: the impulse of the step before, already applied.
            if let Some(p) = impulses[i] {
                local.impulse = p;
                for (response, d) in local.responses.iter().zip(&p) {
                    *next_v += response * *d;
                }
            }
            locals.push(local);
        }
        Ok((locals, approach))
    }

    /// Records the changes of mode of one step at its midpoint `tm`: an
    /// impact (or a closing without speed) for a contact that takes an
    /// impulse after being apart; a contact that bounces off is apart again
    /// after it. A contact in force that takes none lifts off; one that
    /// stops slipping sticks, and the other way. Returns the modes after the
    /// step.
    fn note_changes(&mut self, tm: T, before: &[Mode<T>], after: &Outcome<T>) -> Vec<Mode<T>> {
        let rest = T::lit(self.settings.rest_speed);
        let mut modes = after.modes.clone();
        for (i, (old, new)) in before.iter().zip(&after.modes).enumerate() {
            let kind = match (old, new) {
                (Mode::Open, Mode::Open) => continue,
                (Mode::Open, _) => {
                    let speed = after.leaving[i];
                    if speed > rest {
                        modes[i] = Mode::Open;
                    }
                    match after.approach[i] < -rest {
                        true => ChangeKind::Impact {
                            before: after.approach[i],
                            after: speed,
                        },
                        false => ChangeKind::Closes,
                    }
                }
                (_, Mode::Open) => ChangeKind::LiftsOff,
                (Mode::Sliding { .. }, Mode::Sticking) => ChangeKind::Sticks,
                (Mode::Sticking, Mode::Sliding { .. }) => ChangeKind::Slips,
                _ => continue,
            };
            self.record(tm, i, kind);
        }
        // A new phase only where a contact's state changed (a sliding
        // contact's direction turns every step).
        let same = |m: &[Mode<T>]| {
            m.iter()
                .zip(&modes)
                .all(|(&a, &b)| ContactState::from(a) == ContactState::from(b))
        };
        if !self.phases.last().is_some_and(|(_, m)| same(m)) {
            self.phases.push((tm, modes.clone()));
        }
        modes
    }
}

/// A contact's mode after the step, from how its impulse met Coulomb's
/// law (a contact without friction in force is sliding, as the
/// event-driven run has it).
fn mode_of<T: Real, const N: usize>(c: &Local<T, N>) -> Mode<T> {
    match c.branch {
        Branch::Apart => Mode::Open,
        Branch::Sticking if c.tangents.is_empty() => Mode::Sliding {
            hint: [T::zero(); 2],
        },
        Branch::Sticking => Mode::Sticking,
        Branch::Sliding { s } => Mode::Sliding {
            hint: in_axes(&c.tangents, s),
        },
    }
}

/// A slip direction over the rows a contact rubs along, in its two tangent
/// axes.
fn in_axes<T: Real>(tangents: &[usize], s: [T; 2]) -> [T; 2] {
    let mut hint = [T::zero(); 2];
    for (k, &axis) in tangents.iter().enumerate() {
        hint[axis] = s[k];
    }
    hint
}
