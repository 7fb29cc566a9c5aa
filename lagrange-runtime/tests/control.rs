//! Controlled simulation: open-loop signals and tables, continuous and sampled
//! feedback, constrained and reduced forms, typed errors. Every system here is
//! hand-written (`Lagrangian` + `Driven`), and every check is against a closed
//! form or an independent formulation.

mod common;
use common::Oscillator;
use common::constrained::CartesianPendulum;
use common::driven::{Arm, Skate};
use lagrange_runtime::{Dopri5, Drift, Error, Event, InputTable, Rk4, Simulation};
use nalgebra::{Vector1, Vector2, Vector3};

// ---------------------------------------------------------------------------
// Helpers

/// max over the stored points of |x − exact(t)| and |v − exact'(t)|.
fn max_error(tr: &lagrange_runtime::Trajectory<f64, 1>, exact: impl Fn(f64) -> (f64, f64)) -> f64 {
    let mut err: f64 = 0.0;
    for ((&t, q), v) in tr.times().iter().zip(tr.positions()).zip(tr.velocities()) {
        let (x, xd) = exact(t);
        err = err.max((q[0] - x).abs()).max((v[0] - xd).abs());
    }
    err
}

/// m ẍ + k x = F (constant) from (x0, v0) at t0, evaluated at t.
fn spring_constant_force(s: &Oscillator, f: f64, t0: f64, x0: f64, v0: f64, t: f64) -> (f64, f64) {
    let w = (s.k / s.m).sqrt();
    let (sn, cs) = (w * (t - t0)).sin_cos();
    let xs = f / s.k;
    (
        xs + (x0 - xs) * cs + v0 / w * sn,
        -(x0 - xs) * w * sn + v0 * cs,
    )
}

const SPRING: Oscillator = Oscillator { m: 2.0, k: 18.0 }; // ω = 3

// ---------------------------------------------------------------------------
// Open loop

#[test]
fn open_loop_constant_and_sine_match_closed_forms() {
    let s = SPRING;
    let (x0, v0, f) = (0.3, -0.2, 1.5);
    let run = Simulation::new(&s)
        .integrator(Dopri5::tol(1e-12))
        .open_loop(|_| [f])
        .run([x0], [v0], 0.0..10.0)
        .unwrap();
    let err = max_error(run.trajectory(), |t| {
        spring_constant_force(&s, f, 0.0, x0, v0, t)
    });
    println!("constant force: max error {err:.2e}");
    assert!(err < 1e-9, "{err:e}");
    assert!(run.inputs().iter().all(|u| u[0] == f));
    assert_eq!(run.inputs().len(), run.trajectory().len());

    // u = sin Ωt: x = A cos ωt + B sin ωt + a sin Ωt, a = 1/(m(ω² − Ω²)).
    let big_w = 1.3;
    let w = 3.0;
    let a = 1.0 / (s.m * (w * w - big_w * big_w));
    let (ca, cb) = (x0, (v0 - a * big_w) / w);
    let exact = |t: f64| {
        (
            ca * (w * t).cos() + cb * (w * t).sin() + a * (big_w * t).sin(),
            -ca * w * (w * t).sin() + cb * w * (w * t).cos() + a * big_w * (big_w * t).cos(),
        )
    };
    let run = Simulation::new(&s)
        .integrator(Dopri5::tol(1e-12))
        .open_loop(|t: f64| [(big_w * t).sin()])
        .run([x0], [v0], 0.0..10.0)
        .unwrap();
    let err = max_error(run.trajectory(), exact);
    println!("sine force: max error {err:.2e}");
    assert!(err < 1e-9, "{err:e}");
    for (t, u) in run.trajectory().times().iter().zip(run.inputs()) {
        assert_eq!(u[0], (big_w * t).sin());
    }

    // The same signal from a linear table with step dt: the interpolation error
    // is at most dt² Ω²/8, and the response error at most that times
    // ∫|sin ω(t−s)|/(mω) ds ≤ T/(mω); it must also fall as dt².
    let table_error = |dt: f64| {
        let n = (10.0 / dt).round() as usize;
        let times: Vec<f64> = (0..=n).map(|i| i as f64 * dt).collect();
        let values: Vec<[f64; 1]> = times.iter().map(|&t| [(big_w * t).sin()]).collect();
        let table = InputTable::linear(times, values).unwrap();
        let run = Simulation::new(&s)
            .integrator(Dopri5::tol(1e-12))
            .control(table)
            .run([x0], [v0], 0.0..10.0)
            .unwrap();
        // A restart at every breakpoint: at least n steps.
        assert!(run.trajectory().stats().accepted >= n);
        max_error(run.trajectory(), exact)
    };
    let (e1, e2) = (table_error(0.02), table_error(0.01));
    let bound = 0.02f64.powi(2) * big_w * big_w / 8.0 * 10.0 / (s.m * w);
    println!("linear table: error {e1:.2e} (dt 0.02), {e2:.2e} (dt 0.01); bound {bound:.2e}");
    assert!(e1 < bound, "{e1:e} vs {bound:e}");
    assert!(e1 / e2 > 3.5 && e1 / e2 < 4.5, "ratio {}", e1 / e2);
}

