//! Planning with a free orientation, on the catalog's 3-D quadrotor (its
//! q̈ and derivatives emitted, `emit(jacobians)`): the step on the group
//! against central differences through the retraction, the hover's thrusts
//! against m g / 4, and the hover found from a tilted guess with the
//! attitude free (yaw left where it was: the least change).

use crate::catalog::control::Quadrotor;
use lagrange::linear::{OperatingPoint, StepMethod, Transition, Trim};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector3};
use lagrange::orientation::{self, configuration_minus, configuration_plus};

type Q7 = SVector<f64, 7>;
type V6 = SVector<f64, 6>;
type U4 = SVector<f64, 4>;

fn configuration(p: [f64; 3], turn: &lagrange::nalgebra::Vector4<f64>) -> Q7 {
    Q7::from([p[0], p[1], p[2], turn[0], turn[1], turn[2], turn[3]])
}

/// ∂x⁺/∂(x, u) by central differences through the retraction (ε = 1e-6),
/// the ends measured from F(x) in its tangent space.
fn differences(tr: &Transition<Quadrotor>, q: Q7, v: V6, u: U4) -> (DMatrix<f64>, DMatrix<f64>) {
    let quad = tr.system();
    let eps = 1e-6;
    let (q0, v0) = tr.step(&q, &v, &u, 0.0).unwrap();
    let at = |d: &DVector<f64>, du: &U4| {
        let delta = V6::from_fn(|i, _| d[i]);
        let q1 = configuration_plus(quad, &q, &delta).unwrap();
        let (q2, v2) = tr
            .step(&q1, &(v + V6::from_fn(|i, _| d[6 + i])), &(u + du), 0.0)
            .unwrap();
        let dq = configuration_minus(quad, &q2, &q0).unwrap();
        DVector::from_iterator(12, dq.iter().copied().chain((v2 - v0).iter().copied()))
    };
    let mut dx = DMatrix::zeros(12, 12);
    for j in 0..12 {
        let e = DVector::from_fn(12, |i, _| if i == j { eps } else { 0.0 });
        dx.set_column(
            j,
            &((at(&e, &U4::zeros()) - at(&-&e, &U4::zeros())) / (2.0 * eps)),
        );
    }
    let mut du = DMatrix::zeros(12, 4);
    for k in 0..4 {
        let e = U4::from_fn(|i, _| if i == k { eps } else { 0.0 });
        let none = DVector::zeros(12);
        du.set_column(k, &((at(&none, &e) - at(&none, &-e)) / (2.0 * eps)));
    }
    (dx, du)
}

/// The emitted derivatives through the stages on the group, at tumbling
/// states anywhere on the sphere with unequal thrusts, to 1e-6 of the
/// largest entry.
#[test]
fn the_quadrotor_s_step_derivatives_match_differences_through_the_retraction() {
    let quad = Quadrotor::standard();
    let states = [
        (
            [0.3, -1.0, 2.0],
            [0.2, 0.9, -0.4, 0.1],
            [1.0, -0.5, 0.2, 3.0, -2.0, 1.5],
            [1.0, 3.0, 2.0, 4.0],
        ),
        (
            [0.0, 0.0, 1.0],
            [-0.6, 0.1, 0.7, -0.3],
            [0.0, 2.0, -1.0, -6.0, 4.0, 8.0],
            [5.0, 0.0, 2.5, 1.0],
        ),
    ];
    for method in [StepMethod::Rk4, StepMethod::SemiImplicitEuler] {
        let tr = Transition::new(&quad, 0.02).unwrap().method(method);
        for (p, turn, v, u) in states {
            let turn = lagrange::nalgebra::Vector4::from(turn).normalize();
            let (q, v, u) = (configuration(p, &turn), V6::from(v), U4::from(u));
            let d = tr.derivatives(&q, &v, &u, 0.0).unwrap();
            let (dx, du) = differences(&tr, q, v, u);
            let (ex, eu) = ((&d.dx - &dx).amax(), (&d.du - &du).amax());
            assert!(
                ex < 1e-6 * dx.amax() && eu < 1e-6 * du.amax(),
                "{method:?}: ∂x {ex:e} of {:e}, ∂u {eu:e} of {:e}",
                dx.amax(),
                du.amax()
            );
        }
    }
}

/// Held level at a point, the four thrusts that hover it are m g / 4 each.
#[test]
fn the_quadrotor_hovers_on_a_quarter_of_its_weight_per_rotor() {
    let quad = Quadrotor::standard();
    let level = orientation::identity();
    let at = OperatingPoint::on_group(configuration([1.0, 2.0, 3.0], &level), V6::zeros());
    let hover = Trim::new()
        .hold(&["x", "y", "z", "att"])
        .solve(&quad, &at)
        .unwrap();
    assert!(
        (hover.u - U4::repeat(quad.hover_thrust())).amax() < 1e-12,
        "u = {}",
        hover.u
    );
    assert!(hover.residual < 1e-12);
}

/// From a tilted guess with the attitude free: the hover is level, at m g
/// / 4 per rotor, and yaw, which any hover may have, stays where the guess
/// had it (the Gauss–Newton step is the least change).
#[test]
fn the_quadrotor_s_hover_levels_a_tilted_guess_and_keeps_its_yaw() {
    let quad = Quadrotor::standard();
    let yaw = orientation::from_axis_angle(&Vector3::z(), 0.5).unwrap();
    let tilted = orientation::plus(&yaw, &Vector3::new(0.2, -0.1, 0.0)).unwrap();
    let at = OperatingPoint::on_group(configuration([0.0, 0.0, 1.0], &tilted), V6::zeros());
    let hover = Trim::new()
        .hold(&["x", "y", "z"])
        .solve(&quad, &at)
        .unwrap();
    let turn = hover.q.fixed_rows::<4>(3).into_owned();
    let r = orientation::rotation_matrix(&turn).unwrap();
    assert!(
        (r[(2, 2)] - 1.0).abs() < 1e-12,
        "the body's z axis: {}",
        r.column(2)
    );
    assert!(
        (hover.u - U4::repeat(quad.hover_thrust())).amax() < 1e-9,
        "u = {}",
        hover.u
    );
    let heading = r[(1, 0)].atan2(r[(0, 0)]);
    assert!((heading - 0.5).abs() < 0.05, "yaw {heading}");
}
