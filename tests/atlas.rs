//! The atlas (`emit(atlas)`, `Simulation::run_atlas`): a system written in
//! Euler angles runs through its chart's singular set by switching to the
//! second chart, against the same system with a quaternion.

use crate::catalog;

use catalog::free::{
    Brick, EulerTop, QuaternionTop, SphericalChain, sleeping_top_growth, sleeping_top_threshold,
};
use lagrange::numeric::euler::EulerChart;
use lagrange::numeric::orientation::rotation_matrix;
use lagrange::prelude::*;
use nalgebra::{Matrix3, SVector, Vector3};

const EULER_TOP: EulerTop = EulerTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};
const TOP: QuaternionTop = QuaternionTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};

fn matrix(q: &[f64]) -> Matrix3<f64> {
    let r = rotation_matrix([q[0], q[1], q[2], q[3]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

/// Started exactly upright (θ = 0, where z-x-z is singular) with a nudge
/// across, the atlas top and the quaternion top move alike.
#[test]
fn the_upright_top_in_euler_angles_matches_the_quaternion_top() {
    let (spin, nudge) = (30.0, 0.3);
    let sim = Simulation::new(&EULER_TOP).integrator(Dopri5::tol(1e-11));
    let run = sim
        .run_atlas([0.0, 0.0, 0.0], [0.0, nudge, spin], 0.0..3.0)
        .unwrap();
    let reference = Simulation::new(&TOP)
        .integrator(Dopri5::tol(1e-11))
        .run([1.0, 0.0, 0.0, 0.0], [nudge, 0.0, spin], 0.0..3.0)
        .unwrap();
    // It starts in the second chart and, sleeping, stays there.
    assert_eq!(run.charts()[0], 1);
    let traj = run.charted();
    let mut worst: f64 = 0.0;
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.state_at(t).unwrap();
        worst = worst.max((run.rotation(i, 0) - matrix(q.as_slice())).abs().max());
    }
    assert!(worst < 1e-7, "{worst:e}");
    assert!(traj.integral_drift() < 1e-8, "{:e}", traj.integral_drift());
    // The user's own run refuses that start, naming the direction with no
    // inertia (ψ and φ turn about the same axis) and saying to run through
    // the atlas.
    let e = sim
        .run([0.0, 0.0, 0.0], [0.0, nudge, spin], 0.0..3.0)
        .unwrap_err();
    assert!(
        matches!(&e.error, Error::SingularMassMatrix { direction, atlas: true, .. }
            if direction.contains("psi") && direction.contains("phi") && !direction.contains("theta")),
        "{e}"
    );
    assert!(e.to_string().contains("call `run_atlas`"), "{e}");
}

/// The quaternion of the z-x-z angles (ψ, θ, φ).
fn zxz_quaternion([psi, theta, phi]: [f64; 3]) -> [f64; 4] {
    let r = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), psi)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), theta)
        * nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), phi);
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&r);
    [q.w, q.i, q.j, q.k]
}

