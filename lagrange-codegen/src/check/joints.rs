//! The `joint` items' rules: one per coordinate, on a coordinate, and a
//! motor that is an input.

use super::what_is;
use crate::ast::System;
use crate::ctxt::Ctxt;

/// Each `joint` names a coordinate, at most one joint per coordinate, and
/// its motor one of the inputs.
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
    }
}
