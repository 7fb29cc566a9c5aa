//! Systems and closed forms for the work-precision study (examples/work_precision/):
//! the Kepler problem, a stiff spring-pendulum, exact pendulum periods and Kepler
//! orbits, and a wrapper that gives a derived system the ∂T/∂q the symplectic Gauss
//! integrator needs.

use super::elliptic_k;
use lagrange::Lagrangian;

/// The Kepler problem in Cartesian coordinates: a point of mass `m` in the
/// potential −k/r. The mass matrix is constant, so Störmer–Verlet is symplectic
/// here.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y),
    point(p, mass = m, at = [x, y]),
    potential = -k / sqrt((x^2) + (y^2)),
    emit(hamiltonian),
)]
pub struct Kepler {
    pub m: f64,
    pub k: f64,
}

/// A pendulum whose rod is a stiff spring (stiffness `k`, rest length `l`), in
/// Cartesian coordinates: for k/m ≫ g/l the radial oscillation (frequency √(k/m))
/// is far faster than the swing (√(g/l)), the classic stiff mechanical system.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y),
    define(r = sqrt((x^2) + (y^2))),
    point(bob, mass = m, at = [x, y]),
    gravity = [0, -g],
    potential = k * ((r - l)^2) / 2,
    emit(hamiltonian),
)]
pub struct SpringPendulum {
    pub m: f64,
    pub k: f64,
    pub l: f64,
    pub g: f64,
}

impl SpringPendulum {
    /// Released from rest at angle `theta` from the downward vertical with the
    /// spring at its static stretch k (r − l) = m g cos θ, so that the fast radial
    /// mode starts (almost) unexcited and the solution is smooth: the case where
    /// stiffness, not accuracy, limits an explicit method's step.
    pub fn at_rest(&self, theta: f64) -> ([f64; 2], [f64; 2]) {
        let r = self.l + self.m * self.g * theta.cos() / self.k;
        ([r * theta.sin(), -r * theta.cos()], [0.0, 0.0])
    }
}

/// Exact period of a simple pendulum (length `l`, gravity `g`) released from rest
/// at amplitude `theta0`: T = 4 K(sin(θ0/2)) / √(g/l).
pub fn pendulum_period(l: f64, g: f64, theta0: f64) -> f64 {
    4.0 * elliptic_k((0.5 * theta0).sin()) / (g / l).sqrt()
}

/// The Jacobi elliptic function sn(u | m), parameter m = k², by the arithmetic–
/// geometric mean and descending Landen transformation (Abramowitz & Stegun
/// 16.4): a_{n+1} = (a_n + b_n)/2, b_{n+1} = √(a_n b_n), c_{n+1} = (a_n − b_n)/2 until
/// c_N vanishes, then φ_N = 2^N a_N u and φ_{n−1} = (φ_n + asin(c_n sin φ_n / a_n))/2;
/// sn = sin φ_0. Accurate to a few ulps for 0 ≤ m < 1.
pub fn jacobi_sn(u: f64, m: f64) -> f64 {
    let (mut a, mut c) = ([0.0f64; 16], [0.0f64; 16]);
    let (mut an, mut bn) = (1.0f64, (1.0 - m).sqrt());
    a[0] = an;
    c[0] = m.sqrt();
    let mut n = 0;
    while n + 1 < a.len() && (an - bn).abs() > 4.0 * f64::EPSILON * an {
        n += 1;
        (an, bn, c[n]) = (0.5 * (an + bn), (an * bn).sqrt(), 0.5 * (an - bn));
        a[n] = an;
    }
    let mut phi = 2f64.powi(n as i32) * a[n] * u;
    for j in (1..=n).rev() {
        phi = 0.5 * (phi + (c[j] * phi.sin() / a[j]).asin());
    }
    phi.sin()
}

/// Exact angle of a simple pendulum released from rest at `theta0` ∈ (0, π):
/// θ(t) = 2 asin(k sn(K − ω0 t | k²)), k = sin(θ0/2), ω0 = √(g/l).
pub fn pendulum_angle(l: f64, g: f64, theta0: f64, t: f64) -> f64 {
    let k = (0.5 * theta0).sin();
    let u = elliptic_k(k) - (g / l).sqrt() * t;
    2.0 * (k * jacobi_sn(u, k * k)).asin()
}

/// A Kepler orbit with semi-major axis `a`, eccentricity `e` and gravitational
/// parameter μ = k/m, starting at pericentre on the positive x axis and moving
/// counter-clockwise.
#[derive(Clone, Copy, Debug)]
pub struct KeplerOrbit {
    pub a: f64,
    pub e: f64,
    pub mu: f64,
}

impl KeplerOrbit {
    /// Initial position and velocity at pericentre: r = a (1 − e),
    /// v = √(μ (1 + e) / (a (1 − e))).
    pub fn initial(&self) -> ([f64; 2], [f64; 2]) {
        let (a, e) = (self.a, self.e);
        let v = (self.mu * (1.0 + e) / (a * (1.0 - e))).sqrt();
        ([a * (1.0 - e), 0.0], [0.0, v])
    }

    /// The orbital period 2π √(a³/μ).
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.mean_motion()
    }

    fn mean_motion(&self) -> f64 {
        (self.mu / self.a.powi(3)).sqrt()
    }

    /// The exact position at time t: the eccentric anomaly E solves Kepler's
    /// equation E − e sin E = n t (Newton's method), then
    /// x = a (cos E − e), y = a √(1 − e²) sin E.
    pub fn position(&self, t: f64) -> [f64; 2] {
        let (a, e) = (self.a, self.e);
        // Reduce the mean anomaly to [−π, π]: Newton then converges from E = M
        // (for e < 0.8; π is the safe start beyond) in a few iterations.
        let tau = 2.0 * std::f64::consts::PI;
        let m =
            (self.mean_motion() * t + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI;
        let mut big_e = if e < 0.8 {
            m
        } else {
            std::f64::consts::PI.copysign(m)
        };
        for _ in 0..50 {
            let step = (big_e - e * big_e.sin() - m) / (1.0 - e * big_e.cos());
            big_e -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        [
            a * (big_e.cos() - e),
            a * (1.0 - e * e).sqrt() * big_e.sin(),
        ]
    }
}

/// A rigid body turning freely about its centre of mass, principal moments
/// `i1 < i2 < i3`, its orientation a quaternion (no chart): spun near the
/// intermediate axis it flips over and over (the Dzhanibekov effect), and
/// Hamilton's form lets the symplectic Gauss method step it on the group.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    orientation(turn),
    body(b, mass = 1, inertia = [i1, i2, i3], at = [0, 0, 0], rotation = turn),
    // Drawn as the plate with moments (1, 2, 3): sides √24, √12 (visual only).
    shape(b, box(size = [4.9, 3.46, 0.15])),
    emit(hamiltonian),
)]
pub struct TumblingBody {
    pub i1: f64,
    pub i2: f64,
    pub i3: f64,
}

impl TumblingBody {
    /// The body of the studies: principal moments 1, 2, 3 (a plate).
    pub const PLATE: TumblingBody = TumblingBody {
        i1: 1.0,
        i2: 2.0,
        i3: 3.0,
    };
    /// Its spin in the studies, in body axes: near the intermediate axis,
    /// a flip every 7.42 s.
    pub const SPIN: [f64; 3] = [0.3, 1.0, 0.3];
}
