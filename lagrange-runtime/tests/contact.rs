//! Unilateral contacts run event by event, on hand-written systems, against
//! closed forms: a bouncing ball's impact times, heights and rest time; a
//! block sliding to a stop; a block on an incline sticking or sliding; a
//! sphere thrown sliding that rolls; a pendulum against a stop.

use lagrange_runtime::{
    ChangeKind, ContactFault, ContactLaw, ContactRows, ContactRun, ContactSettings, ContactState,
    Contacts, Dop853, Error, Lagrangian, Simulation,
};
use nalgebra::{SMatrix, SVector};

const G: f64 = 9.81;

/// A rigid body moving in the vertical plane (x, z) and turning about y
/// (θ), a sphere of radius r and mass m with I = k m r², against the
/// floor z = r (its centre r above the ground plane) or a plane through
/// the origin tilted by α about y.
#[derive(Clone, Copy)]
struct Planar {
    m: f64,
    r: f64,
    k: f64,
    alpha: f64,
    law: ContactLaw,
    /// Whether friction at the contact point turns the body (a sphere) or
    /// not (a block, its θ left alone).
    rolls: bool,
}

impl Planar {
    /// The plane's unit normal and its tangent down the x axis, in (x, z).
    fn axes(&self) -> ([f64; 2], [f64; 2]) {
        let (s, c) = self.alpha.sin_cos();
        ([-s, c], [c, s])
    }
}

