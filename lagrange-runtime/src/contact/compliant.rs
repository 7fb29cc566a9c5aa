//! Compliant contacts: each contact a spring and damper along its normal
//! while the gap is closed, with friction regularised near zero slip, so
//! that the motion is an ordinary differential equation that any
//! integrator runs without events (the model of MuJoCo and of most game
//! engines, here as an option beside the rigid schemes).
//!
//! A contact sunk by δ = −φ > 0 pushes with λₙ = max(0, k δ + c δ̇), where
//! c = 2 ζ √(k m) with m = 1/(n M⁻¹ nᵀ) its effective mass at the state,
//! and the damping ratio ζ is the one whose isolated impact (linear spring
//! and damper that cannot pull, Schwager and Pöschel 2007) leaves at e
//! times its arrival speed, e the contact's restitution: the rigid law's e
//! whatever the stiffness. Friction is −μ λₙ u / √(|u|² + ε²) for the slip
//! u, Coulomb's force once the slip is well above ε, and a viscous one
//! below: a compliant contact creeps where a rigid one sticks.

use super::driver::Driver;
use super::form::{ContactForm, Mode};
use super::run::{ChangeKind, ContactForce};
use crate::error::{Error, SettingsError};
use crate::event::{Event, Events};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation::Orientation;
use crate::ode::{Continuation, Integrator, SecondOrder, Trajectory};
use crate::system::{ContactLaw, ContactRows, Contacts};
use nalgebra::SVector;
use std::ops::Range;

/// The compliant contact model
/// ([`Simulation::compliant_contacts`](crate::Simulation::compliant_contacts)):
/// a normal stiffness k (N/m, or N·m/rad for a stop on an angle) and the
/// slip speed ε below which friction is viscous.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compliant {
    stiffness: f64,
    slip_speed: f64,
}

/// The most damping a compliant contact takes: a restitution below
/// e(ζ = 5) ≈ 0.0093 is given ζ = 5 (the linear model reaches e = 0 only
/// with infinite damping, and an ever stiffer equation on the way).
const MOST_DAMPING: f64 = 5.0;

impl Compliant {
    /// Contacts of normal stiffness `k`, friction viscous below a slip of
    /// 1e-4 (in the units of the slip rows, m/s for a point).
    pub fn stiffness(k: f64) -> Self {
        Self {
            stiffness: k,
            slip_speed: 1e-4,
        }
    }

    /// The slip speed ε of the regularised friction.
    pub fn slip_speed(mut self, speed: f64) -> Self {
        self.slip_speed = speed;
        self
    }

    /// The normal stiffness.
    pub fn normal_stiffness(&self) -> f64 {
        self.stiffness
    }

