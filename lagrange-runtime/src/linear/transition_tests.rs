//! The step against closed forms (a body under constant thrust, a linear
//! oscillator whose RK4 step is the Taylor polynomial of e^{hA}) and its
//! derivatives against central differences of the step itself.

use super::*;
use crate::linear::test_systems::{
    G, Oscillator, Pendulum, PivotedBody, SPHERICAL_STATES, Spherical, Thrusters,
};
use crate::orientation::tests::CartAndBall;
use crate::system::Lagrangian;
use nalgebra::{DVector, Matrix2, Vector1, Vector2};

const METHODS: [StepMethod; 2] = [StepMethod::Rk4, StepMethod::SemiImplicitEuler];

/// ∂x⁺/∂(x, u) by central differences of `step`, ε = 1e-6.
fn differences<S, const N: usize, const P: usize>(
    tr: &Transition<S>,
    q: SVector<f64, N>,
    v: SVector<f64, N>,
    u: SVector<f64, P>,
) -> (DMatrix<f64>, DMatrix<f64>)
where
    S: Driven<f64, N, P>,
{
    let eps = 1e-6;
    let flat = |(q, v): (SVector<f64, N>, SVector<f64, N>)| {
        DMatrix::from_iterator(2 * N, 1, q.iter().chain(v.iter()).copied())
    };
    let at = |q: SVector<f64, N>, v: SVector<f64, N>, u: SVector<f64, P>| {
        flat(tr.step(&q, &v, &u, 0.3).unwrap())
    };
    let mut dx = DMatrix::zeros(2 * N, 2 * N);
    for j in 0..2 * N {
        let (mut qp, mut vp, mut qm, mut vm) = (q, v, q, v);
        if j < N {
            qp[j] += eps;
            qm[j] -= eps;
        } else {
            vp[j - N] += eps;
            vm[j - N] -= eps;
        }
        dx.set_column(
            j,
            &((at(qp, vp, u) - at(qm, vm, u)) / (2.0 * eps)).column(0),
        );
    }
    let mut du = DMatrix::zeros(2 * N, P);
    for k in 0..P {
        let (mut up, mut um) = (u, u);
        up[k] += eps;
        um[k] -= eps;
        du.set_column(k, &((at(q, v, up) - at(q, v, um)) / (2.0 * eps)).column(0));
    }
    (dx, du)
}

/// ÿ = u₁ + u₂ − g is a polynomial motion: RK4 is exact, semi-implicit
/// Euler puts the velocity's change into the position a step early.
#[test]
fn constant_thrust_in_closed_form() {
    let (h, y, vy) = (0.1, 2.0, -0.5);
    let u = Vector2::new(3.0, 4.0);
    let acc = u.sum() - G;
    for method in METHODS {
        let tr = Transition::new(&Thrusters, h).unwrap().method(method);
        let d = tr
            .derivatives(&Vector1::new(y), &Vector1::new(vy), &u, 0.0)
            .unwrap();
        let (y1, dq_dv, dq_du) = match method {
            StepMethod::Rk4 => (y + vy * h + 0.5 * acc * h * h, h, 0.5 * h * h),
            StepMethod::SemiImplicitEuler => (y + (vy + acc * h) * h, h, h * h),
        };
        assert!((d.q[0] - y1).abs() < 1e-14, "{method:?}: y⁺ = {}", d.q[0]);
        assert!((d.v[0] - (vy + acc * h)).abs() < 1e-14);
        let dx = DMatrix::from_row_slice(2, 2, &[1.0, dq_dv, 0.0, 1.0]);
        let du = DMatrix::from_row_slice(2, 2, &[dq_du, dq_du, h, h]);
        assert!((&d.dx - dx).amax() < 1e-12, "{method:?}: {}", d.dx);
        assert!((&d.du - du).amax() < 1e-12, "{method:?}: {}", d.du);
    }
}

