//! The reduced form is finite and accurate wherever its stacked velocity rows
//! [U; G] are regular, whatever pivots a symbolic solution would have chosen
//! (the runtime solves the rows with complete pivoting at each state); where
//! they are not, the error names the dependent rows and the state.

use crate::catalog;

use catalog::constrained::{ChaplyginSleigh, RollingDisk};
use lagrange::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// A particle kept on rays from the origin (x ẏ − y ẋ = 0), reduced on the
/// speed ẋ: ẏ = y ẋ / x, which has no solution on the y axis, where the speed
/// and the constraint row are parallel ([U; G] loses rank).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(p, mass = m, at = [x, y]),
    gravity = [0, -g],
    nonholonomic(radial = x * dot(y) - y * dot(x)),
    speeds(u = dot(x)),
    formulation(reduced, multipliers),
)]
pub struct Ray {
    pub m: f64,
    pub g: f64,
}

/// A knife edge whose independent velocities the macro picks (no `speeds`):
/// any one of ẋ, ẏ solved from −sin θ ẋ + cos θ ẏ = 0 divides by a function
/// of θ that vanishes somewhere, so this is where symbolic pivots fail.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, theta),
    body(sled, mass = m, inertia = [0, 0, i], at = [x + b * cos(theta), y + b * sin(theta), 0],
         rotation = rot_z(theta)),
    point(blade, on = sled, at = [-b, 0, 0]),
    potential = k * (sled.x^2) / 2,
    nonholonomic(sideways = -sin(theta) * dot(blade.x) + cos(theta) * dot(blade.y)),
    formulation(reduced, multipliers),
)]
pub struct DefaultKnife {
    pub m: f64,
    pub i: f64,
    pub b: f64,
    pub k: f64,
}

#[test]
fn dependent_rows_are_a_typed_error_naming_them() {
    let ray = Ray { m: 1.0, g: 9.81 };
    match Simulation::new(&ray).run_reduced([0.0, 1.0], [0.0, 0.5], 0.0..1.0) {
        Err(Failure {
            error: e @ Error::ReducedFormBreakdown { .. },
            partial,
        }) => {
            assert_eq!(partial.len(), 1, "refused before the first step");
            let msg = e.to_string();
            assert!(
                msg.contains("x = 0") && msg.contains("run_constrained"),
                "{msg}"
            );
            let Error::ReducedFormBreakdown { rows, t, .. } = e else {
                unreachable!()
            };
            assert_eq!(rows, ["u", "radial"]);
            assert_eq!(t, 0.0);
        }
        other => panic!("expected ReducedFormBreakdown, got {other:?}"),
    }
    // Off the axis the reduced form runs, and agrees with the multiplier form.
    let (q0, v0) = ([0.6, 0.8], [0.3, 0.4]);
    let reduced = Simulation::new(&ray)
        .integrator(Dopri5::tol(1e-11))
        .run_reduced(q0, v0, 0.0..0.1)
        .unwrap();
    let multipliers = Simulation::new(&ray)
        .integrator(Dopri5::tol(1e-11))
        .run_constrained(q0, v0, 0.0..0.1)
        .unwrap();
    let d = (reduced.final_state().0 - multipliers.final_state().0)
        .abs()
        .max();
    assert!(d < 1e-9, "{d}");
}

/// Largest difference between the reduced and the multiplier form's
/// accelerations at (q, v), relative to the largest acceleration.
fn acceleration_gap<S, const N: usize, const K: usize, const M: usize>(
    sys: &S,
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
) -> f64
where
    S: Reduced<f64, N, K> + Constrained<f64, N, M>,
{
    let reduced = ReducedDynamics::<_, f64, K>::new(sys);
    let v = reduced.consistent_velocities(0.0, q, v).unwrap();
    let (_, a) = reduced.solve(0.0, q, &v).unwrap();
    let b = ConstrainedDynamics::<_, f64, M>::new(sys)
        .solve(0.0, q, &v)
        .unwrap()
        .accelerations;
    (a - b).amax() / b.amax().max(1.0)
}

