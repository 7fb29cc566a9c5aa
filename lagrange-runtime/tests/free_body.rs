//! Free rotations stored as unit quaternions (nq = nv + 1 per orientation),
//! against closed forms: the intermediate-axis flip (Landau–Lifshitz §37),
//! torque-free precession, a thrown body's parabola, the heavy top's
//! turning points and a swing through the upright where Euler angles stop.

mod common;

use common::agm;
use common::rigid::{FreeBody, HeavyTop, rotation};
use lagrange_runtime::{Dop853, Dopri5, Error, Integrator, Radau5, Rk4, Simulation, StormerVerlet};
use nalgebra::{Rotation3, SVector, Unit, Vector3};
use std::f64::consts::PI;

/// A free body at rest at the origin, turned by (w, x, y, z), spinning at ω.
fn spinning(quat: [f64; 4], omega: [f64; 3]) -> (SVector<f64, 7>, SVector<f64, 6>) {
    let [w, x, y, z] = quat;
    let q = SVector::from([0.0, 0.0, 0.0, w, x, y, z]);
    let v = SVector::from([0.0, 0.0, 0.0, omega[0], omega[1], omega[2]]);
    (q, v)
}

/// The time between sign changes of ω₂ for principal moments I₁ < I₂ < I₃
/// when L² > 2 E I₂: half the period 4K(k)/s of Landau–Lifshitz §37, with
/// s² = (I₃ − I₂)(L² − 2EI₁)/(I₁I₂I₃), k² = (I₂ − I₁)(2EI₃ − L²)/((I₃ − I₂)(L² − 2EI₁)).
fn flip_period([i1, i2, i3]: [f64; 3], w: [f64; 3]) -> f64 {
    let two_e = i1 * w[0] * w[0] + i2 * w[1] * w[1] + i3 * w[2] * w[2];
    let l2 = (i1 * w[0]).powi(2) + (i2 * w[1]).powi(2) + (i3 * w[2]).powi(2);
    assert!(l2 > two_e * i2, "the other case of §37");
    let s = ((i3 - i2) * (l2 - two_e * i1) / (i1 * i2 * i3)).sqrt();
    let k2 = (i2 - i1) * (two_e * i3 - l2) / ((i3 - i2) * (l2 - two_e * i1));
    let complete_k = PI / (2.0 * agm(1.0, (1.0 - k2).sqrt()));
    2.0 * complete_k / s
}

#[test]
fn intermediate_axis_flips_a_thousand_times_at_the_elliptic_period() {
    let body = FreeBody {
        m: 1.0,
        inertia: [1.0, 2.0, 3.0],
        g: 0.0,
    };
    let omega = [0.02, 1.0, 0.03];
    let half = flip_period(body.inertia, omega);
    let (q0, v0) = spinning([1.0, 0.0, 0.0, 0.0], omega);
    let span = 1000.5 * half;
    let traj = Simulation::new(&body)
        .integrator(Dop853::tol(1e-12).max_steps(10_000_000))
        .run(q0, v0, 0.0..span)
        .unwrap();
    let flips = traj.crossings(|_, _, v| v[4]).unwrap();
    assert!(flips.len() >= 1000, "{} flips", flips.len());
    let mean = (flips[flips.len() - 1] - flips[0]) / (flips.len() - 1) as f64;
    let l0 = body.world_momentum(&q0, &v0);
    let momentum_drift = traj
        .positions()
        .iter()
        .zip(traj.velocities())
        .map(|(q, v)| (body.world_momentum(q, v) - l0).norm() / l0.norm())
        .fold(0.0, f64::max);
    eprintln!(
        "{} flips, period {mean} vs {half} (closed form), energy drift {:e}, momentum drift {momentum_drift:e}, unit error {:e}, {:?}",
        flips.len(),
        traj.integral_drift(),
        traj.max_unit_error(),
        traj.stats()
    );
    assert!((mean - half).abs() < 1e-8 * half, "{mean} vs {half}");
    assert!(traj.integral_drift() < 1e-9);
    assert!(momentum_drift < 1e-8, "{momentum_drift:e}");
    assert!(traj.max_unit_error() < 1e-15);
}

