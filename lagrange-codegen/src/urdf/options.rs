//! The options of `urdf("path", ..)`, each refused at its token when it
//! cannot hold: an unknown key, a key given twice, an unknown value, a snap
//! tolerance that could move a real angle.

use quote::ToTokens;
use syn::parse::ParseStream;
use syn::{Ident, Token};

/// The largest `snap` tolerance, in radians: a file's π/2 written to ten or
/// more digits is within 1e-10 of it, while a real angle is never that close
/// to a multiple of π/2 without being one.
pub const SNAP_BOUND: f64 = 1e-6;

/// The `snap` tolerance without the option, in radians: π/2 written to nine
/// or more decimals (the UR and Kinova files' `1.57079632679`, 5e-12 off)
/// is that quarter turn; fewer digits (the xArm7's `1.5708`) are kept as
/// written unless `snap` asks for more. `snap = 0` keeps every angle.
pub const DEFAULT_SNAP: f64 = 1e-9;

/// Where the robot's base is (`base = ..`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Base {
    /// As the file says: on a free root if its root link holds a floating
    /// joint, fixed in space otherwise.
    #[default]
    AsFile,
    /// `base = fixed`: fixed in space; a file's floating joint at the root
    /// becomes a fixed joint, so the base stays where its origin puts it.
    Fixed,
    /// `base = floating`: the root link on a free joint (three coordinates for
    /// its position, an orientation for its rotation), Pinocchio's
    /// `JointModelFreeFlyer` root; the same as the file's own floating joint.
    Floating,
}

/// What becomes of an `<inertia>` that is no rigid body's (`inertia = ..`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum InertiaRule {
    /// Refused, at the file and line, naming the link.
    #[default]
    Check,
    /// `inertia = repair`: the nearest physical inertia (principal moments
    /// projected onto the triangle inequalities, principal axes kept), each
    /// change listed in `URDF_REPAIRED`.
    Repair,
    /// `inertia = as_written`: used as the file writes it, unchecked.
    AsWritten,
}

/// What becomes of the joints' `<dynamics damping friction>` (`dynamics = ..`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DynamicsRule {
    /// Not written: a file whose `<dynamics>` are all zero reads as the
    /// rigid-body dynamics; one with a non-zero value is refused, naming the
    /// first such joint and its line, so that no loss the file states is
    /// dropped without a word.
    #[default]
    Unset,
    /// `dynamics = read`: each joint's damping and friction become
    /// `joint(q, damping = b, friction = fc)` (a mimic joint's b times its
    /// multiplier squared, and fc times its absolute value, on the joint it
    /// follows).
    Read,
    /// `dynamics = ignore`: the rigid-body dynamics, what Pinocchio's
    /// `rnea` and `aba` compute.
    Ignore,
}

/// What becomes of the joints' `<limit lower upper>` (`limits = ..`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LimitRule {
    /// Watched: a run that leaves them stops with `Error::JointLimit` (or
    /// goes on, as the run's `LimitPolicy` says).
    #[default]
    Watch,
    /// `limits = stops`: each finite bound becomes a plastic
    /// `stop(<q>_lower, q >= lower, restitution = 0)` (and `_upper`), which
    /// `run_contacts` enforces: the joint meets its end stop and stays.
    Stops,
}

/// The options of `urdf("path", ..)`.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// `snap = tol`: angles within `tol` (at most [`SNAP_BOUND`]) of a
    /// multiple of π/2 become it; [`DEFAULT_SNAP`] without the option, none
    /// with `snap = 0`.
    pub snap: f64,
    /// `base = fixed | floating`.
    pub base: Base,
    /// `inertia = repair | as_written`.
    pub inertia: InertiaRule,
    /// `dynamics = read | ignore`.
    pub dynamics: DynamicsRule,
    /// `limits = stops`.
    pub limits: LimitRule,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            snap: DEFAULT_SNAP,
            base: Base::default(),
            inertia: InertiaRule::default(),
            dynamics: DynamicsRule::default(),
            limits: LimitRule::default(),
        }
    }
}

const OPTIONS: &str = "the options are `snap = tolerance` (angles within it, at most 1e-6 rad, \
     of a multiple of π/2 become it; 1e-9 without the option, none with `snap = 0`), \
     `base = fixed | floating`, `inertia = repair | as_written` (an inertia that is no rigid \
     body's made the nearest physical one, or used unchecked), `dynamics = read | ignore` \
     (the joints' `<dynamics>` damping read as `joint(..)` items, or left out) and \
     `limits = stops` (the joints' `<limit>`s as plastic `stop(..)` items, which \
     `run_contacts` enforces)";

