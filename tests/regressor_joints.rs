//! A joint's damping, friction and armature as columns of the regressor:
//! Y π equals the inverse dynamics (which has the damping and the armature)
//! plus the slipping friction fc sign(q̇), on a tree, off one and on a URDF
//! read with its `<dynamics>`; the energy and momentum regressors take the
//! armature; the first joint's armature regroups into link 1's axial
//! inertia; noise-free data give the drives' coefficients back to 1e-9,
//! also under the consistent estimate, which refuses a negative one.

use lagrange::identify::{
    BaseParameters, Consistency, Sample, identify, identify_consistent, inconsistent_bodies,
};
use lagrange::{IdentifyError, Lagrangian};
use nalgebra::{DVector, SVector};

use crate::regressor::{Lcg, state};

/// The planar 2R arm of `tests/regressor.rs` with drives (and inertias
/// that a real body has, for the consistent estimate): a damped, rubbing
/// first joint with a rotor, a second driven through a gear whose rotor is
/// reflected as n² Ir.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(q1, q2),
    inputs(u),
    body(link1, mass = m1, inertia = [0.05, 0.06, i1], com = [c1, d1, 0],
         at = [0, 0, 0], rotation = rot_z(q1)),
    point(elbow, on = link1, at = [l1, 0, 0]),
    body(link2, mass = m2, inertia = [0.03, 0.04, i2], com = [c2, d2, 0],
         at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
    gravity = [0, -9.81, 0],
    joint(q1, damping = b1, friction = 0.4, armature = ia),
    joint(q2, damping = b2, motor = u, gear = n, rotor = ir),
    emit(regressor, inverse_dynamics),
)]
struct DrivenArm {
    m1: f64,
    m2: f64,
    l1: f64,
    c1: f64,
    d1: f64,
    c2: f64,
    d2: f64,
    i1: f64,
    i2: f64,
    b1: f64,
    b2: f64,
    ia: f64,
    n: f64,
    ir: f64,
}

const ARM: DrivenArm = DrivenArm {
    m1: 2.0,
    m2: 1.5,
    l1: 0.7,
    c1: 0.3,
    d1: 0.02,
    c2: 0.25,
    d2: -0.03,
    i1: 0.09,
    i2: 0.05,
    b1: 0.3,
    b2: 0.15,
    ia: 0.02,
    n: 20.0,
    ir: 3e-5,
};

/// A pendulum of a point mass (no tree: Y by the generic route) on a damped,
/// rubbing joint with a rotor.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    joint(theta, damping = b, friction = 0.25, armature = ia),
    emit(regressor, inverse_dynamics),
)]
struct DrivenPendulum {
    m: f64,
    l: f64,
    g: f64,
    b: f64,
    ia: f64,
}

/// The Z1 with its file's damping and friction at every joint.
#[derive(Lagrangian)]
#[lagrange(urdf("robots/z1.urdf", dynamics = read), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
struct Z1Read {}

/// Each coordinate's friction bound, read from π by its name.
fn frictions<S: Lagrangian<f64, N>, const N: usize>(pi: &DVector<f64>) -> SVector<f64, N> {
    let mut fc = SVector::zeros();
    for (k, name) in S::REGRESSOR_PARAMETERS.iter().enumerate() {
        if let Some(joint) = name.strip_suffix(".friction") {
            let i = S::COORDINATES.iter().position(|c| *c == joint);
            fc[i.expect("a coordinate's name")] = pi[k];
        }
    }
    fc
}

/// τ a slipping robot's motors give: the inverse dynamics plus fc sign(q̇).
fn slipping_torque<S: Lagrangian<f64, N>, const N: usize>(
    sys: &S,
    (q, v, a): (&SVector<f64, N>, &SVector<f64, N>, &SVector<f64, N>),
) -> SVector<f64, N> {
    let pi = sys.inertial_parameters().expect("π");
    let fc = frictions::<S, N>(&pi);
    sys.inverse_dynamics(q, v, a, 0.0) + fc.component_mul(&v.map(f64::signum))
}

/// Max over 20 random states of the relative errors of Y π against the
/// slipping torque, Y_E π against T + V and Y_p π against M q̇.
fn worst_error<S: Lagrangian<f64, N>, const N: usize>(sys: &S) -> f64 {
    let pi = sys.inertial_parameters().expect("π");
    let mut rng = Lcg(5);
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let (q, v, a) = state::<S, N, N>(&mut rng);
        let y = sys.regressor(&q, &v, &a, 0.0).expect("Y");
        let tau = slipping_torque(sys, (&q, &v, &a));
        let relative = |x: f64, y: f64| (x - y).abs() / (1.0 + y.abs());
        for (got, want) in (&y * &pi).iter().zip(tau.iter()) {
            worst = worst.max(relative(*got, *want));
        }
        let y_e = sys.energy_regressor(&q, &v, 0.0).expect("Y_E");
        let energy = sys.kinetic_energy(&q, &v, 0.0) + sys.potential_energy(&q, 0.0);
        worst = worst.max(relative(y_e.dot(&pi), energy));
        let y_p = sys.momentum_regressor(&q, &v, 0.0).expect("Y_p");
        let momentum = sys.mass_matrix(&q, 0.0) * v;
        for (got, want) in (&y_p * &pi).iter().zip(momentum.iter()) {
            worst = worst.max(relative(*got, *want));
        }
    }
    worst
}