/// For ẋ = A x + B u, RK4's step is x⁺ = T(hA) x + h S(hA) B u with T the
/// Taylor polynomial of e^z to degree 4 and S(z) = Σ_{k<4} z^k / (k+1)!.
#[test]
fn rk4_on_a_linear_oscillator_is_the_taylor_polynomial() {
    let (k, c, h) = (4.0, 0.3, 0.2);
    let osc = Oscillator { k, c };
    let a = Matrix2::new(0.0, 1.0, -k, -c);
    let z = a * h;
    let (mut t, mut s, mut power, mut factorial) = (
        Matrix2::identity(),
        Matrix2::zeros(),
        Matrix2::identity(),
        1.0,
    );
    for n in 1..=4 {
        s += power / (factorial * n as f64);
        power *= z;
        factorial *= n as f64;
        t += power / factorial;
    }
    let tr = Transition::new(&osc, h).unwrap();
    let d = tr
        .derivatives(
            &Vector1::new(0.4),
            &Vector1::new(-1.0),
            &Vector1::new(0.7),
            0.0,
        )
        .unwrap();
    let du = s * Vector2::new(0.0, 1.0) * h;
    assert!(
        (d.dx.clone() - DMatrix::from_iterator(2, 2, t.iter().copied())).amax() < 1e-14,
        "{}",
        d.dx
    );
    assert!((d.du.column(0) - du).amax() < 1e-14, "{}", d.du);
    let x1 = t * Vector2::new(0.4, -1.0) + du * 0.7;
    assert!((Vector2::new(d.q[0], d.v[0]) - x1).amax() < 1e-14);
}

/// Nonlinear, velocity-dependent, two inputs: the chain rule through the
/// stages against central differences of the step, at several states.
#[test]
fn derivatives_match_differences_of_the_step() {
    let sys = Spherical { l: 0.9 };
    let states = SPHERICAL_STATES;
    for method in METHODS {
        let tr = Transition::new(&sys, 0.05).unwrap().method(method);
        for (q, v, u) in states {
            let d = tr.derivatives(&q, &v, &u, 0.3).unwrap();
            let (dx, du) = differences(&tr, q, v, u);
            let (ex, eu) = ((&d.dx - &dx).amax(), (&d.du - &du).amax());
            assert!(
                ex < 1e-7 && eu < 1e-7,
                "{method:?} at {q:?}: ∂x {ex:e}, ∂u {eu:e}"
            );
        }
    }
    let tr = Transition::new(&Pendulum, 0.01).unwrap();
    let (q, v, u) = (Vector1::new(2.0), Vector1::new(-0.5), Vector1::new(1.0));
    let d = tr.derivatives(&q, &v, &u, 0.3).unwrap();
    let (dx, du) = differences(&tr, q, v, u);
    assert!((&d.dx - dx).amax() < 1e-8 && (&d.du - du).amax() < 1e-8);
}

#[test]
fn bad_steps_and_inputs() {
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = Transition::new(&Pendulum, h).unwrap_err();
        assert!(
            matches!(e, Error::Settings(SettingsError::Value { .. })),
            "h = {h}: {e}"
        );
    }
    let tr = Transition::new(&Pendulum, 0.01).unwrap();
    let e = tr
        .step(
            &Vector1::new(0.1),
            &Vector1::new(0.0),
            &Vector1::new(f64::NAN),
            0.0,
        )
        .unwrap_err();
    assert!(matches!(e, Error::NonFiniteInput { .. }), "{e}");
    assert_eq!(tr.h(), 0.01);
}

