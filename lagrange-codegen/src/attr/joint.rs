//! `joint(q, damping = b, friction = fc, armature = Ia, motor = u, gear = n,
//! rotor = Ir)`: what a joint's drive adds on its coordinate. The options are spelled in
//! `keyword::JOINT_OPTIONS`; a negative literal is refused here, at its
//! token (a value computed from the parameters is checked when lowered, in
//! `physical::joint`, or at run time by `check_parameters`). Friction's
//! bound is a number written out, as a contact's μ is.

use syn::parse::ParseStream;
use syn::spanned::Spanned;
use syn::{Expr, Ident, Token};

use super::contact::number;
use super::keyword::{JOINT_OPTIONS, JointOption};
use crate::ast::Joint;

/// The form the messages show.
const FORM: &str =
    "joint(q, damping = b, friction = fc, armature = Ia, motor = u, gear = n, rotor = Ir)";

/// `joint(q, option = value, ..)`.
pub(super) fn parse_joint(input: ParseStream) -> syn::Result<Joint> {
    let content;
    syn::parenthesized!(content in input);
    let coordinate: Ident = content.parse()?;
    let mut joint = Joint {
        coordinate,
        damping: None,
        armature: None,
        friction: None,
        motor: None,
        gear: None,
        rotor: None,
    };
    let mut written: Vec<JointOption> = Vec::new();
    while content.parse::<Option<Token![,]>>()?.is_some() && !content.is_empty() {
        let key: Ident = content.parse()?;
        let option = option(&key, &joint.coordinate)?;
        if written.contains(&option) {
            return Err(syn::Error::new(
                key.span(),
                format!("`{key}` is written twice for joint `{}`", joint.coordinate),
            ));
        }
        written.push(option);
        content.parse::<Token![=]>()?;
        match option {
            JointOption::Motor => joint.motor = Some(motor(&content)?),
            JointOption::Damping => {
                joint.damping = Some(non_negative(content.parse()?, "damping")?);
            }
            JointOption::Armature => {
                joint.armature = Some(non_negative(content.parse()?, "armature")?);
            }
            JointOption::Friction => joint.friction = friction(&content.parse()?)?,
            JointOption::Gear => joint.gear = Some(gear(content.parse()?)?),
            JointOption::Rotor => joint.rotor = Some(non_negative(content.parse()?, "rotor")?),
        }
    }
    if let (Some(n), None, None) = (&joint.gear, &joint.motor, &joint.rotor) {
        return Err(syn::Error::new(
            n.span(),
            format!(
                "a gear on joint `{}` scales a motor's torque and its rotor's inertia: add `motor = u` (an input) or `rotor = Ir`",
                joint.coordinate
            ),
        ));
    }
    if !content.is_empty() {
        return Err(content.error(format!(
            "expected `, option = value` after the joint's coordinate: `{FORM}`"
        )));
    }
    if written.is_empty() {
        return Err(syn::Error::new(
            joint.coordinate.span(),
            format!(
                "joint `{}` says nothing: write `{FORM}` (any option may be left out, not all)",
                joint.coordinate
            ),
        ));
    }
    Ok(joint)
}

/// The option `key` spells, or the error that suggests the one meant.
fn option(key: &Ident, coordinate: &Ident) -> syn::Result<JointOption> {
    let word = key.to_string();
    JOINT_OPTIONS.find(&word).ok_or_else(|| {
        let expected = JOINT_OPTIONS.alternatives();
        let message = match JOINT_OPTIONS.closest(&word) {
            Some(w) => format!(
                "unknown option `{word}` of joint `{coordinate}`; did you mean `{w}`? (expected {expected})"
            ),
            None => format!(
                "unknown option `{word}` of joint `{coordinate}`; expected {expected}:\n{}",
                JOINT_OPTIONS.described()
            ),
        };
        syn::Error::new(key.span(), message)
    })
}

/// A value that must not be negative: a literal is checked now; an
/// expression of the parameters is kept for lowering.
fn non_negative(value: Expr, what: &str) -> syn::Result<Expr> {
    if let Ok(x) = number(&value, what)
        && x < 0.0
    {
        return Err(syn::Error::new(
            value.span(),
            format!("{what} = {x}: a joint's {what} is ≥ 0 (a negative one feeds energy in)"),
        ));
    }
    Ok(value)
}

/// The input a motor's torque is: a name (`check` finds it among the inputs).
fn motor(content: ParseStream) -> syn::Result<Ident> {
    content
        .parse()
        .map_err(|e| syn::Error::new(e.span(), "`motor = u` names one of `inputs(...)`"))
}

/// A gear ratio: a literal must be > 0 (the motor turns n times per turn of
/// the joint; a reversed motor is a negative torque, not a negative ratio).
fn gear(value: Expr) -> syn::Result<Expr> {
    if let Ok(n) = number(&value, "gear")
        && n <= 0.0
    {
        return Err(syn::Error::new(
            value.span(),
            format!("gear = {n}: a gear ratio is > 0 (motor turns per joint turn)"),
        ));
    }
    Ok(value)
}

/// Coulomb friction's bound: a number written out, ≥ 0 (0 is none).
fn friction(value: &Expr) -> syn::Result<Option<f64>> {
    let fc = number(value, "friction")?;
    if fc < 0.0 {
        return Err(syn::Error::new(
            value.span(),
            format!("friction = {fc}: a joint's Coulomb friction bound is ≥ 0"),
        ));
    }
    Ok((fc > 0.0).then_some(fc))
}
