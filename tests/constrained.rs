//! Constrained catalog systems (issue 3) against closed forms, conserved quantities
//! and second formulations: multipliers vs minimal coordinates, bodies vs
//! particles, reduced vs multiplier form, Gibbs–Appell vs Cartesian.

use crate::catalog;

use catalog::constrained::*;
use catalog::{Dumbbell, SphericalPendulum};
use lagrange::prelude::*;
use lagrange::{ConstrainedDynamics, Drift, Error};
use nalgebra::{SVector, Vector2, Vector3};

fn sph_to_cart(l: f64, q: &Vector2<f64>, v: &Vector2<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let (th, ph, thd, phd) = (q[0], q[1], v[0], v[1]);
    let x = Vector3::new(
        l * th.sin() * ph.cos(),
        l * th.sin() * ph.sin(),
        -l * th.cos(),
    );
    let xd = Vector3::new(
        l * (th.cos() * ph.cos() * thd - th.sin() * ph.sin() * phd),
        l * (th.cos() * ph.sin() * thd + th.sin() * ph.cos() * phd),
        l * th.sin() * thd,
    );
    (x, xd)
}

/// C1 both ways: the Cartesian model with a multiplier and the (θ, φ) chart give
/// the same motion; the thread tension from λ is m(|v|²/l − g⃗·n) with n the unit
/// vector from the bob to the pivot.
#[test]
fn spherical_pendulum_cartesian_matches_chart_and_tension() {
    let chart = SphericalPendulum {
        m: 1.2,
        l: 0.9,
        g: 9.81,
    };
    let cart = CartesianSphericalPendulum {
        m: 1.2,
        l: 0.9,
        g: 9.81,
    };
    let (q0, v0) = (Vector2::new(1.1, 0.2), Vector2::new(0.3, 1.7));
    let (x0, xd0) = sph_to_cart(chart.l, &q0, &v0);
    let span = 0.0..6.0;
    let a = Simulation::new(&chart)
        .integrator(Dopri5::tol(1e-12))
        .run(q0, v0, span.clone())
        .unwrap();
    let b = Simulation::new(&cart)
        .integrator(Dopri5::tol(1e-12))
        .drift(Drift::projection())
        .run_constrained(x0, xd0, span)
        .unwrap();
    let mut worst = 0.0f64;
    for k in 0..=60 {
        let t = 0.1 * k as f64;
        let (qa, va) = a.state_at(t).unwrap();
        let (xa, _) = sph_to_cart(chart.l, &qa, &va);
        let (xb, _) = b.state_at(t).unwrap();
        worst = worst.max((xa - xb).amax());
    }
    assert!(worst < 1e-8, "positions differ by {worst:e}");
    assert!(b.max_residuals()[0] < 1e-11, "{:?}", b.max_residuals());

    // Tension along the run.
    let dynamics = ConstrainedDynamics::<_, f64, 1>::new(&cart);
    for (k, (&t, (x, v))) in b
        .times()
        .iter()
        .zip(b.positions().iter().zip(b.velocities()))
        .enumerate()
        .step_by(37)
    {
        let sol = dynamics.solve(t, x, v).unwrap();
        let reaction = cart.reactions(x, v, t, &sol.multipliers)[0];
        let n = -x / x.norm();
        let tension =
            cart.m * (v.norm_squared() / cart.l - Vector3::new(0.0, 0.0, -cart.g).dot(&n));
        assert!(
            (reaction.norm() - tension).abs() < 1e-9 * tension,
            "point {k}: |R| = {} vs {tension}",
            reaction.norm()
        );
        assert!(reaction.dot(&n) > 0.0, "a thread pulls towards the pivot");
    }
}