    /// The damping ratio ζ whose isolated impact has restitution `e`: the
    /// inverse of [`restitution`](Self::restitution), by bisection, at most
    /// 5 (e ≈ 0.0093); 0 for e ≥ 1.
    pub fn damping_ratio(e: f64) -> f64 {
        if e >= 1.0 {
            return 0.0;
        }
        let (mut lo, mut hi) = (0.0f64, MOST_DAMPING);
        if Self::restitution(hi) >= e {
            return hi;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if Self::restitution(mid) > e {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The restitution of an isolated impact against a linear spring and
    /// damper of damping ratio ζ that cannot pull: the body leaves when the
    /// force k δ + c δ̇ falls to zero, at t_c, with speed e·v. In units
    /// ω₀ = 1 and v = 1, δ(t) = e^(−ζt) sin(ωt)/ω with ω = √(1 − ζ²) (sinh
    /// and √(ζ² − 1) when overdamped, t e^(−t) at ζ = 1), and the force
    /// vanishes at ω t_c = atan2(2ζω, 2ζ² − 1).
    pub fn restitution(zeta: f64) -> f64 {
        if zeta <= 0.0 {
            return 1.0;
        }
        if (zeta - 1.0).abs() < 1e-9 {
            return (-2.0f64).exp();
        }
        if zeta < 1.0 {
            let w = (1.0 - zeta * zeta).sqrt();
            let phi = (2.0 * zeta * w).atan2(2.0 * zeta * zeta - 1.0);
            let t = phi / w;
            -(-zeta * t).exp() * (phi.cos() - zeta * phi.sin() / w)
        } else {
            let w = (zeta * zeta - 1.0).sqrt();
            let psi = (2.0 * zeta * w / (2.0 * zeta * zeta - 1.0)).atanh();
            let t = psi / w;
            -(-zeta * t).exp() * (psi.cosh() - zeta * psi.sinh() / w)
        }
    }

    /// The forces of the model at (t, q, v), per contact in its normal and
    /// tangent axes.
    pub(crate) fn forces<S: Contacts<T, N, Q>, T: Real, F, const N: usize, const Q: usize>(
        &self,
        form: &ContactForm<'_, S, T, F>,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<Vec<ContactForce<T>>, Error> {
        let compliant = CompliantForm {
            form,
            stiffness: T::lit(self.stiffness),
            slip_speed: T::lit(self.slip_speed),
            damping: (form.laws.iter())
                .map(|l| T::lit(Self::damping_ratio(l.restitution)))
                .collect(),
        };
        let m = form.system.mass_matrix(q, t);
        let chol = form.factor(t, q, m)?;
        Ok(compliant
            .pushes(t, q, v, &chol)?
            .into_iter()
            .map(|p| ContactForce {
                normal: p.normal,
                tangential: p.friction,
            })
            .collect())
    }

    /// k and ε positive and finite.
    pub(crate) fn check(&self) -> Result<(), Error> {
        for (setting, value) in [
            ("stiffness", self.stiffness),
            ("slip_speed", self.slip_speed),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(SettingsError::Value {
                    owner: "compliant contacts",
                    setting,
                    value,
                    requirement: "positive and finite".into(),
                }
                .into());
            }
        }
        Ok(())
    }
}

/// The equations of motion with compliant contacts.
pub(crate) struct CompliantForm<'s, 'f, S, T: Real, F = NoForcing> {
    pub form: &'f ContactForm<'s, S, T, F>,
    pub stiffness: T,
    pub slip_speed: T,
    /// ζ per contact, from its restitution.
    pub damping: Vec<T>,
}

/// What one contact does at a state: its normal force, its friction
/// along its tangent rows, and the generalized force they exert (the rows'
/// transposes times them).
pub(crate) struct Push<T: Real, const N: usize> {
    pub normal: T,
    pub friction: [T; 2],
    pub generalized: SVector<T, N>,
}

impl<S, T: Real, F> CompliantForm<'_, '_, S, T, F> {
    /// Contact `i`'s spring and damper force before it is kept from
    /// pulling, k δ + c δ̇, while it is sunk; `apart` while it is not. Its
    /// fall through zero is the contact letting go (with `apart` positive,
    /// so that leaving the surface is no fall), its rise the contact
    /// pressing again without having opened (with `apart` negative, where
    /// the touch is a rise too, which the run's record skips).
    pub fn unclipped<const N: usize, const Q: usize>(
        &self,
        i: usize,
        (t, q, v): (T, &SVector<T, Q>, &SVector<T, N>),
        apart: T,
    ) -> T
    where
        S: Contacts<T, N, Q>,
    {
        let nan = T::lit(f64::NAN);
        let Ok(r) = self.form.rows(i, t, q, v) else {
            return nan;
        };
        if r.gap >= T::zero() {
            return apart;
        }
        let m = self.form.system.mass_matrix(q, t);
        let Ok(chol) = Cholesky::new(m, self.form.singular) else {
            return nan;
        };
        -self.stiffness * r.gap - self.damper(i, &r.normal, &chol) * r.normal.dot(v)
    }

    /// Contact `i`'s damper c = 2ζ√(k m), m = 1/(n M⁻¹ nᵀ) its effective
    /// mass along its normal row n.
    fn damper<const N: usize>(&self, i: usize, normal: &SVector<T, N>, chol: &Cholesky<T, N>) -> T {
        let mass = T::one() / normal.dot(&chol.solve(*normal));
        T::lit(2.0) * self.damping[i] * (self.stiffness * mass).sqrt()
    }

    /// The forces of every contact at (t, q, v), given M's factor.
    pub fn pushes<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        chol: &Cholesky<T, N>,
    ) -> Result<Vec<Push<T, N>>, Error>
    where
        S: Contacts<T, N, Q>,
    {
        let mut out = Vec::with_capacity(self.damping.len());
        for i in 0..self.damping.len() {
            let r = self.form.rows(i, t, q, v)?;
            if self.form.laws[i].is_dry_friction() {
                out.push(self.dry(i, &r, v));
                continue;
            }
            let depth = -r.gap;
            if depth <= T::zero() {
                out.push(Push {
                    normal: T::zero(),
                    friction: [T::zero(); 2],
                    generalized: SVector::zeros(),
                });
                continue;
            }
            let c = self.damper(i, &r.normal, chol);
            let normal = (self.stiffness * depth - c * r.normal.dot(v)).max(T::zero());
            let slip = ContactForm::<S, T, F>::slip(&r, v);
            let speed =
                (slip[0] * slip[0] + slip[1] * slip[1] + self.slip_speed * self.slip_speed).sqrt();
            let scale = -T::lit(self.form.laws[i].friction) * normal / speed;
            let friction = [scale * slip[0], scale * slip[1]];
            let generalized =
                r.normal * normal + r.tangents[0] * friction[0] + r.tangents[1] * friction[1];
            out.push(Push {
                normal,
                friction,
                generalized,
            });
        }
        Ok(out)
    }
}

impl<S, T: Real, F> CompliantForm<'_, '_, S, T, F> {
    /// Dry friction regularised like a contact's: −fc u / √(|u|² + ε²).
    fn dry<const N: usize>(
        &self,
        i: usize,
        r: &ContactRows<T, N>,
        v: &SVector<T, N>,
    ) -> Push<T, N> {
        let slip = ContactForm::<S, T, F>::slip(r, v);
        let speed =
            (slip[0] * slip[0] + slip[1] * slip[1] + self.slip_speed * self.slip_speed).sqrt();
        let scale = -T::lit(self.form.laws[i].friction) / speed;
        let friction = [scale * slip[0], scale * slip[1]];
        Push {
            normal: T::zero(),
            friction,
            generalized: r.tangents[0] * friction[0] + r.tangents[1] * friction[1],
        }
    }
}

impl<S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>
    SecondOrder<T, N, Q> for CompliantForm<'_, '_, S, T, F>
{
    const ORIENTATIONS: &'static [Orientation] = S::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        let (m, mut rhs) = self.form.dynamics(t, q, v)?;
        let chol = self.form.factor(t, q, m)?;
        for push in self.pushes(t, q, v, &chol)? {
            rhs += push.generalized;
        }
        let accel = chol.solve(rhs);
        if accel.iter().all(|a| a.is_finite()) {
            Ok(accel)
        } else {
            Err(Error::non_finite(t, q, v))
        }
    }

