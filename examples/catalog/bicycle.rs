//! The Whipple bicycle of the benchmark by Meijaard, Papadopoulos, Ruina & Schwab
//! (Proc. R. Soc. A 463, 2007): a rear frame with rider, a front frame (fork and
//! handlebar) turning about a steer axis tilted back by λ, and two knife-edge
//! wheels rolling without slipping on level ground.
//!
//! World axes here: x forward, y to the left, z up (the paper's are x forward,
//! y right, z down: a rotation by π about x, which flips the sign of the
//! products of inertia I_xz and of the heights). Coordinates: the rear contact
//! (x, y), yaw ψ, roll φ, the rear frame's pitch θ, the rear wheel's rotation
//! θ_r, the steer angle δ and the front wheel's rotation θ_f. The pitch is
//! fixed by the front wheel touching the ground (a holonomic constraint); the
//! four rolling conditions leave three speeds: roll rate, steer rate and rear
//! wheel rate (forward speed).
//!
//! Written in the order a designer thinks (rear wheel, rear frame on its hub,
//! steer axis on the rear frame, front frame about it, front wheel on the
//! fork): each body is placed at a point of the one before.

use lagrange::Lagrangian;
use lagrange::linear::{Linear, Linearizer, OperatingPoint};
use lagrange::nalgebra::SVector;

/// The Whipple bicycle; see the module docs. The fields are the benchmark's
/// parameters with heights measured up from the ground (the paper's z_B = −0.9
/// is `h_b = 0.9`) and products of inertia converted to these axes.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, psi, phi, pitch, theta_r, delta, theta_f),
    // The rear wheel's "up" direction in its plane, (sψ sφ, −cψ sφ, cφ).
    define(up_x = sin(psi) * sin(phi), up_y = -cos(psi) * sin(phi), up_z = cos(phi)),
    body(rear_wheel, mass = m_r, inertia = [i_rxx, i_ryy, i_rxx],
         at = [x + r_r * up_x, y + r_r * up_y, r_r * up_z],
         rotation = rot_z(psi) * rot_x(phi) * rot_y(pitch + theta_r)),
    body(rear_frame, mass = m_b, inertia = [i_bxx, i_byy, i_bzz, 0, i_bxz, 0],
         at = [rear_wheel.x, rear_wheel.y, rear_wheel.z], com = [x_b, 0, h_b - r_r],
         rotation = rot_z(psi) * rot_x(phi) * rot_y(pitch)),
    // Where the steer axis meets the ground in the reference configuration,
    // the trail c ahead of the front contact.
    point(steer_base, on = rear_frame, at = [w + c, 0, -r_r]),
    body(front_frame, mass = m_h, inertia = [i_hxx, i_hyy, i_hzz, 0, i_hxz, 0],
         at = [steer_base.x, steer_base.y, steer_base.z], com = [x_h - w - c, 0, h_h],
         rotation = rot_z(psi) * rot_x(phi) * rot_y(pitch) * rot_y(-lambda) * rot_z(delta)
             * rot_y(lambda)),
    point(front_hub, on = front_frame, at = [-c, 0, r_f]),
    point(front_axle, on = front_frame, at = [-c, 1, r_f]),
    body(front_wheel, mass = m_f, inertia = [i_fxx, i_fyy, i_fxx],
         at = [front_hub.x, front_hub.y, front_hub.z],
         rotation = rot_z(psi) * rot_x(phi) * rot_y(pitch) * rot_y(-lambda) * rot_z(delta)
             * rot_y(lambda) * rot_y(theta_f)),
    // The front axle a (a unit vector) and the front contact, the lowest point
    // of the wheel: hub + d with d = −r_f (e_z − a_z a) / s, s = √(1 − a_z²).
    define(
        a_x = front_axle.x - front_hub.x,
        a_y = front_axle.y - front_hub.y,
        a_z = front_axle.z - front_hub.z,
        s = sqrt(1 - (a_z^2)),
        d_x = r_f * a_z * a_x / s,
        d_y = r_f * a_z * a_y / s,
        d_z = -r_f * s
    ),
    gravity = [0, 0, -g],
    holonomic(front_on_ground = front_hub.z + d_z),
    // Rolling without slipping: the material point of each wheel at its contact
    // has no horizontal velocity, v_hub + ω × (contact − hub) = 0.
    nonholonomic(
        rear_x = dot(rear_wheel.x) - r_r * (rear_wheel.omega_y * up_z - rear_wheel.omega_z * up_y),
        rear_y = dot(rear_wheel.y) - r_r * (rear_wheel.omega_z * up_x - rear_wheel.omega_x * up_z),
        front_x = dot(front_hub.x) + front_wheel.omega_y * d_z - front_wheel.omega_z * d_y,
        front_y = dot(front_hub.y) + front_wheel.omega_z * d_x - front_wheel.omega_x * d_z
    ),
    // What the scene draws (visual only, no equation reads it): the wheels as
    // discs with a cross to show them turn, the frame as tubes between
    // massless points (bottom bracket, seat, head tube on the steer axis), a
    // saddle and the handlebar.
    point(bottom_bracket, on = rear_frame, at = [0.4, 0, -0.02]),
    point(seat, on = rear_frame, at = [0.25, 0, 0.65]),
    point(head_low, on = rear_frame,
          at = [w + c - 0.75 * sin(lambda), 0, 0.75 * cos(lambda) - r_r]),
    point(head_high, on = rear_frame,
          at = [w + c - 1.05 * sin(lambda), 0, 1.05 * cos(lambda) - r_r]),
    point(stem, on = front_frame, at = [-1.1 * sin(lambda), 0, 1.1 * cos(lambda)]),
    shape(rear_wheel, cylinder(radius = r_r, length = 0.03, axis = y)),
    shape(rear_wheel, box(size = [1.9 * r_r, 0.05, 0.03])),
    shape(rear_wheel, box(size = [0.03, 0.05, 1.9 * r_r])),
    shape(front_wheel, cylinder(radius = r_f, length = 0.03, axis = y)),
    shape(front_wheel, box(size = [1.9 * r_f, 0.05, 0.03])),
    shape(front_wheel, box(size = [0.03, 0.05, 1.9 * r_f])),
    shape(line(rear_wheel, bottom_bracket, head_low, head_high, seat, rear_wheel)),
    shape(line(seat, bottom_bracket)),
    shape(line(front_hub, head_low)),
    shape(line(head_high, stem)),
    shape(rear_frame, box(size = [0.26, 0.14, 0.05]), at = [0.25, 0, 0.68]),
    shape(front_frame, capsule(radius = 0.018, length = 0.55, axis = y),
          at = [-1.1 * sin(lambda) - 0.05, 0, 1.1 * cos(lambda)]),
    // Both forms: the reduced one on the roll, rear wheel and steer rates.
    speeds(roll = dot(phi), rear = dot(theta_r), steer = dot(delta)),
    formulation(multipliers, reduced),
    // Symbolic derivatives of the constrained dynamics, for the linearisation
    // about upright straight rolling.
    emit(jacobians),
)]
pub struct Bicycle {
    pub w: f64,
    pub c: f64,
    pub lambda: f64,
    pub g: f64,
    pub r_r: f64,
    pub m_r: f64,
    pub i_rxx: f64,
    pub i_ryy: f64,
    pub x_b: f64,
    pub h_b: f64,
    pub m_b: f64,
    pub i_bxx: f64,
    pub i_byy: f64,
    pub i_bzz: f64,
    pub i_bxz: f64,
    pub x_h: f64,
    pub h_h: f64,
    pub m_h: f64,
    pub i_hxx: f64,
    pub i_hyy: f64,
    pub i_hzz: f64,
    pub i_hxz: f64,
    pub r_f: f64,
    pub m_f: f64,
    pub i_fxx: f64,
    pub i_fyy: f64,
}

