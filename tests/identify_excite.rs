//! Exciting trajectories: the Fourier series' closed-form speeds and
//! accelerations against finite differences of its positions, its period;
//! the optimised trajectory's condition number against its start's, its
//! limits at a fine grid, identification from its noise-free samples; and
//! the typed errors of bad limits and settings.

use lagrange::identify::{
    BaseParameters, Excitation, Fourier, JointLimits, condition_number, exciting_trajectory,
    identify,
};
use lagrange::{IdentifyError, Lagrangian};
use nalgebra::{DMatrix, SVector, Vector2};

/// A planar 2R arm in the vertical plane, every inertial quantity a field
/// (link frames at the joints, x along the link, gravity along −y).
#[derive(Lagrangian)]
#[lagrange(
    coordinates(q1, q2),
    body(link1, mass = m1, inertia = [ix1, iy1, iz1], com = [c1, d1, 0],
         at = [0, 0, 0], rotation = rot_z(q1)),
    point(elbow, on = link1, at = [l1, 0, 0]),
    body(link2, mass = m2, inertia = [ix2, iy2, iz2], com = [c2, d2, 0],
         at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
    gravity = [0, -9.81, 0],
    emit(regressor, inverse_dynamics),
)]
pub(crate) struct Planar {
    pub(crate) m1: f64,
    pub(crate) m2: f64,
    pub(crate) l1: f64,
    pub(crate) c1: f64,
    pub(crate) d1: f64,
    pub(crate) c2: f64,
    pub(crate) d2: f64,
    pub(crate) ix1: f64,
    pub(crate) iy1: f64,
    pub(crate) iz1: f64,
    pub(crate) ix2: f64,
    pub(crate) iy2: f64,
    pub(crate) iz2: f64,
}

pub(crate) const PLANAR: Planar = Planar {
    m1: 2.0,
    m2: 1.5,
    l1: 0.7,
    c1: 0.3,
    d1: 0.02,
    c2: 0.25,
    d2: -0.03,
    ix1: 0.01,
    iy1: 0.09,
    iz1: 0.09,
    ix2: 0.005,
    iy2: 0.05,
    iz2: 0.05,
};

fn limits() -> JointLimits<2> {
    JointLimits::new(
        Vector2::new(-1.5, -2.0),
        Vector2::new(1.5, 2.0),
        Vector2::new(2.0, 3.0),
        Vector2::new(8.0, 10.0),
    )
    .expect("limits")
}

/// Small settings: a test's budget, not the literature's.
fn settings() -> Excitation {
    Excitation {
        harmonics: 4,
        period: 4.0,
        samples: 30,
        iterations: 400,
        restarts: 2,
        seed: 5,
    }
}

#[test]
fn fourier_speeds_and_accelerations_are_the_derivatives_of_its_positions() {
    let a = DMatrix::from_row_slice(2, 3, &[0.4, -0.2, 0.1, 0.3, 0.25, -0.15]);
    let b = DMatrix::from_row_slice(2, 3, &[-0.1, 0.35, 0.05, 0.2, -0.3, 0.1]);
    let f = Fourier::new(1.7, Vector2::new(0.3, -0.5), a, b).expect("a series");
    let h = 1e-5;
    let mut worst = 0.0f64;
    for k in 0..40 {
        let t = 0.137 * k as f64;
        let (q, v, acc) = f.state(t);
        assert_eq!(q, f.position(t));
        let dq = (f.position(t + h) - f.position(t - h)) / (2.0 * h);
        let dv = (f.velocity(t + h) - f.velocity(t - h)) / (2.0 * h);
        worst = worst.max((dq - v).amax()).max((dv - acc).amax() / 10.0);
        assert_eq!(acc, f.acceleration(t));
    }
    assert!(worst < 1e-8, "{worst:e}");
    // One period: q and q̇ (and q̈) repeat; q0 is the mean.
    let period = f.period();
    assert!((period - std::f64::consts::TAU / 1.7).abs() < 1e-15);
    let (start, end) = (f.state(0.0), f.state(period));
    assert!((start.0 - end.0).amax() < 1e-12 && (start.1 - end.1).amax() < 1e-12);
    assert!((start.2 - end.2).amax() < 1e-12);
    let states = f.states(200);
    let mean = states
        .iter()
        .fold(SVector::<f64, 2>::zeros(), |m, s| m + s.0)
        / 200.0;
    assert!((mean - f.offset()).amax() < 1e-12);
}

