//! What happens at an event: the impacts of the contacts at the surface, and
//! the choice of the contacts' modes for the next stretch.

use super::driver::{Driver, Forced};
use super::form::{Mode, has_tangent};
use super::impact::impulse;
use super::run::ChangeKind;
use crate::error::{ContactFault, Error};
use crate::mechanics::Forcing;
use crate::numeric::Real;
use crate::system::{ContactLaw, ContactRows, Contacts};
use nalgebra::SVector;

/// A contact meeting the impulse problem: its target normal speed and what
/// the run records of it.
struct Meeting<T> {
    contact: usize,
    target: T,
    before: T,
    zeno: Option<T>,
}

impl<S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>
    Driver<'_, S, T, N, Q, F>
{
    /// At (q, v) at t, with the contacts in `modes` before: refuses a
    /// penetrating state, applies the impacts (changing v), and chooses the
    /// modes that follow.
    pub(super) fn settle(
        &mut self,
        t: T,
        q: &SVector<T, Q>,
        v: &mut SVector<T, N>,
        modes: &[Mode<T>],
        forced: Forced,
    ) -> Result<Vec<Mode<T>>, Error> {
        let form = self.form(modes.to_vec());
        let tolerance = T::lit(self.settings.gap_tolerance);
        let mut rows = Vec::with_capacity(self.laws.len());
        for i in 0..self.laws.len() {
            rows.push(form.rows(i, t, q, v)?);
        }
        if let Some(i) = (0..rows.len()).find(|&i| rows[i].gap < -tolerance) {
            let fault = ContactFault::Penetrates {
                gap: rows[i].gap.to_f64(),
                tolerance: self.settings.gap_tolerance,
            };
            return Err(form.fault(i, t, q, fault));
        }
        let meetings = self.meetings(t, q, v, &rows, modes, forced)?;
        let set: Vec<(usize, T)> = meetings.iter().map(|m| (m.contact, m.target)).collect();
        let after = impulse(&form, &set, t, q, v)?;
        drop(form);
        for m in &meetings {
            let speed = rows[m.contact].normal.dot(&after);
            let kind = if let Some(accumulation) = m.zeno {
                let speed = -T::lit(self.laws[m.contact].restitution) * m.before;
                ChangeKind::Rests {
                    speed,
                    accumulation,
                }
            } else if m.before < -T::lit(self.settings.rest_speed) {
                ChangeKind::Impact {
                    before: m.before,
                    after: speed,
                }
            } else if modes[m.contact] == Mode::Open {
                ChangeKind::Closes
            } else {
                continue;
            };
            self.record(t, m.contact, kind);
        }
        *v = after;
        // A contact the impulse left leaving (its impulse zero, a frictional
        // impact's other contacts moving it away) is open, not closing.
        let rest = T::lit(self.settings.rest_speed);
        let closing: Vec<usize> = meetings
            .iter()
            .filter(|m| m.target == T::zero() && rows[m.contact].normal.dot(v) <= rest)
            .map(|m| m.contact)
            .collect();
        let chosen = self.choose(t, q, v, &rows, &closing, modes, forced)?;
        for (i, (old, new)) in modes.iter().zip(&chosen).enumerate() {
            let kind = match (old, new) {
                (Mode::Sliding { .. }, Mode::Sticking) => ChangeKind::Sticks,
                (Mode::Sticking, Mode::Sliding { .. }) => ChangeKind::Slips,
                (Mode::Sliding { .. } | Mode::Sticking, Mode::Open)
                    if forced != Forced::Open(i) =>
                {
                    ChangeKind::LiftsOff
                }
                _ => continue,
            };
            self.record(t, i, kind);
        }
        Ok(chosen)
    }

    /// The contacts at the surface that meet the impulse problem: those
    /// approaching (Newton's law, or closing if the bounce would be slower
    /// than the rest speed while the motion presses them back), those at
    /// rest on it, and the closed ones (unless the event opened them).
    fn meetings(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        rows: &[ContactRows<T, N>],
        modes: &[Mode<T>],
        forced: Forced,
    ) -> Result<Vec<Meeting<T>>, Error> {
        let rest = T::lit(self.settings.rest_speed);
        let tolerance = T::lit(self.settings.gap_tolerance);
        // The motion with every contact at the surface open: whether it
        // presses a contact back (the bounces then accumulate).
        let free = self
            .form(vec![Mode::Open; rows.len()])
            .solve(t, q, v)?
            .accel;
        let mut meetings = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            // Dry friction's bounded force takes no impulse.
            if forced == Forced::Open(i) || r.gap > tolerance || self.laws[i].is_dry_friction() {
                continue;
            }
            let before = r.normal.dot(v);
            let closed = modes[i] != Mode::Open;
            let e = T::lit(self.laws[i].restitution);
            let bounce = -e * before;
            let (target, zeno) = if before < -rest && bounce > rest {
                (bounce, None)
            } else if before < -rest {
                let pressed = r.normal.dot(&free) + r.normal_bias;
                let accumulation = (bounce > T::zero() && pressed < T::zero())
                    .then(|| t + T::lit(2.0) * bounce / (-pressed * (T::one() - e)));
                (T::zero(), accumulation)
            } else if before <= rest || closed {
                (T::zero(), None)
            } else {
                continue;
            };
            meetings.push(Meeting {
                contact: i,
                target,
                before,
                zeno,
            });
        }
        Ok(meetings)
    }

    /// The modes after an event: the closing contacts start sticking (or
    /// sliding, if they slip or have no friction), then contacts that would
    /// pull open and sticking ones whose friction would leave the cone
    /// slide, until every force is admissible.
    #[allow(clippy::too_many_arguments)]
    fn choose(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        rows: &[ContactRows<T, N>],
        closing: &[usize],
        before: &[Mode<T>],
        forced: Forced,
    ) -> Result<Vec<Mode<T>>, Error> {
        let mut modes = vec![Mode::Open; rows.len()];
        let dry = (0..rows.len()).filter(|&i| self.laws[i].is_dry_friction());
        for i in closing.iter().copied().chain(dry) {
            modes[i] = self.first_mode(i, &rows[i], v);
        }
        if let Forced::Slide(i) = forced {
            let held = self.form(before.to_vec()).solve(t, q, v)?.tangential[i];
            modes[i] = Mode::Sliding {
                hint: opposite(held),
            };
        }
        for _ in 0..4 * rows.len() + 4 {
            let form = self.form(modes.clone());
            let s = form.solve(t, q, v)?;
            // Before any contact is opened for pulling: a sliding contact
            // that friction presses the harder the more it is pushed makes
            // both answers possible, or neither.
            for (i, mode) in modes.iter().enumerate() {
                let rubs = self.laws[i].friction > 0.0 && !self.laws[i].is_dry_friction();
                if matches!(mode, Mode::Sliding { .. }) && rubs && s.compliance[i] <= T::zero() {
                    let compliance = s.compliance[i].to_f64();
                    return Err(form.fault(i, t, q, ContactFault::Painleve { compliance }));
                }
            }
            let pulling = (0..rows.len())
                .filter(|&i| modes[i] != Mode::Open && s.normal[i] < T::zero())
                .min_by(|&a, &b| {
                    s.normal[a]
                        .partial_cmp(&s.normal[b])
                        .unwrap_or(core::cmp::Ordering::Equal)
                });
            if let Some(i) = pulling {
                modes[i] = Mode::Open;
                continue;
            }
            let outside = (0..rows.len()).find(|&i| {
                let f = s.tangential[i];
                let bound = self.laws[i].friction_bound(s.normal[i]);
                modes[i] == Mode::Sticking
                    && (f[0] * f[0] + f[1] * f[1]).sqrt() > bound * T::lit(1.0 + 1e-9)
            });
            if let Some(i) = outside {
                modes[i] = Mode::Sliding {
                    hint: opposite(s.tangential[i]),
                };
                continue;
            }
            // An opened contact must not be driven into the surface.
            let sinking = closing.iter().find(|&&i| {
                let r = &rows[i];
                modes[i] == Mode::Open
                    && forced != Forced::Open(i)
                    && r.normal.dot(&s.accel) + r.normal_bias
                        < -T::lit(1e-9) * (T::one() + s.accel.amax())
            });
            if let Some(&i) = sinking {
                return Err(form.fault(i, t, q, ContactFault::NoConsistentMode));
            }
            return Ok(modes);
        }
        let first = closing.first().copied().unwrap_or(0);
        Err(self
            .form(modes)
            .fault(first, t, q, ContactFault::NoConsistentMode))
    }

    /// The modes before a run's first step: dry friction in force, sticking
    /// where its bound holds it, every other contact apart until the start
    /// is settled.
    pub(super) fn starting_modes(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<Vec<Mode<T>>, Error> {
        let open = vec![Mode::Open; self.laws.len()];
        if !self.laws.iter().any(ContactLaw::is_dry_friction) {
            return Ok(open);
        }
        let form = self.form(Vec::new());
        let mut rows = Vec::with_capacity(self.laws.len());
        for i in 0..self.laws.len() {
            rows.push(form.rows(i, t, q, v)?);
        }
        self.choose(t, q, v, &rows, &[], &open, Forced::Nothing)
    }

    /// A closing contact's first mode: sliding without friction or without
    /// tangents, sliding along its slip if it slips, sticking otherwise.
    fn first_mode(&self, i: usize, rows: &ContactRows<T, N>, v: &SVector<T, N>) -> Mode<T> {
        let rubs = self.laws[i].friction > 0.0 && rows.tangents.iter().any(has_tangent);
        if !rubs {
            return Mode::Sliding {
                hint: [T::zero(); 2],
            };
        }
        let slip = [rows.tangents[0].dot(v), rows.tangents[1].dot(v)];
        let speed = (slip[0] * slip[0] + slip[1] * slip[1]).sqrt();
        if speed <= T::lit(self.settings.stick_speed) {
            Mode::Sticking
        } else {
            Mode::Sliding {
                hint: [slip[0] / speed, slip[1] / speed],
            }
        }
    }
}

/// The unit vector opposite to a tangential force (the direction a contact
/// starts to slip in when that force cannot hold it); zero for a zero force.
fn opposite<T: Real>(f: [T; 2]) -> [T; 2] {
    let size = (f[0] * f[0] + f[1] * f[1]).sqrt();
    if size > T::zero() {
        [-f[0] / size, -f[1] / size]
    } else {
        [T::zero(); 2]
    }
}