/// Through the pole: the chart reports its singular matrix there, while the
/// Cartesian model starts from the same state and just moves on.
#[test]
fn cartesian_pendulum_passes_the_pole() {
    let chart = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let cart = CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    // At the bottom (θ = 0, the pole of this chart), moving sideways.
    let err = Simulation::new(&chart).run([0.0, 0.3], [0.5, 0.0], 0.0..1.0);
    assert!(
        matches!(
            err,
            Err(Failure {
                error: Error::SingularMassMatrix { .. },
                ..
            })
        ),
        "{err:?}"
    );
    let x0 = Vector3::new(0.0, 0.0, -1.0);
    let xd0 = Vector3::new(0.5 * 0.3f64.cos(), 0.5 * 0.3f64.sin(), 0.0);
    let traj = Simulation::new(&cart)
        .integrator(Dopri5::tol(1e-11))
        .drift(Drift::projection())
        .run_constrained(x0, xd0, 0.0..3.0)
        .unwrap();
    // A planar swing through the bottom and back: it crosses the pole again.
    let crossings = traj.crossings(|_, x, _| x[0]).unwrap();
    assert!(crossings.len() >= 2, "{crossings:?}");
    assert!(traj.integral_drift() < 1e-9);
    assert!(traj.max_residuals()[0] < 1e-11);
}

/// The two particles' positions and velocities, stacked (x1, x2), from the
/// minimal dumbbell's centre of mass, polar and azimuth angles, with the
/// particles at distances a and b from the centre of mass along the rod.
fn dumbbell_particles(
    a: f64,
    b: f64,
    q: &SVector<f64, 5>,
    v: &SVector<f64, 5>,
) -> (SVector<f64, 6>, SVector<f64, 6>) {
    let (s, c) = (q[3].sin(), q[3].cos());
    let (sp, cp) = (q[4].sin(), q[4].cos());
    let e = Vector3::new(s * cp, s * sp, c);
    let ed = Vector3::new(
        c * cp * v[3] - s * sp * v[4],
        c * sp * v[3] + s * cp * v[4],
        -s * v[3],
    );
    let xc = Vector3::new(q[0], q[1], q[2]);
    let vc = Vector3::new(v[0], v[1], v[2]);
    let p1 = xc + e * a;
    let p2 = xc - e * b;
    let (v1, v2) = (vc + ed * a, vc - ed * b);
    (
        SVector::<f64, 6>::from([p1[0], p1[1], p1[2], p2[0], p2[1], p2[2]]),
        SVector::<f64, 6>::from([v1[0], v1[1], v1[2], v2[0], v2[1], v2[2]]),
    )
}

/// C3: the rod as a constraint between free particles moves like the minimal
/// model; in ex. 100's set-up (rod turning in a vertical plane at constant φ̇0, no
/// gravity) the rod pulls m1 towards the centre of mass with m1 a φ̇0².
#[test]
fn rod_constraint_matches_minimal_dumbbell_and_reaction() {
    let (m1, m2, l) = (1.5, 0.7, 2.0);
    let g = [0.3, -0.2, -9.81];
    let minimal = Dumbbell {
        m1,
        m2,
        l,
        gx: g[0],
        gy: g[1],
        gz: g[2],
    };
    let pair = RodPair {
        m1,
        m2,
        l,
        gx: g[0],
        gy: g[1],
        gz: g[2],
    };
    let (a, b) = (m2 * l / (m1 + m2), m1 * l / (m1 + m2));
    let cart = |q: &SVector<f64, 5>, v: &SVector<f64, 5>| dumbbell_particles(a, b, q, v);
    let q0 = SVector::<f64, 5>::from([0.1, 0.2, 3.0, 0.8, 0.4]);
    let v0 = SVector::<f64, 5>::from([0.5, -0.3, 2.0, 1.1, 0.7]);
    let (x0, xd0) = cart(&q0, &v0);
    let ta = Simulation::new(&minimal)
        .integrator(Dopri5::tol(1e-12))
        .run(q0, v0, 0.0..3.0)
        .unwrap();
    let tb = Simulation::new(&pair)
        .integrator(Dopri5::tol(1e-12))
        .drift(Drift::projection())
        .run_constrained(x0, xd0, 0.0..3.0)
        .unwrap();
    for k in 0..=30 {
        let t = 0.1 * k as f64;
        let (qa, va) = ta.state_at(t).unwrap();
        let (xa, _) = cart(&qa, &va);
        let (xb, _) = tb.state_at(t).unwrap();
        assert!((xa - xb).amax() < 1e-8, "t = {t}: {:e}", (xa - xb).amax());
    }

    // Ex. 100: no gravity, rod in the vertical plane ψ = 0 turning at φ̇0.
    let free = RodPair {
        gx: 0.0,
        gy: 0.0,
        gz: 0.0,
        ..pair
    };
    let phid = 2.5;
    let (x0, xd0) = cart(
        &SVector::from([0.0, 0.0, 0.0, 0.4, 0.0]),
        &SVector::from([0.0, 0.0, 0.0, phid, 0.0]),
    );
    let dynamics = ConstrainedDynamics::<_, f64, 1>::new(&free);
    let sol = dynamics.solve(0.0, &x0, &xd0).unwrap();
    let r1 = free.reactions(&x0, &xd0, 0.0, &sol.multipliers)[0];
    let expected = m1 * a * phid * phid;
    assert!(
        (r1.norm() - expected).abs() < 1e-12 * expected,
        "|R1| = {} vs m1 a φ̇0² = {expected}",
        r1.norm()
    );
    // Directed from m1 towards the centre of mass (the origin here).
    let p1 = Vector3::new(x0[0], x0[1], x0[2]);
    assert!((r1.normalize() + p1.normalize()).norm() < 1e-12);
}