impl Lagrangian<f64, 3> for Planar {
    const COORDINATES: [&'static str; 3] = ["x", "z", "theta"];
    const RHEONOMIC: bool = false;
    const CONTACTS: &'static [&'static str] = &["ground"];
    fn mass_matrix(&self, _: &SVector<f64, 3>, _: f64) -> SMatrix<f64, 3, 3> {
        let i = self.k * self.m * self.r * self.r;
        SMatrix::<f64, 3, 3>::from_diagonal(&SVector::<f64, 3>::new(self.m, self.m, i))
    }
    fn bias(&self, _: &SVector<f64, 3>, _: &SVector<f64, 3>, _: f64) -> SVector<f64, 3> {
        SVector::zeros()
    }
    fn generalized_forces(
        &self,
        _: &SVector<f64, 3>,
        _: &SVector<f64, 3>,
        _: f64,
    ) -> SVector<f64, 3> {
        SVector::<f64, 3>::new(0.0, -self.m * G, 0.0)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, 3>,
        v: &SVector<f64, 3>,
        t: f64,
    ) -> (SMatrix<f64, 3, 3>, SVector<f64, 3>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, q: &SVector<f64, 3>, v: &SVector<f64, 3>, t: f64) -> f64 {
        0.5 * v.dot(&(self.mass_matrix(q, t) * v))
    }
    fn potential_energy(&self, q: &SVector<f64, 3>, _: f64) -> f64 {
        self.m * G * q[1]
    }
    fn integral(&self, q: &SVector<f64, 3>, v: &SVector<f64, 3>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Contacts<f64, 3> for Planar {
    fn contact_laws(&self) -> Vec<ContactLaw> {
        vec![self.law]
    }
    fn contact_rows(
        &self,
        index: usize,
        q: &SVector<f64, 3>,
        _: &SVector<f64, 3>,
        _: f64,
    ) -> Option<ContactRows<f64, 3>> {
        (index == 0).then(|| {
            let (n, t) = self.axes();
            // The contact point is −r n from the centre; its slip along t is
            // the centre's plus (θ̇ ŷ × (−r n))·t = −r θ̇ (n and t unit and
            // orthogonal in the plane normal to ŷ).
            ContactRows {
                gap: n[0] * q[0] + n[1] * q[1] - self.r,
                normal: SVector::<f64, 3>::new(n[0], n[1], 0.0),
                normal_bias: 0.0,
                tangents: [
                    SVector::<f64, 3>::new(t[0], t[1], if self.rolls { -self.r } else { 0.0 }),
                    SVector::zeros(),
                ],
                tangent_bias: [0.0, 0.0],
            }
        })
    }
}

fn law(restitution: f64, friction: f64) -> ContactLaw {
    ContactLaw::unilateral("ground", restitution, friction)
}

fn ball(e: f64, mu: f64) -> Planar {
    Planar {
        m: 0.3,
        r: 0.1,
        k: 0.4,
        alpha: 0.0,
        law: law(e, mu),
        rolls: true,
    }
}

fn block(alpha: f64, mu: f64) -> Planar {
    Planar {
        m: 2.0,
        r: 0.05,
        k: 1.0,
        alpha,
        law: law(0.0, mu),
        rolls: false,
    }
}

/// The times of the changes of one kind.
fn times(run: &ContactRun<f64, 3>, kind: fn(&ChangeKind<f64>) -> bool) -> Vec<f64> {
    run.changes
        .iter()
        .filter(|c| kind(&c.kind))
        .map(|c| c.t)
        .collect()
}

fn run(sys: &Planar, q0: [f64; 3], v0: [f64; 3], end: f64) -> ContactRun<f64, 3> {
    Simulation::new(sys)
        .integrator(Dop853::tol(1e-13))
        .contact_settings(ContactSettings {
            rest_speed: 1e-7,
            ..ContactSettings::default()
        })
        .run_contacts(q0, v0, 0.0..end)
        .unwrap()
}

/// Along the run: the gap never below −1e-12, every closed contact's normal
/// force compressive, friction inside the cone (to round-off).
fn invariants(sys: &Planar, run: &ContactRun<f64, 3>) {
    let traj = &run.trajectory;
    for ((&t, q), v) in traj
        .times()
        .iter()
        .zip(traj.positions())
        .zip(traj.velocities())
    {
        let gap = sys.contact_rows(0, q, v, t).unwrap().gap;
        assert!(gap > -1e-12, "t = {t}: gap {gap:e}");
        let f = run.forces(sys, t, q, v).unwrap()[0];
        assert!(f.normal >= -1e-9, "t = {t}: λ_n = {}", f.normal);
        let size = f.tangential[0].hypot(f.tangential[1]);
        assert!(
            size <= sys.law.friction * f.normal + 1e-9,
            "t = {t}: outside the cone"
        );
    }
}

/// Dropped from h₀: impact k (from 0) at t₁ + Σ 2 eʲ v₁/g, leaving at eᵏ⁺¹ v₁,
/// so the apex after it is e^(2(k+1)) h₀; the bounces accumulate at
/// t₁ (1 + e)/(1 − e), where the ball comes to rest in contact.
#[test]
fn a_bouncing_ball_rests_at_the_accumulation_time() {
    let (e, h0) = (0.5, 1.0);
    let sys = ball(e, 0.0);
    let run = run(&sys, [0.0, h0 + sys.r, 0.0], [0.0; 3], 2.0);
    let t1 = (2.0 * h0 / G).sqrt();
    let v1 = G * t1;
    let impacts: Vec<_> = run
        .changes
        .iter()
        .filter_map(|c| match c.kind {
            ChangeKind::Impact { before, after } => Some((c.t, before, after)),
            _ => None,
        })
        .collect();
    assert!(impacts.len() > 15, "{} impacts", impacts.len());
    let (mut t_exact, mut worst_t, mut worst_h) = (t1, 0.0f64, 0.0f64);
    for (k, &(t, before, after)) in impacts.iter().enumerate() {
        let speed = e.powi(k as i32) * v1;
        worst_t = worst_t.max((t - t_exact).abs());
        assert!(
            (before + speed).abs() < 1e-9,
            "impact {k}: {before} vs {}",
            -speed
        );
        assert!((after + e * before).abs() < 1e-12, "impact {k}");
        let apex = after * after / (2.0 * G);
        worst_h = worst_h.max((apex - e.powi(2 * (k as i32 + 1)) * h0).abs());
        // The apex on the trajectory itself, half a flight later.
        let (q, _) = run.trajectory.state_at(t + after / G).unwrap();
        assert!(
            (q[1] - sys.r - apex).abs() < 1e-9,
            "impact {k}: apex {}",
            q[1] - sys.r
        );
        t_exact += 2.0 * e * speed / G;
    }
    let rest = run
        .changes
        .iter()
        .find_map(|c| match c.kind {
            ChangeKind::Rests { accumulation, .. } => Some(accumulation),
            _ => None,
        })
        .expect("the bounces end in a rest");
    let t_rest = t1 * (1.0 + e) / (1.0 - e);
    eprintln!(
        "ball: {} impacts, times to {worst_t:.1e}, heights to {worst_h:.1e}, rest at {rest} vs {t_rest} ({:.1e})",
        impacts.len(),
        (rest - t_rest).abs()
    );
    assert!(worst_t < 1e-9 && worst_h < 1e-9);
    assert!((rest - t_rest).abs() < 1e-9, "{rest} vs {t_rest}");
    assert_eq!(run.states(2.0), [ContactState::Sliding]);
    let (q, v) = run.trajectory.final_state();
    assert!((q[1] - sys.r).abs() < 1e-12 && v.norm() < 1e-9, "{q} {v}");
    // Energy never rises at a change.
    let energy = |q: &SVector<f64, 3>, v: &SVector<f64, 3>| sys.integral(q, v, 0.0);
    let traj = &run.trajectory;
    let worst = traj
        .positions()
        .iter()
        .zip(traj.velocities())
        .map(|(q, v)| energy(q, v))
        .collect::<Vec<_>>()
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::MIN, f64::max);
    assert!(worst < 1e-12, "energy rose by {worst:e}");
    invariants(&sys, &run);
}

/// A block pushed along the floor at v₀ decelerates at μg, stops at
/// v₀/(μg) after v₀²/(2μg), and then sticks.
#[test]
fn a_sliding_block_stops_at_v0_over_mu_g_and_sticks() {
    let (mu, v0) = (0.4, 3.0);
    let sys = block(0.0, mu);
    let run = run(&sys, [0.0, sys.r, 0.0], [v0, 0.0, 0.0], 1.5);
    let sticks = times(&run, |k| matches!(k, ChangeKind::Sticks));
    let (t_stop, distance) = (v0 / (mu * G), v0 * v0 / (2.0 * mu * G));
    assert_eq!(sticks.len(), 1, "{:?}", run.changes);
    let (q, v) = run.trajectory.final_state();
    eprintln!(
        "block: stops at {:.1e} from v0/(μg), {:.1e} from v0²/(2μg)",
        (sticks[0] - t_stop).abs(),
        (q[0] - distance).abs()
    );
    assert!(
        (sticks[0] - t_stop).abs() < 1e-9,
        "{} vs {t_stop}",
        sticks[0]
    );
    assert!((q[0] - distance).abs() < 1e-9, "{} vs {distance}", q[0]);
    assert!(v.norm() < 1e-12 && (q[1] - sys.r).abs() < 1e-12);
    // Halfway through the slide: v = v₀ − μ g t.
    let (_, v) = run.trajectory.state_at(0.5 * t_stop).unwrap();
    assert!((v[0] - 0.5 * v0).abs() < 1e-9, "{}", v[0]);
    assert_eq!(run.states(1.5), [ContactState::Sticking]);
    invariants(&sys, &run);
}

/// On an incline of angle α at rest: friction holds it when tan α ≤ μ;
/// otherwise it slides down at g (sin α − μ cos α).
#[test]
fn a_block_on_an_incline_sticks_or_slides_by_tan_alpha() {
    let mu = 0.5;
    for alpha in [0.4f64, 0.5, 0.6] {
        let sys = block(alpha, mu);
        let (n, t) = sys.axes();
        let q0 = [sys.r * n[0], sys.r * n[1], 0.0];
        let end = 0.8;
        let run = run(&sys, q0, [0.0; 3], end);
        let (q, _) = run.trajectory.final_state();
        let along = (q[0] - q0[0]) * t[0] + (q[1] - q0[1]) * t[1];
        let accel = G * (alpha.sin() - mu * alpha.cos());
        if alpha.tan() <= mu {
            assert_eq!(run.states(end), [ContactState::Sticking], "α = {alpha}");
            assert!(along.abs() < 1e-12, "α = {alpha}: moved {along:e}");
        } else {
            assert_eq!(run.states(end), [ContactState::Sliding], "α = {alpha}");
            let exact = -0.5 * accel * end * end;
            eprintln!(
                "incline α = {alpha}: {:.1e} from −g(sin α − μ cos α)t²/2",
                (along - exact).abs()
            );
            assert!(
                (along - exact).abs() < 1e-9,
                "α = {alpha}: {along} vs {exact}"
            );
        }
        invariants(&sys, &run);
    }
}

/// A solid sphere (I = 2/5 m r²) thrown without spin slides until
/// t = 2v₀/(7μg) and then rolls at 5/7 v₀.
#[test]
fn a_sphere_thrown_sliding_rolls_at_five_sevenths() {
    let (mu, v0) = (0.3, 2.0);
    let sys = ball(0.0, mu);
    let run = run(&sys, [0.0, sys.r, 0.0], [v0, 0.0, 0.0], 1.0);
    let sticks = times(&run, |k| matches!(k, ChangeKind::Sticks));
    let t_roll = 2.0 * v0 / (7.0 * mu * G);
    let (_, v) = run.trajectory.final_state();
    eprintln!(
        "sphere: rolls {:.1e} from 2v0/(7μg) at {:.1e} from 5/7 v0",
        (sticks[0] - t_roll).abs(),
        (v[0] - 5.0 / 7.0 * v0).abs()
    );
    assert!(
        (sticks[0] - t_roll).abs() < 1e-9,
        "{} vs {t_roll}",
        sticks[0]
    );
    assert!((v[0] - 5.0 / 7.0 * v0).abs() < 1e-9, "{}", v[0]);
    assert!(
        (v[0] - sys.r * v[2]).abs() < 1e-12,
        "rolls without slipping"
    );
    invariants(&sys, &run);
}

#[test]
fn bad_laws_and_a_penetrating_start_are_typed_errors() {
    for (e, mu, setting) in [(1.2, 0.3, "restitution"), (0.5, -0.1, "friction")] {
        let sys = ball(e, mu);
        let failure = Simulation::new(&sys)
            .run_contacts([0.0, 1.0, 0.0], [0.0; 3], 0.0..1.0)
            .unwrap_err();
        assert!(
            matches!(&failure.error, Error::Settings(s) if s.to_string().contains(setting)),
            "{}",
            failure.error
        );
    }
    let sys = ball(0.5, 0.3);
    let failure = Simulation::new(&sys)
        .run_contacts([0.0, 0.05, 0.0], [0.0; 3], 0.0..1.0)
        .unwrap_err();
    let Error::Contact(error) = &failure.error else {
        panic!("{}", failure.error)
    };
    assert!(
        matches!(error.fault, ContactFault::Penetrates { .. }),
        "{error}"
    );
    assert_eq!(error.contact, "ground");
    // A law `CONTACTS` does not list: the other runs would not refuse the
    // system, so this one does, naming both lists.
    let mut unlisted = ball(0.5, 0.3);
    unlisted.law.name = "floor";
    let failure = Simulation::new(&unlisted)
        .run_contacts([0.0, 1.0, 0.0], [0.0; 3], 0.0..1.0)
        .unwrap_err();
    let Error::Contact(error) = &failure.error else {
        panic!("{}", failure.error)
    };
    assert_eq!(
        error.fault,
        ContactFault::NotListed {
            listed: &["ground"]
        },
        "{error}"
    );
    assert_eq!(error.contact, "floor");
    assert!(error.to_string().contains("CONTACTS"), "{error}");
    assert_eq!(failure.partial.trajectory.len(), 1);
}

/// A uniform rod (half-length l, I = m l²/3) whose lower end slides on the
/// floor: (x, y) its centre, θ its angle to the floor, the end at
/// (x − l cos θ, y − l sin θ).
struct Rod {
    m: f64,
    l: f64,
    mu: f64,
}

impl Lagrangian<f64, 3> for Rod {
    const COORDINATES: [&'static str; 3] = ["x", "y", "theta"];
    const RHEONOMIC: bool = false;
    const CONTACTS: &'static [&'static str] = &["end"];
    fn mass_matrix(&self, _: &SVector<f64, 3>, _: f64) -> SMatrix<f64, 3, 3> {
        let i = self.m * self.l * self.l / 3.0;
        SMatrix::<f64, 3, 3>::from_diagonal(&SVector::<f64, 3>::new(self.m, self.m, i))
    }
    fn bias(&self, _: &SVector<f64, 3>, _: &SVector<f64, 3>, _: f64) -> SVector<f64, 3> {
        SVector::zeros()
    }
    fn generalized_forces(
        &self,
        _: &SVector<f64, 3>,
        _: &SVector<f64, 3>,
        _: f64,
    ) -> SVector<f64, 3> {
        SVector::<f64, 3>::new(0.0, -self.m * G, 0.0)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, 3>,
        v: &SVector<f64, 3>,
        t: f64,
    ) -> (SMatrix<f64, 3, 3>, SVector<f64, 3>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, q: &SVector<f64, 3>, v: &SVector<f64, 3>, t: f64) -> f64 {
        0.5 * v.dot(&(self.mass_matrix(q, t) * v))
    }
    fn potential_energy(&self, q: &SVector<f64, 3>, _: f64) -> f64 {
        self.m * G * q[1]
    }
    fn integral(&self, q: &SVector<f64, 3>, v: &SVector<f64, 3>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Contacts<f64, 3> for Rod {
    fn contact_laws(&self) -> Vec<ContactLaw> {
        vec![ContactLaw::unilateral("end", 0.0, self.mu)]
    }
    fn contact_rows(
        &self,
        index: usize,
        q: &SVector<f64, 3>,
        v: &SVector<f64, 3>,
        _: f64,
    ) -> Option<ContactRows<f64, 3>> {
        let (s, c) = q[2].sin_cos();
        let w = v[2];
        (index == 0).then(|| ContactRows {
            gap: q[1] - self.l * s,
            normal: SVector::<f64, 3>::new(0.0, 1.0, -self.l * c),
            // d/dt(−l cos θ) θ̇ = l sin θ θ̇².
            normal_bias: self.l * s * w * w,
            tangents: [
                SVector::<f64, 3>::new(1.0, 0.0, self.l * s),
                SVector::zeros(),
            ],
            tangent_bias: [self.l * c * w * w, 0.0],
        })
    }
}

/// Painlevé: the rod at 60° sliding towards its leaning side with μ = 2 has
/// the effective normal compliance (1 + 3 cos²θ − 3 μ sin θ cos θ)/m < 0,
/// so rigid contact has no answer or two: a typed error, not a pick. With
/// μ = 0.5 the same start slides.
#[test]
fn painleve_s_rod_is_a_typed_error() {
    let theta = 60f64.to_radians();
    let start = |rod: &Rod| {
        Simulation::new(rod)
            .integrator(Dop853::tol(1e-12))
            .run_contacts(
                [0.0, rod.l * theta.sin(), theta],
                [-1.0, 0.0, 0.0],
                0.0..0.05,
            )
    };
    let rod = Rod {
        m: 1.0,
        l: 0.5,
        mu: 2.0,
    };
    let failure = start(&rod).unwrap_err();
    let Error::Contact(error) = &failure.error else {
        panic!("{}", failure.error)
    };
    let (s, c) = theta.sin_cos();
    let expected = 1.0 + 3.0 * c * c - 3.0 * rod.mu * s * c;
    match error.fault {
        ContactFault::Painleve { compliance } => {
            assert!(
                (compliance - expected).abs() < 1e-12,
                "{compliance} vs {expected}"
            )
        }
        ref other => panic!("{other}"),
    }
    assert!(error.to_string().contains("Painlevé"), "{error}");
    let run = start(&Rod { mu: 0.5, ..rod }).unwrap();
    assert_eq!(run.states(0.0), [ContactState::Sliding]);
}
