use super::*;
use crate::{Dopri5, Dynamics, Lagrangian, Orientation, ode::Integrator};
use nalgebra::{SMatrix, SVector};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

const SEQUENCES: [[usize; 3]; 12] = [
    [0, 1, 0],
    [0, 2, 0],
    [1, 0, 1],
    [1, 2, 1],
    [2, 0, 2],
    [2, 1, 2],
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

fn axis(k: usize) -> Vector3<f64> {
    let mut e = Vector3::zeros();
    e[k] = 1.0;
    e
}

/// Two unit quaternions are one orientation: equal up to sign.
fn same_orientation(a: &Vector4<f64>, b: &Vector4<f64>, tol: f64) -> bool {
    (a - b).amax() < tol || (a + b).amax() < tol
}

#[test]
fn a_turn_about_z_minus_the_identity_is_its_rotation_vector() {
    for theta in [0.0, 1e-9, 0.3, -1.2, 3.0] {
        let q = from_axis_angle(&Vector3::z(), theta).unwrap();
        let d = minus(&q, &identity()).unwrap();
        assert!(
            (d - Vector3::new(0.0, 0.0, theta)).amax() < 1e-15,
            "{theta}: {d}"
        );
    }
    // Past π the short way is the other way round.
    let d = minus(&from_axis_angle(&Vector3::z(), 3.5).unwrap(), &identity()).unwrap();
    assert!(
        (d - Vector3::new(0.0, 0.0, 3.5 - 2.0 * PI)).amax() < 1e-14,
        "{d}"
    );
}

#[test]
fn minus_takes_the_short_way_whatever_the_sign() {
    let q0 = from_axis_angle(&Vector3::new(1.0, -2.0, 0.5), 0.8).unwrap();
    let q = plus(&q0, &Vector3::new(0.4, 0.1, -0.7)).unwrap();
    let d = minus(&q, &q0).unwrap();
    assert_eq!(minus(&-q, &q0).unwrap(), d);
    assert!((minus(&q, &-q0).unwrap() - d).amax() < 1e-15);
    assert!((d - Vector3::new(0.4, 0.1, -0.7)).amax() < 1e-15);
    // A half turn and a bit, written the long way: ⊖ gives |δ| ≤ π.
    let long = from_axis_angle(&Vector3::x(), 2.0 * PI - 0.2).unwrap();
    let d = minus(&long, &identity()).unwrap();
    assert!((d - Vector3::new(-0.2, 0.0, 0.0)).amax() < 1e-14, "{d}");
}

#[test]
fn single_axis_euler_angles_are_axis_angle_turns() {
    for axes in SEQUENCES {
        let sequence = EulerSequence::new(axes).unwrap();
        for (k, &a) in axes.iter().enumerate() {
            let mut angles = [0.0; 3];
            angles[k] = 0.9;
            let euler = from_euler(sequence, angles).unwrap();
            let turn = from_axis_angle(&axis(a), 0.9).unwrap();
            assert!(same_orientation(&euler, &turn, 1e-15), "{axes:?} {k}");
        }
    }
    // `euler_zyx(yaw, pitch, roll)`: yaw about z, then pitch about the new y.
    let q = from_euler(EulerSequence::ZYX, [FRAC_PI_2, 0.3, 0.0]).unwrap();
    let expected = plus(
        &from_axis_angle(&Vector3::z(), FRAC_PI_2).unwrap(),
        &Vector3::new(0.0, 0.3, 0.0),
    );
    assert!(same_orientation(&q, &expected.unwrap(), 1e-15));
}

#[test]
fn bad_input_is_a_typed_error() {
    let off = Vector4::new(1.1, 0.0, 0.0, 0.0);
    assert!(matches!(
        minus(&off, &identity()),
        Err(Error::NonUnitQuaternion { .. })
    ));
    assert!(matches!(
        plus(&off, &Vector3::zeros()),
        Err(Error::NonUnitQuaternion { .. })
    ));
    assert!(matches!(
        rotation_matrix(&Vector4::new(f64::NAN, 0.0, 0.0, 0.0)),
        Err(Error::NonUnitQuaternion { .. })
    ));
    assert!(matches!(
        from_axis_angle(&Vector3::zeros(), 1.0),
        Err(Error::Settings(_))
    ));
    assert!(matches!(
        from_axis_angle(&Vector3::x(), f64::INFINITY),
        Err(Error::Settings(_))
    ));
    assert!(matches!(
        plus(&identity(), &Vector3::new(f64::NAN, 0.0, 0.0)),
        Err(Error::Settings(_))
    ));
    assert!(matches!(
        from_euler(EulerSequence::ZXZ, [0.0, f64::NAN, 0.0]),
        Err(Error::Settings(_))
    ));
    assert!(EulerSequence::new([2, 2, 0]).is_err() && EulerSequence::new([0, 1, 3]).is_err());
    let mirror = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
    assert!(matches!(
        from_rotation_matrix(&mirror),
        Err(Error::Settings(_))
    ));
    assert!(matches!(
        from_rotation_matrix(&(Matrix3::identity() * 1.01)),
        Err(Error::Settings(_))
    ));
    // Within the tolerance a quaternion is normalised, as a run's start is.
    let near = Vector4::new(1.0 + 1e-8, 0.0, 0.0, 0.0);
    assert_eq!(minus(&near, &identity()).unwrap(), Vector3::zeros());
}

fn unit_quaternion() -> impl Strategy<Value = Vector4<f64>> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("not too short", |(w, x, y, z)| {
            w * w + x * x + y * y + z * z > 0.01
        })
        .prop_map(|(w, x, y, z)| Vector4::new(w, x, y, z).normalize())
}