/// C4, Suslov ex. 97: three rigidly attached particles and the same body by mass and
/// inertia tensor move identically.
#[test]
fn three_particles_equal_their_rigid_body() {
    let particles = ThreeParticleBody::example(9.81);
    let body = particles.as_body();
    let q0 = SVector::<f64, 6>::from([0.0, 0.0, 1.0, 0.3, 1.1, -0.4]);
    let v0 = SVector::<f64, 6>::from([0.2, 0.1, 3.0, 0.7, -0.5, 2.0]);
    let run = |traj: Result<Trajectory<f64, 6>, Failure<Trajectory<f64, 6>>>| traj.unwrap();
    let ta = run(Simulation::new(&particles)
        .integrator(Dopri5::tol(1e-13))
        .run(q0, v0, 0.0..2.0));
    let tb = run(Simulation::new(&body)
        .integrator(Dopri5::tol(1e-13))
        .run(q0, v0, 0.0..2.0));
    let (qa, _) = ta.final_state();
    let (qb, _) = tb.final_state();
    assert!((qa - qb).amax() < 1e-9, "{:e}", (qa - qb).amax());
    assert!(ta.integral_drift() < 1e-10 && tb.integral_drift() < 1e-10);
}

/// Spin components of a z-x-z rotation in world axes: the sphere's ω.
fn omega_world(q: &[f64], v: &[f64]) -> Vector3<f64> {
    let (psi, theta) = (q[0], q[1]);
    let (psid, thetad, phid) = (v[0], v[1], v[2]);
    Vector3::new(
        thetad * psi.cos() + phid * theta.sin() * psi.sin(),
        thetad * psi.sin() - phid * theta.sin() * psi.cos(),
        psid + phid * theta.cos(),
    )
}

