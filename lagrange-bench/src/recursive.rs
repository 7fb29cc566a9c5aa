//! A hand-written recursive Newton–Euler implementation of issue 10's spatial
//! chain: the in-process peer of the derived models (what a tree-structured
//! derivation should match in cost), checked against them in
//! `tests/spatial.rs`.
//!
//! One forward pass gives each body's angular velocity and acceleration and
//! its centre of mass acceleration (the base accelerating at −g stands for
//! gravity); one backward pass sums forces and moments towards the base, and
//! the joint torque is the moment along the joint axis. h − Q is that torque at
//! q̈ = 0; M's column j is the torque for q̈ = e_j at rest without gravity.

use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Unit, Vector3};

/// One rigid rod of the chain.
#[derive(Clone, Debug)]
pub struct Link {
    /// The joint axis in the parent's frame (which the joint rotates about).
    pub axis: Unit<Vector3<f64>>,
    /// The joint's position in the parent's frame.
    pub offset: Vector3<f64>,
    pub mass: f64,
    /// Centre of mass in the link's frame, from its joint.
    pub com: Vector3<f64>,
    /// Inertia tensor about the centre of mass, in the link's frame.
    pub inertia: Matrix3<f64>,
}

/// A serial chain of revolute joints under gravity.
#[derive(Clone, Debug)]
pub struct SerialChain {
    pub links: Vec<Link>,
    pub gravity: Vector3<f64>,
}

/// Kinematics of one body, in world axes.
struct Body {
    joint: Vector3<f64>,
    rotation: Matrix3<f64>,
    axis: Vector3<f64>,
    omega: Vector3<f64>,
    alpha: Vector3<f64>,
    com: Vector3<f64>,
    com_acc: Vector3<f64>,
}

impl SerialChain {
    /// The benchmark chain of n rods (mass 1 + 0.1k, length 1 − 0.02k, radius
    /// 0.05, axes alternating z, y, gravity 9.81 down z).
    pub fn benchmark(n: usize) -> Self {
        let links = (0..n)
            .map(|k| {
                let m = 1.0 + 0.1 * k as f64;
                let l = 1.0 - 0.02 * k as f64;
                let r = 0.05;
                let previous = if k == 0 {
                    0.0
                } else {
                    1.0 - 0.02 * (k - 1) as f64
                };
                let transverse = m * (3.0 * r * r + l * l) / 12.0;
                Link {
                    axis: if k % 2 == 0 {
                        Vector3::z_axis()
                    } else {
                        Vector3::y_axis()
                    },
                    offset: Vector3::new(previous, 0.0, 0.0),
                    mass: m,
                    com: Vector3::new(l / 2.0, 0.0, 0.0),
                    inertia: Matrix3::from_diagonal(&Vector3::new(
                        m * r * r / 2.0,
                        transverse,
                        transverse,
                    )),
                }
            })
            .collect();
        Self {
            links,
            gravity: Vector3::new(0.0, 0.0, -9.81),
        }
    }

    /// Joint torques τ(q, q̇, q̈) that produce the accelerations q̈, with the
    /// gravity `g` (inverse dynamics).
    pub fn inverse_dynamics(
        &self,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        g: &Vector3<f64>,
    ) -> DVector<f64> {
        let bodies = self.forward(q, v, a, g);
        let n = self.links.len();
        let mut tau = DVector::zeros(n);
        let (mut f_next, mut n_next): (Vector3<f64>, Vector3<f64>) =
            (Vector3::zeros(), Vector3::zeros());
        let mut joint_next: Option<Vector3<f64>> = None;
        for i in (0..n).rev() {
            let b = &bodies[i];
            let link = &self.links[i];
            let inertia = b.rotation * link.inertia * b.rotation.transpose();
            let force = link.mass * b.com_acc + f_next;
            let mut moment = inertia * b.alpha
                + b.omega.cross(&(inertia * b.omega))
                + (b.com - b.joint).cross(&(link.mass * b.com_acc))
                + n_next;
            if let Some(next) = joint_next {
                moment += (next - b.joint).cross(&f_next);
            }
            tau[i] = b.axis.dot(&moment);
            (f_next, n_next, joint_next) = (force, moment, Some(b.joint));
        }
        tau
    }

    /// The forward pass: each body's frame, axis, velocities and accelerations.
    fn forward(
        &self,
        q: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
        g: &Vector3<f64>,
    ) -> Vec<Body> {
        let mut rotation = Matrix3::identity();
        let (mut joint, mut omega, mut alpha) =
            (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        let mut joint_acc = -g;
        let mut out = Vec::with_capacity(self.links.len());
        for (i, link) in self.links.iter().enumerate() {
            // The joint sits on the parent: carried by its motion.
            let r = rotation * link.offset;
            joint_acc += alpha.cross(&r) + omega.cross(&omega.cross(&r));
            joint += r;
            let axis = rotation * link.axis.into_inner();
            let spin = axis * v[i];
            alpha += axis * a[i] + omega.cross(&spin);
            omega += spin;
            rotation *= Rotation3::from_axis_angle(&link.axis, q[i]).into_inner();
            let d = rotation * link.com;
            let com_acc = joint_acc + alpha.cross(&d) + omega.cross(&omega.cross(&d));
            out.push(Body {
                joint,
                rotation,
                axis,
                omega,
                alpha,
                com: joint + d,
                com_acc,
            });
        }
        out
    }

    /// M(q) (column j: the torques for q̈ = e_j at rest, without gravity) and
    /// Q − h = −τ(q, q̇, 0) with gravity.
    pub fn mass_matrix_and_rhs(
        &self,
        q: &DVector<f64>,
        v: &DVector<f64>,
    ) -> (DMatrix<f64>, DVector<f64>) {
        let n = self.links.len();
        let zero = DVector::zeros(n);
        let none = Vector3::zeros();
        let mut m = DMatrix::zeros(n, n);
        for j in 0..n {
            let mut e = DVector::zeros(n);
            e[j] = 1.0;
            m.set_column(j, &self.inverse_dynamics(q, &zero, &e, &none));
        }
        let rhs = -self.inverse_dynamics(q, v, &zero, &self.gravity);
        (m, rhs)
    }
}