    /// The system's integral plus the springs' energy ½ k δ² of the sunk
    /// contacts: conserved by an elastic contact without friction.
    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        let springs = (0..self.damping.len())
            .filter_map(|i| self.form.system.contact_rows(i, q, v, t))
            .map(|r| {
                let depth = (-r.gap).max(T::zero());
                T::lit(0.5) * self.stiffness * depth * depth
            })
            .fold(T::zero(), |a, b| a + b);
        self.form.system.integral(q, v, t) + springs
    }
}

/// The run of a system with compliant contacts: one integration with the
/// contacts' forces in the equations, each contact's closing and opening
/// located as events (not stopping the run) for the changes and the modes.
impl<S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>
    Driver<'_, S, T, N, Q, F>
{
    pub(super) fn comply<I: Integrator>(
        &mut self,
        model: &Compliant,
        integrator: &I,
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        span: Range<T>,
    ) -> Result<(), Error> {
        let (t0, t1) = (span.start, span.end);
        self.check_start((t0, t1), &q0, &v0)?;
        model.check()?;
        let count = self.laws.len();
        let owned = self.form(vec![Mode::Open; count]);
        let form = &owned;
        let compliant = CompliantForm {
            form,
            stiffness: T::lit(model.stiffness),
            slip_speed: T::lit(model.slip_speed),
            damping: (self.laws.iter())
                .map(|l| T::lit(Compliant::damping_ratio(l.restitution)))
                .collect(),
        };
        let events = switches(&compliant, &self.laws);
        let mut modes = Vec::with_capacity(count);
        for i in 0..count {
            let pressed = compliant.unclipped(i, (t0, &q0, &v0), T::one()) > T::zero();
            let sunk = form.rows(i, t0, &q0, &v0)?.gap <= T::zero();
            modes.push(if sunk && pressed {
                in_force()
            } else {
                Mode::Open
            });
        }
        // One piece, or one per held input's sample, each sample taken at
        // the state its piece ends in.
        let mut pieces: Option<Trajectory<T, N, Q>> = None;
        let mut occurrences = Vec::new();
        let (mut t, mut q, mut v) = (t0, q0, v0);
        let outcome = loop {
            let sample = self.forcing.next_sample(t0, t).filter(|&b| b < t1);
            let from = pieces
                .as_ref()
                .map_or(Continuation::start(t0), Trajectory::continuation);
            let end = sample.unwrap_or(t1);
            let run = events.continue_run(integrator, (&compliant, &[]), from, t, end, q, v);
            let (run, outcome) = match run {
                Ok(run) => (run, Ok(())),
                Err(failure) => (*failure.partial, Err(failure.error)),
            };
            occurrences.extend(run.occurrences);
            (q, v) = run.trajectory.final_state();
            match &mut pieces {
                Some(whole) => {
                    whole.append(run.trajectory);
                }
                None => pieces = Some(run.trajectory),
            }
            let Some(b) = sample.filter(|_| outcome.is_ok()) else {
                break outcome;
            };
            if let Err(error) = self.forcing.take_sample(b, &q, &v) {
                break Err(error);
            }
            t = b;
        };
        drop(events);
        drop(owned);
        self.phases.push((t0, modes.clone()));
        self.record_switches(&mut modes, &occurrences);
        self.trajectory = pieces;
        outcome
    }

    /// The changes and modes of a compliant run from its switches' events
    /// (see [`switches`]), `modes` those before them.
    fn record_switches(
        &mut self,
        modes: &mut [Mode<T>],
        occurrences: &[crate::event::Occurrence<T, N, Q>],
    ) {
        for o in occurrences {
            let (contact, closes) = (o.event / 3, o.event % 3 != 1);
            // A touch is also a rise of its force from `apart`: one change.
            if closes == (modes[contact] != Mode::Open) {
                continue;
            }
            modes[contact] = if closes { in_force() } else { Mode::Open };
            let kind = if closes {
                ChangeKind::Closes
            } else {
                ChangeKind::LiftsOff
            };
            self.record(o.t, contact, kind);
            self.phases.push((o.t, modes.to_vec()));
        }
    }
}