/// C5: the rolling sphere. Its centre moves in a straight line at constant
/// velocity, the spin about the vertical is constant, energy is conserved, the
/// constraints hold; the multiplier and reduced forms agree.
#[test]
fn rolling_sphere_both_forms() {
    let (m, a) = (2.0, 0.3);
    let full = RollingSphere {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
    };
    let reduced = RollingSphereReduced {
        m,
        j: full.j,
        a,
        g: 9.81,
    };
    let (angles, rates) = ([0.2, 0.9, 0.1], [1.5, -0.7, 4.0]);
    let w = omega_world(&angles, &rates);
    let (xd, yd) = (a * w[1], -a * w[0]);
    let q5 = SVector::<f64, 5>::from([0.0, 0.0, angles[0], angles[1], angles[2]]);
    let v5 = SVector::<f64, 5>::from([xd, yd, rates[0], rates[1], rates[2]]);
    let q6 = SVector::<f64, 6>::from([0.0, 0.0, a, angles[0], angles[1], angles[2]]);
    let v6 = SVector::<f64, 6>::from([xd, yd, 0.0, rates[0], rates[1], rates[2]]);
    let span = 0.0..10.0;
    let tr = Simulation::new(&reduced)
        .integrator(Dopri5::tol(1e-12))
        .run_reduced(q5, v5, span.clone())
        .unwrap();
    let tf = Simulation::new(&full)
        .integrator(Dopri5::tol(1e-12))
        .drift(Drift::projection())
        .run_constrained(q6, v6, span)
        .unwrap();
    for (traj_q, traj_v, t) in tr
        .positions()
        .iter()
        .zip(tr.velocities())
        .zip(tr.times())
        .map(|((q, v), t)| (q, v, *t))
    {
        // Straight line at constant velocity, constant vertical spin.
        assert!((traj_q[0] - xd * t).abs() < 1e-9 && (traj_q[1] - yd * t).abs() < 1e-9);
        let wz = omega_world(&traj_q.as_slice()[2..], &traj_v.as_slice()[2..])[2];
        assert!((wz - w[2]).abs() < 1e-9, "ω_z {wz} vs {}", w[2]);
    }
    assert!(tr.integral_drift() < 1e-10, "{}", tr.integral_drift());
    assert!(tf.integral_drift() < 1e-10, "{}", tf.integral_drift());
    assert!(tr.max_residuals()[1] < 1e-12 && tf.max_residuals().iter().all(|r| *r < 1e-11));
    let (qr, _) = tr.final_state();
    let (qf, _) = tf.final_state();
    let qf5 = SVector::<f64, 5>::from([qf[0], qf[1], qf[3], qf[4], qf[5]]);
    assert!((qr - qf5).amax() < 1e-8, "{:e}", (qr - qf5).amax());
    assert!((qf[2] - a).abs() < 1e-12);

    // The six-coordinate model in its own reduced form (z kept, ż = 0 imposed at
    // the velocity level): the same motion, and z never leaves a.
    let t6 = Simulation::new(&full)
        .integrator(Dopri5::tol(1e-12))
        .run_reduced(q6, v6, 0.0..10.0)
        .unwrap();
    let (q, _) = t6.final_state();
    assert!((q - qf).amax() < 1e-8, "{:e}", (q - qf).amax());
    assert!(t6.positions().iter().all(|q| (q[2] - a).abs() < 1e-14));
}

/// C6: the untwistable thread between two tops: energy conserved, thread kept, and
/// the thread really transmits a torque (the tops are asymmetric; for symmetric
/// tops with equal axial moments each spin is conserved on its own and the thread
/// would carry nothing).
#[test]
fn threaded_tops_conserve_energy_and_keep_the_thread() {
    let sys = ThreadedTops {
        m: 1.0,
        a: 0.3,
        b: 0.2,
        c: 0.5,
        l: 0.4,
        d: 2.0,
        g: 9.81,
    };
    // Spins opposite and equal, so the thread starts untwisted: ψ̇1 + cosθ1 φ̇1 = 10.
    let q0 = SVector::<f64, 6>::from([0.0, 0.4, 0.0, 0.5, 0.7, 0.0]);
    let (phid1, phid2) = (1.0, -0.5);
    let psid1 = 10.0 - q0[1].cos() * phid1;
    let psid2 = -10.0 - q0[4].cos() * phid2;
    let v0 = SVector::<f64, 6>::from([phid1, 0.2, psid1, phid2, -0.1, psid2]);
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-11))
        .drift(Drift::projection())
        .run_constrained(q0, v0, 0.0..5.0)
        .unwrap();
    assert!(traj.integral_drift() < 1e-9, "{}", traj.integral_drift());
    assert!(
        traj.max_residuals()[1] < 1e-11,
        "{:?}",
        traj.max_residuals()
    );
    let dynamics = ConstrainedDynamics::new(&sys);
    let torque = traj
        .times()
        .iter()
        .zip(traj.positions().iter().zip(traj.velocities()))
        .map(|(&t, (q, v))| dynamics.solve(t, q, v).unwrap().multipliers[0].abs())
        .fold(0.0, f64::max);
    assert!(torque > 1e-2, "the thread transmits a torque ({torque})");
}

