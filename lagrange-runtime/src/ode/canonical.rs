//! Hamilton's equations in canonical coordinates (q, P), P conjugate to
//! every number of q, for the symplectic [`Gauss`](crate::Gauss) method.
//!
//! Without orientations P is the momentum p = ∂L/∂q̇ of [`Mechanical`].
//! A free orientation has four numbers u in q but three speeds ω, so its
//! momentum π = ∂L/∂ω (in body axes) is not conjugate to u. The quaternion
//! is then taken as four ordinary coordinates with four momenta P, and the
//! Hamiltonian extended off the rotations by
//!
//! ```text
//! H̃(u, P) = H(û, π),   π = ½ S(u)ᵀ P = ½ Im(ū ⊗ P),   û = u / |u|
//! ```
//!
//! with S(u) = [u ⊗ e₁, u ⊗ e₂, u ⊗ e₃] (the quaternion embedding of Miller
//! et al., J. Chem. Phys. 116, 8649 (2002)). Hamilton's equations of H̃ are
//!
//! ```text
//! u̇ = ½ u ⊗ (0, ω),   Ṗ = (2/|u|) û ⊗ (0, g) + ½ P ⊗ (0, ω),
//! ```
//!
//! ω = ∂H/∂π and g = X T + Q_θ the torque the momentum rate of
//! [`Mechanical`] gives for the orientation (T's derivative along body-axis
//! turns at fixed ω, plus the generalized forces); they give Euler's
//! π̇ = π × ω + g on the rotations. Why this form: u̇ is orthogonal to u
//! for every (u, P), so |u|² is a quadratic first integral of the whole
//! vector field, and a Gauss method keeps every quadratic first integral
//! exactly (Hairer, Lubich and Wanner, *Geometric Numerical Integration*,
//! §IV.2): the quaternion stays unit to round-off with no projection. So
//! does any momentum of a symmetry acting linearly on (u, P): the world
//! angular momentum of a torque-free system, a top's vertical and axial
//! momenta. The method is symplectic in (q, P), and H̃ is invariant under
//! u → λu, P → P/λ, so it is symplectic on the rotations too.

use super::Mechanical;
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation, Slot, multiply, norm, quaternion};
use nalgebra::SVector;

/// A mechanical system seen in canonical coordinates (q, P).
pub(crate) struct Canonical<'m, T: Real, const N: usize, const Q: usize> {
    mech: &'m dyn Mechanical<T, N, Q>,
    layout: &'static [Orientation],
}

/// (q̇, Ṗ) at a canonical state, and the velocity v there.
pub(crate) struct Field<T: Real, const N: usize, const Q: usize> {
    pub q_rate: SVector<T, Q>,
    pub p_rate: SVector<T, Q>,
    pub velocity: SVector<T, N>,
}

impl<'m, T: Real, const N: usize, const Q: usize> Canonical<'m, T, N, Q> {
    /// The system `mech`, its orientations at `layout`.
    pub fn new(mech: &'m dyn Mechanical<T, N, Q>, layout: &'static [Orientation]) -> Self {
        Self { mech, layout }
    }

    /// P at (t, q, v).
    ///
    /// # Errors
    /// Whatever prevents the momentum's evaluation.
    pub fn momentum(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, Q>, Error> {
        let p = self.mech.momentum(t, &self.unit(q), v)?;
        let mut out = SVector::<T, Q>::zeros();
        for slot in orientation::slots(self.layout, Q) {
            match slot {
                Slot::Ordinary(i, j) => out[i] = p[j],
                Slot::Rotation(o) => {
                    // P = 2 S(u) π = 2 u ⊗ (0, π), with uᵀP = 0.
                    let pi = [p[o.v], p[o.v + 1], p[o.v + 2]];
                    let rate = orientation::quaternion_rate(quaternion(q.as_slice(), o.q), pi);
                    for (k, r) in rate.iter().enumerate() {
                        out[o.q + k] = T::lit(4.0) * *r;
                    }
                }
            }
        }
        Ok(out)
    }

    /// The velocity at (t, q, P).
    ///
    /// # Errors
    /// [`Error::SingularMassMatrix`] and whatever prevents M's evaluation.
    pub fn velocity(
        &self,
        t: T,
        q: &SVector<T, Q>,
        p: &SVector<T, Q>,
    ) -> Result<SVector<T, N>, Error> {
        self.mech
            .velocity(t, &self.unit(q), &self.body_momentum(q, p))
    }

    /// (q̇, Ṗ) at (t, q, P), with the velocity there.
    ///
    /// # Errors
    /// Whatever prevents the momentum rate's evaluation.
    pub fn field(
        &self,
        t: T,
        q: &SVector<T, Q>,
        p: &SVector<T, Q>,
    ) -> Result<Field<T, N, Q>, Error> {
        let unit = self.unit(q);
        let v = self.mech.velocity(t, &unit, &self.body_momentum(q, p))?;
        let rate = self.mech.momentum_rate(t, &unit, &v)?;
        let mut q_rate = SVector::<T, Q>::zeros();
        orientation::rate(
            self.layout,
            q.as_slice(),
            v.as_slice(),
            q_rate.as_mut_slice(),
        );
        let mut p_rate = SVector::<T, Q>::zeros();
        for slot in orientation::slots(self.layout, Q) {
            match slot {
                Slot::Ordinary(i, j) => p_rate[i] = rate[j],
                Slot::Rotation(o) => {
                    let u = quaternion(q.as_slice(), o.q);
                    let u_hat = quaternion(unit.as_slice(), o.q);
                    let torque = [T::zero(), rate[o.v], rate[o.v + 1], rate[o.v + 2]];
                    let omega = [T::zero(), v[o.v], v[o.v + 1], v[o.v + 2]];
                    let scale = T::lit(2.0) / norm(u);
                    let turned = multiply(u_hat, torque);
                    let carried = multiply(quaternion(p.as_slice(), o.q), omega);
                    for k in 0..4 {
                        p_rate[o.q + k] = scale * turned[k] + T::lit(0.5) * carried[k];
                    }
                }
            }
        }
        Ok(Field {
            q_rate,
            p_rate,
            velocity: v,
        })
    }

    /// The momentum in the speeds: P itself for an ordinary coordinate,
    /// π = ½ Im(ū ⊗ P) for an orientation.
    fn body_momentum(&self, q: &SVector<T, Q>, p: &SVector<T, Q>) -> SVector<T, N> {
        let mut out = SVector::<T, N>::zeros();
        for slot in orientation::slots(self.layout, Q) {
            match slot {
                Slot::Ordinary(i, j) => out[j] = p[i],
                Slot::Rotation(o) => {
                    let [w, x, y, z] = quaternion(q.as_slice(), o.q);
                    let product = multiply([w, -x, -y, -z], quaternion(p.as_slice(), o.q));
                    for k in 0..3 {
                        out[o.v + k] = T::lit(0.5) * product[k + 1];
                    }
                }
            }
        }
        out
    }

    /// q with its quaternions scaled to unit norm, where the system's
    /// functions are evaluated (H̃ depends on u only through û).
    fn unit(&self, q: &SVector<T, Q>) -> SVector<T, Q> {
        let mut unit = *q;
        orientation::normalise(self.layout, unit.as_mut_slice());
        unit
    }
}
