//! Free orientations in the description language (`orientation(name)`, a
//! unit quaternion with the angular velocity in body axes as its speeds),
//! against Euler's equations, the same top in Euler angles where that chart
//! is regular, and the elliptic period of the intermediate-axis flip.

use crate::catalog;
use crate::common;
use crate::floating;

use catalog::free::{
    Brick, QuaternionTop, SphericalChain, flip_half_period, sleeping_top_growth,
    sleeping_top_threshold,
};
use common::numeric::Lcg;
use floating::FloatingArm;
use lagrange::prelude::*;
use nalgebra::{Matrix3, SVector, Vector3};
use std::f64::consts::PI;

/// The same top in Euler angles z-x-z (singular at θ = 0).
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(phi, theta, psi),
    body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
         at = [0, 0, 0], rotation = euler_zxz(phi, theta, psi)),
    gravity = [0, 0, -g],
)]
struct EulerTop {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

const TOP: QuaternionTop = QuaternionTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};
const EULER_TOP: EulerTop = EulerTop {
    m: 1.5,
    a: 0.8,
    c: 0.5,
    l: 0.4,
    g: 9.81,
};

/// The Hamilton product.
fn mul([a, b, c, d]: [f64; 4], [w, x, y, z]: [f64; 4]) -> [f64; 4] {
    [
        a * w - b * x - c * y - d * z,
        a * x + b * w + c * z - d * y,
        a * y - b * z + c * w + d * x,
        a * z + b * y - c * x + d * w,
    ]
}

/// (q, ω) of Euler angles z-x-z and their rates: q = q_z(φ) q_x(θ) q_z(ψ),
/// ω in body axes.
fn from_euler(e: [f64; 3], rate: [f64; 3]) -> ([f64; 4], [f64; 3]) {
    let [phi, theta, psi] = e;
    let about_z = |a: f64| [(a / 2.0).cos(), 0.0, 0.0, (a / 2.0).sin()];
    let about_x = |a: f64| [(a / 2.0).cos(), (a / 2.0).sin(), 0.0, 0.0];
    let q = mul(mul(about_z(phi), about_x(theta)), about_z(psi));
    let [dphi, dtheta, dpsi] = rate;
    let omega = [
        dphi * theta.sin() * psi.sin() + dtheta * psi.cos(),
        dphi * theta.sin() * psi.cos() - dtheta * psi.sin(),
        dphi * theta.cos() + dpsi,
    ];
    (q, omega)
}

fn uniform(rng: &mut Lcg, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * 0.5 * (rng.next() + 1.0)
}

fn unit_quaternion(rng: &mut Lcg) -> [f64; 4] {
    let q = [0; 4].map(|_| rng.next());
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    q.map(|x| x / n)
}

fn rotation_of(q: &[f64]) -> Matrix3<f64> {
    let r = lagrange::numeric::orientation::rotation_matrix([q[0], q[1], q[2], q[3]]);
    Matrix3::from_fn(|i, j| r[i][j])
}

#[test]
fn a_free_body_has_euler_s_equations_at_every_orientation() {
    // Its moments set directly (the box's sides only draw it).
    let brick = Brick {
        a: 0.1,
        b: 0.3,
        c: 0.4,
        g: 9.81,
        ..Brick::solid(2.0, [1.0; 3])
    };
    let mut rng = Lcg(7);
    for _ in 0..20 {
        let [w, x, y, z] = unit_quaternion(&mut rng);
        let q = SVector::from([0.3, -1.0, 2.0, w, x, y, z]);
        let v = rng.vector::<6>(3.0);
        let (m, rhs) = brick.mass_matrix_and_rhs(&q, &v, 0.0);
        let diagonal = SVector::<f64, 6>::from([2.0, 2.0, 2.0, 0.1, 0.3, 0.4]);
        assert_eq!(m, nalgebra::SMatrix::<f64, 6, 6>::from_diagonal(&diagonal));
        let omega = Vector3::new(v[3], v[4], v[5]);
        let euler = -omega.cross(&Vector3::new(0.1 * v[3], 0.3 * v[4], 0.4 * v[5]));
        let expected = [0.0, 0.0, -2.0 * 9.81, euler[0], euler[1], euler[2]];
        for k in 0..6 {
            assert!(
                (rhs[k] - expected[k]).abs() < 1e-13,
                "{k}: {} vs {}",
                rhs[k],
                expected[k]
            );
        }
    }
    assert_eq!(
        Brick::COORDINATES[3..],
        ["turn.w", "turn.x", "turn.y", "turn.z"]
    );
    assert_eq!(Brick::VELOCITIES[3..], ["turn.wx", "turn.wy", "turn.wz"]);
    assert_eq!(Brick::ORIENTATIONS, &[lagrange::Orientation { q: 3, v: 3 }]);
}