impl Bicycle {
    /// The benchmark bicycle of Meijaard et al. (2007), Table 1, in these axes.
    pub fn benchmark() -> Self {
        Bicycle {
            w: 1.02,
            c: 0.08,
            lambda: std::f64::consts::PI / 10.0,
            g: 9.81,
            r_r: 0.3,
            m_r: 2.0,
            i_rxx: 0.0603,
            i_ryy: 0.12,
            x_b: 0.3,
            h_b: 0.9,
            m_b: 85.0,
            i_bxx: 9.2,
            i_byy: 11.0,
            i_bzz: 2.8,
            // The paper's I_Bxz = 2.4 with z down.
            i_bxz: -2.4,
            x_h: 0.9,
            h_h: 0.7,
            m_h: 4.0,
            i_hxx: 0.05892,
            i_hyy: 0.06,
            i_hzz: 0.00708,
            // The paper's I_Hxz = −0.00756 with z down.
            i_hxz: 0.00756,
            r_f: 0.35,
            m_f: 3.0,
            i_fxx: 0.1405,
            i_fyy: 0.28,
        }
    }

    /// Upright, straight ahead along x at forward speed `v`: every angle zero
    /// (the benchmark's reference configuration satisfies the front contact
    /// exactly), both wheels rolling at v / r.
    pub fn upright(&self, v: f64) -> ([f64; 8], [f64; 8]) {
        (
            [0.0; 8],
            [v, 0.0, 0.0, 0.0, 0.0, v / self.r_r, 0.0, v / self.r_f],
        )
    }

    /// The linearised lateral dynamics about upright straight rolling at forward
    /// speed `v`, in the benchmark's states (roll φ, steer δ and their rates).
    ///
    /// The multiplier form is linearised in the independent coordinates (all
    /// but the pitch, which the front contact fixes) and the independent speeds
    /// (roll, rear wheel and steer rates); position, heading, wheel angles and
    /// the forward speed do not feed the lateral motion and are dropped.
    pub fn lateral(&self, v: f64) -> Result<Linear, lagrange::Error> {
        let (q, qd) = self.upright(v);
        let op = OperatingPoint::new(SVector::from(q), SVector::from(qd));
        Linearizer::new()
            .coordinates(&["x", "y", "psi", "phi", "theta_r", "delta", "theta_f"])
            .speeds(&["phi", "theta_r", "delta"])
            .constrained(self, &op)?
            .select(&["phi", "delta", "phi'", "delta'"])
    }
}

/// The benchmark's published coefficient matrices (Meijaard et al. 2007, eq. (A 21)
/// ff.) for M q̈ + v C1 q̇ + (g K0 + v² K2) q = f, q = (φ, δ), in the paper's
/// sign convention (steer positive to the right).
pub mod published {
    /// M.
    pub const M: [[f64; 2]; 2] = [
        [80.81722, 2.31941332208709],
        [2.31941332208709, 0.29784188199686],
    ];
    /// C1.
    pub const C1: [[f64; 2]; 2] = [
        [0.0, 33.86641391492494],
        [-0.85035641456978, 1.68540397397560],
    ];
    /// K0.
    pub const K0: [[f64; 2]; 2] = [
        [-80.95, -2.59951685249872],
        [-2.59951685249872, -0.80329488458618],
    ];
    /// K2.
    pub const K2: [[f64; 2]; 2] = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]];
    /// The weave speed, where the oscillatory mode turns stable (m/s).
    pub const WEAVE_SPEED: f64 = 4.2923825363;
    /// The capsize speed, where the capsize mode turns unstable (m/s).
    pub const CAPSIZE_SPEED: f64 = 6.0242620154;
}