#[test]
fn the_optimised_trajectory_conditions_the_regressor_and_keeps_the_limits() {
    let base = BaseParameters::of(&PLANAR).expect("a regressor");
    let limits = limits();
    let excited = exciting_trajectory(&PLANAR, &base, &limits, &settings()).expect("optimises");
    eprintln!(
        "2R arm: cond(W_b) {:.1} from {:.1} at the start ({} evaluations)",
        excited.condition, excited.start_condition, excited.evaluations
    );
    // Measured: 3.76 from 12.25 (the start already uses the limits' room:
    // its coefficients are scaled up to them, not small).
    assert!(
        excited.condition * 3.0 < excited.start_condition,
        "{} from {}",
        excited.condition,
        excited.start_condition
    );
    // Other seeds start elsewhere and improve as much: not a lucky draw.
    // (Nelder–Mead finds a local minimum; the seeds end between 3.8 and
    // 5.1.)
    for seed in [1, 2] {
        let other = Excitation { seed, ..settings() };
        let found = exciting_trajectory(&PLANAR, &base, &limits, &other).expect("optimises");
        eprintln!(
            "2R arm, seed {seed}: cond(W_b) {:.2} from {:.2}",
            found.condition, found.start_condition
        );
        assert!(found.condition * 2.5 < found.start_condition);
    }
    // The reported figure is the trajectory's own.
    let again = condition_number(&PLANAR, &base, &excited.trajectory, 30).expect("Y");
    assert!((again - excited.condition).abs() < 1e-9 * again);
    // Within the limits at every one of 5000 times, not only at the 30.
    assert!(excited.within_limits);
    excited
        .trajectory
        .check(&limits, 5000)
        .expect("within the limits");
    // Deterministic: the same seed, the same trajectory.
    let twice = exciting_trajectory(&PLANAR, &base, &limits, &settings()).expect("optimises");
    assert_eq!(twice.trajectory, excited.trajectory);
    // Noise-free samples along it give π_b to 1e-9.
    let pi = PLANAR.inertial_parameters().expect("π");
    let truth = base.of_parameters(&pi).expect("π's length");
    let samples = excited
        .trajectory
        .samples(&PLANAR, &pi, 30)
        .expect("samples");
    let fit = identify(&PLANAR, &base, &samples, &Vector2::repeat(0.1)).expect("identifies");
    let err = (&fit.values - &truth).amax() / truth.amax();
    assert!(err < 1e-9, "{err:e}");
    // τ = Y π is the arm's inverse dynamics.
    let s = &samples[7];
    let tau = PLANAR.inverse_dynamics(&s.q, &s.v, &s.a, 0.0);
    assert!((tau - s.tau).amax() < 1e-12);
}

#[test]
fn a_trajectory_outside_its_limits_is_reported_where() {
    let a = DMatrix::from_row_slice(2, 1, &[2.5, 0.0]);
    let b = DMatrix::zeros(2, 1);
    let f = Fourier::new(1.0, Vector2::zeros(), a, b).expect("a series");
    // q̇₀ = 2.5 cos t: beyond joint 0's speed limit 2 at t = 0.
    match f.check(&limits(), 100) {
        Err(IdentifyError::OutsideLimits {
            joint: 0,
            quantity: "speed",
            time,
            value,
            limit,
        }) => {
            assert_eq!((time, value, limit), (0.0, 2.5, 2.0));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_limits_are_typed_errors() {
    let v = |x: f64, y: f64| Vector2::new(x, y);
    let ok = v(1.0, 1.0);
    let range = JointLimits::new(v(-1.0, 0.5), v(1.0, 0.5), ok, ok);
    assert!(matches!(
        range,
        Err(IdentifyError::LimitRange { joint: 1, .. })
    ));
    let nan = JointLimits::new(v(f64::NAN, 0.0), v(1.0, 1.0), ok, ok);
    assert!(matches!(
        nan,
        Err(IdentifyError::LimitRange { joint: 0, .. })
    ));
    let speed = JointLimits::new(v(-1.0, -1.0), ok, v(1.0, -2.0), ok);
    assert!(matches!(
        speed,
        Err(IdentifyError::LimitRate {
            joint: 1,
            quantity: "speed",
            ..
        })
    ));
    let acceleration = JointLimits::new(v(-1.0, -1.0), ok, ok, v(0.0, 1.0));
    let message = acceleration.as_ref().map(|_| ()).unwrap_err().to_string();
    assert!(
        message.contains("acceleration limit must be positive"),
        "{message}"
    );
}

#[test]
fn bad_settings_and_coefficients_are_typed_errors() {
    let base = BaseParameters::of(&PLANAR).expect("a regressor");
    let run = |settings: Excitation| exciting_trajectory(&PLANAR, &base, &limits(), &settings);
    let no_harmonics = run(Excitation {
        harmonics: 0,
        ..settings()
    });
    assert!(matches!(
        no_harmonics,
        Err(IdentifyError::Setting {
            setting: "harmonics",
            ..
        })
    ));
    let period = run(Excitation {
        period: -1.0,
        ..settings()
    });
    assert!(matches!(
        period,
        Err(IdentifyError::Setting {
            setting: "period",
            ..
        })
    ));
    // Six base parameters, two joints: three samples at least.
    let few = run(Excitation {
        samples: 2,
        ..settings()
    });
    assert!(matches!(
        few,
        Err(IdentifyError::TooFewSamples { needed: 3, .. })
    ));

    let bad = Fourier::new(
        0.0,
        Vector2::zeros(),
        DMatrix::zeros(2, 1),
        DMatrix::zeros(2, 1),
    );
    assert!(matches!(
        bad,
        Err(IdentifyError::Setting {
            setting: "frequency",
            ..
        })
    ));
    let shape = Fourier::new(
        1.0,
        Vector2::zeros(),
        DMatrix::zeros(2, 2),
        DMatrix::zeros(2, 1),
    );
    assert!(matches!(
        shape,
        Err(IdentifyError::Lengths {
            got: 1,
            expected: 2,
            ..
        })
    ));
    let mut a = DMatrix::zeros(2, 1);
    a[(1, 0)] = f64::INFINITY;
    let infinite = Fourier::new(1.0, Vector2::zeros(), a, DMatrix::zeros(2, 1));
    assert!(matches!(
        infinite,
        Err(IdentifyError::NotFiniteValue {
            what: "a",
            index: 1,
            ..
        })
    ));
}
