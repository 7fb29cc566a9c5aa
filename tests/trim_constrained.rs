//! Equilibria of constrained systems (`Trim::solve_constrained`) against
//! closed forms: a bob on a rod written in (x, y) held out by a sideways
//! force (m g tan θ, from a guess off the rod) and left where a constant
//! force puts it; a two-link arm whose tool a wall holds, its torques the
//! least-norm ones (gravity's torques less what the wall can take, by the
//! projection onto G's null space); a rod with a free orientation pinned at
//! its tip and held tilted by a body torque (m g l sin α); Chaplygin's ball
//! rolling straight, a steady motion of its nonholonomic rows, and the
//! same ball slipping, which has none; and a pose the constraint cannot
//! reach, a typed error.

use lagrange::LinearError;
use lagrange::linear::{OperatingPoint, Trim};
use lagrange::prelude::*;
use nalgebra::{DMatrix, DVector, SVector, Vector1, Vector2};

use crate::constrained_control::ROD;

/// A bob on a rod of length l, in (x, y), pushed sideways by f.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    inputs(f),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    force(bob, [f, 0]),
    holonomic(rod = x * x + y * y - l * l),
)]
struct Pushed {
    m: f64,
    l: f64,
    g: f64,
}

const BOB: Pushed = Pushed {
    m: 2.0,
    l: 1.5,
    g: 9.81,
};

#[test]
fn a_bob_on_a_rod_held_out_and_pushed() {
    for x in [0.3, 0.9, -1.2] {
        // The guess is off the rod (y = −1 whatever x): the search brings
        // it on.
        let guess = OperatingPoint::new(Vector2::new(x, -1.0), Vector2::zeros());
        let held = Trim::new()
            .hold(&["x"])
            .solve_constrained(&BOB, &guess)
            .expect("an equilibrium");
        let theta = (x / BOB.l).asin();
        let force = BOB.m * BOB.g * theta.tan();
        eprintln!(
            "x = {x}: f = {} (m g tan θ = {force}), {} iterations",
            held.u[0], held.iterations
        );
        assert!((held.u[0] - force).abs() < 1e-9, "{}", held.u[0]);
        assert!((held.q[1] + BOB.l * theta.cos()).abs() < 1e-10);
        assert_eq!(held.q[0], x);
        assert!(held.residual <= 1e-10);
    }
    // A constant force of 5 N leaves it at tan θ = f / (m g).
    let guess =
        OperatingPoint::new(Vector2::new(0.1, -1.5), Vector2::zeros()).input(Vector1::new(5.0));
    let rest = Trim::new()
        .hold_inputs(&["f"])
        .solve_constrained(&BOB, &guess)
        .expect("an equilibrium");
    let theta = (5.0 / (BOB.m * BOB.g)).atan();
    assert!(
        (rest.q[0] - BOB.l * theta.sin()).abs() < 1e-10,
        "{}",
        rest.q
    );
    assert!(
        (rest.q[1] + BOB.l * theta.cos()).abs() < 1e-10,
        "{}",
        rest.q
    );
}

/// Two links in the vertical plane, torques at both joints, the tool's x
/// held on a wall at x = c.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(q1, q2),
    inputs(u1, u2),
    body(link1, mass = m1, inertia = [0.01, 0.02, 0.09], com = [0.3, 0, 0],
         at = [0, 0, 0], rotation = rot_z(q1)),
    point(elbow, on = link1, at = [l1, 0, 0]),
    body(link2, mass = m2, inertia = [0.01, 0.02, 0.05], com = [0.25, 0, 0],
         at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
    point(tool, on = link2, at = [l2, 0, 0]),
    gravity = [0, -9.81, 0],
    generalized_force(q1 = u1, q2 = u2),
    holonomic(wall = tool.x - c),
    emit(inverse_dynamics),
)]
struct OnTheWall {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    c: f64,
}

const ARM: OnTheWall = OnTheWall {
    m1: 2.0,
    m2: 1.5,
    l1: 0.7,
    l2: 0.6,
    c: 0.9,
};

/// The wall takes what it can of gravity's torques: held still, the arm
/// needs only the part of them the wall's row cannot take, u = (1 − Gᵀ(G
/// Gᵀ)⁻¹G) ∂V/∂q, the least-norm torques.
#[test]
fn a_tool_held_by_a_wall_takes_the_least_norm_torques() {
    // q1 held; q2 found on the wall from a guess off it (on the same side
    // of the elbow's fold, where the tool is furthest out, as the answer).
    let guess = OperatingPoint::new(Vector2::new(0.4, 0.5), Vector2::zeros());
    let held = Trim::new()
        .hold(&["q1"])
        .solve_constrained(&ARM, &guess)
        .expect("an equilibrium");
    let q = held.q;
    let tool_x = ARM.l1 * q[0].cos() + ARM.l2 * (q[0] + q[1]).cos();
    assert!((tool_x - ARM.c).abs() < 1e-10, "tool at x = {tool_x}");
    let gravity = ARM.gravity_torques(&q, 0.0).expect("emitted");
    let (g, _) = ARM.constraint_jacobian(&q, 0.0);
    let g = DMatrix::from_row_slice(1, 2, g.as_slice());
    let gravity = DVector::from_column_slice(gravity.as_slice());
    let along = &g.transpose() * (&g * &g.transpose()).try_inverse().expect("a row") * &g;
    let least = (DMatrix::identity(2, 2) - along) * &gravity;
    let u = DVector::from_column_slice(held.u.as_slice());
    eprintln!("u = {u:?}, projection = {least:?}");
    assert!((&u - &least).amax() < 1e-8, "{u} against {least}");
    // Nothing of them pushes on the wall, and less than holding the arm
    // without it.
    assert!((&g * &u)[0].abs() < 1e-8);
    assert!(u.norm() < gravity.norm());
}

