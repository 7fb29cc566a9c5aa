//! Systems driven by inputs: what controllers are designed for.

use lagrange::Lagrangian;

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
}