/// The quaternion top's M, Q − h and energy equal the Euler-angle top's,
/// carried through the map (q, ω) = f(φ, θ, ψ, φ̇, θ̇, ψ̇): ω̇ from the
/// quaternion top against the Euler top's q̈ differentiated through ω(q, q̇).
#[test]
fn the_quaternion_top_is_the_euler_angle_top_where_that_chart_is_regular() {
    let mut rng = Lcg(11);
    for _ in 0..20 {
        let e = [
            uniform(&mut rng, -PI, PI),
            uniform(&mut rng, 0.2, 2.9),
            uniform(&mut rng, -PI, PI),
        ];
        let rate = [0; 3].map(|_| 4.0 * rng.next());
        let (quat, omega) = from_euler(e, rate);
        let (q, v) = (SVector::from(quat), SVector::from(omega));
        let (qe, ve) = (SVector::from(e), SVector::from(rate));
        let energy = TOP.integral(&q, &v, 0.0);
        let euler_energy = EULER_TOP.integral(&qe, &ve, 0.0);
        assert!(
            (energy - euler_energy).abs() < 1e-12,
            "{energy} vs {euler_energy}"
        );
        // ω̇ by the quaternion top; by the Euler top, d/dt ω(q, q̇) with the
        // Euler top's q̈, by a central difference along its motion.
        let accel = lagrange::accelerations(&TOP, &q, &v, 0.0).unwrap();
        let h = 1e-5;
        let along = |s: f64| {
            let qdd = lagrange::accelerations(&EULER_TOP, &qe, &ve, 0.0).unwrap();
            let (q1, v1) = (qe + ve * s + qdd * (0.5 * s * s), ve + qdd * s);
            from_euler(q1.into(), v1.into()).1
        };
        let (fwd, back) = (along(h), along(-h));
        for k in 0..3 {
            let d = (fwd[k] - back[k]) / (2.0 * h);
            assert!(
                (accel[k] - d).abs() < 1e-6 * (1.0 + d.abs()),
                "{k}: {} vs {d}",
                accel[k]
            );
        }
    }
}

/// Released at tilt θ₀ with spin n, the top nutates between u₀ = cos θ₀ and
/// the root of β(1 − u²) = a²(u₀ − u), a = C n / A, β = 2 m g l / A.
#[test]
fn the_quaternion_top_nutates_between_the_roots_of_the_cubic() {
    let (theta0, n) = (0.6_f64, 6.0);
    let (quat, omega) = from_euler([0.0, theta0, 0.0], [0.0, 0.0, n]);
    let traj = Simulation::new(&TOP)
        .integrator(Dop853::tol(1e-12))
        .run(quat, omega, 0.0..5.0)
        .unwrap();
    let a = TOP.c * n / TOP.a;
    let beta = 2.0 * TOP.m * TOP.g * TOP.l / TOP.a;
    let u0 = theta0.cos();
    let u1 = (a * a - (a.powi(4) - 4.0 * beta * (a * a * u0 - beta)).sqrt()) / (2.0 * beta);
    let tilt_rate = |q: &SVector<f64, 4>, v: &SVector<f64, 3>| {
        let r = rotation_of(q.as_slice());
        r[(2, 0)] * v[1] - r[(2, 1)] * v[0]
    };
    let lowest = traj
        .crossings(|_, q, v| tilt_rate(q, v))
        .unwrap()
        .iter()
        .map(|&t| rotation_of(traj.state_at(t).unwrap().0.as_slice())[(2, 2)])
        .fold(1.0, f64::min);
    assert!((lowest - u1).abs() < 1e-9, "{lowest} vs {u1}");
    assert!(traj.integral_drift() < 1e-10);
    assert!(traj.max_unit_error() < 1e-15);
}

