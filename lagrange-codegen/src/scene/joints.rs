//! `joint(q, damping = b, armature = Ia)` lowered: the damping as the
//! generalized force −b q̇ on its coordinate (so that every output reading Q
//! has it: both routes, the articulated q̈, the inverse dynamics and the
//! derivatives), the armature kept for `mechanics` to add to M's diagonal.

use lagrange_symbolic::Expr as Sym;
use syn::Expr;

use crate::ast::System;
use crate::lower::{Lowerer, Mode, NoInputs};
use crate::lowered::PhysicalCheck;
use crate::physical;

/// What the `joint` items give, per coordinate index.
pub(super) struct Joints {
    /// −b q̇, a generalized force.
    pub damping: Vec<(usize, Sym)>,
    /// Ia.
    pub armature: Vec<(usize, Sym)>,
}

/// Lowers each joint's coefficients (parameters and literals only), checks
/// the constant ones at their tokens and records the others for
/// `check_parameters`.
pub(super) fn joints(lw: &mut Lowerer, system: &System, checks: &mut Vec<PhysicalCheck>) -> Joints {
    let mut out = Joints {
        damping: Vec::new(),
        armature: Vec::new(),
    };
    let velocities = lw.ctx.velocities();
    for j in &system.joints {
        // An unknown coordinate is `check`'s error.
        let Some(i) = system.coordinates.iter().position(|c| *c == j.coordinate) else {
            continue;
        };
        let name = j.coordinate.to_string();
        let mut coefficient = |lw: &mut Lowerer, e: &Expr, what: &'static str| {
            let place = format!("the {what} of joint `{name}`");
            let value = lw.lowering_as(place, |lw| {
                lw.without_inputs(NoInputs::JOINT, |lw| lw.expr(e, Mode::Constant))
            })?;
            checks.extend(physical::joint(lw, &name, what, e, value));
            Some(value)
        };
        if let Some(b) = j
            .damping
            .as_ref()
            .and_then(|e| coefficient(lw, e, "damping"))
        {
            let loss = lw.ctx.mul(b, velocities[i]);
            out.damping.push((i, lw.ctx.neg(loss)));
        }
        if let Some(a) = j
            .armature
            .as_ref()
            .and_then(|e| coefficient(lw, e, "armature"))
        {
            out.armature.push((i, a));
        }
    }
    out
}
