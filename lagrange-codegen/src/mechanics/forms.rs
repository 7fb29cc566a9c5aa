//! The constrained forms' derivation: the multiplier form's rows and the
//! reduced form, when the description asks for them.

use lagrange_symbolic::{Context, Expr as Sym};

use super::{Constrained, DeriveError};
use crate::constraint::{ConstraintSet, Reduction};
use crate::lowered::{OrientationModel, ReducedSpeeds};

/// G, g, Φ and γ, with their derivatives when the Jacobians are asked for.
pub(super) fn multiplier_form(
    ctx: &mut Context,
    c: &Constrained,
    jacobians: bool,
) -> ConstraintSet {
    let mut set = crate::constraint::multiplier_form(ctx, c.holonomic, c.nonholonomic);
    if jacobians {
        set.derivatives = Some(crate::constraint::constraint_derivatives(ctx, &set));
    }
    set
}

/// The reduced form, when `speeds` or `formulation(reduced)` asks for it, on
/// the coordinates' velocities and the orientations' angular velocities.
pub(super) fn reduced_if_asked(
    ctx: &mut Context,
    c: &Constrained,
    coordinates: &[String],
    orientations: &[OrientationModel],
    jacobians: bool,
) -> Result<Option<Reduction>, DeriveError> {
    let Some(speeds) = &c.speeds else {
        return Ok(None);
    };
    let velocities = velocity_names(coordinates, orientations);
    reduced_form(ctx, c, speeds.named(), &velocities, jacobians).map(Some)
}

/// The velocities' names, as `Lagrangian::VELOCITIES` gives them: the
/// coordinates', then each orientation's body-axis angular velocity
/// `name.wx`, `name.wy`, `name.wz`.
fn velocity_names(coordinates: &[String], orientations: &[OrientationModel]) -> Vec<String> {
    let mut names = coordinates.to_vec();
    for o in orientations {
        names.extend(["wx", "wy", "wz"].map(|c| format!("{}.{c}", o.name)));
    }
    names
}

/// The reduced form on the user's speeds, or on speeds chosen from the
/// constraints (`speeds` is `None`).
fn reduced_form(
    ctx: &mut Context,
    c: &Constrained,
    speeds: Option<&[(String, Sym)]>,
    velocities: &[String],
    jacobians: bool,
) -> Result<Reduction, DeriveError> {
    let chosen;
    let speeds = match speeds {
        Some(s) => s,
        None => {
            chosen =
                crate::constraint::default_speeds(ctx, c.holonomic, c.nonholonomic, velocities)
                    .map_err(DeriveError::Reduction)?;
            &chosen[..]
        }
    };
    let mut r = crate::constraint::reduce(ctx, c.holonomic, c.nonholonomic, speeds, velocities)
        .map_err(DeriveError::Reduction)?;
    r.free_speeds = matches!(c.speeds, Some(ReducedSpeeds::Chosen));
    if jacobians {
        r.derivatives = Some(crate::constraint::reduced_derivatives(ctx, &r));
    }
    Ok(r)
}
