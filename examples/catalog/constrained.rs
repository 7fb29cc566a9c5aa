//! Catalog systems with constraints, rigid bodies and quasi-velocities (issue 3):
//! C1 and C3 with multipliers, C4–C6, C8, C9, the rolling disk and the Chaplygin
//! sleigh.

use lagrange::Lagrangian;
use lagrange::linear::{Linear, Linearizer, OperatingPoint};
use lagrange::nalgebra::{SVector, Vector5};

/// C1 in Cartesian coordinates: the bob on a thread of length `l`, kept by a
/// multiplier (Lagrange's equations of the first kind, seed 001 §12). No chart, no
/// pole; the thread tension is the reaction on the bob.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    point(bob, mass = m, at = [x, y, z]),
    gravity = [0, 0, -g],
    holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - (l^2)),
    emit(reactions),
)]
pub struct CartesianSphericalPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// C3 with the rod as a constraint between two free particles (Suslov ex. 96/100).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x1, y1, z1, x2, y2, z2),
    point(p1, mass = m1, at = [x1, y1, z1]),
    point(p2, mass = m2, at = [x2, y2, z2]),
    gravity = [gx, gy, gz],
    holonomic(rod = ((p1.x - p2.x)^2) + ((p1.y - p2.y)^2) + ((p1.z - p2.z)^2) - (l^2)),
    emit(reactions),
)]
pub struct RodPair {
    pub m1: f64,
    pub m2: f64,
    pub l: f64,
    pub gx: f64,
    pub gy: f64,
    pub gz: f64,
}

/// C4, Suslov ex. 97: a free rigid body as three particles fixed in a massless
/// frame (Euler angles z-x-z: precession ψ, nutation θ, spin φ). Body coordinates
/// of the particles are parameters; their centre of mass must be the origin.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(frame, mass = 0, inertia = [0, 0, 0], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    point(p1, on = frame, mass = m1, at = [a1, b1, c1]),
    point(p2, on = frame, mass = m2, at = [a2, b2, c2]),
    point(p3, on = frame, mass = m3, at = [a3, b3, c3]),
    gravity = [0, 0, -g],
)]
pub struct ThreeParticleBody {
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub a1: f64,
    pub b1: f64,
    pub c1: f64,
    pub a2: f64,
    pub b2: f64,
    pub c2: f64,
    pub a3: f64,
    pub b3: f64,
    pub c3: f64,
    pub g: f64,
}

/// C4: the same body given by its mass and inertia tensor about the centre of mass.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(b, mass = m, inertia = [ixx, iyy, izz, ixy, ixz, iyz], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
)]
pub struct InertiaBody {
    pub m: f64,
    pub ixx: f64,
    pub iyy: f64,
    pub izz: f64,
    pub ixy: f64,
    pub ixz: f64,
    pub iyz: f64,
    pub g: f64,
}

impl ThreeParticleBody {
    /// Three particles (masses 1, 2, 1.5) at fixed body coordinates, the third placed
    /// so that their centre of mass is the origin of the body frame.
    pub fn example(g: f64) -> Self {
        let (m1, m2, m3) = (1.0, 2.0, 1.5);
        let (r1, r2) = ([0.5, 0.1, -0.2], [-0.1, 0.4, 0.3]);
        let r3 = [0, 1, 2].map(|i| -(m1 * r1[i] + m2 * r2[i]) / m3);
        ThreeParticleBody {
            m1,
            m2,
            m3,
            a1: r1[0],
            b1: r1[1],
            c1: r1[2],
            a2: r2[0],
            b2: r2[1],
            c2: r2[2],
            a3: r3[0],
            b3: r3[1],
            c3: r3[2],
            g,
        }
    }

    /// The rigid-body description of the same particles: total mass and
    /// I = Σ m (|r|² 1 − r rᵀ) (the particles' centre of mass is the origin).
    pub fn as_body(&self) -> InertiaBody {
        let parts = [
            (self.m1, [self.a1, self.b1, self.c1]),
            (self.m2, [self.a2, self.b2, self.c2]),
            (self.m3, [self.a3, self.b3, self.c3]),
        ];
        let i = |j: usize, k: usize| -> f64 {
            parts
                .iter()
                .map(|(m, r)| {
                    let rr: f64 = r.iter().map(|x| x * x).sum();
                    m * (if j == k { rr } else { 0.0 } - r[j] * r[k])
                })
                .sum()
        };
        InertiaBody {
            m: self.m1 + self.m2 + self.m3,
            ixx: i(0, 0),
            iyy: i(1, 1),
            izz: i(2, 2),
            ixy: i(0, 1),
            ixz: i(0, 2),
            iyz: i(1, 2),
            g: self.g,
        }
    }
}