#[test]
fn the_joints_coefficients_are_columns_of_y() {
    assert_eq!(
        &DrivenArm::REGRESSOR_PARAMETERS[20..],
        [
            "q1.damping",
            "q1.friction",
            "q1.armature",
            "q2.damping",
            "q2.armature"
        ]
    );
    let pi = ARM.inertial_parameters().expect("π");
    // π reads the coefficients off the fields: the rotor through its gear.
    let tail = [ARM.b1, 0.4, ARM.ia, ARM.b2, ARM.n * ARM.n * ARM.ir];
    assert_eq!(&pi.as_slice()[20..], tail);
    let pendulum = DrivenPendulum {
        m: 1.2,
        l: 0.8,
        g: 9.81,
        b: 0.05,
        ia: 0.01,
    };
    for (system, err) in [
        ("driven 2R arm (tree)", worst_error(&ARM)),
        ("driven point pendulum (generic)", worst_error(&pendulum)),
        ("Z1 with its file's dynamics", worst_error(&Z1Read {})),
    ] {
        eprintln!("{system}: max relative error of Y π, Y_E π, Y_p π = {err:.1e}");
        assert!(err < 1e-12, "{system}: {err:e}");
    }
}

/// The first joint turns about an axis fixed in space: its armature shows
/// only as q̈1 on row 1, as link 1's axial inertia does, and regroups into
/// it; the second's, the dampings and the friction are base parameters of
/// their own.
#[test]
fn the_first_armature_regroups_into_the_first_links_inertia() {
    let base = BaseParameters::of(&ARM).expect("a regressor");
    assert_eq!(
        base.names(),
        [
            "link1.mx",
            "link1.my",
            "link1.Izz",
            "link2.mx",
            "link2.my",
            "link2.Izz",
            "q1.damping",
            "q1.friction",
            "q2.damping",
            "q2.armature"
        ]
    );
    let pi = ARM.inertial_parameters().expect("π");
    let pb = base.of_parameters(&pi).expect("π's length");
    let zz1 = ARM.i1 + ARM.m1 * (ARM.c1 * ARM.c1 + ARM.d1 * ARM.d1);
    let zz1r = zz1 + ARM.m2 * ARM.l1 * ARM.l1 + ARM.ia;
    assert!((pb[2] - zz1r).abs() < 1e-14, "{} against {zz1r}", pb[2]);
    assert!(base.expressions()[2].ends_with("q1.armature"));
}

/// Samples at random states with τ the slipping torque.
fn samples<S: Lagrangian<f64, N>, const N: usize>(
    sys: &S,
    count: usize,
    rng: &mut Lcg,
) -> Vec<Sample<N>> {
    (0..count)
        .map(|_| {
            let (q, v, a) = state::<S, N, N>(rng);
            let tau = slipping_torque(sys, (&q, &v, &a));
            Sample { q, v, a, tau }
        })
        .collect()
}

#[test]
fn noise_free_data_give_the_drives_back() {
    let base = BaseParameters::of(&ARM).expect("a regressor");
    let pi = ARM.inertial_parameters().expect("π");
    let truth = base.of_parameters(&pi).expect("π's length");
    let data = samples(&ARM, 60, &mut Lcg(11));
    let sigma = SVector::repeat(0.1);
    let fit = identify(&ARM, &base, &data, &sigma).expect("identifies");
    let err = (&fit.values - &truth).amax() / truth.amax();
    eprintln!("driven 2R arm: π_b error {err:.1e}");
    assert!(err < 1e-9, "{err:e}");
    // The consistent estimate, from a prior that halves every drive. Its
    // pull toward the prior biases π_b by about 1e-7 at this weight on this
    // arm (1.3e-3 at the default 1e-6, as `Consistency` documents).
    let mut prior = pi.clone();
    prior.rows_mut(20, 5).scale_mut(0.5);
    let weak = Consistency {
        regularisation: 1e-10,
        ..Consistency::default()
    };
    let fit = identify_consistent(&ARM, &base, &data, &sigma, &prior, &weak).expect("converges");
    let err = (&fit.base - &truth).amax() / truth.amax();
    eprintln!(
        "driven 2R arm, consistent: π_b (four drives among them) error {err:.1e} in {} iterations",
        fit.iterations
    );
    assert!(err < 1e-6, "{err:e}");
    let names = DrivenArm::REGRESSOR_PARAMETERS;
    assert!(
        inconsistent_bodies(names, &fit.parameters)
            .expect("π")
            .is_empty()
    );
    assert!(fit.parameters.rows(20, 5).min() > 0.0);
}

#[test]
fn a_negative_drive_is_not_physical() {
    let mut pi = ARM.inertial_parameters().expect("π");
    pi[20] = -0.1;
    let names = DrivenArm::REGRESSOR_PARAMETERS;
    assert_eq!(inconsistent_bodies(names, &pi).expect("π"), ["q1.damping"]);
    pi[20] = 0.0;
    assert!(inconsistent_bodies(names, &pi).expect("π").is_empty());
    // The consistent estimate writes each coefficient e^θ: it starts from
    // a positive guess, and says which one is not.
    let base = BaseParameters::of(&ARM).expect("a regressor");
    let data = samples(&ARM, 20, &mut Lcg(3));
    let sigma = SVector::repeat(0.1);
    let fit = identify_consistent(&ARM, &base, &data, &sigma, &pi, &Consistency::default());
    match fit {
        Err(IdentifyError::Inconsistent { body, .. }) => assert_eq!(body, "q1.damping"),
        other => panic!("{other:?}"),
    }
}