/// The stages' derivatives on the stack give the numbers the stages'
/// linearisations gave: the same Jacobians of the emitted path (the
/// oscillator) and the same central differences (the others).
#[test]
fn the_fast_stages_are_the_linearizer_s() {
    let (q, v, u) = (
        Vector2::new(0.7, 0.2),
        Vector2::new(0.3, 2.0),
        Vector2::new(0.5, -0.2),
    );
    let sys = Spherical { l: 0.9 };
    for method in METHODS {
        let fast = Transition::new(&sys, 0.05).unwrap().method(method);
        let slow = fast.clone().through_linearizer(true);
        let (a, b) = (
            fast.derivatives(&q, &v, &u, 0.3).unwrap(),
            slow.derivatives(&q, &v, &u, 0.3).unwrap(),
        );
        assert!(
            (&a.dx - &b.dx).amax() < 1e-12 && (&a.du - &b.du).amax() < 1e-12,
            "{method:?}"
        );
        assert!((a.q - b.q).amax() < 1e-15 && (a.v - b.v).amax() < 1e-15);
        let osc = Oscillator { k: 4.0, c: 0.3 };
        let fast = Transition::new(&osc, 0.05).unwrap().method(method);
        let slow = fast.clone().through_linearizer(true);
        let (q, v, u) = (Vector1::new(0.4), Vector1::new(-1.0), Vector1::new(0.7));
        let (a, b) = (
            fast.derivatives(&q, &v, &u, 0.0).unwrap(),
            slow.derivatives(&q, &v, &u, 0.0).unwrap(),
        );
        assert!(
            (&a.dx - &b.dx).amax() < 1e-15 && (&a.du - &b.du).amax() < 1e-15,
            "{method:?}"
        );
    }
}

/// A unit quaternion and a vector of numbers in [−1, 1) from a seed (a
/// small xorshift: the states are arbitrary, not chosen).
fn arbitrary<const M: usize>(seed: &mut u64) -> SVector<f64, M> {
    SVector::from_fn(|_, _| {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    })
}

/// ∂x⁺/∂(x, u) of a system with orientations by central differences taken
/// through the retraction: (F(x ⊕ ε e_j) ⊖ F(x ⊕ −ε e_j)) / 2ε, the ⊖ of
/// the ends measured from F(x) (ε = 1e-6).
fn group_differences<S, const N: usize, const P: usize, const Q: usize>(
    tr: &Transition<S>,
    (q, v, u): (SVector<f64, Q>, SVector<f64, N>, SVector<f64, P>),
) -> (DMatrix<f64>, DMatrix<f64>)
where
    S: Driven<f64, N, P, Q>,
{
    let (eps, layout) = (1e-6, S::ORIENTATIONS);
    let (q0, v0) = tr.step(&q, &v, &u, 0.3).unwrap();
    let from_centre = |(q1, v1): (SVector<f64, Q>, SVector<f64, N>)| {
        let mut d = DVector::zeros(2 * N);
        orientation::difference(
            layout,
            q0.as_slice(),
            q1.as_slice(),
            &mut d.as_mut_slice()[..N],
        );
        d.rows_mut(N, N).copy_from(&(v1 - v0));
        d
    };
    let at = |dx: &DVector<f64>, du: &SVector<f64, P>| {
        let delta = SVector::<f64, N>::from_fn(|i, _| dx[i]);
        let dv = SVector::<f64, N>::from_fn(|i, _| dx[N + i]);
        let q1 = orientation::plus(layout, &q, &delta);
        from_centre(tr.step(&q1, &(v + dv), &(u + du), 0.3).unwrap())
    };
    let mut dx = DMatrix::zeros(2 * N, 2 * N);
    for j in 0..2 * N {
        let e = DVector::from_fn(2 * N, |i, _| if i == j { eps } else { 0.0 });
        let column = (at(&e, &SVector::zeros()) - at(&-e, &SVector::zeros())) / (2.0 * eps);
        dx.set_column(j, &column);
    }
    let mut du = DMatrix::zeros(2 * N, P);
    let none = DVector::zeros(2 * N);
    for k in 0..P {
        let e = SVector::<f64, P>::from_fn(|i, _| if i == k { eps } else { 0.0 });
        du.set_column(k, &((at(&none, &e) - at(&none, &-e)) / (2.0 * eps)));
    }
    (dx, du)
}

