//! Systems driven by inputs: what controllers are designed for.

use lagrange::Lagrangian;
use lagrange::control::StateFeedback;
use lagrange::linear::{Linear, OperatingPoint, linearize};
use lagrange::nalgebra::{DMatrix, DVector, SVector, Vector1, Vector2, Vector3};
use lagrange::orientation;
use lagrange::plan::{OptimalControl, Waypoint};

/// A cart on a horizontal rail carrying an inverted pendulum (a point mass at
/// the end of a massless rod); θ is measured from the upward vertical, so the
/// upright equilibrium is q = 0. The input is the horizontal force on the cart.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, theta),
    inputs(force),
    point(cart, mass = m_c, at = [x, 0]),
    point(bob, mass = m_p, at = [x + l * sin(theta), l * cos(theta)]),
    gravity = [0, -g],
    generalized_force(x = force),
    emit(jacobians),
)]
pub struct CartPole {
    pub m_c: f64,
    pub m_p: f64,
    pub l: f64,
    pub g: f64,
}

impl CartPole {
    /// A 1 kg cart with a 0.1 kg bob on a 0.5 m rod.
    pub fn standard() -> Self {
        CartPole {
            m_c: 1.0,
            m_p: 0.1,
            l: 0.5,
            g: 9.81,
        }
    }

    /// The linearisation about upright at rest with zero force (states x, θ,
    /// ẋ, θ̇; input the force).
    pub fn upright(&self) -> Result<Linear, lagrange::Error> {
        let op = OperatingPoint::new(Vector2::zeros(), Vector2::zeros()).input(Vector1::zeros());
        linearize(self, &op)
    }

    /// The LQR weights used in the catalog: Q = diag(10, 100, 1, 1), R = 0.1.
    pub fn lqr_weights() -> (DMatrix<f64>, DMatrix<f64>) {
        (
            DMatrix::from_diagonal(&DVector::from_vec(vec![10.0, 100.0, 1.0, 1.0])),
            DMatrix::from_element(1, 1, 0.1),
        )
    }

    /// The LQR law u = −K x with the catalog's weights, about upright: a
    /// static-size feedback that allocates nothing per call.
    pub fn lqr_feedback(&self) -> Result<StateFeedback<f64, 2, 1>, lagrange::Error> {
        let lin = self.upright()?;
        let (q, r) = Self::lqr_weights();
        StateFeedback::from_gain(&lin.lqr(&q, &r)?.gain, &lin, &Self::COORDINATES)
    }
}

/// A two-link arm in a vertical plane with a torque at each joint: point masses
/// at the elbow and the hand, q1 the shoulder angle from the horizontal, q2 the
/// elbow angle relative to the upper arm.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(q1, q2),
    inputs(tau1, tau2),
    point(elbow, mass = m1, at = [l1 * cos(q1), l1 * sin(q1)]),
    point(hand, mass = m2, at = [l1 * cos(q1) + l2 * cos(q1 + q2), l1 * sin(q1) + l2 * sin(q1 + q2)]),
    // The scene's links (visual only): the shoulder a point without mass at
    // the origin, the elbow and hand as balls, the links as lines.
    point(shoulder, mass = 0, at = [0, 0]),
    shape(elbow, sphere(radius = 0.05)),
    shape(hand, sphere(radius = 0.04)),
    shape(line(shoulder, elbow, hand)),
    gravity = [0, -g],
    generalized_force(q1 = tau1, q2 = tau2),
    emit(jacobians),
)]
pub struct TwoLinkArm {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

impl TwoLinkArm {
    /// 2 kg and 1 kg links of 0.6 m and 0.4 m.
    pub fn standard() -> Self {
        TwoLinkArm {
            m1: 2.0,
            m2: 1.0,
            l1: 0.6,
            l2: 0.4,
            g: 9.81,
        }
    }

    /// The reference the catalog's arm tracks, shoulder and elbow swinging at 1
    /// and 1.5 rad/s: q_d(t), q̇_d(t), q̈_d(t).
    pub fn reference(t: f64) -> [Vector2<f64>; 3] {
        [
            Vector2::new(0.5 * t.sin(), 0.8 + 0.4 * (1.5 * t).cos()),
            Vector2::new(0.5 * t.cos(), -0.6 * (1.5 * t).sin()),
            Vector2::new(-0.5 * t.sin(), -0.9 * (1.5 * t).cos()),
        ]
    }

