//! Inputs with the atlas (`inputs(..)` with `emit(atlas)`,
//! `Simulation::run_atlas` with a source): a satellite turned by body-axis
//! torques, its attitude written in yaw–pitch–roll, driven through pitch
//! ±π/2 by a signal of time, by state feedback and by a sampled
//! controller, against the same satellite with a free orientation
//! (`catalog::free::Satellite`).

use crate::catalog;

use catalog::free::Satellite;
use lagrange::numeric::euler::EulerChart;
use lagrange::numeric::orientation::rotation_matrix;
use lagrange::prelude::*;
use nalgebra::{Matrix3, SVector, Vector3, Vector4};

/// The satellite of `catalog::free::Satellite`, its turn in z-y-x angles
/// (singular where the body's x axis is vertical, pitch = ±π/2).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(yaw, pitch, roll),
    inputs(t1, t2, t3),
    body(sat, mass = m, inertia = [a, b, c], at = [0, 0, 0],
         rotation = euler_zyx(yaw, pitch, roll)),
    point(arm_y, on = sat, at = [0, 1, 0]),
    point(arm_z, on = sat, at = [0, 0, 1]),
    point(arm_x, on = sat, at = [1, 0, 0]),
    force(arm_y, [t1 * sat.axis_z.x, t1 * sat.axis_z.y, t1 * sat.axis_z.z]),
    force(arm_z, [t2 * sat.axis_x.x, t2 * sat.axis_x.y, t2 * sat.axis_x.z]),
    force(arm_x, [t3 * sat.axis_y.x, t3 * sat.axis_y.y, t3 * sat.axis_y.z]),
    emit(atlas),
)]
struct EulerSatellite {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
}

const SAT: Satellite = Satellite {
    m: 40.0,
    a: 2.0,
    b: 3.0,
    c: 4.5,
};
const EULER_SAT: EulerSatellite = EulerSatellite {
    m: 40.0,
    a: 2.0,
    b: 3.0,
    c: 4.5,
};

fn zyx() -> EulerChart {
    EulerChart::new([2, 1, 0]).unwrap()
}

