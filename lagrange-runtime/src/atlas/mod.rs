//! The atlas: a system written in Euler angles, run through every
//! orientation by switching each rotation between two charts.
//!
//! Each rotation of [`Atlas::EULER`] has the user's chart (its own sequence)
//! and a second one, the same sequence after the constant turn R_b(π/2)
//! ([`EulerChart::second`]), whose singular set is disjoint from the first's
//! (proved in [`crate::numeric::euler`]: s₁² + s₂² ≥ 1 for the two
//! conditionings). A run leaves the user's chart when its conditioning falls
//! below [`LEAVE_BELOW`] = 0.6 and comes back when it rises above
//! [`RETURN_ABOVE`] = 0.8: while in the second chart s₁ ≤ 0.8, so s₂ ≥
//! √(1 − 0.8²) = 0.6, and whichever chart is in use has conditioning at least
//! 0.6 (the pair that maximises that floor for a gap of 0.2; the rates
//! q̇ = E⁻¹ ω grow as 1/s, and with it the steps an integrator needs: a
//! swing through the upright took 681 DOPRI5 steps with 0.25 / 0.5, 417 with
//! these). The gap is the hysteresis that keeps a body hovering near the
//! boundary from switching at every step. The switches are events ([`crate::event`]), located on the
//! dense output and followed by a restart, so no step straddles one.
//!
//! A switch maps (q, q̇) exactly: the rotation matrix is kept, and so is the
//! body angular velocity ω = E q̇ (the speeds do not change, only the chart
//! reading them). In the user's chart on every rotation the dynamics are the
//! user's own program; otherwise they come from the free twin (each rotation
//! a quaternion and ω), whose M and h depend on no chart: ω̇ from the twin,
//! then q̈ = E⁻¹(ω̇ − Ė q̇) in whichever chart each rotation is in.
//!
//! The charts of a run (`Charts`: which rotations are in their second
//! chart, every switch with its time) are shared by the dynamics, the
//! switching events and whatever reads the user's coordinates: a user's
//! event, a controller, the inputs recorded at the stored points. Those
//! read the state held in the charts of its time through
//! `Charts::user_view`: each rotation in its second chart in the user's
//! chart, nearest the angles it had when it left it. With inputs the
//! dynamics carry a `TwinForcing`: in the user's charts the user's own
//! input forces, in any other the twin's (`DrivenAtlas`), both of the
//! inputs the source gives at the user's view of the state. With
//! constraints, holonomic and nonholonomic, both run the multiplier form
//! (the twin's rows are the user's on its free orientation: positions of
//! points, velocities and ω of bodies), chosen through the description's
//! own form visitor (`form`): the accelerations, the residuals recorded at
//! each point and the consistency of the start.

mod chart;
mod drive;
mod form;
mod held;
mod run;

pub(crate) use chart::{Charts, user_view};
pub(crate) use form::ChartRows;

pub(crate) use drive::{Held, back_to_charts, finish, integrate, unstarted, watched};
pub use held::ChartedTrajectory;
pub use run::{AtlasRun, ChartSwitch, USER_CHART_VALID};