    /// Computed torque τ = M (q̈_d + K_d ė + K_p e) − (Q − h)|_{τ=0}, e = q_d − q:
    /// with the exact model each joint error obeys ë + K_d ė + K_p e = 0 (the
    /// torques are the generalized forces of q1 and q2 one to one).
    pub fn computed_torque(
        &self,
        gains: (f64, f64),
        t: f64,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
    ) -> Vector2<f64> {
        let (kp, kd) = gains;
        let [qd, vd, ad] = Self::reference(t);
        let (m, unforced) = self.mass_matrix_and_rhs(q, v, t);
        m * (ad + (vd - v) * kd + (qd - q) * kp) - unforced
    }
}

/// Spong's acrobot: a double pendulum in a vertical plane driven only at
/// the elbow. Point masses at the elbow and the hand; q1 the upper link's
/// angle from the downward vertical, q2 the elbow's relative to it, so it
/// hangs at rest at q = 0 and stands upright at (π, 0).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(q1, q2),
    inputs(tau),
    point(elbow, mass = m1, at = [l1 * sin(q1), -l1 * cos(q1)]),
    point(hand, mass = m2, at = [l1 * sin(q1) + l2 * sin(q1 + q2), -l1 * cos(q1) - l2 * cos(q1 + q2)]),
    point(shoulder, mass = 0, at = [0, 0]),
    shape(elbow, sphere(radius = 0.06)),
    shape(hand, sphere(radius = 0.06)),
    shape(line(shoulder, elbow, hand)),
    gravity = [0, -g],
    generalized_force(q2 = tau),
    emit(jacobians),
)]
pub struct Acrobot {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

impl Acrobot {
    /// Two 1 kg masses on 1 m links.
    pub fn standard() -> Self {
        Acrobot {
            m1: 1.0,
            m2: 1.0,
            l1: 1.0,
            l2: 1.0,
            g: 9.81,
        }
    }
}

/// A quadrotor in a vertical plane: two rotors of mass m/2 at ±d from the
/// centre along the body's axis, each pushing along the body's normal
/// (−sin θ, cos θ) with its thrust. x and z place the centre, θ turns the
/// body (counter-clockwise), so a hover is θ = 0 with each thrust m g / 2
/// and a flip takes θ from 0 to 2π.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, z, theta),
    inputs(right, left),
    point(rotor_right, mass = m / 2, at = [x + d * cos(theta), z + d * sin(theta)]),
    point(rotor_left, mass = m / 2, at = [x - d * cos(theta), z - d * sin(theta)]),
    point(centre, mass = 0, at = [x, z]),
    shape(rotor_right, sphere(radius = 0.05)),
    shape(rotor_left, sphere(radius = 0.05)),
    shape(line(rotor_left, centre, rotor_right)),
    force(rotor_right, [-right * sin(theta), right * cos(theta)]),
    force(rotor_left, [-left * sin(theta), left * cos(theta)]),
    gravity = [0, -g],
    emit(jacobians),
)]
pub struct PlanarQuadrotor {
    pub m: f64,
    pub d: f64,
    pub g: f64,
}

impl PlanarQuadrotor {
    /// 1 kg, rotors 0.2 m from the centre.
    pub fn standard() -> Self {
        PlanarQuadrotor {
            m: 1.0,
            d: 0.2,
            g: 9.81,
        }
    }

    /// Each rotor's thrust in a hover.
    pub fn hover_thrust(&self) -> f64 {
        self.m * self.g / 2.0
    }
}

/// A quadrotor in space: a rigid body (mass m, principal moments a, a, c
/// about its centre) with a free orientation, its four rotors on the
/// body's x and y axes at d from the centre ("+" layout: 1 at +x, 2 at +y,
/// 3 at −x, 4 at −y). Each pushes along the body's z axis with its thrust
/// and, spinning, drags the body about z with k times it: rotors 1 and 3
/// one way, 2 and 4 the other. A hover is level with each thrust m g / 4.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    orientation(att),
    inputs(f1, f2, f3, f4),
    body(frame, mass = m, inertia = [a, a, c], at = [x, y, z], rotation = att),
    point(rotor1, on = frame, at = [d, 0, 0]),
    point(rotor2, on = frame, at = [0, d, 0]),
    point(rotor3, on = frame, at = [-d, 0, 0]),
    point(rotor4, on = frame, at = [0, -d, 0]),
    force(rotor1, [f1 * frame.axis_z.x, f1 * frame.axis_z.y, f1 * frame.axis_z.z]),
    force(rotor2, [f2 * frame.axis_z.x, f2 * frame.axis_z.y, f2 * frame.axis_z.z]),
    force(rotor3, [f3 * frame.axis_z.x, f3 * frame.axis_z.y, f3 * frame.axis_z.z]),
    force(rotor4, [f4 * frame.axis_z.x, f4 * frame.axis_z.y, f4 * frame.axis_z.z]),
    torque(frame, [0, 0, k * (f2 + f4 - f1 - f3)], axes = body),
    gravity = [0, 0, -g],
    shape(frame, box(size = [2 * d, 0.03, 0.02])),
    shape(frame, box(size = [0.03, 2 * d, 0.02])),
    emit(jacobians),
)]
pub struct Quadrotor {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub d: f64,
    pub k: f64,
    pub g: f64,
}

