//! C10 (seed 001, unilateral constraint): a heavy point inside a spherical
//! cavity of radius R, |x| ≤ R.
//!
//! The point moves freely (the derived [`CavityParticle`]) until it reaches the
//! wall, found as the falling zero crossing of g = R² − |x|² ([`contact_event`]).
//! There Newton's impact law with restitution e reverses the normal velocity,
//! v ← v − (1 + e)(v·n) n with n = x/|x| the outward normal ([`impact`]), and
//! leaves the tangential velocity alone (a frictionless wall).
//!
//! **Sliding contact.** With e < 1 a point resting against the wall would
//! bounce infinitely often in finite time (Zeno). [`Cavity::simulate`]
//! therefore switches to the bilateral constraint |x| = R — the catalog's
//! [`CartesianSphericalPendulum`] with l = R, kept by a multiplier — as soon as
//! an impact leaves a normal speed below [`Cavity::slide_speed`] *and* the
//! wall must push (the normal reaction is compressive, λ < 0 in the multiplier
//! convention M q̈ = Q + Gᵀλ with G = 2xᵀ). The dropped normal speed costs at
//! most ½ m slide_speed² of energy. While sliding the reaction −2λx is
//! watched: when λ rises through zero the wall would have to pull (tensile),
//! so the constraint is released and the point flies freely again. A point
//! started on the wall with tangential velocity and a compressive reaction
//! starts sliding.
//!
//! The two phases are different systems with the same coordinates (x, y, z),
//! so the run is a list of [`Phase`]s rather than one trajectory.

use super::constrained::CartesianSphericalPendulum;
use lagrange::{
    ConstrainedDynamics, Dopri5, Drift, Error, Event, Lagrangian, SettingsError, Simulation,
    Trajectory,
};
use nalgebra::Vector3;

/// The free heavy point of C10: (x, y, z) Cartesian, gravity along −z.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    point(p, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
)]
pub struct CavityParticle {
    pub m: f64,
    pub g: f64,
}

/// The contact event: g = R² − |x|² falls through zero when the point reaches
/// the wall; the action is the impact law with restitution `e`, after which the
/// event layer restarts the integration (bouncing only; [`Cavity::simulate`]
/// adds the switch to sliding with [`Event::terminal_if`]).
pub fn contact_event(r: f64, e: f64) -> Event<'static, f64, 3> {
    Event::new(move |_, q: &Vector3<f64>, _| r * r - q.norm_squared())
        .falling()
        .named("wall")
        .action(move |_, q, v| impact(e, q, v))
}

/// Newton's impact law at the wall point `q`: the normal velocity (along the
/// outward normal n = q/|q|) is reversed and scaled by `e`, the tangential
/// velocity is kept.
pub fn impact(e: f64, q: &Vector3<f64>, v: &mut Vector3<f64>) {
    let n = q / q.norm();
    *v -= n * ((1.0 + e) * v.dot(&n));
}

/// One impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Impact {
    pub t: f64,
    pub q: Vector3<f64>,
    pub v_before: Vector3<f64>,
    pub v_after: Vector3<f64>,
}

impl Impact {
    /// The outward normal at the impact point.
    pub fn normal(&self) -> Vector3<f64> {
        self.q / self.q.norm()
    }

    /// Normal velocity (along the outward normal) before and after.
    pub fn normal_speeds(&self) -> (f64, f64) {
        let n = self.normal();
        (self.v_before.dot(&n), self.v_after.dot(&n))
    }

    /// Tangential velocity before and after.
    pub fn tangential(&self) -> (Vector3<f64>, Vector3<f64>) {
        let n = self.normal();
        (
            self.v_before - n * self.v_before.dot(&n),
            self.v_after - n * self.v_after.dot(&n),
        )
    }
}

/// A stretch of the motion: free flight or sliding on the wall.
#[derive(Clone, Debug)]
pub enum Phase {
    Free(Trajectory<f64, 3>),
    Sliding(Trajectory<f64, 3>),
}

impl Phase {
    pub fn trajectory(&self) -> &Trajectory<f64, 3> {
        match self {
            Phase::Free(t) | Phase::Sliding(t) => t,
        }
    }
}