/// C8: the Gibbs–Appell equations in the quasi-velocity w = x ẏ − y ẋ reproduce the
/// Cartesian motion.
#[test]
fn quasi_velocity_matches_cartesian() {
    let polar = PolarQuasiVelocity {
        m: 1.3,
        k: 2.0,
        s: 0.4,
    };
    let cart = PlanarParticle {
        m: 1.3,
        k: 2.0,
        s: 0.4,
    };
    let (r0, th0, rd0, thd0) = (1.0f64, 0.3f64, 0.2, 0.9);
    let tp = Simulation::new(&polar)
        .integrator(Dopri5::tol(1e-12))
        .run_reduced([r0, th0], [rd0, thd0], 0.0..5.0)
        .unwrap();
    let x0 = Vector2::new(r0 * th0.cos(), r0 * th0.sin());
    let xd0 = Vector2::new(
        rd0 * th0.cos() - r0 * th0.sin() * thd0,
        rd0 * th0.sin() + r0 * th0.cos() * thd0,
    );
    let tc = Simulation::new(&cart)
        .integrator(Dopri5::tol(1e-12))
        .run(x0, xd0, 0.0..5.0)
        .unwrap();
    for k in 0..=50 {
        let t = 0.1 * k as f64;
        let (q, _) = tp.state_at(t).unwrap();
        let (x, _) = tc.state_at(t).unwrap();
        let xp = Vector2::new(q[0] * q[1].cos(), q[0] * q[1].sin());
        assert!((xp - x).amax() < 1e-8, "t = {t}: {:e}", (xp - x).amax());
    }
}

/// C9, Pars 13.5: on a plane turning at Ω, a rolling homogeneous sphere's centre
/// moves on a circle at the constant angular velocity 2Ω/7.
#[test]
fn sphere_on_turntable_circles_at_two_sevenths() {
    let (m, a, big_omega) = (1.0, 0.2, 3.0);
    let sys = SphereOnTurntable {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
        big_omega,
    };
    let q0 = SVector::<f64, 5>::from([1.0, 0.5, 0.3, 1.2, 0.0]);
    let v0 = SVector::<f64, 5>::from([0.0, 0.0, 0.8, -0.4, 2.0]);
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run_reduced(q0, v0, 0.0..10.0)
        .unwrap();
    let rate = 2.0 * big_omega / 7.0;
    // The centre's velocity turns at 2Ω/7: v(t) = rot(2Ωt/7) v(0).
    let vel0 = Vector2::new(traj.velocities()[0][0], traj.velocities()[0][1]);
    assert!(vel0.norm() > 0.1, "the ball moves");
    for (t, v) in traj.times().iter().zip(traj.velocities()) {
        let (s, c) = ((rate * t).sin(), (rate * t).cos());
        let expected = Vector2::new(c * vel0[0] - s * vel0[1], s * vel0[0] + c * vel0[1]);
        let got = Vector2::new(v[0], v[1]);
        assert!(
            (got - expected).amax() < 1e-8,
            "t = {t}: {got} vs {expected}"
        );
    }
}

/// The rolling disk: a circular motion started from the steady-motion condition
/// (see [`RollingDisk::steady_circle`]) stays steady.
#[test]
fn rolling_disk_steady_circle() {
    let (m, a) = (1.0, 0.5);
    let sys = RollingDisk {
        m,
        a,
        b: m * a * a / 4.0,
        c: m * a * a / 2.0,
        g: 9.81,
    };
    let (theta0, big_omega) = (0.3, 2.0);
    let (q0, v0) = sys.steady_circle(theta0, big_omega);
    let phid = v0[4];
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run_reduced(q0, v0, 0.0..3.0)
        .unwrap();
    for (q, v) in traj.positions().iter().zip(traj.velocities()) {
        assert!((q[3] - theta0).abs() < 1e-8, "tilt drifted to {}", q[3]);
        assert!((v[2] - big_omega).abs() < 1e-8, "heading rate {}", v[2]);
        assert!((v[4] - phid).abs() < 1e-8, "spin {}", v[4]);
    }
    assert!(traj.integral_drift() < 1e-11);
}

