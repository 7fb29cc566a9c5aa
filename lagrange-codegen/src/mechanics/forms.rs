//! The constrained forms' derivation: the multiplier form's rows and the
//! reduced form, when the description asks for them.

use lagrange_symbolic::{Context, Expr as Sym};

use super::{Constrained, DeriveError};
use crate::constraint::{ConstraintSet, Reduction};

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

/// The reduced form, when `speeds` or `formulation(reduced)` asks for it.
pub(super) fn reduced_if_asked(
    ctx: &mut Context,
    c: &Constrained,
    coordinates: &[String],
    jacobians: bool,
) -> Result<Option<Reduction>, DeriveError> {
    let Some(speeds) = &c.speeds else {
        return Ok(None);
    };
    reduced_form(ctx, c, speeds.as_deref(), coordinates, jacobians).map(Some)
}

/// The reduced form on the user's speeds, or on speeds chosen from the
/// constraints (`speeds` is `None`).
fn reduced_form(
    ctx: &mut Context,
    c: &Constrained,
    speeds: Option<&[(String, Sym)]>,
    coordinates: &[String],
    jacobians: bool,
) -> Result<Reduction, DeriveError> {
    let chosen;
    let speeds = match speeds {
        Some(s) => s,
        None => {
            chosen =
                crate::constraint::default_speeds(ctx, c.holonomic, c.nonholonomic, coordinates)
                    .map_err(DeriveError::Reduction)?;
            &chosen[..]
        }
    };
    let mut r = crate::constraint::reduce(ctx, c.holonomic, c.nonholonomic, speeds, coordinates)
        .map_err(DeriveError::Reduction)?;
    r.free_speeds = c.speeds.as_ref().is_some_and(|s| s.is_none());
    if jacobians {
        r.derivatives = Some(crate::constraint::reduced_derivatives(ctx, &r));
    }
    Ok(r)
}
