//! Typed errors from the user-facing API, and CSV output.

mod common;

use common::{Pendulum, SphericalPendulum, sv};
use lagrange_runtime::Failure;
use lagrange_runtime::{Dopri5, Error, Lagrangian, Rk4, Simulation, accelerations};

#[test]
fn nan_parameters_give_non_finite_state() {
    let sys = Pendulum {
        m: f64::NAN,
        l: 1.0,
        g: 9.81,
    };
    for result in [
        Simulation::new(&sys).run(sv([0.1]), sv([0.0]), 0.0..1.0),
        Simulation::new(&sys)
            .integrator(Rk4::step(0.1))
            .run(sv([0.1]), sv([0.0]), 0.0..1.0),
    ] {
        match result {
            Err(Failure {
                error: Error::NonFiniteState { t, q, v },
                ..
            }) => {
                assert_eq!((t, q, v), (0.0, vec![0.1], vec![0.0]))
            }
            other => panic!("expected NonFiniteState, got {other:?}"),
        }
    }
    let e = accelerations(&sys, &sv([0.1]), &sv([0.0]), 0.0).unwrap_err();
    assert!(e.to_string().contains("q = [0.1]"), "{e}");
}

#[test]
fn invalid_settings() {
    let sys = Pendulum::standard();
    let sim = |m: Dopri5, span: std::ops::Range<f64>| {
        Simulation::new(&sys)
            .integrator(m)
            .run(sv([0.1]), sv([0.0]), span)
    };
    let cases = [
        sim(Dopri5::tol(1e-8).rtol(0.0), 0.0..1.0),
        sim(Dopri5::tol(1e-8), 1.0..1.0),
        sim(Dopri5::tol(1e-8), 1.0..0.0),
        Simulation::new(&sys).run(sv([f64::NAN]), sv([0.0]), 0.0..1.0),
        Simulation::new(&sys)
            .singular_tolerance(-1.0)
            .run(sv([0.1]), sv([0.0]), 0.0..1.0),
    ];
    for case in cases {
        match case {
            Err(Failure {
                error: Error::Settings(e),
                ..
            }) => assert!(!e.to_string().is_empty()),
            other => panic!("expected a settings error, got {other:?}"),
        }
    }
}

#[test]
fn free_accelerations_function() {
    let sys = SphericalPendulum::standard();
    let (q, v) = (sv([0.5, 0.0]), sv([0.2, 1.5]));
    let a = accelerations(&sys, &q, &v, 0.0).unwrap();
    // θ̈ = sinθ cosθ φ̇² − (g/l) sinθ, φ̈ = −2 cotθ θ̇ φ̇.
    let (s, c) = 0.5f64.sin_cos();
    assert!((a[0] - (s * c * 1.5 * 1.5 - 9.81 * s)).abs() < 1e-14);
    assert!((a[1] - (-2.0 * c / s * 0.2 * 1.5)).abs() < 1e-14);
}

#[test]
fn csv_parses_back() {
    let sys = SphericalPendulum::standard();
    let tr = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-8))
        .run(sv([1.0, 0.0]), sv([0.0, 2.0]), 0.0..2.0)
        .unwrap();
    let mut buf = Vec::new();
    tr.write_csv(&mut buf, &SphericalPendulum::COORDINATES)
        .unwrap();
    let text = String::from_utf8(buf).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,theta,phi,dot_theta,dot_phi,integral,residual_position,residual_velocity")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), tr.len());
    for (k, row) in rows.iter().enumerate() {
        let (q, v) = (tr.positions()[k], tr.velocities()[k]);
        // Shortest round-trip formatting: the values come back bit for bit.
        let [rp, rv] = tr.residuals()[k];
        assert_eq!(
            row,
            &[
                tr.times()[k],
                q[0],
                q[1],
                v[0],
                v[1],
                tr.integrals()[k],
                rp,
                rv
            ]
        );
    }
    // save_csv writes the same bytes to a file.
    let path =
        std::env::temp_dir().join(format!("lagrange-runtime-test-{}.csv", std::process::id()));
    tr.save_csv(&path, &SphericalPendulum::COORDINATES).unwrap();
    let saved = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(saved, text);
    // An unwritable path is an Io error.
    let e = tr.save_csv("/nonexistent-dir/x.csv", &[]).unwrap_err();
    assert!(matches!(e, Error::Io(_)), "{e:?}");
}

/// A tolerance the scalar cannot resolve is a settings error at once, naming
/// the scalar, not a step-size collapse later (f32 at 1e-14 used to end in
/// `TooManySteps` at t = 0.03).
#[test]
fn tolerance_below_the_scalar_precision_is_a_settings_error() {
    use lagrange_runtime::{Dop853, Integrator, Radau5};
    let sys = Pendulum::<f32> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    fn run<I: Integrator>(sys: &Pendulum<f32>, m: I) -> Result<f32, Error> {
        let tr = Simulation::new(sys)
            .integrator(m)
            .run([0.5f32], [0.0f32], 0.0..1.0)?;
        Ok(tr.final_state().0[0])
    }
    for case in [
        run(&sys, Dopri5::tol(1e-14)),
        run(&sys, Dop853::tol(1e-14)),
        run(&sys, Radau5::tol(1e-14)),
    ] {
        match case {
            Err(Error::Settings(e)) => {
                let msg = e.to_string();
                assert!(msg.contains("f32") && msg.contains("rtol"), "{msg}")
            }
            other => panic!("expected a settings error, got {other:?}"),
        }
    }
    // What f32 can resolve still runs.
    assert!(run(&sys, Dopri5::tol(1e-5)).is_ok());
    assert!(run(&sys, Dop853::tol(1e-5)).is_ok());
}
