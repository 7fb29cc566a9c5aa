//! The batched programs of `emit(batched)` (four states per call, in the
//! lanes of `F64x4`) against the scalar programs emitted from the same
//! outputs, lane by lane, bit for bit: the same operations in the same
//! order, each lane rounding as `f64` does (`mul_add` fuses in both or in
//! neither; sin, cos and the powers are the scalar functions lane by lane). On a URDF arm
//! through `jacobians` (q̈ and its derivatives), an arm through
//! `articulated`, a floating base through both and a description with
//! parameters; five states, so the last call has three spare lanes; and the
//! per-state errors, which are the scalar reading's.

use lagrange::prelude::*;
use lagrange::{Batched, BatchedDifferentiable, Differentiable};
use nalgebra::SVector;

#[derive(Lagrangian)]
#[lagrange(urdf = "robots/ur5.urdf", gravity = [0, 0, -9.81], emit(jacobians, batched))]
struct Ur5 {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/xarm7.urdf", dynamics = ignore), gravity = [0, 0, -9.81], emit(articulated, batched))]
struct Xarm7 {}

#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/solo12.urdf", base = floating),
    gravity = [0, 0, -9.81],
    emit(articulated, jacobians, batched)
)]
struct Solo12 {}

/// A double pendulum whose masses and length are parameters (splatted into
/// the lanes); massless, M is singular.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(a, b),
    point(p, at = [l * sin(a), -l * cos(a)], mass = m1),
    point(r, at = [p.x + l * sin(b), p.y - l * cos(b)], mass = m2),
    gravity = [0, -g],
    emit(jacobians, batched)
)]
struct Double {
    m1: f64,
    m2: f64,
    l: f64,
    g: f64,
}

const STATES: usize = 5;

/// Five states (q, v, τ), distinct in every coordinate; with orientations
/// (Q > N), q's last four entries a unit quaternion.
#[allow(clippy::type_complexity)]
fn states<const N: usize, const Q: usize>() -> (
    Vec<SVector<f64, Q>>,
    Vec<SVector<f64, N>>,
    Vec<SVector<f64, N>>,
) {
    let q = (0..STATES).map(|s| {
        let mut q = SVector::from_fn(|k, _| 0.3 - 0.17 * k as f64 + 0.11 * s as f64);
        if Q > N {
            let w = [0.9, 0.1 + 0.05 * s as f64, -0.3, 0.2];
            let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
            for (c, x) in w.iter().enumerate() {
                q[Q - 4 + c] = x / norm;
            }
        }
        q
    });
    let v = (0..STATES).map(|s| SVector::from_fn(|k, _| 0.5 - 0.21 * k as f64 - 0.07 * s as f64));
    let tau = (0..STATES).map(|s| SVector::from_fn(|k, _| 0.2 * k as f64 - 0.4 + 0.3 * s as f64));
    (q.collect(), v.collect(), tau.collect())
}

fn same_bits(what: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len());
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!(
            x.to_bits(),
            y.to_bits(),
            "{what}[{i}]: {x} in lanes, {y} scalar"
        );
    }
}

/// The batched derivatives against the scalar program, state by state, and
/// the batched q̈ against the scalar derivatives' q̈: the same expressions,
/// but emitted alone they make another program (a divisor read once is a
/// division there, a reciprocal and products in the whole), which rounds
/// differently in the last bits.
fn derivatives_match<S, const N: usize, const Q: usize>(name: &str, sys: &S)
where
    S: BatchedDifferentiable<N, Q> + Batched<N, Q>,
{
    let (q, v, tau) = states::<N, Q>();
    let batched = lagrange::batched_acceleration_derivatives(sys, &q, &v, &tau, 0.0)
        .expect("one of each per state");
    let accelerations =
        lagrange::batched_accelerations(sys, &q, &v, &tau, 0.0).expect("one of each per state");
    assert_eq!((batched.len(), accelerations.len()), (STATES, STATES));
    for s in 0..STATES {
        let scalar = lagrange::acceleration_derivatives(sys, &q[s], &v[s], &tau[s], 0.0)
            .expect("a regular state");
        let lanes = batched[s].as_ref().expect("a regular state");
        let what = |m: &str| format!("{name} state {s} {m}");
        same_bits(
            &what("q''"),
            lanes.acceleration.as_slice(),
            scalar.acceleration.as_slice(),
        );
        same_bits(&what("dq"), lanes.dq.as_slice(), scalar.dq.as_slice());
        same_bits(&what("dv"), lanes.dv.as_slice(), scalar.dv.as_slice());
        same_bits(&what("dtau"), lanes.dtau.as_slice(), scalar.dtau.as_slice());
        let a = accelerations[s].as_ref().expect("a regular state");
        let off = (a - scalar.acceleration).abs().max() / scalar.acceleration.abs().max();
        assert!(off < 1e-13, "{}: off by {off}", what("q'' alone"));
    }
}

/// The batched q̈ against the scalar articulated-body program.
fn articulated_matches<S, const N: usize, const Q: usize>(name: &str, sys: &S)
where
    S: Batched<N, Q>,
{
    let (q, v, tau) = states::<N, Q>();
    let batched =
        lagrange::batched_accelerations(sys, &q, &v, &tau, 0.0).expect("one of each per state");
    assert_eq!(batched.len(), STATES);
    for s in 0..STATES {
        let (scalar, _) = (sys.forward_dynamics(&q[s], &v[s], &tau[s], 0.0)).expect("articulated");
        let lanes = batched[s].as_ref().expect("a regular state");
        same_bits(
            &format!("{name} state {s} q''"),
            lanes.as_slice(),
            scalar.as_slice(),
        );
    }
}