/// Spun exactly upright, where euler_zxz's chart is singular (θ = 0), the
/// top runs; the Euler-angle top refuses that state.
#[test]
fn the_quaternion_top_runs_from_exactly_upright() {
    let traj = Simulation::new(&TOP)
        .run([1.0, 0.0, 0.0, 0.0], [0.01, 0.0, 30.0], 0.0..2.0)
        .unwrap();
    let r = rotation_of(traj.final_state().0.as_slice());
    assert!(r[(2, 2)] > 0.99, "a fast top sleeps: cos θ = {}", r[(2, 2)]);
    assert!(traj.integral_drift() < 1e-6);
    let refused = Simulation::new(&EULER_TOP).run([0.0, 0.0, 0.0], [0.0, 0.0, 30.0], 0.0..2.0);
    assert!(refused.is_err());
}

/// Twenty flips of a brick spun near its intermediate axis, at the
/// elliptic-function period of Landau–Lifshitz §37.
#[test]
fn the_derived_brick_flips_at_the_elliptic_period() {
    let brick = Brick {
        a: 1.0,
        b: 2.0,
        c: 3.0,
        ..Brick::solid(1.0, [1.0, 1.0, 1.0])
    };
    let w = [0.02_f64, 1.0, 0.03];
    let half = flip_half_period([1.0, 2.0, 3.0], w);
    let traj = Simulation::new(&brick)
        .integrator(Dop853::tol(1e-11))
        .run(
            [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, w[0], w[1], w[2]],
            0.0..20.5 * half,
        )
        .unwrap();
    let flips = traj.crossings(|_, _, v| v[4]).unwrap();
    assert_eq!(flips.len(), 20);
    let mean = (flips[19] - flips[0]) / 19.0;
    assert!((mean - half).abs() < 1e-8 * half, "{mean} vs {half}");
}

/// The sleeping top linearised in the tangent space (δθ ∈ R³, not four
/// quaternion components): the real parts of A's eigenvalues are those of
/// A ξ̈ − i C n ξ̇ − m g l ξ = 0, zero above the threshold C² n² = 4 A m g l
/// and √(4 A m g l − C² n²) / (2A) below it.
#[test]
fn the_sleeping_top_is_stable_above_the_threshold_spin() {
    let mgl = TOP.m * TOP.g * TOP.l;
    let threshold = sleeping_top_threshold(TOP.a, TOP.c, mgl);
    for ratio in [0.9, 0.99, 1.01, 1.5] {
        let n = ratio * threshold;
        let lin = Linearizer::new()
            .tangent(
                &TOP,
                &SVector::from([1.0, 0.0, 0.0, 0.0]),
                &SVector::from([0.0, 0.0, n]),
                0.0,
            )
            .unwrap();
        assert_eq!(lin.states()[..3], ["spin.θx", "spin.θy", "spin.θz"]);
        let growth = lin.eigenvalues()[0].re;
        let expected = sleeping_top_growth(TOP.a, TOP.c, mgl, n);
        eprintln!("n/n_c = {ratio}: largest real part {growth:e}, closed form {expected:e}");
        assert!(
            (growth - expected).abs() < 1e-6 * (1.0 + expected),
            "{growth} vs {expected}"
        );
    }
}