/// A slow top swung over the top through the upright, again and again:
/// each pass leaves the user's chart and comes back, and the motion matches
/// the quaternion top's.
#[test]
fn a_top_swung_through_the_upright_switches_charts_and_back() {
    let q0 = [0.2, 0.6, -0.4];
    let v0 = [0.0, -6.0, 2.0];
    let sim = Simulation::new(&EULER_TOP).integrator(Dopri5::tol(1e-11));
    let run = sim.run_atlas(q0, v0, 0.0..4.0).unwrap();
    let omega0 = EulerChart::new([2, 0, 2]).unwrap().rates(q0) * Vector3::from(v0);
    let reference = Simulation::new(&TOP)
        .integrator(Dopri5::tol(1e-11))
        .run(
            zxz_quaternion(q0),
            [omega0[0], omega0[1], omega0[2]],
            0.0..4.0,
        )
        .unwrap();
    let traj = run.charted();
    let mut worst: f64 = 0.0;
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.state_at(t).unwrap();
        worst = worst.max((run.rotation(i, 0) - matrix(q.as_slice())).abs().max());
    }
    let switches = run.switches();
    eprintln!(
        "{} switches, worst {worst:e}, drift {:e}",
        switches.len(),
        traj.integral_drift()
    );
    assert!(switches.len() >= 4, "{switches:?}");
    assert!(
        switches
            .iter()
            .zip(switches.iter().skip(1))
            .all(|(a, b)| a.to_second != b.to_second)
    );
    assert!(worst < 1e-7, "{worst:e}");
    assert!(traj.integral_drift() < 1e-8, "{:e}", traj.integral_drift());
    // In the second chart the user's coordinates are still there to read,
    // wherever their chart is valid: the same rotation and the same ω.
    let user = EulerChart::new([2, 0, 2]).unwrap();
    let mut read = 0;
    for i in (0..traj.len()).filter(|&i| run.charts()[i] == 1) {
        let Some((q, v)) = run.user_state(i) else {
            continue;
        };
        let x = [q[0], q[1], q[2]];
        assert!((user.matrix(x) - run.rotation(i, 0)).abs().max() < 1e-12);
        let omega = user.rates(x) * Vector3::new(v[0], v[1], v[2]);
        assert!((omega - run.angular_velocity(i, 0)).norm() < 1e-9 * (1.0 + omega.norm()));
        read += 1;
    }
    assert!(read > 10, "{read}");
    let mut csv = Vec::new();
    run.table(&EULER_TOP).unwrap().write(&mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.contains("psi,theta,phi") && header.contains("top.chart,top.w,top.x,top.y,top.z")
    );
    assert_eq!(csv.lines().count(), traj.len() + 1);
    let mapped = run.user_trajectory().unwrap();
    assert!(mapped.len() + 2 >= traj.len() && mapped.segments().is_empty());
    // Back in the user's chart the user's angles read as the chart holds them.
    let charts = run.charts();
    let last = traj.len() - 1;
    if charts[last] == 0 {
        let (q, _) = run.user_state(last).unwrap();
        assert!((q - traj.positions()[last]).abs().max() < 1e-12);
    }
}

/// A brick thrown spinning, its turn written in yaw–pitch–roll (z-y-x,
/// singular where the body's x axis is vertical), with an atlas.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z, yaw, pitch, roll),
    body(brick, mass = m, inertia = [a, b, c], at = [x, y, z],
         rotation = euler_zyx(yaw, pitch, roll)),
    gravity = [0, 0, -g],
    emit(atlas),
)]
struct EulerBrick {
    m: f64,
    a: f64,
    b: f64,
    c: f64,
    g: f64,
}

/// Spun about its intermediate axis lying level, the brick's x axis passes
/// the vertical twice a turn and the flips carry it everywhere: the chart
/// switches dozens of times, and energy, the angular momentum about the
/// centre and the centre's parabola hold, as in the quaternion brick.
#[test]
fn a_tumbling_brick_in_yaw_pitch_roll_runs_through_every_orientation() {
    let brick = Brick {
        g: 9.81,
        ..Brick::solid(2.0, [0.3, 0.2, 0.1])
    };
    let euler = EulerBrick {
        m: brick.m,
        a: brick.a,
        b: brick.b,
        c: brick.c,
        g: brick.g,
    };
    // Body y along the world's x: yaw −π/2.
    let angles = [-std::f64::consts::FRAC_PI_2, 0.1, 0.05];
    let chart = EulerChart::new([2, 1, 0]).unwrap();
    let w = Vector3::new(0.05, 6.0, 0.08);
    let rates = chart.rates(angles).try_inverse().unwrap() * w;
    let q0 = [0.0, 0.0, 0.0, angles[0], angles[1], angles[2]];
    let v0 = [1.0, -0.5, 12.0, rates[0], rates[1], rates[2]];
    let span = 0.0..6.0;
    let run = Simulation::new(&euler)
        .integrator(Dopri5::tol(1e-11))
        .run_atlas(q0, v0, span.clone())
        .unwrap();
    let r0 = chart.matrix(angles);
    let quaternion = nalgebra::UnitQuaternion::from_matrix(&r0);
    let reference = Simulation::new(&brick)
        .integrator(Dopri5::tol(1e-11))
        .run(
            [
                0.0,
                0.0,
                0.0,
                quaternion.w,
                quaternion.i,
                quaternion.j,
                quaternion.k,
            ],
            [1.0, -0.5, 12.0, w[0], w[1], w[2]],
            span,
        )
        .unwrap();
    let traj = run.charted();
    let inertia = Matrix3::from_diagonal(&Vector3::new(brick.a, brick.b, brick.c));
    let momentum = |i: usize| run.rotation(i, 0) * inertia * run.angular_velocity(i, 0);
    let (mut worst, mut drift, mut parabola) = (0.0f64, 0.0f64, 0.0f64);
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.state_at(t).unwrap();
        worst = worst.max(
            (run.rotation(i, 0) - matrix(&q.as_slice()[3..]))
                .abs()
                .max(),
        );
        drift = drift.max((momentum(i) - momentum(0)).norm());
        let centre = traj.positions()[i].fixed_rows::<3>(0).into_owned();
        let exact = Vector3::new(t, -0.5 * t, 12.0 * t - 0.5 * 9.81 * t * t);
        parabola = parabola.max((centre - exact).norm());
    }
    let switches = run.switches().len();
    eprintln!(
        "{switches} switches, worst {worst:e}, L drift {drift:e}, parabola {parabola:e}, energy {:e}",
        traj.integral_drift()
    );
    assert!(switches >= 10, "{switches}");
    // The flip amplifies the integrators' errors: 1.4e-8 at 1e-11.
    assert!(worst < 1e-7, "{worst:e}");
    assert!(drift < 1e-8, "{drift:e}");
    assert!(parabola < 1e-9, "{parabola:e}");
    assert!(traj.integral_drift() < 1e-8);
}

