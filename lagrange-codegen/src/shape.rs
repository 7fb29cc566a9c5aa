//! `shape(...)` items: their syntax and their structural rules. Shapes are what
//! the scene draws and nothing else: no stage after this one reads them into an
//! equation, only the poses' emitter.
//!
//! ```text
//! shape(B, box(size = [lx, ly, lz]), at = [x, y, z])
//! shape(B, sphere(radius = r))
//! shape(B, cylinder(radius = r, length = l, axis = y))
//! shape(B, capsule(radius = r, length = l, axis = z))
//! shape(line(P, Q, ...))
//! ```

use syn::ext::IdentExt;
use syn::parse::ParseStream;
use syn::punctuated::Punctuated;
use syn::{Expr, Ident, Lit, Token, UnOp};

use crate::ast::{Shape, Solid, System};
use crate::ctxt::Ctxt;

/// The solids, as the error for an unknown one lists them.
const SOLIDS: &str = "`box(size = [lx, ly, lz])`, `sphere(radius = r)`, `cylinder(radius = r, length = l, axis = x|y|z)`, `capsule(radius = r, length = l, axis = x|y|z)` or `line(a, b, ...)`";

/// Parses the parenthesised body of a `shape` item.
pub fn parse(input: ParseStream) -> syn::Result<Shape> {
    let content;
    syn::parenthesized!(content in input);
    let first = Ident::parse_any(&content)?;
    if first == "line" && content.peek(syn::token::Paren) {
        return parse_line(&content, &first);
    }
    content.parse::<Token![,]>()?;
    let keyword = Ident::parse_any(&content)?;
    let args;
    syn::parenthesized!(args in content);
    let keys = Punctuated::<KeyValue, Token![,]>::parse_terminated(&args)?;
    let solid = solid(&keyword, keys.into_iter().collect())?;
    let mut at = None;
    while !content.is_empty() {
        content.parse::<Token![,]>()?;
        if content.is_empty() {
            break;
        }
        let KeyValue(key, value) = content.parse()?;
        if key != "at" || at.is_some() {
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "unexpected `{key}` in `shape({first}, ...)`; after the solid only `at = [x, y, z]` (its centre in body coordinates) may follow, once"
                ),
            ));
        }
        at = Some(Box::new(value));
    }
    Ok(Shape::Solid {
        target: first,
        solid: Box::new(solid),
        keyword,
        at,
    })
}

/// `line(a, b, ...)`: at least two names, nothing after it.
fn parse_line(content: ParseStream, keyword: &Ident) -> syn::Result<Shape> {
    let inner;
    syn::parenthesized!(inner in content);
    let names = Punctuated::<Ident, Token![,]>::parse_terminated(&inner)?;
    if names.len() < 2 {
        return Err(syn::Error::new(
            keyword.span(),
            "`line(...)` joins two or more points or bodies: write `shape(line(a, b))`",
        ));
    }
    let _ = content.parse::<Option<Token![,]>>()?;
    if !content.is_empty() {
        return Err(content.error("`shape(line(a, b, ...))` takes nothing after the line"));
    }
    Ok(Shape::Line(names.into_iter().collect()))
}

/// `key = value` inside a solid's parentheses.
struct KeyValue(Ident, Expr);

impl syn::parse::Parse for KeyValue {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let key: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        Ok(KeyValue(key, input.parse()?))
    }
}

/// The solid named by `keyword` with its keys, each required key present once.
fn solid(keyword: &Ident, keys: Vec<KeyValue>) -> syn::Result<Solid> {
    let word = keyword.to_string();
    let wanted: &[&str] = match word.as_str() {
        "box" => &["size"],
        "sphere" => &["radius"],
        "cylinder" | "capsule" => &["radius", "length", "axis"],
        _ => {
            return Err(syn::Error::new(
                keyword.span(),
                format!("unknown shape `{word}`; expected {SOLIDS}"),
            ));
        }
    };
    let mut slots: Vec<Option<Expr>> = vec![None; wanted.len()];
    for KeyValue(key, value) in keys {
        let Some(i) = wanted.iter().position(|w| key == w) else {
            let list: Vec<String> = wanted.iter().map(|w| format!("`{w} = ..`")).collect();
            return Err(syn::Error::new(
                key.span(),
                format!(
                    "unknown key `{key}` in `{word}`; expected {}",
                    list.join(", ")
                ),
            ));
        };
        slots[i] = Some(value);
    }
    let mut take = |i: usize| {
        slots[i].take().ok_or_else(|| {
            syn::Error::new(
                keyword.span(),
                format!("`{word}` needs `{} = ..`", wanted[i]),
            )
        })
    };
    Ok(match word.as_str() {
        "box" => Solid::Box { size: take(0)? },
        "sphere" => Solid::Sphere { radius: take(0)? },
        _ => {
            let radius = take(0)?;
            let length = take(1)?;
            // The axis defaults to z, the axis of symmetry of most tops.
            let axis = slots[2].take().map_or(Ok(2), |a| axis(&a))?;
            if word == "cylinder" {
                Solid::Cylinder {
                    radius,
                    length,
                    axis,
                }
            } else {
                Solid::Capsule {
                    radius,
                    length,
                    axis,
                }
            }
        }
    })
}