fn rotation_vector(max: f64) -> impl Strategy<Value = Vector3<f64>> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, 0.0..max)
        .prop_filter("a direction", |(x, y, z, _)| x * x + y * y + z * z > 0.01)
        .prop_map(|(x, y, z, a)| Vector3::new(x, y, z).normalize() * a)
}

proptest! {
    #[test]
    fn minus_inverts_plus_below_a_half_turn(q in unit_quaternion(), delta in rotation_vector(PI - 1e-6)) {
        let back = minus(&plus(&q, &delta)?, &q)?;
        prop_assert!((back - delta).amax() < 1e-12, "{back} vs {delta}");
    }

    #[test]
    fn plus_inverts_minus(q in unit_quaternion(), q0 in unit_quaternion()) {
        let moved = plus(&q0, &minus(&q, &q0)?)?;
        prop_assert!(same_orientation(&moved, &q, 1e-12));
    }

    #[test]
    fn euler_angles_round_trip_through_the_sequence_s_matrix(
        k in 0..12usize,
        a in -3.0..3.0f64,
        b in 0.05..(PI - 0.05),
        c in -3.0..3.0f64,
    ) {
        let sequence = EulerSequence::new(SEQUENCES[k])?;
        let [first, _, last] = SEQUENCES[k];
        // The middle angle away from the sequence's singular set.
        let b = if first == last { b } else { b - FRAC_PI_2 };
        let q = from_euler(sequence, [a, b, c])?;
        let r = rotation_matrix(&q)?;
        prop_assert!((r - sequence.matrix([a, b, c])).amax() < 1e-14);
        let back = to_euler(sequence, &q, Some([a, b, c]))?;
        for (x, y) in back.iter().zip([a, b, c]) {
            prop_assert!((x - y).abs() < 1e-9, "{:?} vs {:?}", back, [a, b, c]);
        }
        prop_assert!(same_orientation(&from_rotation_matrix(&r)?, &q, 1e-14));
    }

    #[test]
    fn the_angular_velocity_of_euler_rates_turns_the_quaternion_alike(
        k in 0..12usize,
        angles in (-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64),
        rates in (-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64),
    ) {
        // (q(angles + h rates) ⊖ q(angles)) / h → ω in body axes.
        let sequence = EulerSequence::new(SEQUENCES[k])?;
        let (angles, rates) = ([angles.0, angles.1, angles.2], [rates.0, rates.1, rates.2]);
        let h = 1e-6;
        let at = |s: f64| from_euler(sequence, [0, 1, 2].map(|i| angles[i] + s * rates[i]));
        let omega = minus(&at(h)?, &at(-h)?)? / (2.0 * h);
        let expected = sequence.angular_velocity(angles, rates);
        prop_assert!((omega - expected).amax() < 1e-8, "{omega} vs {expected}");
    }
}

/// A sliding cart x and a free spherical body of unit inertia: no forces,
/// so x moves steadily and the body spins steadily, q(t) = q0 ⊗ exp(ω t).
pub(crate) struct CartAndBall;

