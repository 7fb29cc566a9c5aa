//! The dynamics regressor (`emit(regressor)`) as emitted: Y π equals the
//! emitted inverse dynamics at random states on the robots shipped in
//! `robots/` (Solo 12 on its floating base) and on trees of the catalog's
//! kinds, and on systems that are no trees (point pendulums, a slider-crank
//! in its crank angle: the generic route), and the energy regressor's Y_E π
//! equals T + V; the base parameters of a planar 2R arm against their textbook
//! closed form; identification from noise-free samples (π_b to 1e-9), from
//! noisy ones (the errors within the reported covariance over an ensemble),
//! and its typed errors.

use lagrange::identify::{BaseParameters, Sample, identify};
use lagrange::{IdentifyError, Lagrangian};
use nalgebra::{DVector, SVector};

// The UR5's and the Kinova's numbers as written (`snap = 0`), as Pinocchio
// reads them (`regressor_pinocchio`).
#[derive(Lagrangian)]
#[lagrange(urdf("robots/ur5.urdf", snap = 0), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
pub(crate) struct Ur5 {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/panda.urdf", dynamics = ignore), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
struct Panda {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/kinova.urdf", snap = 0), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
pub(crate) struct Kinova {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/z1.urdf", dynamics = ignore), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
pub(crate) struct Z1 {}

#[derive(Lagrangian)]
#[lagrange(urdf("robots/xarm7.urdf", dynamics = ignore), gravity = [0, 0, -9.81], emit(regressor, inverse_dynamics))]
pub(crate) struct Xarm7 {}

#[derive(Lagrangian)]
#[lagrange(
    urdf("robots/solo12.urdf", base = floating),
    gravity = [0, 0, -9.81],
    emit(regressor, inverse_dynamics)
)]
pub(crate) struct Solo12 {}

/// A pendulum of point masses: no tree of bodies, so Y comes by the generic
/// route.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta),
    point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]),
    gravity = [0, -g],
    emit(regressor),
)]
pub(crate) struct PointPendulum {
    pub(crate) m: f64,
    pub(crate) l: f64,
    pub(crate) g: f64,
}

/// The catalog's double pendulum of point masses, by the generic route.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(th1, th2),
    define(x1 = l1 * sin(th1), y1 = -l1 * cos(th1)),
    point(b1, mass = m1, at = [x1, y1]),
    point(b2, mass = m2, at = [x1 + l2 * sin(th2), y1 - l2 * cos(th2)]),
    gravity = [0, -g],
    emit(regressor),
)]
pub(crate) struct PointDoublePendulum {
    pub(crate) m1: f64,
    pub(crate) m2: f64,
    pub(crate) l1: f64,
    pub(crate) l2: f64,
    pub(crate) g: f64,
}

/// A slider-crank in its crank angle alone (a closed chain in minimal
/// coordinates), its rod a body turning by the angle the loop gives: by the
/// generic route.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(th),
    point(pin, mass = mp, at = [r * cos(th), r * sin(th), 0]),
    point(slider, mass = ms, at = [r * cos(th) + sqrt(l * l - r * r * sin(th) * sin(th)), 0, 0]),
    body(rod, mass = mr, inertia = [0.001, 0.02, j], com = [c, 0.01, 0],
         at = [pin.x, pin.y, 0], rotation = rot_z(-asin(r * sin(th) / l))),
    gravity = [0, -9.81, 0],
    emit(regressor),
)]
pub(crate) struct SliderCrank {
    pub(crate) mp: f64,
    pub(crate) ms: f64,
    pub(crate) mr: f64,
    pub(crate) j: f64,
    pub(crate) c: f64,
    pub(crate) r: f64,
    pub(crate) l: f64,
}

pub(crate) const CRANK: SliderCrank = SliderCrank {
    mp: 0.3,
    ms: 0.8,
    mr: 0.5,
    j: 0.02,
    c: 0.4,
    r: 0.3,
    l: 1.0,
};

/// The catalog's heavy top (Euler angles about a fixed point), its centre
/// off the reference point.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c], com = [0, 0, l],
         at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
    emit(regressor, inverse_dynamics),
)]
struct HeavyTop {
    m: f64,
    a: f64,
    c: f64,
    l: f64,
    g: f64,
}