/// `x`, `y` or `z` → 0, 1, 2.
fn axis(e: &Expr) -> syn::Result<usize> {
    let name = match e {
        Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
        _ => None,
    };
    match name.as_deref() {
        Some("x") => Ok(0),
        Some("y") => Ok(1),
        Some("z") => Ok(2),
        _ => Err(syn::Error::new_spanned(
            e,
            "`axis` names a body axis: `x`, `y` or `z`",
        )),
    }
}

/// The structural rules: every shape on a declared body or point, a box's size
/// and an offset with three components, no literal size that is not positive.
pub fn check(cx: &Ctxt, system: &System) {
    let known = |name: &Ident| {
        system.bodies.iter().any(|b| b.name == *name)
            || system.points.iter().any(|p| p.name == *name)
    };
    for shape in &system.shapes {
        let (targets, sizes, at): (Vec<&Ident>, Vec<&Expr>, _) = match shape {
            Shape::Line(names) => (names.iter().collect(), Vec::new(), None),
            Shape::Solid {
                target, solid, at, ..
            } => (vec![target], sizes(cx, solid), at.as_deref()),
        };
        for name in targets.into_iter().filter(|n| !known(n)) {
            cx.error_at(name.span(), unknown_target(system, name));
        }
        for size in sizes {
            check_positive(cx, size);
        }
        if let Some(at) = at {
            three_components(cx, at, "a shape's `at`");
        }
    }
}

/// The error for a shape on a name that is no body or point, with the likely
/// one if the name is a typo of it.
fn unknown_target(system: &System, name: &Ident) -> String {
    let bodies = system.bodies.iter().map(|b| b.name.to_string());
    let names: Vec<String> = bodies
        .chain(system.points.iter().map(|p| p.name.to_string()))
        .collect();
    let word = name.to_string();
    match crate::spelling::closest(&word, names.iter().map(String::as_str)) {
        Some(near) => format!("shape on unknown body or point `{word}`; did you mean `{near}`?"),
        None => format!(
            "shape on unknown body or point `{word}`; shapes go on the bodies and points declared with `body({word}, ...)` or `point({word}, ...)`"
        ),
    }
}

/// The size expressions of a solid (a box's three edges when written as `[..]`).
fn sizes<'a>(cx: &Ctxt, solid: &'a Solid) -> Vec<&'a Expr> {
    match solid {
        Solid::Sphere { radius } => vec![radius],
        Solid::Cylinder { radius, length, .. } | Solid::Capsule { radius, length, .. } => {
            vec![radius, length]
        }
        Solid::Box { size } => match three_components(cx, size, "a box's `size`") {
            Some(a) => a.elems.iter().collect(),
            None => Vec::new(),
        },
    }
}

fn three_components<'a>(cx: &Ctxt, e: &'a Expr, what: &str) -> Option<&'a syn::ExprArray> {
    match e {
        Expr::Array(a) if a.elems.len() == 3 => Some(a),
        _ => {
            cx.error_spanned_by(e, format!("{what} must be a vector `[x, y, z]`"));
            None
        }
    }
}

/// A size written as a literal must be positive (a parameter is checked when
/// the scene is built, where its value is known).
fn check_positive(cx: &Ctxt, e: &Expr) {
    let value = match e {
        Expr::Lit(l) => literal(&l.lit),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
            Expr::Lit(l) => literal(&l.lit).map(|v| -v),
            _ => None,
        },
        _ => None,
    };
    if value.is_some_and(|v| v <= 0.0) {
        cx.error_spanned_by(
            e,
            format!(
                "a shape's size must be positive, but `{}` is not: write a length greater than zero (sizes are full lengths, radii are radii)",
                quote::ToTokens::to_token_stream(e).to_string().replace("- ", "-")
            ),
        );
    }
}

fn literal(l: &Lit) -> Option<f64> {
    match l {
        Lit::Float(f) => f.base10_parse().ok(),
        Lit::Int(i) => i.base10_parse().ok(),
        _ => None,
    }
}