use crate::error::Error;
use crate::error::SettingsError;
use crate::mechanics::constraint::Drift;
use crate::mechanics::{Dynamics, Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::euler::EulerChart;
use crate::numeric::orientation::{self, Orientation};
use crate::ode::SecondOrder;
use crate::system::{Atlas, EulerRotation, FreeVisitor, Lagrangian};
use nalgebra::{SVector, Vector3};

/// A rotation leaves the user's chart when that chart's conditioning (|sin θ|
/// for z-x-z, |cos θ| for z-y-x) falls below this.
pub const LEAVE_BELOW: f64 = 0.6;
/// ... and comes back when it rises above this.
pub const RETURN_ABOVE: f64 = 0.8;

/// A forcing of a run through the atlas: in the user's charts it is the
/// dynamics' own [`Forcing`] (in the user's coordinates); in any other it
/// gives the twin's generalized forces at the twin's state.
pub(crate) trait TwinForcing<S, T: Real, const N: usize, const F: usize>:
    Forcing<T, N>
{
    /// The twin's ΔQ at its state `free`, the state being `held` in the
    /// charts of the moment.
    fn free_force(
        &self,
        system: &S,
        t: T,
        held: (&SVector<T, N>, &SVector<T, N>),
        free: (&SVector<T, F>, &SVector<T, N>),
    ) -> Result<SVector<T, N>, Error>;
}

impl<S, T: Real, const N: usize, const F: usize> TwinForcing<S, T, N, F> for NoForcing {
    fn free_force(
        &self,
        _: &S,
        _: T,
        _: (&SVector<T, N>, &SVector<T, N>),
        _: (&SVector<T, F>, &SVector<T, N>),
    ) -> Result<SVector<T, N>, Error> {
        Ok(SVector::zeros())
    }
}

/// A generalized force computed beforehand, as a [`Forcing`] of the twin.
struct Given<T: Real, const N: usize>(SVector<T, N>);

impl<T: Real, const N: usize, const F: usize> Forcing<T, N, F> for Given<T, N> {
    fn force(&self, _: T, _: &SVector<T, F>, _: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        Ok(self.0)
    }
}

/// The state in the charts of the moment: the system seen by the integrator
/// between two switches, the charts shared with the switching events.
pub(crate) struct Charted<'s, 'c, S, T: Real, const N: usize, const F: usize, G = NoForcing> {
    dynamics: Dynamics<'s, S, T, G>,
    charts: &'c Charts<T>,
}

impl<'s, 'c, S, T, G, const N: usize, const F: usize> Charted<'s, 'c, S, T, N, F, G>
where
    S: Atlas<T, N, F>,
    T: Real,
    G: TwinForcing<S, T, N, F>,
{
    /// The dynamics in the charts `charts` holds.
    pub fn new(dynamics: Dynamics<'s, S, T, G>, charts: &'c Charts<T>) -> Self {
        Self { dynamics, charts }
    }

    /// The system.
    pub fn system(&self) -> &'s S {
        self.dynamics.system()
    }

    /// Rotation k's chart at the moment.
    fn chart(&self, k: usize) -> EulerChart {
        self.charts.chart_in(self.charts.mask(), k)
    }

    /// The free twin's state at (q, v): the kept coordinates in order, then
    /// each rotation's quaternion and ω.
    fn free_state(&self, q: &SVector<T, N>, v: &SVector<T, N>) -> (SVector<T, F>, SVector<T, N>) {
        let (mut qf, mut vf) = (SVector::<T, F>::zeros(), SVector::<T, N>::zeros());
        for (p, i) in kept::<S, T, N, F>().enumerate() {
            qf[p] = q[i];
            vf[p] = v[i];
        }
        let first = N - 3 * S::EULER.len();
        for (k, rotation) in S::EULER.iter().enumerate() {
            let chart = self.chart(k);
            let x = angles(rotation, q);
            let quaternion = orientation::from_rotation_matrix(&chart.matrix(x));
            let omega = chart.rates(x) * Vector3::from(angles(rotation, v));
            let at_q = first + 4 * k;
            let at_v = first + 3 * k;
            qf.as_mut_slice()[at_q..at_q + 4].copy_from_slice(&quaternion);
            vf.as_mut_slice()[at_v..at_v + 3].copy_from_slice(omega.as_slice());
        }
        (qf, vf)
    }

    /// The constraint rows in the charts of the moment: Φ, G and g with
    /// G q̇ + g the rows' velocity form in these charts, the user's own in
    /// the user's charts, else the twin's with each rotation's ω = E ẋ (no
    /// rows without constraints).
    pub fn rows(&self, t: T, q: &SVector<T, N>) -> ChartRows {
        if self.charts.mask() == 0 {
            let v = SVector::zeros();
            return (self.system()).visit_form(form::Rows(form::At { t, q, v: &v }));
        }
        let (qf, _) = self.free_state(q, &SVector::zeros());
        let mut twin = (self.system()).visit_free(TwinRows(t, &qf));
        let g = twin.g.clone();
        for (p, i) in kept::<S, T, N, F>().enumerate() {
            twin.g.set_column(i, &g.column(p));
        }
        let first = N - 3 * S::EULER.len();
        for (k, rotation) in S::EULER.iter().enumerate() {
            let rates = self.chart(k).rates(angles(rotation, q));
            let e = nalgebra::DMatrix::from_fn(3, 3, |i, j| rates[(i, j)].to_f64());
            let turned = g.columns(first + 3 * k, 3) * e;
            for (j, &i) in rotation.coordinates.iter().enumerate() {
                twin.g.set_column(i, &turned.column(j));
            }
        }
        twin
    }

    /// q̈ in the charts of the moment from the twin's ω̇.
    fn twin_acceleration(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        let (qf, vf) = self.free_state(q, v);
        let tolerance = self.dynamics.singular_tolerance();
        let force = if G::ACTIVE {
            let system = self.dynamics.system();
            let forcing = self.dynamics.forcing();
            Some(forcing.free_force(system, t, (q, v), (&qf, &vf))?)
        } else {
            None
        };
        let af = (self.dynamics.system()).visit_free(TwinAcceleration {
            t,
            q: &qf,
            v: &vf,
            tolerance,
            force,
        })?;
        let mut a = SVector::<T, N>::zeros();
        for (p, i) in kept::<S, T, N, F>().enumerate() {
            a[i] = af[p];
        }
        let first = N - 3 * S::EULER.len();
        for (k, rotation) in S::EULER.iter().enumerate() {
            let chart = self.chart(k);
            let x = angles(rotation, q);
            let dx = angles(rotation, v);
            let dw = Vector3::from_fn(|j, _| af[first + 3 * k + j]);
            let ddx = chart
                .rates(x)
                .try_inverse()
                .map(|e| e * (dw - chart.rate_bias(x, dx)))
                .ok_or_else(|| Error::non_finite(t, q, v))?;
            for (j, &i) in rotation.coordinates.iter().enumerate() {
                a[i] = ddx[j];
            }
        }
        Ok(a)
    }
}