/// A planar 2R arm in the vertical plane: link frames at the joints, x along
/// the link, gravity along −y.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(q1, q2),
    body(link1, mass = m1, inertia = [0.01, 0.02, i1], com = [c1, d1, 0],
         at = [0, 0, 0], rotation = rot_z(q1)),
    point(elbow, on = link1, at = [l1, 0, 0]),
    body(link2, mass = m2, inertia = [0.01, 0.02, i2], com = [c2, d2, 0],
         at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
    gravity = [0, -9.81, 0],
    emit(regressor, inverse_dynamics),
)]
struct Arm2R {
    m1: f64,
    m2: f64,
    l1: f64,
    c1: f64,
    d1: f64,
    c2: f64,
    d2: f64,
    i1: f64,
    i2: f64,
}

const ARM: Arm2R = Arm2R {
    m1: 2.0,
    m2: 1.5,
    l1: 0.7,
    c1: 0.3,
    d1: 0.02,
    c2: 0.25,
    d2: -0.03,
    i1: 0.09,
    i2: 0.05,
};

/// A deterministic sequence in [−1, 1).
pub(crate) struct Lcg(pub(crate) u64);
impl Lcg {
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = (self.0)
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }

    /// A standard normal deviate (Box–Muller).
    pub(crate) fn normal(&mut self) -> f64 {
        let u = 0.5 * (self.next() + 1.0) + 1e-300;
        let v = 0.5 * (self.next() + 1.0);
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// A random state, each free orientation's quaternion on the unit sphere.
pub(crate) fn state<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(
    rng: &mut Lcg,
) -> (SVector<f64, Q>, SVector<f64, N>, SVector<f64, N>) {
    let mut q = SVector::<f64, Q>::from_fn(|_, _| 2.0 * rng.next());
    lagrange::numeric::orientation::normalise(S::ORIENTATIONS, q.as_mut_slice());
    let v = SVector::from_fn(|_, _| 2.0 * rng.next());
    let a = SVector::from_fn(|_, _| 3.0 * rng.next());
    (q, v, a)
}

/// Max |Y π − τ| / (1 + |τ|) and |Y_E π − (T + V)| / (1 + |T + V|) over
/// 20 random states.
fn y_pi_minus_tau<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(sys: &S) -> f64 {
    let pi = sys.inertial_parameters().expect("π is emitted");
    assert_eq!(pi.len(), S::REGRESSOR_PARAMETERS.len());
    let mut rng = Lcg(34);
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let (q, v, a) = state::<S, N, Q>(&mut rng);
        let y = sys.regressor(&q, &v, &a, 0.0).expect("Y is emitted");
        let tau = sys.inverse_dynamics(&q, &v, &a, 0.0);
        let y_pi = &y * &pi;
        for i in 0..N {
            assert!(y_pi[i].is_finite());
            worst = worst.max((y_pi[i] - tau[i]).abs() / (1.0 + tau[i].abs()));
        }
        // The energy regressor: T + V (gravity's alone here) = Y_E π.
        let y_e = sys.energy_regressor(&q, &v, 0.0).expect("Y_E is emitted");
        let energy = sys.kinetic_energy(&q, &v, 0.0) + sys.potential_energy(&q, 0.0);
        worst = worst.max((y_e.dot(&pi) - energy).abs() / (1.0 + energy.abs()));
    }
    worst
}

#[test]
fn y_pi_is_the_inverse_dynamics_on_the_shipped_robots() {
    let worst = [
        ("UR5", y_pi_minus_tau(&Ur5 {})),
        ("Panda", y_pi_minus_tau(&Panda {})),
        ("Kinova", y_pi_minus_tau(&Kinova {})),
        ("Z1", y_pi_minus_tau(&Z1 {})),
        ("xArm7", y_pi_minus_tau(&Xarm7 {})),
        ("Solo 12", y_pi_minus_tau(&Solo12 {})),
    ];
    for (robot, err) in worst {
        eprintln!("{robot}: max |Y π − τ| / (1 + |τ|) = {err:.1e}");
        assert!(err < 1e-12, "{robot}: {err:e}");
    }
}

/// Where there is no tree Y comes by the generic route: Y π = M q̈ + h −
/// Q_gravity, the inverse dynamics of a system whose only force is gravity.
#[test]
fn y_pi_is_the_inverse_dynamics_without_a_tree() {
    let pendulum = PointPendulum {
        m: 1.2,
        l: 0.8,
        g: 9.81,
    };
    let double = PointDoublePendulum {
        m1: 1.0,
        m2: 0.7,
        l1: 0.9,
        l2: 0.6,
        g: 9.81,
    };
    for (system, err) in [
        ("point pendulum", y_pi_minus_tau(&pendulum)),
        ("double pendulum of point masses", y_pi_minus_tau(&double)),
        ("slider-crank", y_pi_minus_tau(&CRANK)),
    ] {
        eprintln!("{system}: max |Y π − τ| / (1 + |τ|) = {err:.1e}");
        assert!(err < 1e-12, "{system}: {err:e}");
    }
    assert_eq!(PointDoublePendulum::REGRESSOR_PARAMETERS, ["b1.m", "b2.m"]);
}