/// The sleeping top linearised where its own chart is singular: the atlas
/// reads the upright in the second chart, where the spin is the cyclic φ,
/// and A's largest real part is √(4 A m g l − C² n²) / (2A) below the
/// threshold spin and zero above it.
#[test]
fn the_upright_top_linearises_in_its_second_chart() {
    let top = EULER_TOP;
    let mgl = top.m * top.g * top.l;
    let threshold = sleeping_top_threshold(top.a, top.c, mgl);
    for ratio in [0.9, 0.99, 1.01, 1.5] {
        let n = ratio * threshold;
        let lin = Linearizer::new()
            .atlas(&top, &SVector::zeros(), &SVector::from([0.0, 0.0, n]), 0.0)
            .unwrap();
        assert_eq!(lin.states()[..3], ["psi@2", "theta@2", "phi@2"]);
        let growth = lin.eigenvalues()[0].re;
        let expected = sleeping_top_growth(top.a, top.c, mgl, n);
        eprintln!("n/n_c = {ratio}: largest real part {growth:e}, closed form {expected:e}");
        assert!(
            (growth - expected).abs() < 1e-6 * (1.0 + expected),
            "{growth} vs {expected}"
        );
    }
    // Away from the upright the user's own chart is kept.
    let lin = Linearizer::new()
        .atlas(
            &top,
            &SVector::from([0.0, 0.7, 0.0]),
            &SVector::from([0.0, 0.0, 10.0]),
            0.0,
        )
        .unwrap();
    assert_eq!(lin.states()[..3], ["psi", "theta", "phi"]);
}

/// The swing through the upright with every kind of integrator: the
/// switches are events, so fixed-step, implicit and high-order methods all
/// carry the run across, each to its own accuracy.
#[test]
fn every_integrator_carries_the_atlas_across() {
    let (q0, v0) = ([0.2, 0.6, -0.4], [0.0, -6.0, 2.0]);
    let omega0 = EulerChart::new([2, 0, 2]).unwrap().rates(q0) * Vector3::from(v0);
    let reference = Simulation::new(&TOP)
        .integrator(Dop853::tol(1e-12))
        .run(
            zxz_quaternion(q0),
            [omega0[0], omega0[1], omega0[2]],
            0.0..2.0,
        )
        .unwrap();
    let exact = matrix(reference.final_state().0.as_slice());
    fn error<I: Integrator>(integrator: I, exact: &Matrix3<f64>) -> f64 {
        let run = Simulation::new(&EULER_TOP)
            .integrator(integrator)
            .run_atlas([0.2, 0.6, -0.4], [0.0, -6.0, 2.0], 0.0..2.0)
            .unwrap();
        assert!(run.switches().len() >= 4);
        (run.rotation(run.charted().len() - 1, 0) - exact)
            .abs()
            .max()
    }
    let errors = [
        ("dop853", error(Dop853::tol(1e-10), &exact)),
        ("radau5", error(Radau5::tol(1e-8), &exact)),
        ("rk4", error(Rk4::step(1e-3), &exact)),
    ];
    eprintln!("{errors:?}");
    for (name, e) in errors {
        assert!(e < 1e-5, "{name}: {e:e}");
    }
    // Störmer–Verlet is first order with velocity-dependent forces (the
    // Euler angles' Coriolis terms), and stays so across the switches.
    let (coarse, fine) = (
        error(StormerVerlet::step(1e-4), &exact),
        error(StormerVerlet::step(5e-5), &exact),
    );
    eprintln!("verlet {coarse:e} -> {fine:e}");
    assert!(
        (1.6..2.4).contains(&(coarse / fine)),
        "{coarse:e} -> {fine:e}"
    );
}