impl<S, T, G, const N: usize, const F: usize> SecondOrder<T, N> for Charted<'_, '_, S, T, N, F, G>
where
    S: Atlas<T, N, F>,
    T: Real,
    G: TwinForcing<S, T, N, F>,
{
    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        if self.charts.mask() != 0 {
            self.twin_acceleration(t, q, v)
        } else {
            (self.system()).visit_form(form::UserAcceleration {
                dynamics: &self.dynamics,
                at: form::At { t, q, v },
            })
        }
    }

    /// The constraint residuals [max |Φ|, max |G v + g|], the user's in the
    /// user's charts, the twin's (the same constraints) in any other.
    fn residuals(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> [T; 2] {
        if !S::CONSTRAINED {
            [T::zero(); 2]
        } else if self.charts.mask() == 0 {
            (self.system()).visit_form(form::Residuals(form::At { t, q, v }))
        } else {
            let (qf, vf) = self.free_state(q, v);
            (self.system()).visit_free(TwinResiduals(t, &qf, &vf))
        }
    }

    /// The energy (or Jacobi integral) of the state, the same function in
    /// every chart.
    fn integral(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> T {
        if self.charts.mask() == 0 {
            SecondOrder::integral(&self.dynamics, t, q, v)
        } else {
            let (qf, vf) = self.free_state(q, v);
            (self.dynamics.system()).visit_free(TwinIntegral { t, q: &qf, v: &vf })
        }
    }
}

/// The twin's acceleration at its state.
struct TwinAcceleration<'x, T: Real, const N: usize, const F: usize> {
    t: T,
    q: &'x SVector<T, F>,
    v: &'x SVector<T, N>,
    tolerance: T,
    force: Option<SVector<T, N>>,
}

impl<T: Real, const N: usize, const F: usize> FreeVisitor<T, N, F>
    for TwinAcceleration<'_, T, N, F>
{
    type Output = Result<SVector<T, N>, Error>;
    fn visit<L: Lagrangian<T, N, F>>(self, free: &L) -> Self::Output {
        let (at, tolerance) = (
            form::At {
                t: self.t,
                q: self.q,
                v: self.v,
            },
            self.tolerance,
        );
        match self.force {
            Some(force) => free.visit_form(form::Acceleration {
                at,
                tolerance,
                forcing: Given(force),
            }),
            None => free.visit_form(form::Acceleration {
                at,
                tolerance,
                forcing: NoForcing,
            }),
        }
    }
}

/// The twin's constraint residuals at its state.
struct TwinResiduals<'x, T: Real, const N: usize, const F: usize>(
    T,
    &'x SVector<T, F>,
    &'x SVector<T, N>,
);

impl<T: Real, const N: usize, const F: usize> FreeVisitor<T, N, F> for TwinResiduals<'_, T, N, F> {
    type Output = [T; 2];
    fn visit<L: Lagrangian<T, N, F>>(self, free: &L) -> [T; 2] {
        let Self(t, q, v) = self;
        free.visit_form(form::Residuals(form::At { t, q, v }))
    }
}

/// The twin's constraint rows at its configuration.
struct TwinRows<'x, T: Real, const F: usize>(T, &'x SVector<T, F>);