#[test]
fn an_arm_s_lanes_are_its_scalar_programs_bit_for_bit() {
    derivatives_match("UR5", &Ur5 {});
    articulated_matches("xArm7", &Xarm7 {});
}

#[test]
fn a_floating_base_s_lanes_are_its_scalar_programs_bit_for_bit() {
    articulated_matches::<_, 18, 19>("Solo 12", &Solo12 {});
    // The q̈ of `batched_accelerations` is the articulated program's here,
    // the derivatives' q̈ another program: compare the derivatives alone.
    let sys = Solo12 {};
    let (q, v, tau) = states::<18, 19>();
    let batched = lagrange::batched_acceleration_derivatives(&sys, &q, &v, &tau, 0.0)
        .expect("one of each per state");
    for s in 0..STATES {
        let scalar = lagrange::acceleration_derivatives(&sys, &q[s], &v[s], &tau[s], 0.0)
            .expect("a regular state");
        let lanes = batched[s].as_ref().expect("a regular state");
        same_bits("Solo 12 dq", lanes.dq.as_slice(), scalar.dq.as_slice());
        same_bits(
            "Solo 12 dtau",
            lanes.dtau.as_slice(),
            scalar.dtau.as_slice(),
        );
    }
}

#[test]
fn parameters_are_splatted_into_every_lane() {
    let sys = Double {
        m1: 1.0,
        m2: 0.5,
        l: 0.8,
        g: 9.81,
    };
    derivatives_match("double pendulum", &sys);
}

/// One state's error is the scalar reading's, and leaves the other states
/// (in its call and the next) alone.
#[test]
fn a_bad_state_is_its_own_error() {
    let sys = Ur5 {};
    let (mut q, v, mut tau) = states::<6, 6>();
    q[1][2] = f64::NAN;
    tau[4][3] = f64::INFINITY;
    let batched = lagrange::batched_acceleration_derivatives(&sys, &q, &v, &tau, 0.0)
        .expect("one of each per state");
    let accelerations =
        lagrange::batched_accelerations(&sys, &q, &v, &tau, 0.0).expect("one of each per state");
    for s in 0..STATES {
        let scalar = lagrange::acceleration_derivatives(&sys, &q[s], &v[s], &tau[s], 0.0);
        match (&scalar, &batched[s], &accelerations[s]) {
            (Ok(a), Ok(b), Ok(_)) => same_bits("dq", a.dq.as_slice(), b.dq.as_slice()),
            (Err(a), Err(b), Err(c)) => {
                assert_eq!(a.to_string(), b.to_string());
                assert_eq!(a.to_string(), c.to_string());
            }
            _ => panic!("state {s}: scalar {scalar:?}, batched {:?}", batched[s]),
        }
    }
    assert!(matches!(batched[1], Err(Error::NonFiniteState { .. })));
    assert!(matches!(batched[4], Err(Error::NonFiniteInput { .. })));
}

#[test]
fn a_singular_mass_matrix_is_reported_in_every_lane() {
    let massless = Double {
        m1: 0.0,
        m2: 0.0,
        l: 1.0,
        g: 9.81,
    };
    let (q, v, tau) = states::<2, 2>();
    let all = lagrange::batched_accelerations(&massless, &q, &v, &tau, 0.0).expect("one of each");
    for r in all {
        assert!(matches!(r, Err(Error::SingularMassMatrix { .. })), "{r:?}");
    }
    let none = lagrange::batched_accelerations::<Double, 2, 2>(&massless, &[], &[], &[], 0.0);
    assert!(none.expect("no states").is_empty());
    // One τ short: the batch's error, not a panic.
    let short = lagrange::batched_accelerations(&massless, &q, &v, &tau[1..], 0.0);
    let Err(Error::Settings(SettingsError::Lengths { what, .. })) = short else {
        panic!("{short:?}");
    };
    assert!(what.contains(&format!("{} τ", tau.len() - 1)), "{what}");
}

/// The trait methods, unchecked: lane k of the arguments is state k.
#[test]
fn the_unchecked_lanes_take_states_lane_by_lane() {
    use lagrange::F64x4;
    let sys = Ur5 {};
    let (q, v, tau) = states::<6, 6>();
    let pack = |xs: &[SVector<f64, 6>]| {
        std::array::from_fn::<F64x4, 6, _>(|i| F64x4::from_array(std::array::from_fn(|k| xs[k][i])))
    };
    let (d, ratio) = sys.acceleration_derivatives_lanes_unchecked(
        &pack(&q),
        &pack(&v),
        &pack(&tau),
        F64x4::splat(0.0),
    );
    for k in 0..F64x4::LANES {
        let (scalar, r) = sys.acceleration_derivatives_unchecked(&q[k], &v[k], &tau[k], 0.0);
        assert_eq!(d.lane(k), scalar);
        assert_eq!(ratio.lane(k).to_bits(), r.to_bits());
    }
}

/// A setting that is not valid (a negative singular tolerance) is every
/// state's error, as the scalar reading reports it.
#[test]
fn an_invalid_setting_is_every_state_s_error() {
    let sys = Ur5 {};
    let (q, v, tau) = states::<6, 6>();
    let dynamics = lagrange::Dynamics::new(&sys).with_singular_tolerance(-1.0);
    let batched = dynamics
        .batched_accelerations(0.0, &q, &v, &tau)
        .expect("one of each per state");
    let scalar = dynamics
        .acceleration(0.0, &q[0], &v[0])
        .expect_err("refused");
    assert_eq!(batched.len(), STATES);
    for state in batched {
        let error = state.expect_err("refused");
        assert!(matches!(error, Error::Settings(_)), "{error:?}");
        assert_eq!(error.to_string(), scalar.to_string());
    }
}