/// Two bodies on spherical joints, each joint written as three successive
/// `rot_*` of its own angles: z-x-z at the pivot, y-x-z (Tait–Bryan) at the
/// tip. The atlas finds both rotations, each with its own chart.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(p1, t1, s1, a2, b2, c2),
    body(arm, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, -l],
         at = [0, 0, 0], rotation = rot_z(p1) * rot_x(t1) * rot_z(s1)),
    point(tip, on = arm, at = [0, 0, -2 * l]),
    body(hand, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, -l],
         at = [tip.x, tip.y, tip.z],
         rotation = rot_z(p1) * rot_x(t1) * rot_z(s1) * rot_y(a2) * rot_x(b2) * rot_z(c2)),
    gravity = [0, 0, -g],
    emit(atlas),
)]
struct EulerChain {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// Both joints started on their charts' singular sets (t1 = 0, b2 = π/2):
/// each rotation starts in its second chart and switches on its own, and the
/// chain moves as the quaternion chain does.
#[test]
fn a_chain_of_two_euler_joints_switches_each_on_its_own() {
    let (m, a, c, l, g) = (1.0, 0.2, 0.02, 0.3, 9.81);
    let chain = EulerChain { m, a, c, l, g };
    assert_eq!(EulerChain::EULER.len(), 2);
    assert_eq!(
        (EulerChain::EULER[0].axes, EulerChain::EULER[1].axes),
        ([2, 0, 2], [1, 0, 2])
    );
    let q0 = [0.3, 0.0, -0.2, 0.1, std::f64::consts::FRAC_PI_2, 0.4];
    let v0 = [0.5, 5.0, -0.7, 2.0, -1.0, 0.3];
    let span = 0.0..3.0;
    let run = Simulation::new(&chain)
        .integrator(Dopri5::tol(1e-11))
        .run_atlas(q0, v0, span.clone())
        .unwrap();
    assert_eq!(run.charts()[0], 0b11);
    let (upper, lower) = (
        EulerChart::new([2, 0, 2]).unwrap(),
        EulerChart::new([1, 0, 2]).unwrap(),
    );
    let quaternion = |chart: EulerChart, x: [f64; 3]| {
        let r = chart.matrix(x);
        lagrange::numeric::orientation::from_rotation_matrix(&r)
    };
    let (x1, x2) = ([q0[0], q0[1], q0[2]], [q0[3], q0[4], q0[5]]);
    let w1 = upper.rates(x1) * Vector3::new(v0[0], v0[1], v0[2]);
    let w2 = lower.rates(x2) * Vector3::new(v0[3], v0[4], v0[5]);
    let reference = Simulation::new(&SphericalChain { m, a, c, l, g })
        .integrator(Dopri5::tol(1e-11))
        .run(
            SVector::<f64, 8>::from_row_slice(
                &[quaternion(upper, x1), quaternion(lower, x2)].concat(),
            ),
            [w1[0], w1[1], w1[2], w2[0], w2[1], w2[2]],
            span,
        )
        .unwrap();
    let traj = run.charted();
    let mut worst: f64 = 0.0;
    for (i, &t) in traj.times().iter().enumerate() {
        let (q, _) = reference.state_at(t).unwrap();
        worst = worst.max(
            (run.rotation(i, 0) - matrix(&q.as_slice()[0..4]))
                .abs()
                .max(),
        );
        worst = worst.max(
            (run.rotation(i, 1) - matrix(&q.as_slice()[4..8]))
                .abs()
                .max(),
        );
    }
    let by_rotation = |k| run.switches().iter().filter(|s| s.rotation == k).count();
    eprintln!(
        "switches {} + {}, worst {worst:e}, drift {:e}",
        by_rotation(0),
        by_rotation(1),
        traj.integral_drift()
    );
    assert!(by_rotation(0) >= 1 && by_rotation(1) >= 1);
    assert!(worst < 1e-7, "{worst:e}");
    assert!(traj.integral_drift() < 1e-8);
}

/// A generic scalar: the twin carries the struct's type parameter, and the
/// atlas runs in f32 as in f64.
#[test]
fn the_atlas_runs_a_generic_scalar_in_f32() {
    let top = EulerTop::<f32> {
        m: 1.5,
        a: 0.8,
        c: 0.5,
        l: 0.4,
        g: 9.81,
    };
    let run = Simulation::new(&top)
        .integrator(Dopri5::tol(1e-5))
        .run_atlas([0.2f32, 0.6, -0.4], [0.0, -6.0, 2.0], 0.0..2.0)
        .unwrap();
    assert!(run.switches().len() >= 4);
    let wide = Simulation::new(&EULER_TOP)
        .integrator(Dopri5::tol(1e-10))
        .run_atlas([0.2, 0.6, -0.4], [0.0, -6.0, 2.0], 0.0..2.0)
        .unwrap();
    let narrow = run.rotation(run.charted().len() - 1, 0).map(f64::from);
    let apart = (wide.rotation(wide.charted().len() - 1, 0) - narrow)
        .abs()
        .max();
    assert!(apart < 1e-3, "{apart:e}");
    assert!(run.charted().integral_drift() < 1e-3);
}

/// Released at tilt θ₀ = 0.6 (|sin θ₀| below the switching threshold, so it
/// starts in the second chart) with spin n, the Euler-angle top nutates
/// between u₀ = cos θ₀ and the root of β(1 − u²) = a²(u₀ − u), a = C n / A,
/// β = 2 m g l / A, switching charts on the way: its turning points, found
/// on the dense output read in the chart of each instant, are the cubic's.
#[test]
fn the_atlas_top_nutates_between_the_roots_of_the_cubic() {
    let top = EULER_TOP;
    let (theta0, n) = (0.6_f64, 6.0);
    let run = Simulation::new(&top)
        .integrator(Dop853::tol(1e-12))
        .run_atlas([0.0, theta0, 0.0], [0.0, 0.0, n], 0.0..5.0)
        .unwrap();
    assert_eq!(run.charts()[0], 1);
    assert!(!run.switches().is_empty());
    let a = top.c * n / top.a;
    let beta = 2.0 * top.m * top.g * top.l / top.a;
    let u0 = theta0.cos();
    let u1 = (a * a - (a.powi(4) - 4.0 * beta * (a * a * u0 - beta)).sqrt()) / (2.0 * beta);
    // d(cos θ)/dt = (R [ω]×)₂₂ = R₂₀ ω_y − R₂₁ ω_x.
    let tilt_rate = |t: f64| {
        let (r, w) = run.rotation_at(t, 0).unwrap();
        r[(2, 0)] * w[1] - r[(2, 1)] * w[0]
    };
    let turns = run.charted().crossings(|t, _, _, _| tilt_rate(t)).unwrap();
    let lowest = (turns.iter())
        .map(|&t| run.rotation_at(t, 0).unwrap().0[(2, 2)])
        .fold(1.0, f64::min);
    eprintln!(
        "{} turning points, {} switches; lowest cos θ {lowest} vs {u1}",
        turns.len(),
        run.switches().len()
    );
    assert!(turns.len() >= 4);
    assert!((lowest - u1).abs() < 1e-9, "{lowest} vs {u1}");
    assert!(run.charted().integral_drift() < 1e-10);
}

/// `EQUATIONS` says which rotations have a second chart and when a run
/// switches.
#[test]
fn the_equations_name_each_rotation_and_its_second_chart() {
    let text = EulerTop::<f64>::EQUATIONS;
    assert!(
        text.contains("atlas: `top`'s (psi, theta, phi) in z-x-z, and z-x-z after rot_x(π/2)"),
        "{text}"
    );
}

/// The segments of a still with length, rounded away from round-off: the
/// shapes (the paths of a top's fixed pivot are points).
fn drawn(segments: Vec<[nalgebra::Vector2<f64>; 2]>) -> Vec<[nalgebra::Vector2<f64>; 2]> {
    segments
        .into_iter()
        .filter(|[a, b]| (a - b).norm() > 1e-9)
        .collect()
}

/// Every consumer of an atlas run's points reads each point in its own
/// chart: the top started exactly upright runs in the second chart, and
/// its scene, its still, its table and its chart-aware crossings draw and
/// write the rotation the quaternion top has, not the second chart's angles
/// read as the user's.
#[test]
fn the_upright_tops_scene_and_table_show_the_rotation_it_has() {
    let (spin, nudge) = (30.0, 0.3);
    let run = Simulation::new(&EULER_TOP)
        .integrator(Dopri5::tol(1e-11))
        .run_atlas([0.0, 0.0, 0.0], [0.0, nudge, spin], 0.0..1.0)
        .unwrap();
    let twin = Simulation::new(&TOP)
        .integrator(Dopri5::tol(1e-11))
        .run([1.0, 0.0, 0.0, 0.0], [nudge, 0.0, spin], 0.0..1.0)
        .unwrap();
    let held = run.charted();
    // A point in the second chart, tilted: its held angles are not the user's.
    let i = held.len() / 2;
    let t = held.times()[i];
    assert_eq!(held.charts()[i], 1);
    let (q, w) = twin.state_at(t).unwrap();
    let exact = matrix(q.as_slice());
    let user = EulerChart::new([2, 0, 2]).unwrap();
    let x = held.positions()[i];
    let misread = (user.matrix([x[0], x[1], x[2]]) - exact).abs().max();
    assert!(misread > 0.1, "{misread}");
    // The scene draws the twin's rotation at that point.
    let atlas_still = drawn(run.scene(&EULER_TOP).still(t).unwrap());
    let twin_still = drawn(twin.scene(&TOP).still(t).unwrap());
    assert_eq!(atlas_still.len(), twin_still.len());
    assert!(!atlas_still.is_empty());
    let apart = (atlas_still.iter().zip(&twin_still))
        .map(|(a, b)| (a[0] - b[0]).norm().max((a[1] - b[1]).norm()))
        .fold(0.0, f64::max);
    assert!(apart < 1e-6, "{apart:e}");
    // The table writes the user's angles and rates at that point, and leaves
    // the rates empty at the exactly upright start, where they do not exist.
    let mut csv = Vec::new();
    run.table(&EULER_TOP).unwrap().write(&mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let header = rows[0][..7].join(",");
    assert_eq!(header, "t,psi,theta,phi,dot_psi,dot_theta,dot_phi");
    let kinetic = rows[0].iter().position(|&c| c == "kinetic").unwrap();
    assert_eq!(&rows[1][4..7], ["", "", ""]);
    assert_eq!(rows[1][kinetic], "");
    let row: Vec<f64> = rows[i + 1][..7]
        .iter()
        .map(|c| c.parse().unwrap())
        .collect();
    assert_eq!(row[0], t);
    let angles = [row[1], row[2], row[3]];
    assert!((user.matrix(angles) - exact).abs().max() < 1e-7);
    let omega = user.rates(angles) * Vector3::new(row[4], row[5], row[6]);
    assert!((omega - Vector3::new(w[0], w[1], w[2])).norm() < 1e-6 * spin);
    let energy: f64 = rows[i + 1][kinetic].parse().unwrap();
    let expected = TOP.kinetic_energy(&q, &w, t);
    assert!(
        (energy - expected).abs() < 1e-6 * expected,
        "{energy} {expected}"
    );
    // Crossings read each state with its charts: the tilt's cosine (chart-free
    // through the chart given) crosses half way down its range where the
    // twin's does.
    let lowest = (twin.positions().iter())
        .map(|q| matrix(q.as_slice())[(2, 2)])
        .fold(1.0, f64::min);
    let level = 0.5 * (1.0 + lowest);
    let tilt = |charts: u64, q: &SVector<f64, 3>| {
        let chart = if charts & 1 == 1 { user.second() } else { user };
        chart.matrix([q[0], q[1], q[2]])[(2, 2)] - level
    };
    let atlas_turns = held.crossings(|_, q, _, c| tilt(c, q)).unwrap();
    let twin_turns = twin
        .crossings(|_, q, _| matrix(q.as_slice())[(2, 2)] - level)
        .unwrap();
    assert_eq!(atlas_turns.len(), twin_turns.len());
    assert!(!atlas_turns.is_empty());
    for (a, b) in atlas_turns.iter().zip(&twin_turns) {
        assert!((a - b).abs() < 1e-6, "{a} {b}");
    }
}