/// C5, Suslov ex. 98: a homogeneous sphere (radius `a`, J = 2/5 m a²) rolling without
/// slipping on the horizontal plane z = 0: the finite constraint z = a and two
/// nonholonomic ones (the material point at the contact has zero velocity), kept
/// with multipliers; with `emit(atlas)` it rolls through θ = 0.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z, psi, theta, phi),
    body(ball, mass = m, inertia = [j, j, j], at = [x, y, z],
         rotation = euler_zxz(psi, theta, phi)),
    // Drawn as a ball with an axle through it, to see it roll (visual only).
    shape(ball, sphere(radius = a)),
    shape(ball, box(size = [2.3 * a, 0.2 * a, 0.2 * a])),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    // Both forms: the reduced one also eliminates ż through the velocity form of
    // the finite constraint.
    formulation(multipliers, reduced),
    // The atlas takes the ball through θ = 0, where z-x-z stops
    // (`Simulation::run_atlas`, in the multiplier form).
    emit(reactions, atlas),
)]
pub struct RollingSphere {
    pub m: f64,
    pub j: f64,
    pub a: f64,
    pub g: f64,
}

/// C5 reduced: z = a built into the coordinates, the two rolling constraints
/// eliminated (independent speeds ψ̇, θ̇, φ̇ chosen by the macro).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, psi, theta, phi),
    body(ball, mass = m, inertia = [j, j, j], at = [x, y, a],
         rotation = euler_zxz(psi, theta, phi)),
    shape(ball, sphere(radius = a)),
    shape(ball, box(size = [2.3 * a, 0.2 * a, 0.2 * a])),
    gravity = [0, 0, -g],
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    formulation(reduced),
)]
pub struct RollingSphereReduced {
    pub m: f64,
    pub j: f64,
    pub a: f64,
    pub g: f64,
}

/// C6, Suslov ex. 99: two heavy bodies on fixed pivots (principal moments a, b, c,
/// the pivot on the c axis), joined by an untwistable thread along those axes: the
/// spins cancel,
/// ψ̇1 + cos θ1 φ̇1 + ψ̇2 + cos θ2 φ̇2 = 0 (φ precession, θ nutation, ψ spin).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(phi1, theta1, psi1, phi2, theta2, psi2),
    body(top1, mass = m, inertia = [a, b, c],
         at = [l * sin(theta1) * sin(phi1), -l * sin(theta1) * cos(phi1), l * cos(theta1)],
         rotation = euler_zxz(phi1, theta1, psi1)),
    body(top2, mass = m, inertia = [b, a, c],
         at = [d + l * sin(theta2) * sin(phi2), -l * sin(theta2) * cos(phi2), l * cos(theta2)],
         rotation = euler_zxz(phi2, theta2, psi2)),
    gravity = [0, 0, -g],
    nonholonomic(thread = dot(psi1) + cos(theta1) * dot(phi1) + dot(psi2) + cos(theta2) * dot(phi2)),
    // Drawn as spinning discs on spindles from their pivots (visual only).
    shape(top1, cylinder(radius = l, length = l / 5, axis = z)),
    shape(top1, box(size = [2 * l, l / 8, l / 3])),
    shape(top1, capsule(radius = l / 25, length = 1.3 * l, axis = z), at = [0, 0, -0.4 * l]),
    shape(top2, cylinder(radius = l, length = l / 5, axis = z)),
    shape(top2, box(size = [2 * l, l / 8, l / 3])),
    shape(top2, capsule(radius = l / 25, length = 1.3 * l, axis = z), at = [0, 0, -0.4 * l]),
)]
pub struct ThreadedTops {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub l: f64,
    pub d: f64,
    pub g: f64,
}

/// C8, seed 003 (Pars 13.1): a particle in the plane in polar coordinates, with the
/// quasi-velocity w = x ẏ − y ẋ = r² θ̇. Radial force `-k r`, transverse force `s`.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(r, theta),
    point(p, mass = m, at = [r * cos(theta), r * sin(theta)]),
    force(p, [-k * r * cos(theta) - s * sin(theta), -k * r * sin(theta) + s * cos(theta)]),
    speeds(rdot = dot(r), w = p.x * dot(p.y) - p.y * dot(p.x)),
)]
pub struct PolarQuasiVelocity {
    pub m: f64,
    pub k: f64,
    pub s: f64,
}

/// C8's reference: the same particle and forces in Cartesian coordinates.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y),
    define(r = sqrt((x^2) + (y^2))),
    point(p, mass = m, at = [x, y]),
    force(p, [-k * x - s * y / r, -k * y + s * x / r]),
)]
pub struct PlanarParticle {
    pub m: f64,
    pub k: f64,
    pub s: f64,
}

/// C9, seed 003 (Pars 13.5): a homogeneous sphere rolling on a plane that turns at
/// the constant rate Ω about the vertical axis through the origin: the contact
/// point moves with the plane, v_contact = Ω e_z × (x, y, 0).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, psi, theta, phi),
    body(ball, mass = m, inertia = [j, j, j], at = [x, y, a],
         rotation = euler_zxz(psi, theta, phi)),
    shape(ball, sphere(radius = a)),
    shape(ball, box(size = [2.3 * a, 0.2 * a, 0.2 * a])),
    gravity = [0, 0, -g],
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y + big_omega * ball.y,
                 slip_y = dot(ball.y) + a * ball.omega_x - big_omega * ball.x),
    formulation(reduced),
)]
pub struct SphereOnTurntable {
    pub m: f64,
    pub j: f64,
    pub a: f64,
    pub g: f64,
    pub big_omega: f64,
}