/// The Chaplygin sleigh: energy conserved; the turning dies out and the sleigh
/// ends up moving straight ahead with all its energy in translation.
#[test]
fn chaplygin_sleigh_straightens_out() {
    let sys = ChaplyginSleigh {
        m: 1.0,
        i: 0.2,
        b: 0.5,
    };
    let q0 = SVector::<f64, 3>::from([0.0, 0.0, 0.0]);
    let v0 = SVector::<f64, 3>::from([0.3, 0.0, 2.0]);
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-11))
        .run_reduced(q0, v0, 0.0..60.0)
        .unwrap();
    assert!(traj.integral_drift() < 1e-9, "{}", traj.integral_drift());
    let e0 = traj.integrals()[0];
    let (q, v) = traj.final_state();
    let forward = q[2].cos() * v[0] + q[2].sin() * v[1];
    assert!(v[2].abs() < 1e-3, "still turning at {}", v[2]);
    let straight = (2.0 * e0 / sys.m).sqrt();
    assert!(
        (forward - straight).abs() < 1e-3 * straight,
        "{forward} vs {straight}"
    );
    assert!(traj.max_residuals()[1] < 1e-12);
}

/// The thread written twice: a redundant pair of constraints.
#[derive(lagrange::Lagrangian)]
#[lagrange(
    coordinates(x, y),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    holonomic(thread = (x^2) + (y^2) - (l^2), again = 2 * ((x^2) + (y^2) - (l^2))),
)]
struct DoubledThread {
    m: f64,
    l: f64,
    g: f64,
}

/// Redundant constraints are a typed error unless least squares is chosen, which
/// then gives the single-constraint motion; inconsistent initial conditions are a
/// typed error unless projected.
#[test]
fn typed_errors_for_bad_constraint_input() {
    let twice = DoubledThread {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let (x0, v0) = ([0.6, -0.8], [0.8, 0.6]);
    let err = Simulation::new(&twice).run_constrained(x0, v0, 0.0..1.0);
    assert!(
        matches!(
            err,
            Err(Failure {
                error: Error::RedundantConstraints { .. },
                ..
            })
        ),
        "{err:?}"
    );
    let ls = Simulation::new(&twice)
        .integrator(Dopri5::tol(1e-12))
        .least_squares(true)
        .run_constrained(x0, v0, 0.0..1.0)
        .unwrap();
    let (x, _) = ls.final_state();
    // Same as the θ-pendulum from θ0 = asin(0.6), θ̇0 = 1.
    let single = catalog::Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let th = Simulation::new(&single)
        .integrator(Dopri5::tol(1e-12))
        .run([0.6f64.asin()], [1.0], 0.0..1.0)
        .unwrap();
    let (q, _) = th.final_state();
    assert!((x[0] - q[0].sin()).abs() < 1e-8 && (x[1] + q[0].cos()).abs() < 1e-8);

    let cart = CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let err = Simulation::new(&cart).run_constrained([0.5, 0.0, -0.5], [0.0, 0.0, 0.0], 0.0..1.0);
    assert!(
        matches!(
            err,
            Err(Failure {
                error: Error::InconsistentInitialConditions { .. },
                ..
            })
        ),
        "{err:?}"
    );
    let fixed = Simulation::new(&cart)
        .project_initial(true)
        .run_constrained([0.5, 0.0, -0.5], [0.0, 0.0, 0.0], 0.0..1.0)
        .unwrap();
    assert!((fixed.positions()[0].norm() - 1.0).abs() < 1e-12);
}

/// The rolling disk's contact point (x, y) and spin φ are cyclic: no equation,
/// constraint row or reduced row reads them; heading ψ and tilt θ are read.
#[test]
fn rolling_disk_cyclic_coordinates() {
    assert_eq!(
        <RollingDisk as Lagrangian<f64, 5>>::CYCLIC,
        [true, true, false, false, true]
    );
}