#[test]
fn hold_table_is_exact_for_piecewise_constant_input() {
    let s = SPRING;
    let times = [0.0, 0.7, 1.9, 3.1];
    let forces = [1.0, -0.5, 2.0, 0.0];
    let table = InputTable::hold(times, forces.map(|f| [f])).unwrap();
    let (x0, v0) = (0.1, 0.0);
    // Propagate the closed form interval by interval.
    let exact = |t: f64| {
        let (mut x, mut v, mut ta) = (x0, v0, 0.0);
        for (i, &f) in forces.iter().enumerate() {
            let tb = times.get(i + 1).copied().unwrap_or(f64::INFINITY);
            if t <= tb {
                return spring_constant_force(&s, f, ta, x, v, t);
            }
            (x, v) = spring_constant_force(&s, f, ta, x, v, tb);
            ta = tb;
        }
        unreachable!()
    };
    {
        let run = Simulation::new(&s)
            .integrator(Dopri5::tol(1e-12))
            .control(&table)
            .run([x0], [v0], 0.0..5.0)
            .unwrap();
        let err = max_error(run.trajectory(), exact);
        println!("hold table: max error {err:.2e}");
        assert!(err < 1e-9, "{err:e}");
        // Every breakpoint is a stored point; the recorded input there is the
        // new value, and the value before it on the step that ends there.
        let tr = run.trajectory();
        for (i, &tb) in times.iter().enumerate() {
            let k = tr
                .times()
                .iter()
                .position(|&t| t == tb)
                .expect("breakpoint stored");
            assert_eq!(run.inputs()[k][0], forces[i]);
            if k > 0 {
                assert_eq!(run.inputs()[k - 1][0], forces[i - 1]);
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Feedback

#[test]
fn continuous_pd_is_critically_damped() {
    let s = Oscillator { m: 1.0, k: 0.0 };
    let w = 2.5;
    let (x0, v0) = (1.0, 0.5);
    let run = Simulation::new(&s)
        .integrator(Dopri5::tol(1e-12))
        .feedback(|_, q, v| [-w * w * q[0] - 2.0 * w * v[0]])
        .run([x0], [v0], 0.0..6.0)
        .unwrap();
    let c = v0 + w * x0;
    let exact = |t: f64| {
        let e = (-w * t).exp();
        ((x0 + c * t) * e, (v0 - w * c * t) * e)
    };
    let err = max_error(run.trajectory(), exact);
    println!(
        "PD: max error {err:.2e} over {} points",
        run.trajectory().len()
    );
    assert!(err < 1e-10, "{err:e}");
    let tr = run.trajectory();
    for k in 0..tr.len() {
        let (q, v) = (tr.positions()[k], tr.velocities()[k]);
        assert_eq!(run.inputs()[k][0], -w * w * q[0] - 2.0 * w * v[0]);
    }
}

#[test]
fn sampled_feedback_matches_discrete_time_propagation() {
    let s = Oscillator { m: 1.0, k: 0.0 };
    let h = 0.01;
    let gains = [40.0, 9.0];
    let (x0, v0) = (1.0, -0.5);
    let samples = 200;
    // x_{k+1} = A_d x_k + B_d u_k, u_k = −K x_k.
    let mut xs = vec![(x0, v0)];
    let mut us = Vec::new();
    for k in 0..=samples {
        let (x, v) = xs[k];
        let u = -gains[0] * x - gains[1] * v;
        us.push(u);
        xs.push((x + h * v + 0.5 * h * h * u, v + h * u));
    }
    let t_end = samples as f64 * h;
    for (name, run) in [
        (
            "RK4 h/4",
            Simulation::new(&s)
                .integrator(Rk4::step(h / 4.0))
                .sampled(h, |_, q, v| [-gains[0] * q[0] - gains[1] * v[0]])
                .run([x0], [v0], 0.0..t_end)
                .unwrap(),
        ),
        (
            "DOPRI5",
            Simulation::new(&s)
                .integrator(Dopri5::tol(1e-10))
                .sampled(h, |_, q, v| [-gains[0] * q[0] - gains[1] * v[0]])
                .run([x0], [v0], 0.0..t_end)
                .unwrap(),
        ),
    ] {
        let tr = run.trajectory();
        let (mut err, mut err_u) = (0.0f64, 0.0f64);
        let mut found = 0;
        for (k, &t) in tr.times().iter().enumerate() {
            let j = (t / h).round() as usize;
            let on_sample = (t - j as f64 * h).abs() < 1e-12;
            if on_sample {
                found += 1;
                let (x, v) = xs[j];
                err = err
                    .max((tr.positions()[k][0] - x).abs())
                    .max((tr.velocities()[k][0] - v).abs());
                err_u = err_u.max((run.inputs()[k][0] - us[j]).abs());
            } else {
                // Between samples: the value held since the last one.
                let j = (t / h).floor() as usize;
                assert_eq!(run.inputs()[k][0], run.inputs()[k - 1][0]);
                err_u = err_u.max((run.inputs()[k][0] - us[j]).abs());
            }
        }
        println!(
            "sampled ({name}): {} points, {found} sample instants, state error {err:.2e}, input error {err_u:.2e}, {} evaluations",
            tr.len(),
            tr.stats().evaluations
        );
        assert_eq!(found, samples + 1);
        assert!(err < 1e-10 && err_u < 1e-10, "{err:e} {err_u:e}");
    }

    // The controller is called once per sample instant, t0 and the end included,
    // so it may keep state.
    let mut calls = Vec::new();
    Simulation::new(&s)
        .integrator(Rk4::step(h / 3.0))
        .sampled(h, |t, q: &Vector1<f64>, _: &Vector1<f64>| {
            calls.push(t);
            [-q[0]]
        })
        .run([x0], [v0], 0.0..0.1)
        .unwrap();
    assert_eq!(calls.len(), 11);
    for (k, t) in calls.iter().enumerate() {
        assert!((t - k as f64 * h).abs() < 1e-15, "{t}");
    }
}

// ---------------------------------------------------------------------------
// Constrained and reduced forms

#[test]
fn pendulum_cartesian_with_push_matches_angle_model() {
    let (m, l, g) = (1.5, 1.2, 9.81);
    let (kp, kd) = (6.0, 2.0);
    let bob = CartesianPendulum::<1> { m, l, g };
    let arm = Arm { m, l, g };
    let theta0: f64 = 0.8;
    let q0 = Vector2::new(l * theta0.sin(), -l * theta0.cos());
    let t_end = 5.0;
    // u = −kp x − kd ẋ, the same law in both coordinates.
    let cart = Simulation::new(&bob)
        .integrator(Dopri5::tol(1e-11))
        .drift(Drift::projection())
        .feedback(|_, q, v| [-kp * q[0] - kd * v[0]])
        .run_constrained(q0, Vector2::zeros(), 0.0..t_end)
        .unwrap();
    let angle = Simulation::new(&arm)
        .integrator(Dopri5::tol(1e-11))
        .feedback(|_, q, v| {
            let (x, xd) = (l * q[0].sin(), l * q[0].cos() * v[0]);
            [-kp * x - kd * xd]
        })
        .run([theta0], [0.0], 0.0..t_end)
        .unwrap();
    let [phi, vel] = cart.trajectory().max_residuals();
    println!("pendulum: residuals |Phi| {phi:.2e}, |G v| {vel:.2e}");
    assert!(phi < 1e-12 && vel < 1e-12);
    let mut err: f64 = 0.0;
    for t in [1.0, 2.5, t_end] {
        let (qc, vc) = cart.trajectory().state_at(t).unwrap();
        let (qa, va) = angle.trajectory().state_at(t).unwrap();
        let (th, om) = (qa[0], va[0]);
        let expect_q = Vector2::new(l * th.sin(), -l * th.cos());
        let expect_v = Vector2::new(l * th.cos() * om, l * th.sin() * om);
        err = err.max((qc - expect_q).amax()).max((vc - expect_v).amax());
    }
    println!("pendulum: Cartesian vs angle model {err:.2e}");
    assert!(err < 1e-7, "{err:e}");
    // The push really acts: without it the pendulum ends elsewhere.
    let free = Simulation::new(&arm)
        .integrator(Dopri5::tol(1e-11))
        .run([theta0], [0.0], 0.0..t_end)
        .unwrap();
    assert!((free.final_state().0[0] - angle.trajectory().final_state().0[0]).abs() > 1e-2);
}

#[test]
fn reduced_skate_matches_multiplier_form() {
    let skate = Skate { m: 2.0, j: 0.5 };
    let phi0: f64 = 0.3;
    let q0 = Vector3::new(0.0, 0.0, phi0);
    let v0 = Vector3::new(0.5 * phi0.cos(), 0.5 * phi0.sin(), 0.0);
    // Speed to 1 m/s, heading to 1 rad.
    let law = |_: f64, q: &Vector3<f64>, v: &Vector3<f64>| {
        let speed = v[0] * q[2].cos() + v[1] * q[2].sin();
        [-2.0 * (speed - 1.0), -4.0 * (q[2] - 1.0) - 3.0 * v[2]]
    };
    let t_end = 4.0;
    let reduced = Simulation::new(&skate)
        .integrator(Dopri5::tol(1e-11))
        .feedback(law)
        .run_reduced(q0, v0, 0.0..t_end)
        .unwrap();
    let multipliers = Simulation::new(&skate)
        .integrator(Dopri5::tol(1e-11))
        .drift(Drift::projection())
        .feedback(law)
        .run_constrained(q0, v0, 0.0..t_end)
        .unwrap();
    let (qr, vr) = reduced.trajectory().final_state();
    let (qm, vm) = multipliers.trajectory().final_state();
    let err = (qr - qm).amax().max((vr - vm).amax());
    println!("skate: reduced vs multipliers {err:.2e}; final q {qr:?}");
    assert!(err < 1e-8, "{err:e}");
    // The heading loop is linear: j φ̈ = −4(φ − 1) − 3 φ̇, roots −2 and −4.
    let e0 = phi0 - 1.0;
    let phi = 1.0 + e0 * (2.0 * (-2.0 * t_end).exp() - (-4.0 * t_end).exp());
    assert!((qr[2] - phi).abs() < 1e-9, "{} vs {phi}", qr[2]);
    // Speed: m u̇ = −2(u − 1).
    let speed = 1.0 - 0.5 * (-t_end).exp();
    assert!((vr[0] * qr[2].cos() + vr[1] * qr[2].sin() - speed).abs() < 1e-9);
    assert_eq!(reduced.input_names(), &["thrust", "torque"]);

    // A sampled controller drives the reduced form too, and the two forms agree.
    let sampled = |run_reduced: bool| {
        let sim = Simulation::new(&skate)
            .integrator(Dopri5::tol(1e-11))
            .drift(Drift::projection())
            .sampled(0.05, law);
        if run_reduced {
            sim.run_reduced(q0, v0, 0.0..1.0).unwrap()
        } else {
            sim.run_constrained(q0, v0, 0.0..1.0).unwrap()
        }
    };
    let (a, b) = (sampled(true), sampled(false));
    let err = (a.trajectory().final_state().0 - b.trajectory().final_state().0).amax();
    assert!(err < 1e-9, "{err:e}");
    assert!(a.trajectory().max_residuals()[1] < 1e-12);
}

// ---------------------------------------------------------------------------
// Events, output, checks

#[test]
fn events_work_under_control() {
    // Feedback u = −w² x on a double integrator: x = cos wt, first zero at π/(2w).
    let s = Oscillator { m: 1.0, k: 0.0 };
    let w = 2.0;
    let run = Simulation::new(&s)
        .integrator(Dopri5::tol(1e-12))
        .feedback(|_, q, _| [-w * w * q[0]])
        .event(Event::new(|_, q: &Vector1<f64>, _| q[0]).terminal())
        .run([1.0], [0.0], 0.0..10.0)
        .unwrap();
    let t_end = *run.trajectory().times().last().unwrap();
    assert_eq!(run.terminated_by(), Some(0));
    assert!(
        (t_end - std::f64::consts::PI / (2.0 * w)).abs() < 1e-10,
        "{t_end}"
    );
    assert_eq!(run.inputs().len(), run.trajectory().len());

    // Sampled, with a bounce (velocity reversal) at x = 0: events restart
    // inside the pieces and the run continues.
    let run = Simulation::new(&s)
        .integrator(Dopri5::tol(1e-10))
        .sampled(0.1, |_, _, _| [-1.0])
        .event(
            Event::new(|_, q: &Vector1<f64>, _| q[0])
                .falling()
                .action(|_, _, v| *v *= -1.0),
        )
        .run([0.5], [0.0], 0.0..4.0)
        .unwrap();
    // Free fall from 0.5 under unit gravity: impacts every 2 s starting at 1 s.
    let times: Vec<f64> = run.occurrences().iter().map(|o| o.t).collect();
    assert_eq!(times.len(), 2, "{times:?}");
    assert!(
        (times[0] - 1.0).abs() < 1e-9 && (times[1] - 3.0).abs() < 1e-9,
        "{times:?}"
    );
    assert_eq!(run.inputs().len(), run.trajectory().len());
}

#[test]
fn csv_names_every_column() {
    let skate = Skate { m: 1.0, j: 1.0 };
    let run = Simulation::new(&skate)
        .integrator(Rk4::step(0.25))
        .open_loop(|_| [1.0, 0.5])
        .run_reduced(Vector3::zeros(), Vector3::zeros(), 0.0..1.0)
        .unwrap();
    let mut buf = Vec::new();
    run.write_csv(&mut buf).unwrap();
    let text = String::from_utf8(buf).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some(
            "t,x,y,phi,dot_x,dot_y,dot_phi,thrust,torque,integral,residual_position,residual_velocity"
        )
    );
    assert_eq!(lines.next(), Some("0,0,0,0,0,0,0,1,0.5,0,0,0"));
    assert_eq!(lines.count(), 4);
    // With the system: its energies too.
    let mut buf = Vec::new();
    run.table(&skate).unwrap().write(&mut buf).unwrap();
    let text = String::from_utf8(buf).unwrap();
    assert!(
        text.starts_with("t,x,y,phi,dot_x,dot_y,dot_phi,thrust,torque,kinetic,potential,integral,"),
        "{text}"
    );
}

#[test]
fn checks_of_the_plain_simulation_still_apply() {
    let bob = CartesianPendulum::<1> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let e = Simulation::new(&bob)
        .feedback(|_, _, _| [0.0])
        .run_constrained([0.7, -0.7], [0.0, 0.0], 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(e.error, Error::InconsistentInitialConditions { .. }),
        "{e}"
    );
    let e = Simulation::new(&SPRING)
        .feedback(|_, _, _| [0.0])
        .run([f64::NAN], [0.0], 0.0..1.0)
        .unwrap_err();
    assert!(matches!(e.error, Error::Settings(_)), "{e}");
    let e = Simulation::new(&SPRING)
        .singular_tolerance(-1.0)
        .feedback(|_, _, _| [0.0])
        .run([0.0], [0.0], 0.0..1.0)
        .unwrap_err();
    assert!(matches!(e.error, Error::Settings(_)), "{e}");
}

// ---------------------------------------------------------------------------
// Typed errors

#[test]
fn non_finite_inputs_are_typed_errors() {
    let s = SPRING;
    // Continuous: NaN after t = 0.5; RK4 with h = 0.1 first meets it at the
    // stage t = 0.55.
    let e = Simulation::new(&s)
        .integrator(Rk4::step(0.1))
        .feedback(|t, _, _| [if t > 0.5 { f64::NAN } else { 0.0 }])
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    match &e.error {
        Error::NonFiniteInput {
            t, input, value, q, ..
        } => {
            assert_eq!(*input, "force");
            assert!((t - 0.55).abs() < 1e-12, "{t}");
            assert!(value.is_nan() && q.len() == 1);
        }
        other => panic!("{other}"),
    }
    assert!(
        e.to_string().contains("`force`") && e.to_string().contains("t = 0.55"),
        "{e}"
    );

    // Sampled: the sample at t = 0.03 is infinite.
    let e = Simulation::new(&s)
        .sampled(0.01, |t, _, _| {
            [if t > 0.025 { f64::INFINITY } else { 0.0 }]
        })
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    match e.error {
        Error::NonFiniteInput {
            t, input, value, ..
        } => {
            assert_eq!(input, "force");
            assert!((t - 0.03).abs() < 1e-12 && value == f64::INFINITY, "{t}");
        }
        other => panic!("{other}"),
    }

    // Open loop, in the multiplier form, naming the second input.
    let skate = Skate { m: 1.0, j: 1.0 };
    let e = Simulation::new(&skate)
        .open_loop(|t: f64| [0.0, if t >= 0.5 { f64::NAN } else { 1.0 }])
        .run_constrained(Vector3::zeros(), Vector3::zeros(), 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(e.error, Error::NonFiniteInput { input: "torque", t, .. } if t >= 0.5),
        "{e}"
    );
}

#[test]
fn bad_periods_are_invalid_settings() {
    for h in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let e = Simulation::new(&SPRING)
            .sampled(h, |_, _, _| [0.0])
            .run([1.0], [0.0], 0.0..1.0)
            .unwrap_err();
        assert!(
            matches!(&e.error, Error::Settings(m) if m.to_string().contains("period")),
            "{h}: {e}"
        );
    }
}

#[test]
fn bad_tables_are_invalid_settings() {
    let cases: Vec<(&str, Result<InputTable<f64, 1>, Error>)> = vec![
        (
            "no breakpoints",
            InputTable::linear([], Vec::<[f64; 1]>::new()),
        ),
        (
            "2 times but 1 values",
            InputTable::linear([0.0, 1.0], [[0.0]]),
        ),
        (
            "strictly increasing",
            InputTable::hold([0.0, 2.0, 1.0], [[0.0]; 3]),
        ),
        (
            "strictly increasing",
            InputTable::linear([0.0, 1.0, 1.0], [[0.0]; 3]),
        ),
        (
            "time #1 is NaN",
            InputTable::linear([0.0, f64::NAN], [[0.0]; 2]),
        ),
        ("time #0 is inf", InputTable::hold([f64::INFINITY], [[0.0]])),
        (
            "value #1",
            InputTable::linear([0.0, 1.0], [[0.0], [f64::NAN]]),
        ),
    ];
    for (needle, table) in cases {
        match table {
            Err(Error::Settings(m)) => {
                assert!(m.to_string().contains(needle), "{m} lacks {needle}")
            }
            other => panic!("{needle}: {other:?}"),
        }
    }
    // Outside its range a table holds its end values.
    let t = InputTable::linear([1.0, 2.0], [[3.0], [5.0]]).unwrap();
    assert_eq!(
        (t.value_at(0.0)[0], t.value_at(1.5)[0], t.value_at(9.0)[0]),
        (3.0, 4.0, 5.0)
    );
}