/// Headings where a symbolic pivot vanishes, points 1e-6 and 1e-8 from them
/// (where such a pivot loses digits), and random ones.
fn headings() -> Vec<f64> {
    let mut out = Vec::new();
    for h in [0.0, FRAC_PI_2, PI, -FRAC_PI_2] {
        out.extend([h, h + 1e-6, h - 1e-8]);
    }
    let mut x: u64 = 17;
    for _ in 0..20 {
        x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
        out.push(((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * PI);
    }
    out
}

#[test]
fn knife_edges_agree_with_the_multiplier_form_at_every_heading() {
    let sleigh = ChaplyginSleigh {
        m: 2.0,
        i: 0.3,
        b: 0.4,
    };
    let knife = DefaultKnife {
        m: 2.0,
        i: 0.3,
        b: 0.4,
        k: 1.5,
    };
    let mut worst: f64 = 0.0;
    for theta in headings() {
        let q = Vector3::new(0.3, -0.2, theta);
        let v = Vector3::new(1.1 * theta.cos(), 1.1 * theta.sin(), 0.7);
        worst = worst.max(acceleration_gap::<_, 3, 2, 1>(&sleigh, &q, &v));
        worst = worst.max(acceleration_gap::<_, 3, 2, 1>(&knife, &q, &v));
    }
    assert!(worst < 1e-13, "{worst:e}");
}

/// The case: the catalog sleigh started heading north (θ0 = π/2)
/// ended in `TooManySteps` at t ≈ 1e-12; now both forms give one trajectory.
#[test]
fn sleigh_heading_north_runs_in_both_forms() {
    let sleigh = ChaplyginSleigh {
        m: 2.0,
        i: 0.3,
        b: 0.4,
    };
    for theta in [FRAC_PI_2, PI, 0.0] {
        let q0 = [0.0, 0.0, theta];
        let v0 = [theta.cos(), theta.sin(), 1.5];
        let sim = Simulation::new(&sleigh).integrator(Dopri5::tol(1e-11));
        let reduced = sim.run_reduced(q0, v0, 0.0..5.0).unwrap();
        let multipliers = sim.run_constrained(q0, v0, 0.0..5.0).unwrap();
        let (qr, qm) = (reduced.final_state().0, multipliers.final_state().0);
        assert!((qr - qm).amax() < 1e-8, "θ0 = {theta}: {qr} vs {qm}");
        assert!(reduced.max_residuals()[1] < 1e-12);
    }
}

/// The rolling disk upright (θ = 0) and tilted, against the multiplier form.
#[test]
fn rolling_disk_upright_agrees_with_the_multiplier_form() {
    let disk = RollingDisk::thin(1.0, 0.5, 9.81);
    let mut worst: f64 = 0.0;
    for (tilt, heading) in [(0.0, 0.0), (0.0, FRAC_PI_2), (1e-8, PI), (0.4, 1.0)] {
        let q = Vector5::new(0.1, 0.2, heading, tilt, 0.3);
        let v = Vector5::new(0.0, 0.0, 0.2, 0.05, 6.0);
        worst = worst.max(acceleration_gap::<_, 5, 3, 2>(&disk, &q, &v));
    }
    assert!(worst < 1e-13, "{worst:e}");
}

/// `Simulation::run` runs a constrained description in its form: the
/// multiplier form when emitted (here with the sleigh's both forms), the
/// reduced form when only that is (the default-speed knife edge has both too,
/// so the catalog's reduced-only sphere stands in).
#[test]
fn run_picks_the_emitted_form() {
    let sleigh = ChaplyginSleigh {
        m: 2.0,
        i: 0.3,
        b: 0.4,
    };
    let (q0, v0) = ([0.0, 0.0, 0.3], [0.3f64.cos(), 0.3f64.sin(), 1.0]);
    let sim = Simulation::new(&sleigh).integrator(Dopri5::tol(1e-10));
    let by_run = sim.run(q0, v0, 0.0..2.0).unwrap();
    let by_multipliers = sim.run_constrained(q0, v0, 0.0..2.0).unwrap();
    assert_eq!(by_run.positions(), by_multipliers.positions());
    let sphere = catalog::constrained::RollingSphereReduced {
        m: 2.0,
        j: 0.4 * 2.0 * 0.09,
        a: 0.3,
        g: 9.81,
    };
    let (q5, v5) = ([0.0, 0.0, 0.2, 0.9, 0.1], [0.0, 0.0, 1.5, -0.7, 4.0]);
    let sim = Simulation::new(&sphere).integrator(Dopri5::tol(1e-10));
    let by_run = sim.run(q5, v5, 0.0..1.0).unwrap();
    let by_reduced = sim.run_reduced(q5, v5, 0.0..1.0).unwrap();
    assert_eq!(by_run.positions(), by_reduced.positions());
}

/// Event runs and controlled runs pick the form the same way.
#[test]
fn event_and_controlled_runs_pick_the_emitted_form() {
    let sleigh = ChaplyginSleigh {
        m: 2.0,
        i: 0.3,
        b: 0.4,
    };
    let (q0, v0) = ([0.0, 0.0, 0.3], [0.3f64.cos(), 0.3f64.sin(), 1.0]);
    let sim = Simulation::new(&sleigh).integrator(Dopri5::tol(1e-10));
    // Heading crossing 1 rad.
    let heading = || Event::new(|_, q: &Vector3<f64>, _| q[2] - 1.0);
    let a = sim.clone().event(heading()).run(q0, v0, 0.0..2.0).unwrap();
    let b = sim
        .clone()
        .event(heading())
        .run_constrained(q0, v0, 0.0..2.0)
        .unwrap();
    assert_eq!(a.times(0), b.times(0));
    assert_eq!(a.trajectory.positions(), b.trajectory.positions());
    let c = sim
        .clone()
        .open_loop(|_| [0.0f64; 0])
        .run(q0, v0, 0.0..2.0)
        .unwrap();
    let d = sim
        .clone()
        .open_loop(|_| [0.0f64; 0])
        .run_constrained(q0, v0, 0.0..2.0)
        .unwrap();
    assert_eq!(c.trajectory().positions(), d.trajectory().positions());
}
