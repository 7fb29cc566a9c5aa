//! The `joint` items' rules: one per coordinate, on a coordinate, a motor
//! that is an input, and no armature beside the regressor.

use super::what_is;
use crate::ast::{Extra, System};
use crate::ctxt::Ctxt;

/// Each `joint` names a coordinate, at most one joint per coordinate, and
/// its motor one of the inputs; an armature (or a rotor, which is one) is
/// not a column of `emit(regressor)`'s Y (which would then leave Ia q̈ out
/// of τ = Y π), so the two are refused together.
pub(super) fn check_joints(cx: &Ctxt, system: &System) {
    for (k, j) in system.joints.iter().enumerate() {
        if !system.coordinates.contains(&j.coordinate) {
            let hint = if system.orientations.contains(&j.coordinate) {
                " (a free orientation's three rates are not one joint's)"
            } else {
                ""
            };
            cx.error_at(
                j.coordinate.span(),
                format!(
                    "joint on {}; it names one of `coordinates(...)`{hint}",
                    what_is(system, &j.coordinate, "coordinate")
                ),
            );
        } else if system.joints[..k]
            .iter()
            .any(|o| o.coordinate == j.coordinate)
        {
            cx.error_at(
                j.coordinate.span(),
                format!(
                    "a second `joint({})`: write its options in one item",
                    j.coordinate
                ),
            );
        }
        if let Some(u) = &j.motor
            && !system.inputs.contains(u)
        {
            cx.error_at(
                u.span(),
                format!(
                    "the motor of joint `{}` is {}; `motor = u` names one of `inputs(...)`, the motor's torque",
                    j.coordinate,
                    what_is(system, u, "input")
                ),
            );
        }
        let regressor = system.extras.iter().any(|(_, e)| *e == Extra::Regressor);
        if let (true, Some(a)) = (regressor, j.armature.as_ref().or(j.rotor.as_ref())) {
            cx.error_spanned_by(
                a,
                "`emit(regressor)` with an armature is not supported yet: Y π covers the bodies' inertial parameters, not Ia q̈; remove the armature or the regressor",
            );
        }
    }
}