/// A run of [`Cavity::simulate`].
#[derive(Clone, Debug, Default)]
pub struct CavityRun {
    /// Consecutive phases; each starts where the previous one ends.
    pub phases: Vec<Phase>,
    pub impacts: Vec<Impact>,
    /// Times at which sliding started.
    pub slides: Vec<f64>,
    /// Times at which the point left the wall (λ through zero).
    pub releases: Vec<f64>,
}

impl CavityRun {
    /// The final state.
    pub fn final_state(&self) -> (Vector3<f64>, Vector3<f64>) {
        self.phases
            .last()
            .expect("a run has at least one phase")
            .trajectory()
            .final_state()
    }

    /// All recorded points of all phases, (t, q, v).
    pub fn points(&self) -> impl Iterator<Item = (f64, &Vector3<f64>, &Vector3<f64>)> {
        self.phases.iter().flat_map(|p| {
            let tr = p.trajectory();
            tr.times()
                .iter()
                .zip(tr.positions().iter().zip(tr.velocities()))
                .map(|(&t, (q, v))| (t, q, v))
        })
    }
}

/// The point in its cavity.
#[derive(Clone, Copy, Debug)]
pub struct Cavity {
    pub particle: CavityParticle,
    /// Radius of the cavity.
    pub r: f64,
    /// Coefficient of restitution, 0 ≤ e ≤ 1.
    pub e: f64,
    /// Normal speed after an impact below which the contact turns into sliding.
    pub slide_speed: f64,
    /// Tolerance of the DOPRI5 runs.
    pub tol: f64,
}

impl Cavity {
    /// A cavity of radius `r` with restitution `e`, slide speed 1e-6 √(gR),
    /// tolerance 1e-12.
    pub fn new(m: f64, g: f64, r: f64, e: f64) -> Self {
        Self {
            particle: CavityParticle { m, g },
            r,
            e,
            slide_speed: 1e-6 * (g * r).sqrt(),
            tol: 1e-12,
        }
    }

    /// The wall as a bilateral constraint: a spherical pendulum of length R.
    pub fn sphere(&self) -> CartesianSphericalPendulum {
        CartesianSphericalPendulum {
            m: self.particle.m,
            l: self.r,
            g: self.particle.g,
        }
    }

    /// The multiplier λ of the wall constraint x² + y² + z² − R² = 0 while
    /// sliding; the wall's force on the point is 2λx, so λ < 0 means the wall
    /// pushes inwards (compressive, the only kind a wall can exert).
    pub fn multiplier(&self, t: f64, q: &Vector3<f64>, v: &Vector3<f64>) -> Result<f64, Error> {
        let sphere = self.sphere();
        let dynamics = ConstrainedDynamics::<_, f64, 1>::new(&sphere);
        Ok(dynamics.solve(t, q, v)?.multipliers[0])
    }

    /// Integrates from (q0, v0) over `span`, bouncing and sliding as described
    /// in the module docs.
    ///
    /// # Errors
    /// [`Error::Settings`] if the start is outside the cavity or the
    /// parameters are not physical; whatever the runs report.
    pub fn simulate(
        &self,
        q0: Vector3<f64>,
        v0: Vector3<f64>,
        span: std::ops::Range<f64>,
    ) -> Result<CavityRun, Error> {
        let on_wall = self.check(&q0)?;
        let mut out = CavityRun::default();
        let (mut t, mut q, mut v) = (span.start, q0, v0);
        let r = self.r;
        let mut sliding =
            (r * r - q.norm_squared()).abs() <= on_wall && self.slide_ok(t, &q, &v)?;
        // Phases that end where they started: switching back and forth without
        // the motion advancing.
        let mut stalled = 0;
        while t < span.end {
            let t_phase = t;
            if sliding {
                (q, v, t) = self.slide(&mut out, q, v, t..span.end)?;
                sliding = false;
            } else {
                (q, v, t, sliding) = self.fly(&mut out, q, v, t..span.end)?;
            }
            stalled = if t > t_phase { 0 } else { stalled + 1 };
            if stalled >= 3 {
                return Err(Error::EventsAccumulate {
                    t,
                    event: "wall".into(),
                    count: stalled,
                });
            }
        }
        Ok(out)
    }

