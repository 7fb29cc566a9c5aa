//! Planning on the group: a body on a pivot (a free orientation beside a
//! sprung cart, `PivotedBody`) turned to a target attitude. The
//! cost's error is x ⊖ x* (an attitude's is the rotation angle), its model
//! is the derivative along x ⊕ δ, the plan ends at the target attitude with
//! unit quaternions, and from a guess of the states that does not satisfy
//! the dynamics (gaps as tangent vectors) FDDP closes the gaps and reaches
//! the same plan.

use super::ddp::Ddp;
use super::passes::from_guess;
use super::problem::{OptimalControl, state};
use crate::linear::Transition;
use crate::linear::test_systems::PivotedBody;
use crate::numeric::orientation;
use nalgebra::{DMatrix, DVector, SVector};

/// Without gravity's lever: a free body's attitude (Euler's equations)
/// beside the cart its tilt pushes.
const BODY: PivotedBody = PivotedBody {
    inertia: [0.3, 0.5, 0.7],
    lever: 0.0,
};
const STEPS: usize = 20;

fn configuration(x: f64, turn: [f64; 4]) -> SVector<f64, 5> {
    SVector::from([x, turn[0], turn[1], turn[2], turn[3]])
}

/// Hanging: the body's z axis (its centre of mass) down.
fn hanging() -> [f64; 4] {
    orientation::exp([std::f64::consts::PI, 0.0, 0.0])
}

/// Hanging, turned 1.2 rad about a tilted axis in body axes.
fn target() -> [f64; 4] {
    orientation::multiply(hanging(), orientation::exp([0.6, -0.4, 0.9]))
}

/// The angle between the body's attitude in q and `turn`.
fn angle(q: &SVector<f64, 5>, turn: [f64; 4]) -> f64 {
    let mut d = [0.0; 3];
    let at = [q[1], q[2], q[3], q[4]];
    orientation::difference(
        &[orientation::Orientation { q: 0, v: 0 }],
        &turn,
        &at,
        &mut d,
    );
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// From hanging at rest to the target attitude at rest in 2 s, the torques
/// within ±0.4 N·m; the cart's push too.
fn turn() -> OptimalControl<'static, PivotedBody, 4, 4, 5> {
    let tr = Transition::new(&BODY, 0.1).unwrap();
    let start = (configuration(0.0, hanging()), SVector::zeros());
    let weight = |d: [f64; 8]| DMatrix::from_diagonal(&DVector::from_column_slice(&d));
    OptimalControl::new(
        tr,
        STEPS,
        start,
        weight([0.0; 8]),
        DMatrix::identity(4, 4) * 0.01,
    )
    .goal(configuration(0.0, target()), SVector::zeros())
    .final_weight(weight([100.0, 1e3, 1e3, 1e3, 10.0, 10.0, 10.0, 10.0]))
    .input_bounds(SVector::repeat(-0.4), SVector::repeat(0.4))
}

/// The cost of an attitude off the goal by φ about any axis is ½ w φ², and
/// its model's gradient is the derivative along x ⊕ δ.
#[test]
fn the_cost_measures_the_attitude_by_its_angle() {
    let problem = turn();
    let w = 1e3;
    for (axis, phi) in [([1.0, 0.0, 0.0], 0.3), ([0.0, 0.6, 0.8], 2.5)] {
        let off = orientation::multiply(target(), orientation::exp(axis.map(|a| a * phi)));
        let x = state(&configuration(0.0, off), &SVector::<f64, 4>::zeros());
        let cost = problem.terminal(&x);
        assert!((cost - 0.5 * w * phi * phi).abs() < 1e-12 * w, "{cost}");
    }
    let turned = orientation::exp([0.2, 1.1, -0.7]);
    let x = state(
        &configuration(0.3, turned),
        &SVector::<f64, 4>::from([0.1, -0.5, 0.4, 1.0]),
    );
    let model = problem.final_model(&x).unwrap();
    let eps = 1e-6;
    for j in 0..8 {
        let e = DVector::from_fn(8, |i, _| if i == j { eps } else { 0.0 });
        let (up, down) = (problem.plus(&x, &e), problem.plus(&x, &-e));
        let slope = (problem.terminal(&up) - problem.terminal(&down)) / (2.0 * eps);
        assert!(
            (slope - model.lx[j]).abs() < 1e-6 * model.lx.amax(),
            "{j}: {slope} vs {}",
            model.lx[j]
        );
    }
}

