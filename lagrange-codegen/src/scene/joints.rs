//! `joint(q, damping = b, armature = Ia, motor = u, gear = n, rotor = Ir)`
//! lowered: the damping and the motor as the generalized forces −b q̇ and
//! n u on its coordinate (so that every output reading Q has them: both
//! routes, the articulated q̈, the inverse dynamics and the derivatives);
//! the coefficients b, Ia + n² Ir and fc recorded, for `mechanics` to add
//! the armature to M's diagonal and for the regressor's parameters.

use lagrange_symbolic::Expr as Sym;
use syn::{Expr, Ident};

use crate::ast::System;
use crate::lower::{Lowerer, Mode, NoInputs};
use crate::lowered::{JointCoefficient, JointTerm, PhysicalCheck};
use crate::physical;

/// What the `joint` items give, per coordinate index.
pub(super) struct Joints {
    /// −b q̇ and n u, generalized forces.
    pub forces: Vec<(usize, Sym)>,
    /// b, Ia + n² Ir and fc.
    pub coefficients: Vec<JointCoefficient>,
}

/// Lowers each joint's coefficients (parameters and literals only), checks
/// the constant ones at their tokens and records the others for
/// `check_parameters`.
pub(super) fn joints(lw: &mut Lowerer, system: &System, checks: &mut Vec<PhysicalCheck>) -> Joints {
    let mut out = Joints {
        forces: Vec::new(),
        coefficients: Vec::new(),
    };
    let velocities = lw.ctx.velocities();
    for j in &system.joints {
        // An unknown coordinate is `check`'s error.
        let Some(i) = system.coordinates.iter().position(|c| *c == j.coordinate) else {
            continue;
        };
        let name = j.coordinate.to_string();
        let record = |kind, value| JointCoefficient {
            coordinate: (i, name.clone()),
            kind,
            value,
        };
        let mut coefficient = |lw: &mut Lowerer, e: &Expr, what: &'static str| {
            let value = constant(lw, &name, e, what)?;
            checks.extend(match what {
                "gear" => physical::gear(lw, &name, e, value),
                _ => physical::joint(lw, &name, what, e, value),
            });
            Some(value)
        };
        if let Some(b) = j
            .damping
            .as_ref()
            .and_then(|e| coefficient(lw, e, "damping"))
        {
            let loss = lw.ctx.mul(b, velocities[i]);
            out.forces.push((i, lw.ctx.neg(loss)));
            out.coefficients.push(record(JointTerm::Damping, b));
        }
        if let Some(fc) = j.friction {
            out.coefficients
                .push(record(JointTerm::Friction, lw.ctx.float(fc)));
        }
        let gear = match &j.gear {
            Some(e) => coefficient(lw, e, "gear"),
            None => Some(lw.ctx.one()),
        };
        let Some(n) = gear else { continue };
        let input = j.motor.as_ref().filter(|u| system.inputs.contains(u));
        if let Some(u) = input.and_then(|u| motor(lw, u)) {
            out.forces.push((i, lw.ctx.mul(n, u)));
        }
        let own = j
            .armature
            .as_ref()
            .and_then(|e| coefficient(lw, e, "armature"));
        let rotor = j.rotor.as_ref().and_then(|e| coefficient(lw, e, "rotor"));
        let reflected = rotor.map(|r| {
            let n2 = lw.ctx.mul(n, n);
            lw.ctx.mul(n2, r)
        });
        let armature = match (own, reflected) {
            (Some(a), Some(r)) => Some(lw.ctx.add(a, r)),
            (a, r) => a.or(r),
        };
        (out.coefficients).extend(armature.map(|a| record(JointTerm::Armature, a)));
    }
    out
}

/// A joint's coefficient `what`, lowered from the parameters and literals.
fn constant(lw: &mut Lowerer, name: &str, e: &Expr, what: &str) -> Option<Sym> {
    let place = format!("the {what} of joint `{name}`");
    lw.lowering_as(place, |lw| {
        lw.without_inputs(NoInputs::JOINT, |lw| lw.expr(e, Mode::Constant))
    })
}

/// The input a motor's torque is (`check` has reported a name that is not one).
fn motor(lw: &mut Lowerer, u: &Ident) -> Option<Sym> {
    let path: Expr = syn::parse_quote!(#u);
    lw.expr(&path, Mode::State)
}