impl Quadrotor {
    /// 1 kg, rotors 0.2 m from the centre, moments 0.01 and 0.018 kg m²,
    /// drag 0.02 N·m per N of thrust.
    pub fn standard() -> Self {
        Quadrotor {
            m: 1.0,
            a: 0.01,
            c: 0.018,
            d: 0.2,
            k: 0.02,
            g: 9.81,
        }
    }

    /// Each rotor's thrust in a hover.
    pub fn hover_thrust(&self) -> f64 {
        self.m * self.g / 4.0
    }

    /// At (x, y, z), rolled by `angle` about the body's x axis.
    pub fn rolled(position: [f64; 3], angle: f64) -> Result<SVector<f64, 7>, lagrange::Error> {
        let turn = orientation::from_axis_angle(&Vector3::x(), angle)?;
        let [x, y, z] = position;
        Ok(SVector::from([x, y, z, turn[0], turn[1], turn[2], turn[3]]))
    }

    /// A flip: from a hover at the origin back to it in `steps` steps of
    /// `h` seconds (RK4 on the group), rolled once round about the body's x
    /// axis on the way, each thrust between zero and twice the hover's. The
    /// goal alone cannot ask for the turn (rolled by 2π the body is where it
    /// started), so the attitude passes two waypoints, rolled 2π/3 at a
    /// third of the way and 4π/3 at two thirds: each leg shorter than half
    /// a turn, the shortest way from one to the next is forwards.
    pub fn flip(
        &self,
        h: f64,
        steps: usize,
    ) -> Result<OptimalControl<'_, Self, 6, 4, 7>, lagrange::Error> {
        let diagonal = |d: &[f64]| DMatrix::from_diagonal(&DVector::from_column_slice(d));
        let hover = self.hover_thrust();
        let level = Self::rolled([0.0; 3], 0.0)?;
        let still = SVector::<f64, 6>::zeros();
        let mut problem = OptimalControl::new(
            lagrange::linear::Transition::new(self, h)?,
            steps,
            (level, still),
            diagonal(&[0.0; 12]),
            diagonal(&[0.01; 4]),
        )
        .goal(level, still)
        .input_target(SVector::repeat(hover))
        .final_weight(diagonal(&[
            1e3, 1e3, 1e3, 1e3, 1e3, 1e3, 100.0, 100.0, 100.0, 10.0, 10.0, 10.0,
        ]))
        .input_bounds(SVector::zeros(), SVector::repeat(2.0 * hover));
        let attitude = diagonal(&[
            0.0, 0.0, 0.0, 100.0, 100.0, 100.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ]);
        for third in [1, 2] {
            let k = steps * third / 3;
            let turned = Self::rolled([0.0; 3], 2.0 * std::f64::consts::PI * third as f64 / 3.0)?;
            let at = Waypoint::new(self, k as f64 * h, (turned, still), attitude.clone())?;
            problem = problem.running_cost(at);
        }
        Ok(problem)
    }

    /// A guess for the flip's plan that rolls at a constant rate, on the
    /// spot, at the hover's thrusts: not a motion of the quadrotor (upside
    /// down those thrusts push it down), but one that passes the waypoints
    /// in the right order. From the hover alone (no roll at all) the second
    /// waypoint, 4π/3 round, is nearer the other way, −2π/3, and DDP
    /// settles on rolling there and back.
    #[allow(clippy::type_complexity)]
    pub fn flip_guess(
        &self,
        h: f64,
        steps: usize,
    ) -> Result<
        (
            Vec<SVector<f64, 7>>,
            Vec<SVector<f64, 6>>,
            Vec<SVector<f64, 4>>,
        ),
        lagrange::Error,
    > {
        let rate = 2.0 * std::f64::consts::PI / (steps as f64 * h);
        let q = (0..=steps)
            .map(|k| Self::rolled([0.0; 3], rate * k as f64 * h))
            .collect::<Result<Vec<_>, _>>()?;
        let v = vec![SVector::from([0.0, 0.0, 0.0, rate, 0.0, 0.0]); steps + 1];
        Ok((q, v, vec![SVector::repeat(self.hover_thrust()); steps]))
    }

    /// The turn accumulated along a sequence of configurations: the sum of
    /// each step's rotation vector, in the body's axes of the moment (a
    /// roll once round about x reads (2π, 0, 0), which the end's attitude
    /// alone, back at level, cannot tell).
    pub fn accumulated_turn(
        &self,
        qs: &[SVector<f64, 7>],
    ) -> Result<Vector3<f64>, lagrange::Error> {
        let mut sum = Vector3::zeros();
        for pair in qs.windows(2) {
            let d = orientation::configuration_minus(self, &pair[1], &pair[0])?;
            sum += d.fixed_rows::<3>(3);
        }
        Ok(sum)
    }
}
