//! RATTLE on derived systems: the catalog's Cartesian spherical pendulum (C1
//! with a multiplier) and a top held at its tip (a free orientation with
//! holonomic rows). The long-run study is examples/rattle.rs; the runtime's
//! tests cover order, long runs against RK4 and the errors.

use crate::catalog;

use catalog::constrained::CartesianSphericalPendulum;
use catalog::free::QuaternionTop;
use lagrange::Rattle;
use lagrange::nalgebra::{SVector, UnitQuaternion};
use lagrange::prelude::*;

#[test]
fn derived_spherical_pendulum_stays_on_the_sphere() {
    let sys = CartesianSphericalPendulum {
        m: 0.8,
        l: 1.3,
        g: 9.81,
    };
    let th = 1.1f64;
    let q0 = Vector3::new(sys.l * th.sin(), 0.0, -sys.l * th.cos());
    let v0 = Vector3::new(0.5 * th.cos(), 2.0, 0.5 * th.sin());
    let tr = Rattle::step(0.01)
        .integrate(&sys, 0.0, 100.0, q0, v0)
        .unwrap();
    let [phi, vel] = tr.max_residuals();
    assert!(phi < 1e-14 && vel < 1e-14, "{phi:e} {vel:e}");
    let e = tr.integrals();
    let half = e.len() / 2;
    let err = |s: &[f64]| {
        s.iter()
            .map(|x| (x - e[0]).abs() / e[0].abs())
            .fold(0.0, f64::max)
    };
    let (first, second) = (err(&e[..half]), err(&e[half..]));
    eprintln!("energy error: first half {first:.2e}, second half {second:.2e}");
    assert!(
        second < 1e-3 && second < 1.5 * first,
        "{first:e} -> {second:e}"
    );
}

/// The heavy top of `QuaternionTop` as a free body: its centre of mass
/// (x, y, z) and a free orientation, its tip held at the origin by three
/// holonomic rows; its moments about the centre of mass a − m l² and c. M in
/// (ẋ, ẏ, ż, ω) is constant, as RATTLE needs.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    orientation(spin),
    body(top, mass = m, inertia = [a - m * (l^2), a - m * (l^2), c], at = [x, y, z],
         rotation = spin),
    point(tip, on = top, at = [0, 0, -l]),
    gravity = [0, 0, -g],
    holonomic(tip_x = tip.x, tip_y = tip.y, tip_z = tip.z),
)]
struct TippedTop {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

const PIVOTED: QuaternionTop = QuaternionTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};
const TIPPED: TippedTop = TippedTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};

/// The tilted, spinning top's state: the quaternion and ω in body axes, and
/// the free body's (centre of mass, quaternion; its velocity, ω).
fn top_start() -> (
    SVector<f64, 4>,
    Vector3<f64>,
    SVector<f64, 7>,
    SVector<f64, 6>,
) {
    let turn = UnitQuaternion::from_euler_angles(0.5, 0.2, 0.0);
    let omega = Vector3::new(0.3, -0.2, 15.0);
    let c = turn.quaternion();
    let quat = SVector::from([c.w, c.i, c.j, c.k]);
    let arm = Vector3::new(0.0, 0.0, PIVOTED.l);
    let centre = turn * arm;
    let velocity = turn * omega.cross(&arm);
    let q = SVector::from([centre.x, centre.y, centre.z, c.w, c.i, c.j, c.k]);
    let v = SVector::from([
        velocity.x, velocity.y, velocity.z, omega.x, omega.y, omega.z,
    ]);
    (quat, omega, q, v)
}

/// RATTLE with a free orientation (Q ≠ N): the top held at its tip by
/// multipliers follows the pivoted top (no constraints, DOPRI5 at 1e-12) with
/// second-order error, and keeps its tip on the origin and its tip's
/// velocity zero to round-off.
#[test]
fn rattle_turns_a_top_held_at_its_tip_with_second_order() {
    let t_end = 1.0;
    let (quat, omega, q0, v0) = top_start();
    let reference = Simulation::new(&PIVOTED)
        .integrator(Dopri5::tol(1e-12))
        .run(quat, omega, 0.0..t_end)
        .unwrap();
    let (qr, wr) = reference.final_state();
    let error = |h: f64| {
        let tr = Rattle::step(h)
            .integrate(&TIPPED, 0.0, t_end, q0, v0)
            .unwrap();
        let (q, v) = tr.final_state();
        let same = (0..4).map(|i| (q[3 + i] - qr[i]).abs()).fold(0.0, f64::max);
        let opposite = (0..4).map(|i| (q[3 + i] + qr[i]).abs()).fold(0.0, f64::max);
        let spin = (0..3).map(|i| (v[3 + i] - wr[i]).abs()).fold(0.0, f64::max);
        let [phi, vel] = tr.max_residuals();
        (
            same.min(opposite).max(spin / omega.norm()),
            phi,
            vel,
            tr.integral_drift(),
        )
    };
    let runs: Vec<_> = [0.004, 0.002, 0.001].map(error).to_vec();
    for (h, (e, phi, vel, drift)) in [0.004, 0.002, 0.001].iter().zip(&runs) {
        eprintln!(
            "RATTLE top h = {h}: error {e:.3e}, residuals {phi:.1e} {vel:.1e}, energy drift {drift:.1e}"
        );
        assert!(*phi < 1e-13 && *vel < 1e-12, "{phi:e} {vel:e}");
    }
    for pair in runs.windows(2) {
        let ratio = pair[0].0 / pair[1].0;
        eprintln!("RATTLE top: error ratio at half the step {ratio:.3}");
        assert!((ratio - 4.0).abs() < 0.4, "{ratio}");
    }
}