#[test]
fn axisymmetric_body_precesses_about_its_momentum_at_l_over_a() {
    let (a, c) = (2.0, 1.0);
    let body = FreeBody {
        m: 1.0,
        inertia: [a, a, c],
        g: 0.0,
    };
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let (q0, v0) = spinning([h, h * 0.6, 0.0, h * 0.8], [0.3, 0.1, 2.0]);
    let traj = Simulation::new(&body)
        .integrator(Dop853::tol(1e-12))
        .run(q0, v0, 0.0..20.0)
        .unwrap();
    let l0 = body.world_momentum(&q0, &v0);
    let axis0 = rotation(&q0, 3) * Vector3::z();
    let rate = l0.norm() / a;
    for k in 1..=40 {
        let t = 0.5 * k as f64;
        let (q, _) = traj.state_at(t).unwrap();
        let turned = Rotation3::from_axis_angle(&Unit::new_normalize(l0), rate * t) * axis0;
        let axis = rotation(&q, 3) * Vector3::z();
        assert!((axis - turned).norm() < 1e-9, "t = {t}: {axis} vs {turned}");
    }
}

#[test]
fn thrown_spinning_body_s_centre_of_mass_is_on_the_parabola() {
    let body = FreeBody {
        m: 2.0,
        inertia: [0.1, 0.3, 0.4],
        g: 9.81,
    };
    let mut q0 = SVector::from([0.0, 0.0, 1.0, 0.5, 0.5, 0.5, 0.5]);
    q0[3] = 0.5;
    let v0 = SVector::from([1.0, 0.5, 3.0, 0.3, 4.0, 0.2]);
    let t1 = 0.9;
    let traj = Simulation::new(&body)
        .integrator(Rk4::step(1e-3))
        .run(q0, v0, 0.0..t1)
        .unwrap();
    let (q, v) = traj.final_state();
    let exact = [t1, 0.5 * t1, 1.0 + 3.0 * t1 - 0.5 * 9.81 * t1 * t1];
    for k in 0..3 {
        assert!(
            (q[k] - exact[k]).abs() < 1e-12,
            "{k}: {} vs {}",
            q[k],
            exact[k]
        );
    }
    assert!((v[2] - (3.0 - 9.81 * t1)).abs() < 1e-12);
    assert!(traj.integral_drift() < 1e-10, "{:e}", traj.integral_drift());
}

/// Every integrator that takes orientations converges to the same motion at
/// its order: the errors of two step sizes (or tolerances) fall as hᵖ.
#[test]
fn every_integrator_steps_the_quaternion_at_its_order() {
    let body = FreeBody {
        m: 1.0,
        inertia: [1.0, 2.0, 3.0],
        g: 9.81,
    };
    let (q0, v0) = spinning([0.9, 0.1, -0.3, 0.3], [0.5, 2.0, -1.0]);
    let reference = Simulation::new(&body)
        .integrator(Dop853::tol(1e-14))
        .run(q0, v0, 0.0..2.0)
        .unwrap()
        .final_state();
    let error = |method: &dyn Fn() -> (SVector<f64, 7>, SVector<f64, 6>)| {
        let (q, v) = method();
        (q - reference.0).norm() + (v - reference.1).norm()
    };
    let fixed = |h: f64, verlet: bool| {
        let sim = Simulation::new(&body);
        let run = if verlet {
            sim.integrator(StormerVerlet::step(h)).run(q0, v0, 0.0..2.0)
        } else {
            sim.integrator(Rk4::step(h)).run(q0, v0, 0.0..2.0)
        };
        run.unwrap().final_state()
    };
    // Störmer–Verlet's first kick is implicit with orientations (the
    // gyroscopic acceleration depends on ω): order 2; RK4 keeps its 4.
    for (name, order, verlet) in [("RK4", 4.0, false), ("Störmer–Verlet", 2.0, true)] {
        let (coarse, fine) = (
            error(&|| fixed(0.02, verlet)),
            error(&|| fixed(0.01, verlet)),
        );
        let observed = (coarse / fine).log2();
        eprintln!("{name}: errors {coarse:e}, {fine:e}: order {observed:.2}");
        assert!((observed - order).abs() < 0.3, "{name}: order {observed}");
    }
    for tol in [1e-6, 1e-9] {
        let run = |i: &dyn Fn() -> Result<_, _>| {
            error(&|| {
                i().map(|t: lagrange_runtime::Trajectory<f64, 6, 7>| t.final_state())
                    .unwrap()
            })
        };
        let sim = Simulation::new(&body);
        let errs = [
            run(&|| {
                sim.clone()
                    .integrator(Dopri5::tol(tol))
                    .run(q0, v0, 0.0..2.0)
            }),
            run(&|| {
                sim.clone()
                    .integrator(Dop853::tol(tol))
                    .run(q0, v0, 0.0..2.0)
            }),
            run(&|| {
                sim.clone()
                    .integrator(Radau5::tol(tol))
                    .run(q0, v0, 0.0..2.0)
            }),
        ];
        eprintln!("tol {tol:e}: DOPRI5, DOP853, RADAU5 errors {errs:?}");
        for e in errs {
            assert!(e < 100.0 * tol, "{e:e} at tolerance {tol:e}");
        }
    }
}

