//! The joints' `<dynamics damping=".." friction="..">` under `urdf(..,
//! dynamics = ..)`: left out (`ignore`), read as `joint(q, damping = b,
//! friction = fc)` items (`read`), or, without the option, refused at the first moving
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
const CHOOSE: &str = "write `dynamics = read` in `urdf(\"..\", ..)` to add its damping and \
     friction as `joint(q, damping = b, friction = fc)` items (run by `run_contacts` where \
     there is friction), or `dynamics = ignore` for the rigid-body dynamics \
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
/// turns at m q̇, so its loss −b m q̇ does virtual work m δq), and its
/// friction bound, the sum of its joint's fc and of |m| fc for each
/// follower (they slip and stick together); a negative value refused at
/// its line.
fn read<'r>(
    stated: impl Iterator<Item = (&'r Joint, &'r Dynamics)>,
    coordinates: &[Ident],
    angle_of: &BTreeMap<&str, Ident>,
) -> Result<Vec<TokenStream>, ReadError> {
    let mut losses: BTreeMap<String, (f64, f64)> = BTreeMap::new();
    for (j, d) in stated {
        for (what, value) in [("damping", &d.damping), ("friction", &d.friction)] {
            if value.value < 0.0 {
                return Err(ReadError {
                    line: d.line,
                    message: format!(
                        "joint `{}`: {what} = {} is negative (it would feed energy in)",
                        j.name, value.text
                    ),
                });
            }
        }
        let (leader, ratio) = match &j.mimic {
            None => (j.name.as_str(), 1.0),
            Some(m) => (m.joint.as_str(), m.multiplier.value),
        };
        if let Some(q) = angle_of.get(leader) {
            let (b, fc) = losses.entry(q.to_string()).or_insert((0.0, 0.0));
            *b += d.damping.value * ratio * ratio;
            *fc += d.friction.value * ratio.abs();
        }
    }
    let items = coordinates.iter().filter_map(|q| {
        let &(b, fc) = losses.get(&q.to_string())?;
        let mut options = Vec::new();
        if b != 0.0 {
            let b = number(b)?;
            options.push(quote!(damping = #b));
        }
        if fc != 0.0 {
            let fc = number(fc)?;
            options.push(quote!(friction = #fc));
        }
        (!options.is_empty()).then(|| quote!(joint(#q, #(#options),*)))
    });
    Ok(items.collect())
}