    /// Checks the parameters and that q0 is inside; returns the round-off of
    /// |x|² at the wall (within it, a point counts as on the wall).
    fn check(&self, q0: &Vector3<f64>) -> Result<f64, Error> {
        let (r, e) = (self.r, self.e);
        if !(r > 0.0 && (0.0..=1.0).contains(&e) && self.slide_speed >= 0.0) {
            return Err(Error::Settings(SettingsError::Data {
                owner: "cavity",
                problem: format!(
                    "need R > 0, 0 <= e <= 1, slide speed >= 0; got R = {r}, e = {e}, \
                     slide speed {}",
                    self.slide_speed
                ),
            }));
        }
        let on_wall = 16.0 * f64::EPSILON * r * r;
        if q0.norm_squared() - r * r > on_wall {
            return Err(Error::Settings(SettingsError::Data {
                owner: "cavity",
                problem: format!("the start q0 = {q0:?} is outside the cavity of radius {r}"),
            }));
        }
        Ok(on_wall)
    }

    /// A sliding phase from (q, v) at `span.start`: on the wall with the
    /// multiplier until the wall would have to pull (or the span ends).
    /// Returns the state and time where it ends.
    fn slide(
        &self,
        out: &mut CavityRun,
        q: Vector3<f64>,
        v: Vector3<f64>,
        span: std::ops::Range<f64>,
    ) -> Result<(Vector3<f64>, Vector3<f64>, f64), Error> {
        let r = self.r;
        // Onto the sphere exactly, velocity tangent to it.
        let n = q / q.norm();
        let q = n * r;
        let v = v - n * v.dot(&n);
        out.slides.push(span.start);
        let sphere = self.sphere();
        let release = Event::new(|t, q: &Vector3<f64>, v: &Vector3<f64>| {
            // −λ > 0 while the wall pushes; a failed solve is reported
            // by the event layer as a non-finite event function.
            self.multiplier(t, q, v).map_or(f64::NAN, |l| -l)
        })
        .falling()
        .named("release")
        .terminal();
        let run = Simulation::new(&sphere)
            .integrator(Dopri5::tol(self.tol))
            // |Φ| = ||x|² − R²| to 1e-14 R² (round-off is ~1e-16 R²): the
            // point stays on the wall to about 1e-14 R.
            .drift(Drift::Projection {
                tol: 1e-14 * r * r,
                max_iter: 10,
            })
            .event(release)
            .run_constrained(q, v, span)?;
        if let Some(o) = run.occurrences.first() {
            out.releases.push(o.t);
        }
        let (q, v) = run.trajectory.final_state();
        let t = *run.trajectory.times().last().expect("non-empty");
        out.phases.push(Phase::Sliding(run.trajectory));
        Ok((q, v, t))
    }

    /// A free phase from (q, v) at `span.start`. Bounces are restarts inside
    /// the event layer (which keeps the wall's side between them, so that a
    /// tiny bounce inside one step is still seen); the run ends at the impact
    /// after which the point should slide. (If the reaction cannot be computed
    /// there, the point keeps bouncing.) Returns the state and time where it
    /// ends and whether the point slides from there.
    fn fly(
        &self,
        out: &mut CavityRun,
        q: Vector3<f64>,
        v: Vector3<f64>,
        span: std::ops::Range<f64>,
    ) -> Result<(Vector3<f64>, Vector3<f64>, f64, bool), Error> {
        let contact = contact_event(self.r, self.e)
            .terminal_if(|t, q, v| matches!(self.slide_ok(t, q, v), Ok(true)));
        let run = Simulation::new(&self.particle)
            .integrator(Dopri5::tol(self.tol))
            .event(contact)
            .max_events(1_000_000)
            .run(q, v, span)?;
        out.impacts.extend(run.occurrences.iter().map(|o| Impact {
            t: o.t,
            q: o.q,
            v_before: o.v,
            v_after: o.v_after,
        }));
        let (q, v) = run.trajectory.final_state();
        let t = *run.trajectory.times().last().expect("non-empty");
        out.phases.push(Phase::Free(run.trajectory));
        Ok((q, v, t, run.terminated_by.is_some()))
    }

    /// Whether a point at the wall with velocity v should slide: its normal
    /// speed is below the slide speed and the wall would have to push.
    fn slide_ok(&self, t: f64, q: &Vector3<f64>, v: &Vector3<f64>) -> Result<bool, Error> {
        let n = q / q.norm();
        if v.dot(&n).abs() > self.slide_speed {
            return Ok(false);
        }
        let tangent = v - n * v.dot(&n);
        Ok(self.multiplier(t, &(n * self.r), &tangent)? < 0.0)
    }
}