#[test]
fn a_quaternion_off_the_unit_sphere_is_refused_naming_the_body() {
    let body = FreeBody {
        m: 1.0,
        inertia: [1.0, 2.0, 3.0],
        g: 0.0,
    };
    let (q0, v0) = spinning([1.0, 0.1, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let e = Simulation::new(&body).run(q0, v0, 0.0..1.0).unwrap_err();
    match &e.error {
        Error::NonUnitQuaternion {
            orientation, norm, ..
        } => {
            assert_eq!(orientation, "body");
            assert!((norm - 1.01_f64.sqrt()).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().contains("scalar first"), "{e}");
    let (nan, _) = spinning([f64::NAN, 0.0, 0.0, 0.0], [0.0; 3]);
    let e = Simulation::new(&body).run(nan, v0, 0.0..1.0).unwrap_err();
    assert!(
        matches!(
            e.error,
            Error::NonUnitQuaternion { .. } | Error::Settings(_)
        ),
        "{e}"
    );
    // An integrator used directly checks too, naming the quaternion's place.
    let e = Rk4::step(0.01)
        .integrate(&lagrange_runtime::Dynamics::new(&body), 0.0, 1.0, q0, v0)
        .unwrap_err();
    assert!(e.to_string().contains("q[3]"), "{e}");
    // Within the tolerance the quaternion is normalised, not refused.
    let (close, _) = spinning([1.0 + 1e-9, 0.0, 0.0, 0.0], [0.0; 3]);
    let traj = Simulation::new(&body).run(close, v0, 0.0..0.1).unwrap();
    assert_eq!(traj.positions()[0][3], 1.0);
}

/// Turning points of a heavy symmetric top released at tilt θ₀ with spin n and
/// no precession: u = cos θ moves between u₀ and the root of
/// β(1 − u²) = a²(u₀ − u) in [−1, 1], a = C n / A, β = 2 m g l / A.
#[test]
fn heavy_top_nutates_between_the_roots_of_the_cubic() {
    let top = HeavyTop {
        a: 0.8,
        c: 0.5,
        mgl: 2.0,
    };
    let (theta0, n) = (0.6_f64, 6.0);
    let q0 = SVector::from([(theta0 / 2.0).cos(), (theta0 / 2.0).sin(), 0.0, 0.0]);
    let v0 = SVector::from([0.0, 0.0, n]);
    let traj = Simulation::new(&top)
        .integrator(Dop853::tol(1e-12))
        .run(q0, v0, 0.0..10.0)
        .unwrap();
    let (a, beta, u0) = (top.c * n / top.a, 2.0 * top.mgl / top.a, theta0.cos());
    let disc = (a.powi(4) - 4.0 * beta * (a * a * u0 - beta)).sqrt();
    let u1 = (a * a - disc) / (2.0 * beta);
    // d(cos θ)/dt = R₃₁ ω_y − R₃₂ ω_x: zero at the turning points.
    let turning = traj
        .crossings(|_, q, v| {
            let r = rotation(q, 0);
            r[(2, 0)] * v[1] - r[(2, 1)] * v[0]
        })
        .unwrap();
    assert!(turning.len() >= 4, "{turning:?}");
    let cos_theta = |t: f64| rotation(&traj.state_at(t).unwrap().0, 0)[(2, 2)];
    let (lowest, highest) = turning
        .iter()
        .map(|&t| cos_theta(t))
        .fold((1.0_f64, -1.0_f64), |(lo, hi), u| (lo.min(u), hi.max(u)));
    eprintln!("cos θ between {lowest} and {highest}; the cubic: {u1} and {u0}");
    assert!((lowest - u1).abs() < 1e-9, "{lowest} vs {u1}");
    assert!((highest - u0).abs() < 1e-9, "{highest} vs {u0}");
    assert!(traj.integral_drift() < 1e-10);
}

/// A top swung over the top (through θ = 0, where euler_zxz's chart is
/// singular) keeps its energy and its momenta about the vertical and the
/// symmetry axis: no chart anywhere, so nothing stops there.
#[test]
fn heavy_top_swings_through_the_upright() {
    let top = HeavyTop {
        a: 0.8,
        c: 0.5,
        mgl: 2.0,
    };
    // Tilted about x, swinging back towards the upright fast enough to pass
    // it; the upright is on the motion when the momentum about the vertical
    // equals the axial one (p_φ = p_ψ = C n), which ω_y sets.
    let (theta0, n) = (0.5_f64, 3.0);
    let q0 = SVector::from([(theta0 / 2.0).cos(), (theta0 / 2.0).sin(), 0.0, 0.0]);
    let wy = top.c * n * (1.0 - theta0.cos()) / (top.a * theta0.sin());
    let v0 = SVector::from([-5.0, wy, n]);
    let traj = Simulation::new(&top)
        .integrator(Dop853::tol(1e-12))
        .run(q0, v0, 0.0..3.0)
        .unwrap();
    let turning = traj
        .crossings(|_, q, v| {
            let r = rotation(q, 0);
            r[(2, 0)] * v[1] - r[(2, 1)] * v[0]
        })
        .unwrap();
    let highest = turning
        .iter()
        .map(|&t| rotation(&traj.state_at(t).unwrap().0, 0)[(2, 2)])
        .fold(-1.0, f64::max);
    let vertical = |q: &SVector<f64, 4>, v: &SVector<f64, 3>| {
        let r = rotation(q, 0);
        (r * Vector3::new(top.a * v[0], top.a * v[1], top.c * v[2]))[2]
    };
    let p0 = vertical(&q0, &v0);
    let drift = traj
        .positions()
        .iter()
        .zip(traj.velocities())
        .map(|(q, v)| (vertical(q, v) - p0).abs().max((v[2] - n).abs()))
        .fold(0.0, f64::max);
    eprintln!("highest cos θ {highest}, momentum drift {drift:e}");
    assert!(highest > 1.0 - 1e-9, "did not pass the upright: {highest}");
    assert!(drift < 1e-9 && traj.integral_drift() < 1e-10);
}

/// Gauss takes orientations through Hamilton's form written by hand
/// (`kinetic_gradient`): the free body's world angular momentum to
/// round-off, its centre on the parabola; a system without that form is
/// refused by name.
#[test]
fn gauss_steps_a_hand_written_free_body_on_the_group() {
    let body = FreeBody {
        m: 2.0,
        inertia: [1.0, 2.0, 3.0],
        g: 9.81,
    };
    let (mut q0, v0) = spinning([1.0, 0.0, 0.0, 0.0], [0.1, 1.0, 0.1]);
    q0[0] = 0.5;
    let traj = lagrange_runtime::Gauss::step(0.05)
        .integrate(&Simulation::new(&body).dynamics(), 0.0, 20.0, q0, v0)
        .unwrap();
    let l0 = body.world_momentum(&q0, &v0);
    let drift = (traj.positions().iter().zip(traj.velocities()))
        .map(|(q, v)| (body.world_momentum(q, v) - l0).norm() / l0.norm())
        .fold(0.0, f64::max);
    let (q, _) = traj.final_state();
    let fall = (q[2] + 0.5 * 9.81 * 400.0).abs();
    eprintln!(
        "momentum drift {drift:e}, unit {:e}, parabola {fall:e}",
        traj.max_unit_error()
    );
    assert!(drift < 1e-13 && traj.max_unit_error() < 1e-14 && fall < 1e-9);
    assert!((q[0] - 0.5).abs() < 1e-12);
    let top = HeavyTop {
        a: 1.0,
        c: 0.5,
        mgl: 1.0,
    };
    let e = lagrange_runtime::Gauss::step(0.01)
        .integrate(
            &Simulation::new(&top).dynamics(),
            0.0,
            1.0,
            SVector::from([1.0, 0.0, 0.0, 0.0]),
            SVector::from([0.1, 0.0, 5.0]),
        )
        .unwrap_err();
    assert!(e.to_string().contains("kinetic_gradient"), "{e}");
}

/// A spinning brick dropped on a floor: an event at its centre's height
/// h = 0.5 reverses the vertical velocity. The event layer runs on q with a
/// quaternion: the impact times are the free fall's, the quaternion stays
/// unit across the restarts.
#[test]
fn events_locate_impacts_of_a_tumbling_body() {
    use lagrange_runtime::{Dynamics, Event, Events};
    let body = FreeBody {
        m: 1.0,
        inertia: [1.0, 2.0, 3.0],
        g: 9.81,
    };
    let (mut q0, v0) = spinning([1.0, 0.0, 0.0, 0.0], [0.3, 2.0, -1.0]);
    q0[2] = 1.0;
    let floor = Event::new(|_, q: &SVector<f64, 7>, _: &SVector<f64, 6>| q[2] - 0.5)
        .falling()
        .action(|_, _, v: &mut SVector<f64, 6>| v[2] = -v[2]);
    let run = Events::new()
        .with(floor)
        .integrate(&Dop853::tol(1e-12), &Dynamics::new(&body), 0.0, 2.0, q0, v0)
        .unwrap();
    // The builder runs the same events the same way.
    let floor = Event::new(|_, q: &SVector<f64, 7>, _: &SVector<f64, 6>| q[2] - 0.5)
        .falling()
        .action(|_, _, v: &mut SVector<f64, 6>| v[2] = -v[2]);
    let built = Simulation::new(&body)
        .integrator(Dop853::tol(1e-12))
        .event(floor)
        .run(q0, v0, 0.0..2.0)
        .unwrap();
    assert_eq!(built.times(0), run.times(0));
    // Free fall from 1 to 0.5 takes √(2·0.5/g); each bounce returns to 1.
    let fall = (1.0 / 9.81_f64).sqrt();
    let times = run.times(0);
    assert!(times.len() >= 3, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        let expected = fall * (2 * k + 1) as f64;
        assert!((t - expected).abs() < 1e-9, "impact {k}: {t} vs {expected}");
    }
    assert!(run.trajectory.max_unit_error() < 1e-15);
}

/// The CSV of a run with an orientation: q's quaternion by its components'
/// names, ω by its own, and the unit-norm error beside the residuals.
#[test]
fn a_run_with_an_orientation_writes_its_columns_by_name() {
    let body = FreeBody {
        m: 1.0,
        inertia: [1.0, 2.0, 3.0],
        g: 0.0,
    };
    let (q0, v0) = spinning([1.0, 0.0, 0.0, 0.0], [0.3, 2.0, -1.0]);
    let traj = Simulation::new(&body).run(q0, v0, 0.0..0.1).unwrap();
    let mut out = Vec::new();
    traj.table(&body).write(&mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let header = text.lines().next().unwrap();
    assert_eq!(
        header,
        "t,x,y,z,body.w,body.x,body.y,body.z,dot_x,dot_y,dot_z,body.wx,body.wy,body.wz,\
         kinetic,potential,integral,residual_position,residual_velocity,unit_error"
    );
    assert_eq!(text.lines().count(), traj.len() + 1);
}

/// Störmer–Verlet's implicit first kick is the implicit midpoint rule on
/// Euler's equations: a tumbling body's kinetic energy is kept to round-off
/// over many flips at a coarse step (the explicit kick's grew until it
/// overflowed).
#[test]
fn stormer_verlet_keeps_a_tumbling_body_s_energy() {
    let body = FreeBody {
        m: 1.0,
        inertia: [1.0, 2.0, 3.0],
        g: 0.0,
    };
    let (q0, v0) = spinning([1.0, 0.0, 0.0, 0.0], [0.3, 1.0, 0.3]);
    let traj = Simulation::new(&body)
        .integrator(StormerVerlet::step(0.2))
        .run(q0, v0, 0.0..1500.0)
        .unwrap();
    let drift = traj.integral_drift();
    eprintln!("{} steps: energy drift {drift:e}", traj.len());
    assert!(drift < 1e-12, "{drift:e}");
}

/// A step far too large for a tumbling body: Gauss and Störmer–Verlet say
/// their implicit iteration did not converge, with the step and the advice
/// to take a smaller one, at h = 5 as at h = 2 (at h = 5 an iterate left
/// the region where the dynamics are finite, once reported as a non-finite
/// state at t = 0).
#[test]
fn a_step_far_too_large_for_a_tumbling_body_is_a_convergence_failure() {
    let body = FreeBody {
        m: 2.0,
        inertia: [1.0, 2.0, 3.0],
        g: 0.0,
    };
    let (q0, v0) = spinning([1.0, 0.0, 0.0, 0.0], [0.1, 6.0, 0.1]);
    let dynamics = Simulation::new(&body).dynamics();
    for h in [2.0, 5.0, 50.0] {
        let errors = [
            lagrange_runtime::Gauss::step(h).integrate(&dynamics, 0.0, 100.0, q0, v0),
            lagrange_runtime::Gauss::midpoint(h).integrate(&dynamics, 0.0, 100.0, q0, v0),
            lagrange_runtime::StormerVerlet::step(h).integrate(&dynamics, 0.0, 100.0, q0, v0),
        ]
        .map(|r| r.unwrap_err());
        for e in errors {
            assert!(
                matches!(e.error, Error::NewtonFailure { h: step, .. } if step == h),
                "h = {h}: {e}"
            );
            assert!(e.to_string().contains("try a smaller step"), "{e}");
        }
    }
}

/// Evaluations at a configuration take it as a run takes its start: a
/// quaternion within the unit tolerance (1e-6) normalised, one beyond it
/// refused by name, a NaN refused; the raw trait methods, which check
/// nothing, answer for the scaled quaternion.
#[test]
fn evaluations_check_the_configuration_as_a_run_does() {
    use lagrange_runtime::{Configuration, Lagrangian};
    let top = HeavyTop {
        a: 0.8,
        c: 0.5,
        mgl: 2.0,
    };
    let u = SVector::from([0.9, 0.3, -0.2, 0.1]).normalize();
    let (v, acc) = (
        SVector::from([0.3, -1.0, 6.0]),
        SVector::from([1.0, 2.0, 3.0]),
    );
    let at = |q| Configuration::new(&top, q, 0.0);
    let unit = at(u).unwrap();
    // The raw method at 2u answers for another rotation (V scales by 4).
    let raw = top.potential_energy(&(u * 2.0), 0.0) - top.potential_energy(&u, 0.0);
    assert!(raw.abs() > 0.1, "{raw}");
    for scale in [2.0, 1.0 + 2e-6, 1.0 - 2e-6] {
        let e = at(u * scale).unwrap_err();
        assert!(
            matches!(e, Error::NonUnitQuaternion { ref orientation, norm, tolerance }
                if orientation == "top" && (norm - scale).abs() < 1e-12 && tolerance == 1e-6),
            "{e}"
        );
    }
    for scale in [1.0 + 9e-7, 1.0 - 9e-7] {
        let near = at(u * scale).unwrap();
        assert!((near.q() - u).amax() < 1e-15);
        assert!((near.potential_energy() - unit.potential_energy()).abs() < 1e-15);
        let tau = near.inverse_dynamics(&v, &acc).unwrap();
        assert!((tau - unit.inverse_dynamics(&v, &acc).unwrap()).amax() < 1e-14);
    }
    // A run refuses and normalises on the same side of the tolerance.
    let sim = Simulation::new(&top).integrator(Dopri5::tol(1e-8));
    assert!(sim.run(u * (1.0 + 9e-7), v, 0.0..0.1).is_ok());
    let e = sim.run(u * (1.0 + 2e-6), v, 0.0..0.1).unwrap_err();
    assert!(matches!(e.error, Error::NonUnitQuaternion { .. }), "{e}");
    // NaN: a typed error, not a NaN answer.
    let mut nan = u;
    nan[2] = f64::NAN;
    assert!(matches!(at(nan).unwrap_err(), Error::NonFiniteState { .. }));
    let mut bad_v = v;
    bad_v[0] = f64::NAN;
    assert!(matches!(
        unit.kinetic_energy(&bad_v),
        Err(Error::NonFiniteState { .. })
    ));
    assert!(matches!(
        unit.inverse_dynamics(&v, &bad_v),
        Err(Error::NonFiniteState { .. })
    ));
    assert!(matches!(
        unit.momentum(&bad_v),
        Err(Error::NonFiniteState { .. })
    ));
    assert_eq!(unit.mass_matrix(), top.mass_matrix(&u, 0.0));
}