/// A free body spinning steadily (unit inertia, no forces) beside a cart
/// moving steadily: the step on the group is exact, q⁺ = q ⊗ exp(h ω), for
/// both methods, and its quaternion is unit.
#[test]
fn a_steady_spin_is_stepped_exactly_on_the_group() {
    let turn = orientation::exp([0.3, -0.8, 0.5]);
    let q = SVector::<f64, 5>::from([0.2, turn[0], turn[1], turn[2], turn[3]]);
    let v = SVector::<f64, 4>::from([0.7, 1.1, -2.0, 0.6]);
    let h = 0.1;
    let spun = orientation::multiply(turn, orientation::exp([1.1 * h, -2.0 * h, 0.6 * h]));
    for method in METHODS {
        let tr = Transition::new(&CartAndBall, h).unwrap().method(method);
        let (q1, v1) = tr.step(&q, &v, &SVector::<f64, 0>::zeros(), 0.0).unwrap();
        assert!((q1[0] - (0.2 + 0.7 * h)).abs() < 1e-15 && v1 == v);
        for k in 0..4 {
            assert!((q1[1 + k] - spun[k]).abs() < 1e-15, "{method:?}: {q1}");
        }
        let d = tr
            .derivatives(&q, &v, &SVector::<f64, 0>::zeros(), 0.0)
            .unwrap();
        assert_eq!((d.q, d.v), (q1, v1));
    }
}

/// The chain rule on the group against central differences through the
/// retraction, at arbitrary states (quaternions anywhere on the sphere,
/// fast spins, the body's dynamics and the cart's depending on the
/// orientation): to 1e-6 of the largest entry.
#[test]
fn group_derivatives_match_differences_through_the_retraction() {
    let body = PivotedBody {
        inertia: [0.3, 0.5, 0.7],
        lever: 0.4,
    };
    let mut seed = 0x9e37_79b9_7f4a_7c15;
    for method in METHODS {
        let tr = Transition::new(&body, 0.05).unwrap().method(method);
        for _ in 0..4 {
            let turn = arbitrary::<4>(&mut seed).normalize();
            let x = arbitrary::<1>(&mut seed)[0];
            let q = SVector::<f64, 5>::from([x, turn[0], turn[1], turn[2], turn[3]]);
            let v = arbitrary::<4>(&mut seed) * 3.0;
            let u = arbitrary::<4>(&mut seed);
            let d = tr.derivatives(&q, &v, &u, 0.3).unwrap();
            let (dx, du) = group_differences(&tr, (q, v, u));
            let (ex, eu) = ((&d.dx - &dx).amax(), (&d.du - &du).amax());
            assert!(
                ex < 1e-6 * dx.amax() && eu < 1e-6 * du.amax(),
                "{method:?} at {q}: ∂x {ex:e} of {:e}, ∂u {eu:e} of {:e}",
                dx.amax(),
                du.amax()
            );
            assert!((d.dx.clone() - DMatrix::identity(8, 8)).amax() > 1e-3);
        }
    }
}

/// RK4 on the group is of fourth order: halving the step divides the
/// error of a second of the heavy body's motion by about 2⁴ (against a
/// run of 1/1600 s steps).
#[test]
fn rk4_on_the_group_is_of_fourth_order() {
    let body = PivotedBody {
        inertia: [0.3, 0.5, 0.7],
        lever: 0.4,
    };
    let turn = orientation::exp([0.4, 0.9, -0.2]);
    let q0 = SVector::<f64, 5>::from([0.1, turn[0], turn[1], turn[2], turn[3]]);
    let v0 = SVector::<f64, 4>::from([0.0, 1.0, -2.0, 3.0]);
    let u = SVector::<f64, 4>::from([0.5, 0.1, 0.0, -0.2]);
    let run = |steps: usize| {
        let tr = Transition::new(&body, 1.0 / steps as f64).unwrap();
        let (mut q, mut v) = (q0, v0);
        for _ in 0..steps {
            (q, v) = tr.step(&q, &v, &u, 0.0).unwrap();
        }
        (q, v)
    };
    let (q_ref, v_ref) = run(1600);
    let error = |steps| {
        let (q, v) = run(steps);
        let mut d = [0.0; 4];
        orientation::difference(
            PivotedBody::ORIENTATIONS,
            q_ref.as_slice(),
            q.as_slice(),
            &mut d,
        );
        d.iter().fold((v - v_ref).amax(), |m, x| m.max(x.abs()))
    };
    let (coarse, fine) = (error(50), error(100));
    let ratio = coarse / fine;
    assert!(
        (12.0..20.0).contains(&ratio),
        "{coarse:e} / {fine:e} = {ratio}"
    );
}