impl Lagrangian<f64, 4, 5> for CartAndBall {
    const COORDINATES: [&'static str; 5] = ["x", "ball.w", "ball.x", "ball.y", "ball.z"];
    const VELOCITIES: [&'static str; 4] = ["x", "ball.wx", "ball.wy", "ball.wz"];
    const ORIENTATIONS: &'static [Orientation] = &[Orientation { q: 1, v: 1 }];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &SVector<f64, 5>, _: f64) -> SMatrix<f64, 4, 4> {
        SMatrix::identity()
    }
    fn bias(&self, _: &SVector<f64, 5>, _: &SVector<f64, 4>, _: f64) -> SVector<f64, 4> {
        SVector::zeros()
    }
    fn generalized_forces(
        &self,
        _: &SVector<f64, 5>,
        _: &SVector<f64, 4>,
        _: f64,
    ) -> SVector<f64, 4> {
        SVector::zeros()
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, 5>,
        _: &SVector<f64, 4>,
        t: f64,
    ) -> (SMatrix<f64, 4, 4>, SVector<f64, 4>) {
        (self.mass_matrix(q, t), SVector::zeros())
    }
    fn kinetic_energy(&self, _: &SVector<f64, 5>, v: &SVector<f64, 4>, _: f64) -> f64 {
        v.norm_squared() / 2.0
    }
    fn potential_energy(&self, _: &SVector<f64, 5>, _: f64) -> f64 {
        0.0
    }
    fn integral(&self, q: &SVector<f64, 5>, v: &SVector<f64, 4>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t)
    }
}

impl crate::system::Driven<f64, 4, 0, 5> for CartAndBall {}

pub(crate) fn configuration(x: f64, q: Vector4<f64>) -> SVector<f64, 5> {
    SVector::from([x, q[0], q[1], q[2], q[3]])
}

#[test]
fn whole_configurations_move_every_coordinate_in_the_layout() {
    let q0 = configuration(
        2.0,
        from_axis_angle(&Vector3::new(0.0, 1.0, 1.0), 0.4).unwrap(),
    );
    let delta = SVector::<f64, 4>::from([0.5, 0.1, -0.2, 0.3]);
    let q = configuration_plus(&CartAndBall, &q0, &delta).unwrap();
    assert_eq!(q[0], 2.5);
    let ball = plus(&q0.fixed_rows::<4>(1).into(), &Vector3::new(0.1, -0.2, 0.3)).unwrap();
    assert!((q.fixed_rows::<4>(1) - ball).amax() < 1e-15);
    let back = configuration_minus(&CartAndBall, &q, &q0).unwrap();
    assert!((back - delta).amax() < 1e-15, "{back}");
    let v = SVector::<f64, 4>::from([1.0, 0.0, 0.0, 2.0]);
    let (dq, dv) = state_minus(&CartAndBall, (&q, &v), (&q0, &SVector::zeros())).unwrap();
    assert_eq!((dq, dv), (back, v));
    let off = configuration(0.0, Vector4::new(0.0, 0.0, 2.0, 0.0));
    assert!(matches!(
        configuration_minus(&CartAndBall, &off, &q0),
        Err(Error::NonUnitQuaternion { ref orientation, .. }) if orientation == "ball"
    ));
}

#[test]
fn the_tangent_error_of_a_steady_spin_is_its_angle() {
    let (vx, spin) = (0.5, 0.8);
    let v0 = SVector::<f64, 4>::from([vx, 0.0, 0.0, spin]);
    let q0 = configuration(0.0, identity());
    let dynamics = Dynamics::new(&CartAndBall);
    let run = |tol| {
        Dopri5::tol(tol)
            .integrate(&dynamics, 0.0, 6.0, q0, v0)
            .unwrap()
    };
    let (fine, coarse) = (run(1e-12), run(1e-5));
    // Against the start held still: x − 0 = vx t, the turn about z is spin·t
    // the short way round (past t = π/spin it comes back from −π).
    let errors = fine.tangent_error(&CartAndBall, (&q0, &v0)).unwrap();
    assert_eq!(errors.len(), fine.len());
    for e in &errors {
        let angle = (spin * e.t + PI).rem_euclid(2.0 * PI) - PI;
        let expected = SVector::<f64, 4>::from([vx * e.t, 0.0, 0.0, angle]);
        assert!(
            (e.position - expected).amax() < 1e-9,
            "t = {}: {}",
            e.t,
            e.position
        );
        assert!(e.velocity.amax() < 1e-12);
    }
    assert!(errors.iter().any(|e| e.position[3] < -1.0)); // it did wrap
    // Two tolerances' runs compared at the coarse run's points.
    let along = coarse.tangent_error_along(&CartAndBall, &fine).unwrap();
    let worst = along.iter().map(|e| e.position.amax()).fold(0.0, f64::max);
    assert!(worst > 0.0 && worst < 1e-3, "{worst}");
    let short = Dopri5::tol(1e-8)
        .integrate(&dynamics, 0.0, 1.0, q0, v0)
        .unwrap();
    assert!(matches!(
        fine.tangent_error_along(&CartAndBall, &short),
        Err(Error::Settings(_))
    ));
}
