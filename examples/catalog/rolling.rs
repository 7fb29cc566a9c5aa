//! Rolling bodies with free orientations (`orientation(..)` with
//! `holonomic` and `nonholonomic` rows, multiplier form): the sphere and the
//! disk of `constrained.rs` without their Euler-angle charts.

use lagrange::prelude::*;

/// A sphere (radius `a`, centre of mass at its centre, principal moments
/// j1, j2, j3: Chaplygin's ball; j1 = j2 = j3 = 2/5 m a² for a homogeneous
/// one) rolling without slipping on the plane z = 0, its centre (x, y, z)
/// and a free orientation: the rows of `RollingSphere` with no chart.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    orientation(ball_q),
    body(ball, mass = m, inertia = [j1, j2, j3], at = [x, y, z], rotation = ball_q),
    shape(ball, sphere(radius = a)),
    shape(ball, box(size = [2.3 * a, 0.2 * a, 0.2 * a])),
    gravity = [0, 0, -g],
    holonomic(height = ball.z - a),
    nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                 slip_y = dot(ball.y) + a * ball.omega_x),
    emit(reactions),
)]
pub struct QuaternionSphere {
    pub m: f64,
    pub j1: f64,
    pub j2: f64,
    pub j3: f64,
    pub a: f64,
    pub g: f64,
}

/// A thin disk (radius `a`, axial moment `c` about its axle, the body y
/// axis, diametral `b`) rolling on the plane, its centre (x, y, z) and a
/// free orientation: the centre stands a·√(1 − n_z²) above the plane (n the
/// axle), and the material point at the contact, centre − a u with
/// u = (e_z − n_z n)/√(1 − n_z²), has no velocity. The rows of
/// `RollingDisk` with no chart (the disk flat, n vertical, has no contact
/// point: the rows are singular there whatever the coordinates).
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(x, y, z),
    orientation(disk_q),
    body(disk, mass = m, inertia = [b, c, b], at = [x, y, z], rotation = disk_q),
    shape(disk, cylinder(radius = a, length = a / 10, axis = y)),
    shape(disk, box(size = [1.9 * a, a / 6, a / 8])),
    gravity = [0, 0, -g],
    define(nz = disk.axis_y.z,
           s = sqrt(1 - pow(nz, 2)),
           ux = -nz * disk.axis_y.x / s,
           uy = -nz * disk.axis_y.y / s),
    holonomic(height = disk.z - a * s),
    nonholonomic(
        roll_x = dot(disk.x) - a * (disk.omega_y * s - disk.omega_z * uy),
        roll_y = dot(disk.y) - a * (disk.omega_z * ux - disk.omega_x * s)
    ),
)]
pub struct QuaternionDisk {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub g: f64,
}

impl QuaternionDisk {
    /// A thin uniform disk of mass `m` and radius `a` (as
    /// `RollingDisk::thin`).
    pub fn thin(m: f64, a: f64, g: f64) -> Self {
        QuaternionDisk {
            m,
            a,
            b: m * a * a / 4.0,
            c: m * a * a / 2.0,
            g,
        }
    }
}