/// A rod pinned at its tip by three rows, turned by α about x and held
/// there by a body torque: τx = m g l sin α about the pin, the others zero.
#[test]
fn a_pinned_rod_with_a_free_orientation_held_tilted() {
    let alpha: f64 = 0.4;
    let half = 0.5 * alpha;
    let turn = [half.cos(), half.sin(), 0.0, 0.0];
    // Its centre guessed upright above the pin, not where the turn puts it.
    let q = SVector::<f64, 7>::from([0.0, 0.0, ROD.l, turn[0], turn[1], turn[2], turn[3]]);
    let guess = OperatingPoint::on_group(q, SVector::<f64, 6>::zeros());
    let held = Trim::new()
        .hold(&["turn"])
        .solve_constrained(&ROD, &guess)
        .expect("an equilibrium");
    let want = ROD.m * ROD.g * ROD.l * alpha.sin();
    eprintln!("τ = {:?} (m g l sin α = {want})", held.u);
    assert!((held.u[0].abs() - want).abs() < 1e-8, "{}", held.u);
    assert!(
        held.u[1].abs() < 1e-8 && held.u[2].abs() < 1e-8,
        "{}",
        held.u
    );
    // The centre is where the turn puts it: l (0, −sin α, cos α).
    let centre = [held.q[0], held.q[1], held.q[2]];
    let expected = [0.0, -ROD.l * alpha.sin(), ROD.l * alpha.cos()];
    for (got, want) in centre.iter().zip(expected) {
        assert!((got - want).abs() < 1e-10, "{centre:?}");
    }
}

/// A pose the rod cannot take: held at x = 2 > l, the rod's residual
/// x² + y² − l² is at least 4 − l² = 1.75 wherever y goes, and the search
/// says so with the best point it reached (naming whichever residual is
/// largest there: the acceleration the reaction cannot balance off the
/// rod, here).
#[test]
fn a_pose_off_the_constraint_is_a_typed_error() {
    let guess = OperatingPoint::new(Vector2::new(2.0, -1.0), Vector2::zeros());
    let err = Trim::new()
        .hold(&["x"])
        .solve_constrained(&BOB, &guess)
        .expect_err("no equilibrium");
    eprintln!("{err}");
    match err {
        lagrange::Error::Linear(LinearError::NoEquilibrium { residual, best, .. }) => {
            assert!(residual >= 1.75 - 1e-12, "{residual}");
            assert_eq!(best.q[0], 2.0);
        }
        other => panic!("{other:?}"),
    }
}

/// Chaplygin's ball (unequal moments) rolling straight along x about its
/// principal y axis: ω along a principal axis stays there (ω × Jω = 0), so
/// every rate is steady, q̈ = 0. From a guess sunk into the plane the search
/// finds the height a and keeps the speeds; a guess that slips (ω ≠ v/a) has
/// no steady motion on the constraints, and the rolling row is named.
#[test]
fn a_ball_rolling_straight_is_a_steady_motion_of_its_rows() {
    use crate::rolling::BALL;
    let speed = 1.2;
    let v = SVector::<f64, 6>::from([speed, 0.0, 0.0, 0.0, speed / BALL.a, 0.0]);
    let q = SVector::<f64, 7>::from([0.3, -0.2, 0.5 * BALL.a, 1.0, 0.0, 0.0, 0.0]);
    let steady = Trim::new()
        .solve_constrained(&BALL, &OperatingPoint::on_group(q, v))
        .expect("a steady motion");
    // To the search's tolerance, 1e-10.
    assert!((steady.q[2] - BALL.a).abs() < 1e-10, "z = {}", steady.q[2]);
    assert_eq!(steady.v, v);
    // Only the height moved: the minimum-norm step.
    assert!((steady.q[0] - 0.3).abs() < 1e-10 && (steady.q[1] + 0.2).abs() < 1e-10);
    let slipping = SVector::<f64, 6>::from([speed, 0.0, 0.0, 0.0, 0.5 * speed / BALL.a, 0.0]);
    let err = Trim::new()
        .solve_constrained(&BALL, &OperatingPoint::on_group(q, slipping))
        .expect_err("no steady motion");
    match err {
        lagrange::Error::Linear(LinearError::NoEquilibrium {
            worst, residual, ..
        }) => {
            assert_eq!(worst, "velocity of constraint `slip_x`");
            assert!((residual - 0.5 * speed).abs() < 1e-12, "{residual}");
        }
        other => panic!("{other:?}"),
    }
}

/// A bob on a rod written with a square root, guessed where the root has
/// no value: a typed error at the guess, not an answer with a NaN in it.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(x, y),
    inputs(f),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    force(bob, [f, 0]),
    holonomic(rod = sqrt(l * l - x * x) + y),
)]
struct RootRod {
    m: f64,
    l: f64,
    g: f64,
}

#[test]
fn a_guess_where_a_constraint_has_no_value_is_refused() {
    let rod = RootRod {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let guess = OperatingPoint::new(Vector2::new(1.5, -1.0), Vector2::zeros());
    let err = Trim::new()
        .hold(&["x"])
        .solve_constrained(&rod, &guess)
        .expect_err("no value at the guess");
    eprintln!("{err}");
    // The multiplier form refuses the point, naming it.
    match err {
        lagrange::Error::NonFiniteState { q, .. } => assert_eq!(q, [1.5, -1.0]),
        other => panic!("{other:?}"),
    }
}