/// The switches of the compliant forces, per contact in this order: the
/// touch (the gap falling through zero), the letting go (the force falling
/// through zero while sunk) and the pressing again; each restarts the
/// integrator, which then never steps across a switch.
fn switches<
    'f,
    S: Contacts<T, N, Q>,
    T: Real,
    F: Forcing<T, N, Q>,
    const N: usize,
    const Q: usize,
>(
    compliant: &'f CompliantForm<'_, 'f, S, T, F>,
    laws: &[ContactLaw],
) -> Events<'f, T, N, Q> {
    let nan = T::lit(f64::NAN);
    let form = compliant.form;
    let (one, minus) = (T::one(), -T::one());
    let mut events = Events::new();
    for (i, law) in laws.iter().enumerate() {
        let name = law.name;
        // Dry friction has no gap: never touches (nor lets go, its
        // unclipped force being `apart`).
        let dry = law.is_dry_friction();
        let gap = move |t, q: &SVector<T, Q>, v: &SVector<T, N>| match dry {
            true => one,
            false => form.rows(i, t, q, v).map_or(nan, |r| r.gap),
        };
        let lets_go =
            move |t, q: &SVector<T, Q>, v: &SVector<T, N>| compliant.unclipped(i, (t, q, v), one);
        let presses =
            move |t, q: &SVector<T, Q>, v: &SVector<T, N>| compliant.unclipped(i, (t, q, v), minus);
        let touches = Event::new(gap).named(format!("{name} touches"));
        let lets_go = Event::new(lets_go).named(format!("{name} lets go"));
        let presses = Event::new(presses).named(format!("{name} presses"));
        events = events
            .with(touches.falling().restart())
            .with(lets_go.falling().restart())
            .with(presses.rising().restart());
    }
    events
}

/// A compliant contact in force: its friction is regularised, so it is
/// always (if ever so slowly) sliding.
fn in_force<T: Real>() -> Mode<T> {
    Mode::Sliding {
        hint: [T::zero(); 2],
    }
}

#[cfg(test)]
mod tests {
    use super::Compliant;

    #[test]
    fn restitution_matches_the_known_values() {
        assert_eq!(Compliant::restitution(0.0), 1.0);
        // Critical damping: e = e⁻², continuous on both sides.
        let critical = (-2.0f64).exp();
        assert!((Compliant::restitution(1.0) - critical).abs() < 1e-15);
        assert!((Compliant::restitution(1.0 - 1e-6) - critical).abs() < 1e-5);
        assert!((Compliant::restitution(1.0 + 1e-6) - critical).abs() < 1e-5);
        // ζ = 1/2: the force vanishes at ω t_c = 2π/3, and e = exp(−ζ t_c).
        let w = 0.75f64.sqrt();
        let expected = (-0.5 * (2.0 * std::f64::consts::PI / 3.0) / w).exp();
        assert!((Compliant::restitution(0.5) - expected).abs() < 1e-15);
    }

    #[test]
    fn damping_ratio_inverts_restitution() {
        for e in [0.9, 0.6, 0.5, 0.2, 0.1, 0.02] {
            let zeta = Compliant::damping_ratio(e);
            assert!((Compliant::restitution(zeta) - e).abs() < 1e-12, "e = {e}");
        }
        assert_eq!(Compliant::damping_ratio(1.0), 0.0);
        assert_eq!(Compliant::damping_ratio(0.0), 5.0);
    }

    #[test]
    fn refuses_bad_settings() {
        assert!(Compliant::stiffness(0.0).check().is_err());
        assert!(
            Compliant::stiffness(1e5)
                .slip_speed(f64::NAN)
                .check()
                .is_err()
        );
        assert!(Compliant::stiffness(1e5).check().is_ok());
    }
}