fn matrix(q: &SVector<f64, 4>) -> Matrix3<f64> {
    let r = rotation_matrix([q[0], q[1], q[2], q[3]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

/// The user's start (angles, rates) and the quaternion's (q, ω) for it.
fn start(angles: [f64; 3], w: Vector3<f64>) -> ([f64; 3], [f64; 3], SVector<f64, 4>) {
    let rates = zyx().rates(angles).try_inverse().unwrap() * w;
    let q = nalgebra::UnitQuaternion::from_matrix(&zyx().matrix(angles));
    let quaternion = SVector::from(Vector4::new(q.w, q.i, q.j, q.k));
    (angles, [rates[0], rates[1], rates[2]], quaternion)
}

/// The largest gap between the atlas run's rotation and angular velocity
/// and the quaternion run's, over the atlas run's points.
fn gap<const P: usize>(run: &AtlasRun<f64, 3, P>, reference: &Trajectory<f64, 3, 4>) -> (f64, f64) {
    let (mut rotation, mut omega) = (0.0f64, 0.0f64);
    for (i, &t) in run.charted().times().iter().enumerate() {
        let (q, w) = reference.state_at(t).unwrap();
        rotation = rotation.max((run.rotation(i, 0) - matrix(&q)).abs().max());
        omega = omega.max((run.angular_velocity(i, 0) - w).amax());
    }
    (rotation, omega)
}

/// The least angle between the body's x axis and the vertical over the
/// run's points (|π/2 − |pitch||).
fn closest_to_vertical<const P: usize>(run: &AtlasRun<f64, 3, P>) -> f64 {
    (0..run.charted().len())
        .map(|i| run.rotation(i, 0)[(2, 0)].abs().min(1.0).acos())
        .fold(f64::INFINITY, f64::min)
}

/// Pitched up at 1.2 rad with a pitch rate, under torques that vary in
/// time (mostly about the pitch axis, a little about the others): the
/// body's x axis passes within a few milliradians of the vertical again and
/// again (within 0.025 rad at the recorded points), and the motion matches the quaternion satellite's under
/// the same signal; the inputs recorded are the signal's.
#[test]
fn a_torque_signal_drives_the_yaw_pitch_roll_satellite_through_the_vertical() {
    let signal = |t: f64| {
        [
            0.03 * (1.3 * t).sin(),
            1.5 + 0.5 * t.cos(),
            -0.02 * (0.7 * t).cos(),
        ]
    };
    let (angles, rates, quaternion) = start([0.3, 1.2, -0.05], Vector3::new(0.01, 1.0, -0.02));
    let span = 0.0..8.0;
    let run = Simulation::new(&EULER_SAT)
        .integrator(Dopri5::tol(1e-11))
        .open_loop(signal)
        .event(Event::new(|_: f64, q, _| q[1].sin() - 0.99).rising())
        .run_atlas(angles, rates, span.clone())
        .unwrap();
    let reference = Simulation::new(&SAT)
        .integrator(Dopri5::tol(1e-11))
        .open_loop(signal)
        .event(Event::new(|_, q, _| -matrix(q)[(2, 0)] - 0.99).rising())
        .run(quaternion, [0.01, 1.0, -0.02], span)
        .unwrap();
    // sin(pitch) rising through 0.99, in the second chart: located where
    // the quaternion run locates −R₂₀ rising through it.
    let (times, expected) = (run.times(0), reference.occurrences());
    assert_eq!(times.len(), expected.len());
    let event_gap = (times.iter().zip(expected))
        .map(|(t, o)| (t - o.t).abs())
        .fold(0.0f64, f64::max);
    eprintln!(
        "signal: {} crossings of sin(pitch) = 0.99, time gap {event_gap:e}",
        times.len()
    );
    assert!(!times.is_empty() && event_gap < 1e-9, "{event_gap:e}");
    let (rotation, omega) = gap(&run, reference.trajectory());
    let switches = run.switches().len();
    eprintln!("signal: {switches} switches, rotation gap {rotation:e}, ω gap {omega:e}");
    assert!(switches >= 4, "{switches}");
    assert!(rotation < 1e-8 && omega < 1e-8, "{rotation:e} {omega:e}");
    let traj = run.charted();
    assert_eq!(run.inputs().len(), traj.len());
    assert_eq!(run.input_names(), &["t1", "t2", "t3"]);
    let mut csv = Vec::new();
    run.table(&EULER_SAT).unwrap().write(&mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.contains("sat.chart,sat.w,sat.x,sat.y,sat.z,t1,t2,t3"),
        "{header}"
    );
    for (u, &t) in run.inputs().iter().zip(traj.times()) {
        assert_eq!(*u, SVector::from(signal(t)));
    }
    // The body's x axis passes close by the vertical (cos pitch = |R₂₀|⊥).
    let nearest = closest_to_vertical(&run);
    eprintln!("signal: the x axis's least angle to the vertical {nearest:e} rad");
    assert!(nearest < 0.05, "{nearest}");
}

/// A law written on the orientation R and ω in body axes: despin and turn
/// the body's x axis towards `target` (a torque k x̂ × Rᵀ target).
fn law(r: &Matrix3<f64>, w: &Vector3<f64>) -> [f64; 3] {
    let target = Vector3::new(-(0.3f64.sin()), 0.0, 0.3f64.cos());
    let u = Vector3::x().cross(&(r.transpose() * target)) * 6.0 - w * 6.0;
    [u[0], u[1], u[2]]
}

/// State feedback written on the user's coordinates (R and ω from the
/// angles and their rates) swings the satellite's x axis over the vertical
/// (pitch −0.5 to past −π/2) to 0.3 rad beyond it, where the user's chart
/// is poor (|cos pitch| = 0.3): the run ends in the second chart, the controller reading the user's
/// angles all along, and matches the quaternion satellite under the same
/// law read on its quaternion and ω.
#[test]
fn state_feedback_on_the_users_angles_holds_the_satellite_near_the_vertical() {
    let user_law = |_: f64, q: &SVector<f64, 3>, v: &SVector<f64, 3>| {
        let x = [q[0], q[1], q[2]];
        law(&zyx().matrix(x), &(zyx().rates(x) * v))
    };
    let quaternion_law =
        |_: f64, q: &SVector<f64, 4>, v: &SVector<f64, 3>| law(&matrix(q), &Vector3::from(*v));
    let (angles, rates, quaternion) = start([0.1, -0.5, 0.2], Vector3::new(0.3, -0.5, 0.2));
    let span = 0.0..40.0;
    let run = Simulation::new(&EULER_SAT)
        .integrator(Dopri5::tol(1e-11))
        .feedback(user_law)
        .run_atlas(angles, rates, span.clone())
        .unwrap();
    let reference = Simulation::new(&SAT)
        .integrator(Dopri5::tol(1e-11))
        .feedback(quaternion_law)
        .run(quaternion, [0.3, -0.5, 0.2], span)
        .unwrap();
    let (rotation, omega) = gap(&run, reference.trajectory());
    let last = run.charted().len() - 1;
    let x_axis = run.rotation(last, 0).column(0).into_owned();
    let target = Vector3::new(-(0.3f64.sin()), 0.0, 0.3f64.cos());
    let (off, spin) = (
        (x_axis - target).norm(),
        run.angular_velocity(last, 0).norm(),
    );
    let switches = run.switches().len();
    let nearest = closest_to_vertical(&run);
    eprintln!("feedback: the x axis's least angle to the vertical {nearest:e} rad");
    assert!(nearest < 0.05, "{nearest}");
    eprintln!(
        "feedback: {switches} switches, rotation gap {rotation:e}, ω gap {omega:e}, final axis off {off:e}, ω {spin:e}"
    );
    assert!(switches >= 1 && run.charts()[last] == 1, "{switches}");
    assert!(rotation < 1e-8 && omega < 1e-8, "{rotation:e} {omega:e}");
    assert!(off < 1e-6 && spin < 1e-6, "{off:e} {spin:e}");
    // The inputs recorded are the law's at the user's state of each point.
    for i in [0, last / 2, last] {
        let (q, v) = run.user_state(i).unwrap();
        let u = SVector::from(user_law(0.0, &q, &v));
        assert!((run.inputs()[i] - u).amax() < 1e-12, "point {i}");
    }
}

/// A sampled controller (zero-order hold, every 0.05 s) on the same law:
/// the run restarts at each sample and at each switch, and matches the
/// quaternion satellite's sampled run.
#[test]
fn a_sampled_controller_drives_the_satellite_through_the_switches() {
    let user_law = |_: f64, q: &SVector<f64, 3>, v: &SVector<f64, 3>| {
        let x = [q[0], q[1], q[2]];
        law(&zyx().matrix(x), &(zyx().rates(x) * v))
    };
    let quaternion_law =
        |_: f64, q: &SVector<f64, 4>, v: &SVector<f64, 3>| law(&matrix(q), &Vector3::from(*v));
    let (angles, rates, quaternion) = start([0.1, -0.5, 0.2], Vector3::new(0.3, -0.5, 0.2));
    let span = 0.0..6.0;
    let run = Simulation::new(&EULER_SAT)
        .integrator(Dopri5::tol(1e-11))
        .sampled(0.05, user_law)
        .run_atlas(angles, rates, span.clone())
        .unwrap();
    let reference = Simulation::new(&SAT)
        .integrator(Dopri5::tol(1e-11))
        .sampled(0.05, quaternion_law)
        .run(quaternion, [0.3, -0.5, 0.2], span)
        .unwrap();
    let (rotation, omega) = gap(&run, reference.trajectory());
    let switches = run.switches().len();
    eprintln!("sampled: {switches} switches, rotation gap {rotation:e}, ω gap {omega:e}");
    assert!(switches >= 1, "{switches}");
    assert!(rotation < 1e-8 && omega < 1e-8, "{rotation:e} {omega:e}");
}

/// `Linearizer::atlas_driven`: at a regular state its A and B are the
/// ordinary linearisation of the user's description; through the pole (pitch
/// π/2, read in the second chart) the rates' rows of B satisfy E B = I⁻¹,
/// since the torques act on ω̇ = I⁻¹(τ − ω × Iω) and ω = E(y) ẏ.
#[test]
fn atlas_driven_linearisation_has_the_torques_input_matrix_in_either_chart() {
    let lin = Linearizer::new();
    let (v, u) = (
        SVector::from([0.2, -0.3, 0.5]),
        SVector::from([0.4, -0.1, 0.7]),
    );
    let q = SVector::from([0.3, 0.4, -0.2]);
    let atlas = lin
        .atlas_driven(&EULER_SAT, &q, &v, &u, 0.0)
        .expect("linearises");
    let plain = lin
        .tangent_driven(&EULER_SAT, &q, &v, &u, 0.0)
        .expect("linearises");
    assert_eq!(atlas.states(), plain.states());
    let off = |x: &nalgebra::DMatrix<f64>, y: &nalgebra::DMatrix<f64>| (x - y).amax() / y.amax();
    let (off_a, off_b) = (off(atlas.a(), plain.a()), off(atlas.b(), plain.b()));
    assert!(off_a < 1e-8 && off_b < 1e-8, "A: {off_a:e}, B: {off_b:e}");

    let q = SVector::from([0.3, std::f64::consts::FRAC_PI_2, 0.2]);
    let atlas = lin
        .atlas_driven(&EULER_SAT, &q, &v, &u, 0.0)
        .expect("linearises at the pole");
    assert_eq!(&atlas.states()[..3], ["yaw@2", "pitch@2", "roll@2"]);
    let second = zyx().second();
    let r = zyx().matrix([q[0], q[1], q[2]]);
    let e = second.rates(second.angles(&r, None));
    let rates = Matrix3::from_fn(|i, k| atlas.b()[(3 + i, k)]);
    let inertia = Vector3::new(EULER_SAT.a, EULER_SAT.b, EULER_SAT.c);
    let gap = (e * rates - Matrix3::from_diagonal(&inertia.map(|x| 1.0 / x))).amax();
    println!("regular: A {off_a:.1e}, B {off_b:.1e}; at the pole: E B − I⁻¹ {gap:.1e}");
    assert!(gap < 1e-8, "E B − I⁻¹ = {gap:e}");
    assert!(
        atlas.b().rows(0, 3).amax() == 0.0,
        "no input acts on the angles directly"
    );
}
