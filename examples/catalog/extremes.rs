//! Systems for the stability studies at the extremes (issue "Stability at the
//! extremes"): a stiff spring pendulum, the heavy symmetric top, and a wrapper that
//! gives a constant-mass-matrix system the ∂T/∂q the symplectic Gauss method needs.

use lagrange::Lagrangian;
use lagrange::nalgebra::{SMatrix, SVector};

/// A pendulum whose rod is a stiff spring: polar coordinates (r, θ) of the bob,
/// θ from the downward vertical, spring stiffness `k` and rest length `l0`. With
/// k/m = 10⁸ the radial mode is 10⁴ times faster than the swing: a stiff system.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(r, theta),
    point(bob, mass = m, at = [r * sin(theta), -r * cos(theta)]),
    gravity = [0, -g],
    potential = k * ((r - l0)^2) / 2,
)]
pub struct SpringPendulum {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub g: f64,
}

/// The heavy symmetric top (Lagrange's top) on a fixed pivot: centre of mass at
/// distance `l` up the symmetry axis, moments `a` (transverse, about the centre of
/// mass) and `c` (axial); z-x-z Euler angles ψ (precession), θ (nutation), φ (spin).
/// ψ and φ are cyclic, so p_ψ and p_φ are conserved along with the energy.
#[derive(Lagrangian, Clone, Copy, Debug)]
#[lagrange(
    coordinates(psi, theta, phi),
    body(top, mass = m, inertia = [a, a, c],
         at = [l * sin(theta) * sin(psi), -l * sin(theta) * cos(psi), l * cos(theta)],
         rotation = euler_zxz(psi, theta, phi)),
    gravity = [0, 0, -g],
)]
pub struct HeavyTop {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub l: f64,
    pub g: f64,
}

/// A system whose mass matrix does not depend on q, given the kinetic-energy
/// gradient ∂T/∂q = 0 that the derive does not emit, so that the symplectic
/// [`Gauss`](lagrange::Gauss) integrator can run it in (q, p). Everything else is
/// delegated. Wrapping a system with a configuration-dependent M would make Gauss
/// integrate the wrong equations: [`ConstantMetric::new`] refuses such systems by
/// comparing M at a few configurations.
#[derive(Clone, Copy, Debug)]
pub struct ConstantMetric<S>(pub S);

impl<S> ConstantMetric<S> {
    /// Wraps `sys` after checking that M(q) is the same at q = 0 and at a few
    /// other configurations; `None` if it is not.
    pub fn new<const N: usize>(sys: S) -> Option<Self>
    where
        S: Lagrangian<f64, N>,
    {
        let m0 = sys.mass_matrix(&SVector::zeros(), 0.0);
        let same = [0.3, -1.7, 2.9]
            .into_iter()
            .all(|x| sys.mass_matrix(&SVector::repeat(x), 0.0) == m0);
        same.then_some(Self(sys))
    }
}

impl<S: Lagrangian<f64, N>, const N: usize> Lagrangian<f64, N> for ConstantMetric<S> {
    const COORDINATES: [&'static str; N] = S::COORDINATES;
    const RHEONOMIC: bool = S::RHEONOMIC;

    fn mass_matrix(&self, q: &SVector<f64, N>, t: f64) -> SMatrix<f64, N, N> {
        self.0.mass_matrix(q, t)
    }
    fn bias(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> SVector<f64, N> {
        self.0.bias(q, v, t)
    }
    fn generalized_forces(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        t: f64,
    ) -> SVector<f64, N> {
        self.0.generalized_forces(q, v, t)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        t: f64,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        self.0.mass_matrix_and_rhs(q, v, t)
    }
    fn kinetic_energy(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> f64 {
        self.0.kinetic_energy(q, v, t)
    }
    fn potential_energy(&self, q: &SVector<f64, N>, t: f64) -> f64 {
        self.0.potential_energy(q, t)
    }
    fn integral(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> f64 {
        self.0.integral(q, v, t)
    }
    fn momentum(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, t: f64) -> SVector<f64, N> {
        self.0.momentum(q, v, t)
    }
    fn kinetic_gradient(
        &self,
        _q: &SVector<f64, N>,
        _v: &SVector<f64, N>,
        _t: f64,
    ) -> Option<SVector<f64, N>> {
        Some(SVector::zeros())
    }
}
