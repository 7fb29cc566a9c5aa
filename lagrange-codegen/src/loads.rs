//! The grammar of the loads a description applies besides gravity, the
//! potential and the dissipation: `force(point, [..])`, `torque(body, [..])`
//! and `generalized_force(q = ..)`. `check` checks their targets; `lower`
//! turns them into (position, force) pairs for Q.

use syn::parse::ParseStream;
use syn::punctuated::Punctuated;
use syn::{Expr, Ident, Token};

use crate::ast::{Force, GeneralizedForce, Torque};

/// `force(point, [fx, fy, fz])`.
pub(crate) fn parse_force(input: ParseStream) -> syn::Result<Force> {
    let content;
    syn::parenthesized!(content in input);
    let point: Ident = content.parse()?;
    content.parse::<Token![,]>()?;
    let value: Expr = content.parse()?;
    let _ = content.parse::<Option<Token![,]>>()?;
    if !content.is_empty() {
        return Err(content.error("expected `force(point, [fx, fy, fz])`"));
    }
    Ok(Force { point, value })
}

/// `torque(body, [tx, ty, tz])`, in world axes, or `torque(body, [..], axes =
/// body)` in the body's own (`axes = world` is the default, written out).
pub(crate) fn parse_torque(input: ParseStream) -> syn::Result<Torque> {
    let content;
    syn::parenthesized!(content in input);
    let body: Ident = content.parse()?;
    content.parse::<Token![,]>()?;
    let value: Expr = content.parse()?;
    let mut body_axes = false;
    if content.parse::<Option<Token![,]>>()?.is_some() && !content.is_empty() {
        let key: Ident = content.parse()?;
        if key != "axes" {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "unknown option `{key}` of `torque`; expected `axes = world` or `axes = body`"
                ),
            ));
        }
        content.parse::<Token![=]>()?;
        let axes: Ident = content.parse()?;
        body_axes = match axes.to_string().as_str() {
            "body" => true,
            "world" => false,
            other => {
                return Err(syn::Error::new(
                    axes.span(),
                    format!("`axes = {other}`: a torque's axes are `world` or `body`"),
                ));
            }
        };
        let _ = content.parse::<Option<Token![,]>>()?;
    }
    if !content.is_empty() {
        return Err(content
            .error("expected `torque(body, [tx, ty, tz])` or `torque(body, [..], axes = body)`"));
    }
    Ok(Torque {
        body,
        value,
        body_axes,
    })
}

/// `generalized_force(q = expr, ...)`. An orientation's angular velocity
/// (`att.wz`) is not a coordinate it can name: the error points to `torque`.
pub(crate) fn parse_generalized_forces(input: ParseStream) -> syn::Result<Vec<GeneralizedForce>> {
    let content;
    syn::parenthesized!(content in input);
    let fork = content.fork();
    while !fork.is_empty() {
        let name: Ident = fork.parse()?;
        if fork.peek(Token![.]) {
            let dot: Token![.] = fork.parse()?;
            let part = fork
                .parse::<Ident>()
                .map_or("…".to_string(), |p| p.to_string());
            let axis = part.strip_prefix('w').unwrap_or("z");
            let components = match axis {
                "x" => "[t, 0, 0]",
                "y" => "[0, t, 0]",
                _ => "[0, 0, t]",
            };
            return Err(syn::Error::new(
                dot.span,
                format!(
                    "`generalized_force` names coordinates, and `{name}.{part}` is not one (an \
                     orientation's angular velocity is not a coordinate); a torque t about the \
                     body axis {axis} of the body `b` that `{name}` turns is \
                     `torque(b, {components}, axes = body)`"
                ),
            ));
        }
        // Skip to the next entry; the real parse below reports any other error.
        while !fork.is_empty() && !fork.peek(Token![,]) {
            fork.parse::<proc_macro2::TokenTree>()?;
        }
        let _ = fork.parse::<Option<Token![,]>>()?;
    }
    let items = Punctuated::<GeneralizedForce, Token![,]>::parse_terminated(&content)?;
    Ok(items.into_iter().collect())
}

impl syn::parse::Parse for GeneralizedForce {
    /// One `q = expr` entry.
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let coordinate: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value: Expr = input.parse()?;
        Ok(GeneralizedForce { coordinate, value })
    }
}