#[test]
fn y_pi_is_the_inverse_dynamics_on_catalog_trees() {
    let top = HeavyTop {
        m: 1.3,
        a: 0.04,
        c: 0.02,
        l: 0.3,
        g: 9.81,
    };
    assert!(y_pi_minus_tau(&top) < 1e-12);
    assert!(y_pi_minus_tau(&ARM) < 1e-12);
}

/// Khalil and Dombre's regrouping for two parallel revolute joints: of the
/// twenty standard parameters, six base parameters, ZZ1R = ZZ1 + m2 l1²,
/// MX1R = MX1 + m2 l1, MY1, ZZ2, MX2, MY2, ZZ about each joint's origin.
#[test]
fn a_planar_2r_arm_has_the_textbook_base_parameters() {
    let base = BaseParameters::of(&ARM).expect("a regressor");
    assert_eq!(
        base.names(),
        [
            "link1.mx",
            "link1.my",
            "link1.Izz",
            "link2.mx",
            "link2.my",
            "link2.Izz"
        ]
    );
    let k = base.map();
    let column = |name: &str| {
        Arm2R::REGRESSOR_PARAMETERS
            .iter()
            .position(|n| *n == name)
            .expect("a parameter")
    };
    let l1 = ARM.l1;
    let mut want = nalgebra::DMatrix::zeros(6, 20);
    for (row, name) in base.names().iter().enumerate() {
        want[(row, column(name))] = 1.0;
    }
    want[(0, column("link2.m"))] = l1;
    want[(2, column("link2.m"))] = l1 * l1;
    assert!((k - &want).abs().max() < 1e-12, "K = {k}");
    let zz1r = k[(2, column("link2.m"))];
    assert_eq!(base.expressions()[2], format!("link1.Izz + {zz1r}*link2.m"));
    // π_b from the struct's fields: ZZ1R, MX1R in closed form.
    let pi = ARM.inertial_parameters().expect("π");
    let pb = base.of_parameters(&pi).expect("π's length");
    let zz1 = ARM.i1 + ARM.m1 * (ARM.c1 * ARM.c1 + ARM.d1 * ARM.d1);
    assert!((pb[2] - (zz1 + ARM.m2 * l1 * l1)).abs() < 1e-14);
    assert!((pb[0] - (ARM.m1 * ARM.c1 + ARM.m2 * l1)).abs() < 1e-14);
}

/// Samples of `sys` at random states, τ its inverse dynamics plus `noise`
/// times standard normal deviates.
fn samples<S: Lagrangian<f64, N, Q>, const N: usize, const Q: usize>(
    sys: &S,
    count: usize,
    noise: f64,
    rng: &mut Lcg,
) -> Vec<Sample<N, Q>> {
    (0..count)
        .map(|_| {
            let (q, v, a) = state::<S, N, Q>(rng);
            let tau = sys.inverse_dynamics(&q, &v, &a, 0.0)
                + SVector::<f64, N>::from_fn(|_, _| noise * rng.normal());
            Sample { q, v, a, tau }
        })
        .collect()
}

#[test]
fn noise_free_samples_give_the_base_parameters_to_1e_9() {
    let ur5 = Ur5 {};
    let base = BaseParameters::of(&ur5).expect("a regressor");
    let truth = base
        .of_parameters(&ur5.inertial_parameters().expect("π"))
        .expect("π's length");
    let data = samples(&ur5, 200, 0.0, &mut Lcg(7));
    let fit = identify(&ur5, &base, &data, &SVector::repeat(1.0)).expect("identifies");
    let err = (&fit.values - &truth).abs().max() / truth.abs().max();
    eprintln!(
        "UR5: {} base parameters of {}, noise-free error {err:.1e}",
        base.len(),
        Ur5::REGRESSOR_PARAMETERS.len()
    );
    assert!(err < 1e-9, "{err:e}");
    assert!(fit.residual < 1e-9);
}

