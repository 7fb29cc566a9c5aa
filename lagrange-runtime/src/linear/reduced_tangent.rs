//! Linearisation of a system in the reduced form (independent speeds)
//! whose configuration holds orientations, in the tangent space: the model of
//! [`Linearizer::constrained_tangent`], read from the reduced form's
//! dynamics.
//!
//! The reduced form's accelerations a(q, v) (u̇ from M* u̇ = F*, then
//! q̈ = W u̇ + κ) are defined at any v through its independent velocities,
//! and equal the multiplier form's on the admissible states; the model's
//! perturbations stay admissible (δv = C_v δv_s + C_vq δ_i), so only those
//! derivatives enter it, and the two forms of one system give one model. The
//! constraint rows are the last N − K of the stacked rows A = [U; G], the
//! first [`Reduced::HOLONOMIC`] of them Φ_q.

use super::Linear;
use super::constrained_tangent::{GroupForm, GroupStates};
use super::dense::{dm, dv};
use super::settings::{Linearizer, OperatingPoint};
use super::tangent::{Held, states};
use crate::error::Error;
use crate::mechanics::ReducedDynamics;
use crate::numeric::Real;
use crate::ode::SecondOrder;
use crate::system::{Driven, Reduced};
use nalgebra::{DMatrix, DVector, SVector};

impl Linearizer {
    /// Linearises a system in the reduced form (`formulation(reduced)`,
    /// independent speeds) whose configuration holds orientations, about a
    /// point ([`OperatingPoint::on_group`], inputs with
    /// [`input`](OperatingPoint::input)) whose velocities satisfy its
    /// constraints, in independent coordinates and speeds of the tangent
    /// space.
    ///
    /// The states, the axes (an orientation's δθ and δω in its body axes at
    /// the operating point, held fixed in space), the choice of independent
    /// ones and the central differences are those of
    /// [`constrained_tangent`](Self::constrained_tangent), which a system
    /// emitted in both forms gives the same model from its multiplier form.
    /// [`reduced`](Self::reduced) is the call for a reduced system without
    /// orientations (Q = N), from the symbolic derivatives; this one accepts
    /// that case too.
    ///
    /// # Errors
    /// [`Error::NonUnitQuaternion`]; [`LinearError::InconsistentOperatingPoint`](crate::LinearError::InconsistentOperatingPoint)
    /// naming the worst row when Φ or the velocity rows do not hold;
    /// [`LinearError::InvalidPartition`](crate::LinearError::InvalidPartition), [`LinearError::SingularPartition`](crate::LinearError::SingularPartition)
    /// for a bad choice of independent coordinates or speeds;
    /// [`Error::RedundantConstraints`]; [`Error::ReducedFormBreakdown`];
    /// [`Error::SingularMassMatrix`]; [`Error::NonFiniteState`] (also at a
    /// perturbed state). Before any of these: [`Error::Settings`],
    /// [`Error::NonPhysicalParameter`] and [`Error::NonFiniteInput`], as
    /// [`reduced`](Self::reduced).
    pub fn reduced_tangent<
        S,
        T,
        const N: usize,
        const K: usize,
        const P: usize,
        const U: usize,
        const Q: usize,
    >(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U, Q>,
    ) -> Result<Linear, Error>
    where
        S: Reduced<T, N, K, Q> + Driven<T, N, P, Q>,
        T: Real,
    {
        let (u, q, v, t) = self.point_on_group(sys, op)?;
        let accel = |q: &SVector<T, Q>, v: &SVector<T, N>, u: &SVector<T, P>| {
            let dynamics = ReducedDynamics::<_, _, K>::new(sys)
                .with_singular_tolerance(T::lit(self.tolerances.singular))
                .with_forcing(Held { system: sys, u: *u });
            SecondOrder::acceleration(&dynamics, t, q, v)
        };
        let h = S::HOLONOMIC.min(N - K);
        let names = states::<S, T, N, Q>();
        let directions: Vec<&str> = names[..N].iter().map(String::as_str).collect();
        let form = GroupForm {
            accel,
            rows: |q: &SVector<T, Q>| constraint_rows::<S, T, N, K, Q>(sys, q, t),
            phi: dv(&sys.holonomic_positions(&q, t)).rows(0, h).into_owned(),
            holonomic: h,
            row_names: &S::ROWS[K..],
        };
        let states = GroupStates {
            names: &names,
            partition: [&directions, &S::VELOCITIES],
            inputs: &S::INPUTS,
        };
        self.group_model::<S, T, _, _, N, P, Q>(form, (&q, &v, &u, t), states)
    }
}

/// G and g: the constraint rows of the stacked A = [U; G], b = [u₀; g].
fn constraint_rows<S, T, const N: usize, const K: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    t: T,
) -> (DMatrix<f64>, DVector<f64>)
where
    S: Reduced<T, N, K, Q>,
    T: Real,
{
    let (a, b) = sys.velocity_rows(q, t);
    (
        dm(&a).rows(K, N - K).into_owned(),
        dv(&b).rows(K, N - K).into_owned(),
    )
}