/// The attribute's `urdf = "path"`, or `urdf("path", snap = 1e-6, base =
/// floating, inertia = repair)`: the path and the options.
pub fn parse_attribute(input: ParseStream) -> syn::Result<(syn::LitStr, Options)> {
    let mut options = Options::default();
    if input.peek(Token![=]) {
        input.parse::<Token![=]>()?;
        return Ok((input.parse()?, options));
    }
    let content;
    syn::parenthesized!(content in input);
    let path: syn::LitStr = content.parse()?;
    let mut seen: Vec<String> = Vec::new();
    while !content.is_empty() {
        content.parse::<Token![,]>()?;
        if content.is_empty() {
            break;
        }
        let key: Ident = content.parse()?;
        content.parse::<Token![=]>()?;
        let name = key.to_string();
        if seen.contains(&name) {
            return Err(syn::Error::new(
                key.span(),
                format!("`urdf` option `{key}` given twice; write it once"),
            ));
        }
        match name.as_str() {
            "snap" => options.snap = snap_tolerance(&content)?,
            "base" => options.base = base(&content)?,
            "inertia" => options.inertia = inertia(&content)?,
            "dynamics" => options.dynamics = dynamics(&content)?,
            "limits" => options.limits = limits(&content)?,
            _ => {
                return Err(syn::Error::new(
                    key.span(),
                    format!("unknown `urdf` option `{key}`; {OPTIONS}"),
                ));
            }
        }
        seen.push(name);
    }
    Ok((path, options))
}

/// `snap = tol`: finite, from 0 (every angle as written) to [`SNAP_BOUND`].
fn snap_tolerance(content: ParseStream) -> syn::Result<f64> {
    const RANGE: &str = "`snap` needs a tolerance in radians from 0 to 1e-6, such as \
                         `snap = 1e-6`, or `snap = 0` for every angle as the file writes it";
    if content.peek(Token![-]) {
        let minus: Token![-] = content.parse()?;
        return Err(syn::Error::new(minus.span, RANGE));
    }
    let tol: syn::Lit = content.parse()?;
    let value: f64 = match &tol {
        syn::Lit::Float(f) => f.base10_parse()?,
        syn::Lit::Int(i) => i.base10_parse()?,
        _ => f64::NAN,
    };
    if !value.is_finite() {
        return Err(syn::Error::new(tol.span(), RANGE));
    }
    if value > SNAP_BOUND {
        return Err(syn::Error::new(
            tol.span(),
            format!(
                "`snap = {}` could move a real angle onto a multiple of π/2: the tolerance is \
                 at most 1e-6 rad (a file's π/2 written to ten digits is within 1e-10 of it); \
                 write `snap = 1e-6`",
                tol.to_token_stream()
            ),
        ));
    }
    Ok(value)
}

/// `base = floating` or `base = fixed`.
fn base(content: ParseStream) -> syn::Result<Base> {
    let kind: Ident = content.parse()?;
    match kind.to_string().as_str() {
        "floating" => Ok(Base::Floating),
        "fixed" => Ok(Base::Fixed),
        _ => Err(syn::Error::new(
            kind.span(),
            format!(
                "unknown base `{kind}`: write `base = floating` (a free root joint) or `base = \
                 fixed` (fixed in space; a file's floating joint at the root becomes fixed)"
            ),
        )),
    }
}

/// `inertia = repair` or `inertia = as_written`.
fn inertia(content: ParseStream) -> syn::Result<InertiaRule> {
    let kind: Ident = content.parse()?;
    match kind.to_string().as_str() {
        "repair" => Ok(InertiaRule::Repair),
        "as_written" => Ok(InertiaRule::AsWritten),
        _ => Err(syn::Error::new(
            kind.span(),
            format!(
                "unknown inertia rule `{kind}`: write `inertia = repair` (the nearest physical \
                 inertia, listed in `URDF_REPAIRED`) or `inertia = as_written` (unchecked); \
                 without it an inertia that is no rigid body's is refused"
            ),
        )),
    }
}

/// `dynamics = read` or `dynamics = ignore`.
fn dynamics(content: ParseStream) -> syn::Result<DynamicsRule> {
    let kind: Ident = content.parse()?;
    match kind.to_string().as_str() {
        "read" => Ok(DynamicsRule::Read),
        "ignore" => Ok(DynamicsRule::Ignore),
        _ => Err(syn::Error::new(
            kind.span(),
            format!(
                "unknown dynamics rule `{kind}`: write `dynamics = read` (the joints' damping and \
                 friction as `joint(q, damping = b, friction = fc)` items) or `dynamics = ignore` (the rigid-body dynamics, \
                 what Pinocchio's rnea and aba compute)"
            ),
        )),
    }
}

/// `limits = stops`.
fn limits(content: ParseStream) -> syn::Result<LimitRule> {
    let kind: Ident = content.parse()?;
    match kind.to_string().as_str() {
        "stops" => Ok(LimitRule::Stops),
        _ => Err(syn::Error::new(
            kind.span(),
            format!(
                "unknown limit rule `{kind}`: write `limits = stops` (each joint's `<limit>` a \
                 plastic `stop(..)` that `run_contacts` enforces); without it the limits are \
                 watched, and a run that leaves them stops with `Error::JointLimit`"
            ),
        )),
    }
}