/// A quaternion off unit norm is refused by name, as the other integrators
/// refuse it.
#[test]
fn rattle_refuses_a_quaternion_off_unit_norm() {
    let (_, _, mut q0, v0) = top_start();
    q0[3] *= 1.1;
    let err = Rattle::step(0.01)
        .integrate(&TIPPED, 0.0, 1.0, q0, v0)
        .unwrap_err();
    assert!(
        matches!(&err.error, lagrange::Error::NonUnitQuaternion { orientation, .. } if orientation == "spin"),
        "{err}"
    );
}

/// A work-precision study of the Cartesian spherical pendulum with RATTLE
/// among its methods, run through the study's one closure.
fn rattle_study(steps: &[f64]) -> lagrange::study::Study {
    let sys = CartesianSphericalPendulum {
        m: 0.8,
        l: 1.3,
        g: 9.81,
    };
    let th = 0.9f64;
    let q0 = Vector3::new(sys.l * th.sin(), 0.0, -sys.l * th.cos());
    let v0 = Vector3::new(0.4 * th.cos(), 1.5, 0.4 * th.sin());
    WorkPrecision::new(|m| Simulation::new(&sys).integrator(m).run(q0, v0, 0.0..2.0))
        .repeats(1, std::time::Duration::ZERO)
        .sweep(Sweep::steps("RATTLE", steps, Rattle::step))
        .run()
        .unwrap()
}

#[test]
fn rattle_in_a_study_falls_at_second_order() {
    let study = rattle_study(&[0.02, 0.01, 0.005, 0.0025]);
    let errors: Vec<f64> = study
        .rows()
        .iter()
        .map(|r| r.measurement().expect("RATTLE runs").error)
        .collect();
    // Each halving of h divides the error by 4: slope 2 on log–log.
    eprintln!("RATTLE's errors at h = 0.02 / 2^k: {errors:?}");
    for pair in errors.windows(2) {
        let slope = (pair[0] / pair[1]).log2();
        assert!((slope - 2.0).abs() < 0.15, "slope {slope} from {errors:?}");
    }
    // And the constraint held to round-off on every run.
    for row in study.rows() {
        assert!(row.measurement().unwrap().residual < 1e-13);
    }
}

#[test]
fn rattle_where_it_does_not_apply_is_a_failed_row() {
    use catalog::Pendulum;
    use catalog::constrained::ChaplyginSleigh;
    use lagrange::SettingsError;
    let unsupported = |study: &lagrange::study::Study| {
        let row = &study.rows()[0];
        match &row.outcome {
            Err(Error::Settings(SettingsError::Unsupported { owner, .. })) => {
                assert_eq!(*owner, "RATTLE");
            }
            other => panic!("expected RATTLE's refusal, got {other:?}"),
        }
    };
    // No constraints: nothing to hand RATTLE.
    let pendulum = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let study = WorkPrecision::new(|m| {
        Simulation::new(&pendulum)
            .integrator(m)
            .run([0.5], [0.0], 0.0..1.0)
    })
    .repeats(1, std::time::Duration::ZERO)
    .sweep(Sweep::steps("RATTLE", &[0.01], Rattle::step))
    .run()
    .unwrap();
    unsupported(&study);
    // A nonholonomic row has no position level for RATTLE to hold.
    let sleigh = ChaplyginSleigh {
        m: 1.0,
        i: 0.2,
        b: 0.3,
    };
    let study = WorkPrecision::new(|m| {
        let (q0, v0) = (Vector3::zeros(), Vector3::new(1.0, 0.0, 0.5));
        Simulation::new(&sleigh)
            .integrator(m)
            .run_constrained(q0, v0, 0.0..1.0)
    })
    .conservative(false)
    .repeats(1, std::time::Duration::ZERO)
    .sweep(Sweep::steps("RATTLE", &[0.01], Rattle::step))
    .run()
    .unwrap();
    unsupported(&study);
}