/// The same chain in Euler angles z-x-z, each joint its own three angles.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(p1, t1, s1, p2, t2, s2),
    body(arm, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, -l],
         at = [0, 0, 0], rotation = euler_zxz(p1, t1, s1)),
    point(tip, on = arm, at = [0, 0, -2 * l]),
    body(hand, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, -l],
         at = [tip.x, tip.y, tip.z], rotation = euler_zxz(p1, t1, s1) * euler_zxz(p2, t2, s2)),
    gravity = [0, 0, -g],
)]
struct EulerChain {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

#[test]
fn spherical_joints_in_a_chain_are_the_euler_angle_chain_where_it_is_regular() {
    let (m, a, c, l, g) = (1.2, 0.5, 0.1, 0.3, 9.81);
    let quat = SphericalChain { m, a, c, l, g };
    let euler = EulerChain { m, a, c, l, g };
    let mut rng = Lcg(5);
    for _ in 0..10 {
        let angles: [f64; 6] = std::array::from_fn(|k| {
            if k % 3 == 1 {
                uniform(&mut rng, 0.3, 2.8)
            } else {
                uniform(&mut rng, -PI, PI)
            }
        });
        let rates: [f64; 6] = std::array::from_fn(|_| 2.0 * rng.next());
        let (e1, e2) = (
            [angles[0], angles[1], angles[2]],
            [angles[3], angles[4], angles[5]],
        );
        let (r1, r2) = (
            [rates[0], rates[1], rates[2]],
            [rates[3], rates[4], rates[5]],
        );
        let map = |e1, e2, r1, r2| {
            let ((q1, w1), (q2, w2)) = (from_euler(e1, r1), from_euler(e2, r2));
            let q: SVector<f64, 8> = SVector::from_iterator(q1.into_iter().chain(q2));
            let v: SVector<f64, 6> = SVector::from_iterator(w1.into_iter().chain(w2));
            (q, v)
        };
        let (q, v) = map(e1, e2, r1, r2);
        let (qe, ve) = (SVector::from(angles), SVector::from(rates));
        let (energy, euler_energy) = (quat.integral(&q, &v, 0.0), euler.integral(&qe, &ve, 0.0));
        assert!(
            (energy - euler_energy).abs() < 1e-12,
            "{energy} vs {euler_energy}"
        );
        let accel = lagrange::accelerations(&quat, &q, &v, 0.0).unwrap();
        let qdd = lagrange::accelerations(&euler, &qe, &ve, 0.0).unwrap();
        let along = |s: f64| {
            let (q1, v1) = (qe + ve * s + qdd * (0.5 * s * s), ve + qdd * s);
            let e = |x: SVector<f64, 6>, k: usize| [x[k], x[k + 1], x[k + 2]];
            map(e(q1, 0), e(q1, 3), e(v1, 0), e(v1, 3)).1
        };
        let h = 1e-5;
        let (fwd, back) = (along(h), along(-h));
        for k in 0..6 {
            let d = (fwd[k] - back[k]) / (2.0 * h);
            assert!(
                (accel[k] - d).abs() < 1e-6 * (1.0 + d.abs()),
                "{k}: {} vs {d}",
                accel[k]
            );
        }
    }
}

const PINOCCHIO_Q: [f64; 9] = [
    0.1,
    -0.2,
    0.3,
    0.7,
    -0.4,
    0.8295613557843402,
    0.20739033894608505,
    -0.4147806778921701,
    0.3110855084191276,
];
const PINOCCHIO_V: [f64; 8] = [0.3, -0.1, 0.2, 0.5, -0.8, 0.4, -0.6, 0.9];
const PINOCCHIO_M: [[f64; 8]; 8] = [
    [
        7.5,
        -3.470457820992685e-16,
        -1.8137878758184138e-16,
        -0.6908167237583464,
        0.07201089309653413,
        -0.0574123144033089,
        1.035987538776299,
        -1.3225371538658732,
    ],
    [
        -3.470457820992685e-16,
        7.5,
        4.045016528152149e-16,
        0.2760469096494975,
        0.12567534263953878,
        -0.8779703597866136,
        1.0297692338596605,
        0.7303479849183148,
    ],
    [
        -1.8137878758184138e-16,
        4.045016528152149e-16,
        7.5,
        -0.38611023952947454,
        -0.038988966745401865,
        0.40215501358570954,
        -0.3364170233642675,
        -0.5258951857660336,
    ],
    [
        -0.6908167237583464,
        0.2760469096494975,
        -0.38611023952947454,
        0.4173405700806056,
        0.0,
        -0.15636996376057605,
        -0.13170860352896602,
        0.663654108004809,
    ],
    [
        0.07201089309653413,
        0.12567534263953878,
        -0.038988966745401865,
        0.0,
        0.042499999999999996,
        -0.08432309913482881,
        0.12515682330725753,
        0.0068215046227499245,
    ],
    [
        -0.0574123144033089,
        -0.8779703597866136,
        0.40215501358570954,
        -0.15636996376057605,
        -0.08432309913482881,
        0.8440211859079535,
        -0.4993362353348936,
        -0.3238937891644654,
    ],
    [
        1.035987538776299,
        1.0297692338596605,
        -0.3364170233642675,
        -0.13170860352896602,
        0.12515682330725753,
        -0.4993362353348936,
        1.4890501594975785,
        -0.18754987866359576,
    ],
    [
        -1.3225371538658732,
        0.7303479849183148,
        -0.5258951857660336,
        0.663654108004809,
        0.0068215046227499245,
        -0.3238937891644654,
        -0.18754987866359576,
        1.7599676459290126,
    ],
];
const PINOCCHIO_ACCEL: [f64; 8] = [
    -0.08038626277215381,
    0.2288932371846933,
    -9.460747315849554,
    -0.3489975968811522,
    1.2896847046166058,
    -0.034690651250735005,
    0.14557427340742118,
    0.393159401969949,
];

#[test]
fn a_floating_base_matches_pinocchio_s_free_flyer() {
    let arm = FloatingArm { g: 9.81 };
    let (q, v) = (SVector::from(PINOCCHIO_Q), SVector::from(PINOCCHIO_V));
    let m = arm.mass_matrix(&q, 0.0);
    for i in 0..8 {
        for j in 0..8 {
            let (ours, theirs) = (m[(i, j)], PINOCCHIO_M[i][j]);
            assert!(
                (ours - theirs).abs() < 1e-12,
                "M[{i}][{j}]: {ours} vs {theirs}"
            );
        }
    }
    let accel = lagrange::accelerations(&arm, &q, &v, 0.0).unwrap();
    for k in 0..8 {
        let (ours, theirs) = (accel[k], PINOCCHIO_ACCEL[k]);
        assert!(
            (ours - theirs).abs() < 1e-12,
            "accel[{k}]: {ours} vs {theirs}"
        );
    }
}

/// The floating arm's Coriolis matrix: with orientations C is taken in the
/// chart moving with the body (the tree route builds M at the chart's
/// centre; C comes from T in the chart), so C v = h (without gravity, −(Q − h))
/// and Ṁ − 2C is skew-symmetric, Ṁ along the motion (M at q ⊕ ±ε v by
/// central differences).
#[test]
fn the_coriolis_matrix_with_a_free_orientation_factors_h_and_is_passive() {
    let arm = FloatingArm { g: 0.0 };
    let n = (0.8f64 * 0.8 + 0.2 * 0.2 + 0.4 * 0.4 + 0.3 * 0.3).sqrt();
    let q = SVector::<f64, 9>::from([
        0.1,
        -0.2,
        0.3,
        0.7,
        -0.4,
        0.8 / n,
        0.2 / n,
        -0.4 / n,
        0.3 / n,
    ]);
    let v = SVector::<f64, 8>::from([0.3, -0.1, 0.2, 0.5, -0.8, 0.4, -0.6, 0.9]);
    assert_eq!(FloatingArm::ROUTE, lagrange::Route::Recursive);
    let c = arm.coriolis_matrix(&q, &v, 0.0);
    let (_, rhs) = arm.mass_matrix_and_rhs(&q, &v, 0.0);
    let h = -rhs;
    assert!(
        (c * v - h).amax() < 1e-12 * (1.0 + h.amax()),
        "{}",
        (c * v - h).amax()
    );
    let eps = 1e-6;
    let moved = |s: f64| {
        let mut out = [0.0; 9];
        let step: Vec<f64> = v.iter().map(|x| x * s).collect();
        lagrange::numeric::orientation::integrate(
            FloatingArm::ORIENTATIONS,
            q.as_slice(),
            &step,
            &mut out,
        );
        arm.mass_matrix(&SVector::from(out), 0.0)
    };
    let m_dot = (moved(eps) - moved(-eps)) / (2.0 * eps);
    let s = m_dot - c * 2.0;
    let skew = (s + s.transpose()).amax();
    eprintln!("|C v - h| = {:e}, |S + Sᵀ| = {skew:e}", (c * v - h).amax());
    assert!(skew < 1e-8, "{skew:e}");
}