/// Over 200 runs with noise σ = 0.05 N·m, the errors' squared Mahalanobis
/// norm in the reported covariance averages the number of parameters (a
/// χ² with 6 degrees of freedom: mean 6, the mean of 200 within ±10 % but
/// for a 1-in-10⁴ draw, and the sequence is fixed).
#[test]
fn noisy_estimates_lie_within_their_covariance() {
    let base = BaseParameters::of(&ARM).expect("a regressor");
    let truth = base
        .of_parameters(&ARM.inertial_parameters().expect("π"))
        .expect("π's length");
    let mut rng = Lcg(11);
    let runs = 200;
    let mut mean = 0.0;
    for _ in 0..runs {
        let data = samples(&ARM, 40, 0.05, &mut rng);
        let fit = identify(&ARM, &base, &data, &SVector::repeat(0.05)).expect("identifies");
        let e = &fit.values - &truth;
        let info = fit.covariance.clone().try_inverse().expect("a covariance");
        mean += (e.transpose() * info * &e)[(0, 0)] / runs as f64;
    }
    let dof = base.len() as f64;
    assert!((mean - dof).abs() < 0.1 * dof, "mean χ² {mean} for {dof}");
}

#[test]
fn bad_data_are_typed_errors() {
    let base = BaseParameters::of(&ARM).expect("a regressor");
    let sigma = SVector::repeat(0.1);
    let mut rng = Lcg(3);
    let few = samples(&ARM, 2, 0.0, &mut rng);
    assert!(matches!(
        identify(&ARM, &base, &few, &sigma),
        Err(IdentifyError::TooFewSamples { needed: 3, .. })
    ));
    let mut broken = samples(&ARM, 10, 0.0, &mut rng);
    broken[4].a[1] = f64::NAN;
    assert!(matches!(
        identify(&ARM, &base, &broken, &sigma),
        Err(IdentifyError::NotFinite {
            sample: 4,
            field: "a",
            index: 1,
            ..
        })
    ));
    // Held still: gravity alone shows, no inertia about z.
    let mut still = samples(&ARM, 10, 0.0, &mut rng);
    for s in &mut still {
        s.v = SVector::zeros();
        s.a = SVector::zeros();
        s.tau = ARM.inverse_dynamics(&s.q, &s.v, &s.a, 0.0);
    }
    match identify(&ARM, &base, &still, &sigma) {
        Err(IdentifyError::RankDeficient {
            rank,
            unidentifiable,
            ..
        }) => {
            assert_eq!(rank, 4);
            assert_eq!(unidentifiable, ["link1.Izz", "link2.Izz"]);
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        identify(&ARM, &base, &still, &SVector::from([0.1, 0.0])),
        Err(IdentifyError::Noise { joint: 1, .. })
    ));
    // Base parameters found for another system.
    let top = HeavyTop {
        m: 1.3,
        a: 0.04,
        c: 0.02,
        l: 0.3,
        g: 9.81,
    };
    let other = BaseParameters::of(&top).expect("a regressor");
    let fine = samples(&ARM, 10, 0.0, &mut rng);
    let wrong = identify(&ARM, &other, &fine, &sigma);
    assert!(
        matches!(
            wrong,
            Err(IdentifyError::Lengths {
                got: 20,
                expected: 10,
                ..
            })
        ),
        "{wrong:?}"
    );
    assert!(matches!(
        base.of_parameters(&DVector::zeros(3)),
        Err(IdentifyError::Lengths {
            got: 3,
            expected: 20,
            ..
        })
    ));
}

/// `regressor_into` writes Y into a block of a larger matrix, every entry
/// (what was there before is overwritten), and refuses a block of the wrong
/// shape with a typed error, leaving it as it was.
#[test]
fn regressor_into_writes_a_block_and_refuses_a_wrong_shape() {
    let ur5 = Ur5 {};
    let q = SVector::<f64, 6>::from_fn(|k, _| 0.3 - 0.17 * k as f64);
    let v = SVector::<f64, 6>::from_fn(|k, _| 0.5 - 0.21 * k as f64);
    let a = SVector::<f64, 6>::from_fn(|k, _| 0.1 + 0.05 * k as f64);
    let y = ur5.regressor(&q, &v, &a, 0.0).expect("emit(regressor)");
    let p = Ur5::REGRESSOR_PARAMETERS.len();
    let mut w = nalgebra::DMatrix::from_element(18, p, 7.0);
    ur5.regressor_into(&q, &v, &a, 0.0, w.view_mut((6, 0), (6, p)))
        .expect("the block has Y's shape");
    assert_eq!(w.view((6, 0), (6, p)), y);
    assert!(
        w.rows(0, 6)
            .iter()
            .chain(w.rows(12, 6).iter())
            .all(|&x| x == 7.0)
    );
    let before = w.clone();
    let wrong = ur5.regressor_into(&q, &v, &a, 0.0, w.view_mut((0, 0), (6, p - 1)));
    assert!(
        matches!(wrong, Err(IdentifyError::Lengths { got, expected, .. }) if got == p - 1 && expected == p),
        "{wrong:?}"
    );
    assert_eq!(w, before);
}
