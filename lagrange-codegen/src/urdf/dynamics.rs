//! The joints' `<dynamics damping=".." friction="..">` under `urdf(..,
//! dynamics = ..)`: left out (`ignore`), read as `joint(q, damping = b)`
//! items (`read`), or, without the option, refused at the first moving
//! joint that states a loss, so that no file's damping or friction is
//! dropped without a word. A fixed joint's `<dynamics>` moves nothing and
//! is not read.

use std::collections::BTreeMap;

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::model::{Dynamics, Joint, JointType, ReadError, Robot};
use super::options::DynamicsRule;
use super::tokens::number;

/// What to write instead of a file's stated losses, for the refusals.
const CHOOSE: &str = "write `dynamics = read` in `urdf(\"..\", ..)` to add its damping as \
     `joint(q, damping = b)` items, or `dynamics = ignore` for the rigid-body dynamics \
     (what Pinocchio's rnea and aba compute)";

/// The `joint(..)` items `rule` makes of the moving joints' `<dynamics>`,
/// in coordinate order (`coordinates`); `angle_of` maps a moving, non-mimic
/// joint to its coordinate.
pub fn joint_items(
    robot: &Robot,
    rule: DynamicsRule,
    coordinates: &[Ident],
    angle_of: &BTreeMap<&str, Ident>,
) -> Result<Vec<TokenStream>, ReadError> {
    let stated = robot.joints.iter().filter_map(|j| {
        let moving = !matches!(j.kind, JointType::Fixed | JointType::Floating);
        let d = j.dynamics.as_ref().filter(|_| moving)?;
        (!d.damping.is_zero() || !d.friction.is_zero()).then_some((j, d))
    });
    match rule {
        DynamicsRule::Ignore => Ok(Vec::new()),
        DynamicsRule::Unset => match stated.clone().next() {
            None => Ok(Vec::new()),
            Some((j, d)) => Err(ReadError {
                line: d.line,
                message: format!(
                    "joint `{}` states <dynamics damping=\"{}\" friction=\"{}\">, which the \
                     rigid-body equations leave out; {CHOOSE}",
                    j.name, d.damping.text, d.friction.text
                ),
            }),
        },
        DynamicsRule::Read => read(stated, coordinates, angle_of),
    }
}

/// `dynamics = read`: each coordinate's damping, the sum of its joint's b
/// and of b m² for each joint mimicking it with multiplier m (the follower
/// turns at m q̇, so its loss −b m q̇ does virtual work m δq); a negative
/// damping or any friction refused at its line.
fn read<'r>(
    stated: impl Iterator<Item = (&'r Joint, &'r Dynamics)>,
    coordinates: &[Ident],
    angle_of: &BTreeMap<&str, Ident>,
) -> Result<Vec<TokenStream>, ReadError> {
    let mut damping: BTreeMap<String, f64> = BTreeMap::new();
    for (j, d) in stated {
        let at = |message: String| ReadError {
            line: d.line,
            message,
        };
        if d.damping.value < 0.0 {
            return Err(at(format!(
                "joint `{}`: damping = {} is negative (it would feed energy in)",
                j.name, d.damping.text
            )));
        }
        let (leader, ratio) = match &j.mimic {
            None => (j.name.as_str(), 1.0),
            Some(m) => (m.joint.as_str(), m.multiplier.value),
        };
        if !d.friction.is_zero() {
            // The coordinate's name, which the description's items read
            // (the joint's, made a Rust name), not the file's joint name.
            let q = angle_of
                .get(leader)
                .map_or_else(|| leader.to_string(), |q| q.to_string());
            return Err(at(format!(
                "joint `{}`: friction = {}: Coulomb friction at a joint is not supported yet \
                 (it would be dropped); write `dynamics = ignore` and the damping as \
                 `joint({q}, damping = {})`, with friction, if wanted, regularised as \
                 `generalized_force({q} = -fc * tanh(dot({q}) / v_s))`",
                j.name, d.friction.text, d.damping.text
            )));
        }
        if let Some(q) = angle_of.get(leader) {
            *damping.entry(q.to_string()).or_insert(0.0) += d.damping.value * ratio * ratio;
        }
    }
    let items = coordinates.iter().filter_map(|q| {
        let b = number(*damping.get(&q.to_string())?)?;
        Some(quote!(joint(#q, damping = #b)))
    });
    Ok(items.collect())
}
