//! A joint's damping, armature and friction as parameters of Y beside the
//! bodies': the torque a joint needs is linear in each, on its own row alone
//! (b q̇ᵢ, Ia q̈ᵢ, fc sign q̇ᵢ), so each is one column with one entry, as in
//! the identification literature's friction and rotor-inertia columns.
//!
//! The damping and the armature are already in the equations (−b q̇ in Q, Ia
//! on M's diagonal), so Y π stays the inverse dynamics with them. The
//! friction is not: a joint's dry friction is a contact, set-valued at rest,
//! which the inverse dynamics leaves out; its column is the torque it takes
//! while the joint slips, fc sign(q̇), zero at rest, so that Y π is what a
//! slipping robot's motors measure.

use lagrange_symbolic::{Context, Expr as Sym};

use super::super::base_parameters::OwnColumn;
use crate::lowered::{JointCoefficient, JointTerm};

/// One joint coefficient as a parameter of Y: its column (symbol, name,
/// row and entry there: q̇ᵢ, q̈ᵢ or sign(q̇ᵢ)), as the base parameters read
/// it, and what the other outputs take of it.
pub(super) struct JointColumn {
    pub column: OwnColumn,
    /// Its value in the struct's parameters.
    pub value: Sym,
    /// Its share of T + V (½ q̇ᵢ² for an armature, else zero) and of the
    /// momentum's row i (q̇ᵢ for an armature, else zero).
    pub energy: Sym,
    pub momentum: Sym,
}

/// The joints' columns, in the description's order of the joints (damping,
/// friction, armature within one).
pub(super) fn columns(ctx: &mut Context, coefficients: &[JointCoefficient]) -> Vec<JointColumn> {
    let velocities = ctx.velocities();
    let accelerations = ctx.accelerations();
    coefficients
        .iter()
        .map(|c| {
            let (row, coordinate) = (c.coordinate.0, &c.coordinate.1);
            let name = format!("{coordinate}.{}", c.kind.suffix());
            let symbol = ctx.free_symbol(&format!("__pi_{coordinate}_{}", c.kind.suffix()));
            let rate = velocities[row];
            let zero = ctx.zero();
            let (entry, energy, momentum) = match c.kind {
                JointTerm::Damping => (rate, zero, zero),
                JointTerm::Friction => (ctx.sign(rate), zero, zero),
                JointTerm::Armature => {
                    let half = ctx.rational(1, 2);
                    let squared = ctx.mul(rate, rate);
                    (accelerations[row], ctx.mul(half, squared), rate)
                }
            };
            JointColumn {
                column: OwnColumn {
                    symbol,
                    name,
                    row,
                    entry,
                    armature: c.kind == JointTerm::Armature,
                },
                value: c.value,
                energy,
                momentum,
            }
        })
        .collect()
}