impl<T: Real, const N: usize, const F: usize> FreeVisitor<T, N, F> for TwinRows<'_, T, F> {
    type Output = ChartRows;
    fn visit<L: Lagrangian<T, N, F>>(self, free: &L) -> ChartRows {
        let Self(t, q) = self;
        free.visit_form(form::Rows(form::At {
            t,
            q,
            v: &SVector::<T, N>::zeros(),
        }))
    }
}

/// The twin's energy (or Jacobi integral) at its state.
struct TwinIntegral<'x, T: Real, const N: usize, const F: usize> {
    t: T,
    q: &'x SVector<T, F>,
    v: &'x SVector<T, N>,
}

impl<T: Real, const N: usize, const F: usize> FreeVisitor<T, N, F> for TwinIntegral<'_, T, N, F> {
    type Output = T;
    fn visit<L: Lagrangian<T, N, F>>(self, free: &L) -> T {
        SecondOrder::integral(&Dynamics::new(free), self.t, self.q, self.v)
    }
}

/// Whether (q0, v0) at t0, in the user's coordinates, satisfies the
/// system's constraints (if it has any) to `tolerance` at both levels, and
/// the constraint settings are ones the atlas applies.
///
/// # Errors
/// [`Error::InconsistentInitialConditions`], [`Error::NonFiniteState`];
/// [`Error::Settings`] for drift control or least squares.
pub(crate) fn check_start<S, T, const N: usize, const F: usize>(
    system: &S,
    t0: T,
    (q0, v0): (&SVector<T, N>, &SVector<T, N>),
    consistency: f64,
    drift: Drift,
    least_squares: bool,
) -> Result<(), Error>
where
    S: Atlas<T, N, F>,
    T: Real,
{
    if !S::CONSTRAINED {
        return Ok(());
    }
    if !matches!(drift, Drift::None) || least_squares {
        return Err(SettingsError::Unsupported {
            owner: "run_atlas",
            needs: "constraints kept by multipliers without drift control, redundant ones refused"
                .into(),
            remedy: "leave `drift` at Drift::None and `least_squares` off".into(),
        }
        .into());
    }
    system.visit_form(form::Consistency {
        at: form::At {
            t: t0,
            q: q0,
            v: v0,
        },
        tolerance: T::lit(consistency),
    })
}

/// The user's chart of a rotation.
pub(crate) fn user_chart(rotation: &EulerRotation) -> EulerChart {
    EulerChart {
        axes: rotation.axes,
        offset: false,
    }
}

/// A rotation's three numbers in q (its angles) or v (their rates).
pub(crate) fn angles<T: Real, const N: usize>(
    rotation: &EulerRotation,
    x: &SVector<T, N>,
) -> [T; 3] {
    rotation.coordinates.map(|i| x[i])
}

/// The coordinates of q that are no rotation's angles, in order: the twin's
/// first coordinates.
fn kept<S: Atlas<T, N, F>, T: Real, const N: usize, const F: usize>() -> impl Iterator<Item = usize>
{
    (0..N).filter(|i| !S::EULER.iter().any(|r| r.coordinates.contains(i)))
}

/// The error of a system whose [`Atlas`] twin disagrees with itself
/// ([`layout_agrees`] is false).
pub(crate) fn layout_error() -> Error {
    SettingsError::Unsupported {
        owner: "the atlas",
        needs: "the twin's layout documented on `Atlas`".into(),
        remedy: "the system's Atlas twin does not have it; a hand-written Atlas must \
                 follow that layout (the derive's does)"
            .into(),
    }
    .into()
}

/// Whether the twin's layout is the one documented on [`Atlas`]: checked
/// once per run, since a hand-written [`Atlas`] could disagree with itself.
pub(crate) fn layout_agrees<S, T, const N: usize, const F: usize>(system: &S) -> bool
where
    S: Atlas<T, N, F>,
    T: Real,
{
    struct Layout;
    impl<T: Real, const N: usize, const F: usize> FreeVisitor<T, N, F> for Layout {
        type Output = &'static [Orientation];
        fn visit<L: Lagrangian<T, N, F>>(self, _: &L) -> &'static [Orientation] {
            L::ORIENTATIONS
        }
    }
    let n = S::EULER.len();
    let mut used: Vec<usize> = S::EULER.iter().flat_map(|r| r.coordinates).collect();
    used.sort_unstable();
    used.dedup();
    if F != N + n || n > 64 || used.len() != 3 * n || used.iter().any(|&i| i >= N) {
        return false;
    }
    let first = N - 3 * n;
    let layout = system.visit_free(Layout);
    layout.len() == n
        && (layout.iter().enumerate()).all(|(k, o)| o.q == first + 4 * k && o.v == first + 3 * k)
}