/// A thin disk (radius `a`, axial moment `c`, diametral `b`) rolling on the plane:
/// (x, y) is the contact point, ψ the heading, θ the tilt from the vertical, φ the
/// spin about the axle (body y axis).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, psi, theta, phi),
    body(disk, mass = m, inertia = [b, c, b],
         at = [x + a * sin(theta) * sin(psi), y - a * sin(theta) * cos(psi), a * cos(theta)],
         rotation = rot_z(psi) * rot_x(theta) * rot_y(phi)),
    // Drawn as a disc with a cross on it, to see it spin (visual only).
    shape(disk, cylinder(radius = a, length = a / 10, axis = y)),
    shape(disk, box(size = [1.9 * a, a / 6, a / 8])),
    shape(disk, box(size = [a / 8, a / 6, 1.9 * a])),
    gravity = [0, 0, -g],
    // The material point at the contact, centre − a u with u = (sθ sψ, −sθ cψ, cθ) the
    // disk's "up" direction, has zero velocity: v_centre − a ω × u = 0.
    nonholonomic(
        roll_x = dot(disk.x) - a * (disk.omega_y * cos(theta) + disk.omega_z * sin(theta) * cos(psi)),
        roll_y = dot(disk.y) - a * (disk.omega_z * sin(theta) * sin(psi) - disk.omega_x * cos(theta))
    ),
    formulation(reduced, multipliers),
    // Symbolic derivatives for linearising (critical spin of upright rolling).
    emit(jacobians),
)]
pub struct RollingDisk {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub g: f64,
}

impl RollingDisk {
    /// A thin uniform disk of mass `m` and radius `a`: diametral moment m a²/4,
    /// axial m a²/2 (its upright critical spin is √(g / 3a)).
    pub fn thin(m: f64, a: f64, g: f64) -> Self {
        RollingDisk {
            m,
            a,
            b: m * a * a / 4.0,
            c: m * a * a / 2.0,
            g,
        }
    }

    /// The linearised tilt dynamics (tilt, heading rate, tilt rate) about
    /// upright rolling straight ahead at spin Ω, the contact moving at a Ω along
    /// x; position, heading, spin angle and spin rate do not feed them.
    pub fn upright_tilt(&self, spin: f64) -> Result<Linear, lagrange::Error> {
        let v = Vector5::new(self.a * spin, 0.0, 0.0, 0.0, spin);
        Linearizer::new()
            .coordinates(&["x", "y", "psi", "theta", "phi"])
            .speeds(&["psi", "theta", "phi"])
            .constrained(self, &OperatingPoint::new(SVector::zeros(), v))?
            .select(&["theta", "psi'", "theta'"])
    }

    /// The state of steady circular motion at tilt θ0 and heading rate Ω, from the
    /// condition (derived by hand from the angular momentum about the centre, which
    /// turns with Ω about the vertical, and the torque of the contact force):
    ///
    /// ```text
    /// B Ω² sinθ cosθ − (C + m a²) Ω ω_a cosθ − m g a sinθ = 0,   ω_a = Ω sinθ + φ̇
    /// ```
    ///
    /// with B the diametral and C the axial moment. Returns (q0, q̇0); the contact
    /// velocities are left at zero for the reduced form to fill in.
    pub fn steady_circle(&self, theta0: f64, big_omega: f64) -> ([f64; 5], [f64; 5]) {
        let (s, c) = (theta0.sin(), theta0.cos());
        let (m, a) = (self.m, self.a);
        let omega_a = (self.b * big_omega * big_omega * s * c - m * self.g * a * s)
            / ((self.c + m * a * a) * big_omega * c);
        let phid = omega_a - big_omega * s;
        (
            [0.0, 0.0, 0.0, theta0, 0.0],
            [0.0, 0.0, big_omega, 0.0, phid],
        )
    }
}

/// The Chaplygin sleigh: a planar body on a knife edge at distance `b` behind its
/// centre of mass; the edge cannot move sideways. Speeds: forward speed of the edge
/// and the turning rate.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, theta),
    body(sled, mass = m, inertia = [0, 0, i], at = [x + b * cos(theta), y + b * sin(theta), 0],
         rotation = rot_z(theta)),
    point(blade, on = sled, at = [-b, 0, 0]),
    nonholonomic(sideways = -sin(theta) * dot(blade.x) + cos(theta) * dot(blade.y)),
    speeds(forward = cos(theta) * dot(blade.x) + sin(theta) * dot(blade.y), turn = dot(theta)),
    formulation(reduced, multipliers),
)]
pub struct ChaplyginSleigh {
    pub m: f64,
    pub i: f64,
    pub b: f64,
}