/// FDDP on the group turns the body to the target from a guess of the
/// states that is not a motion of it (a slerp at a constant rate, no push,
/// no torque: its gaps are tangent vectors): the gaps closed, unit
/// quaternions all along, the final attitude within a hundredth of a
/// radian, the torques in their box. And the plan is an optimum of the
/// problem the solve from inputs sees: from its inputs, DDP stops at once
/// with the same cost.
#[test]
fn fddp_turns_a_body_to_a_target_attitude_from_a_guess_with_gaps() {
    let problem = turn();
    let rate = [0.6, -0.4, 0.9].map(|r| r / (STEPS as f64 * 0.1));
    let q: Vec<_> = (0..=STEPS)
        .map(|k| {
            let turned = orientation::exp(rate.map(|r| r * k as f64 * 0.1));
            configuration(0.0, orientation::multiply(hanging(), turned))
        })
        .collect();
    let v = vec![SVector::<f64, 4>::from([0.0, rate[0], rate[1], rate[2]]); STEPS + 1];
    let u = vec![SVector::<f64, 4>::zeros(); STEPS];
    let guess = from_guess(&problem, (&q, &v, &u), "test").unwrap();
    assert!(guess.gap() > 0.1, "the guess has gaps: {}", guess.gap());
    let plan = Ddp::new()
        .tolerance(1e-6)
        .solve_from(&problem, &q, &v, &u)
        .unwrap();
    assert_eq!(plan.gap, 0.0);
    let last = plan.q[STEPS];
    assert!(angle(&last, target()) < 1e-2, "{}", angle(&last, target()));
    for q in &plan.q {
        let norm = (q[1] * q[1] + q[2] * q[2] + q[3] * q[3] + q[4] * q[4]).sqrt();
        assert!((norm - 1.0).abs() < 1e-12);
    }
    assert!(plan.u.iter().all(|u| u.amax() <= 0.4));
    assert!(
        plan.u.iter().any(|u| u.amax() == 0.4),
        "no torque at its bound"
    );
    let again = Ddp::new().tolerance(1e-6).solve(&problem, &plan.u).unwrap();
    assert!(again.log.len() <= 2, "{} iterations", again.log.len());
    assert!(
        (again.cost - plan.cost).abs() < 1e-9 * plan.cost,
        "{} vs {}",
        again.cost,
        plan.cost
    );
}

/// A waypoint counts at its time alone, measures the attitude by its angle
/// there, and its model's gradient is the derivative along x ⊕ δ; a weight
/// of the wrong size is refused.
#[test]
fn a_waypoint_measures_its_state_at_its_time_alone() {
    use super::cost::{Cost, Waypoint};
    let w = DMatrix::from_diagonal(&DVector::from_column_slice(&[
        0.0, 5.0, 5.0, 5.0, 0.0, 0.0, 0.0, 0.0,
    ]));
    let through = (configuration(0.0, target()), SVector::<f64, 4>::zeros());
    let point = Waypoint::new(&BODY, 0.7, through, w.clone()).unwrap();
    let off = orientation::multiply(target(), orientation::exp([0.0, 0.0, 0.4]));
    let (q, v) = (
        configuration(1.0, off),
        SVector::<f64, 4>::from([1.0, 2.0, 0.0, 0.0]),
    );
    let value = |t: f64, q: &SVector<f64, 5>| Cost::<4, 4, 5>::value(&point, t, q, &v, None);
    assert_eq!(value(0.6, &q), 0.0);
    assert!((value(0.7, &q) - 0.5 * 5.0 * 0.16).abs() < 1e-14);
    let model = Cost::<4, 4, 5>::model(&point, 0.7, &q, &v, None);
    let x = state(&q, &v);
    let problem = turn();
    let eps = 1e-6;
    for j in 0..8 {
        let e = DVector::from_fn(8, |i, _| if i == j { eps } else { 0.0 });
        let at = |x: DVector<f64>| value(0.7, &SVector::from_fn(|i, _| x[i]));
        let slope = (at(problem.plus(&x, &e)) - at(problem.plus(&x, &-e))) / (2.0 * eps);
        assert!(
            (slope - model.lx[j]).abs() < 1e-8,
            "{j}: {slope} vs {}",
            model.lx[j]
        );
    }
    assert!(Waypoint::new(&BODY, 0.7, through, DMatrix::identity(4, 4)).is_err());
}
