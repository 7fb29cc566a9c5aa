//! `contact(name, on = p, normal = [..], offset = d, radius = r,
//! restitution = e, friction = mu)` (a sphere against a plane),
//! `contact(name, on = a, radius = r, against = b, against_radius = s,
//! restitution = e)` (two spheres) and `stop(name, q >= lower,
//! restitution = e)`: the grammar of unilateral contacts. The options are
//! spelled in `keyword::CONTACT_OPTIONS`; the numbers a law takes are
//! checked here, at their tokens.

use syn::parse::ParseStream;
use syn::spanned::Spanned;
use syn::{BinOp, Expr, Ident, Token, UnOp};

use super::keyword::{CONTACT_OPTIONS, ContactOption};
use crate::ast::{Contact, ContactGeometry};

/// `contact(name, on = p, normal = [..], ..)`.
pub(super) fn parse_contact(input: ParseStream) -> syn::Result<Contact> {
    let content;
    syn::parenthesized!(content in input);
    let name: Ident = content.parse()?;
    let mut options = Options::default();
    while content.parse::<Option<Token![,]>>()?.is_some() && !content.is_empty() {
        options.parse_one(&content, &name)?;
    }
    if !content.is_empty() {
        return Err(content.error("expected `, option = value` after the contact's name"));
    }
    let form = "contact(name, on = point, normal = [0, 0, 1], restitution = e)";
    let missing = |what: &str| {
        syn::Error::new(
            name.span(),
            format!("contact `{name}` needs `{what}`: write `{form}`"),
        )
    };
    let on = options.on.take().ok_or_else(|| missing("on = point"))?;
    let restitution = options
        .restitution
        .ok_or_else(|| missing("restitution = e"))?;
    let friction = options.friction.unwrap_or(0.0);
    let geometry = match options.against.take() {
        Some(against) => spheres(&name, on, against, options)?,
        None => ContactGeometry::Plane {
            on,
            radius: options.radius,
            normal: options
                .normal
                .ok_or_else(|| missing("normal = [nx, ny, nz]"))?,
            offset: options.offset,
        },
    };
    Ok(Contact {
        name,
        geometry,
        restitution,
        friction,
    })
}

/// Two spheres: no plane's `normal` or `offset` (the line of centres is the
/// normal).
fn spheres(
    name: &Ident,
    on: Ident,
    against: Ident,
    options: Options,
) -> syn::Result<ContactGeometry> {
    let plane_only = [
        ("normal", options.normal_key),
        ("offset", options.offset_key),
    ];
    if let Some((word, Some(key))) = plane_only.into_iter().find(|(_, k)| k.is_some()) {
        return Err(syn::Error::new(
            key.span(),
            format!(
                "contact `{name}` is between two spheres (`against = {against}`), whose normal is \
                 the line of their centres: drop `{word}`, or drop `against` for a sphere on a plane"
            ),
        ));
    }
    if against == on {
        return Err(syn::Error::new(
            against.span(),
            format!(
                "contact `{name}`: `against = {against}` names the sphere's own point; two \
                 spheres are two points or bodies: name the other one"
            ),
        ));
    }
    Ok(ContactGeometry::Spheres {
        on,
        radius: options.radius,
        against,
        against_radius: options.against_radius,
    })
}

/// `stop(name, q >= lower, restitution = e)` or `q <= upper`.
pub(super) fn parse_stop(input: ParseStream) -> syn::Result<Contact> {
    let content;
    syn::parenthesized!(content in input);
    let name: Ident = content.parse()?;
    content.parse::<Token![,]>()?;
    let bound: Expr = content.parse()?;
    let form = "stop(name, q >= lower, restitution = e) or stop(name, q <= upper, ..)";
    let Expr::Binary(b) = &bound else {
        return Err(syn::Error::new(
            bound.span(),
            format!("a stop is a coordinate and its bound: `{form}`"),
        ));
    };
    let lower = match b.op {
        BinOp::Ge(_) => true,
        BinOp::Le(_) => false,
        _ => {
            return Err(syn::Error::new(
                b.op.span(),
                format!("a stop bounds its coordinate with `>=` or `<=`: `{form}`"),
            ));
        }
    };
    let coordinate = match &*b.left {
        Expr::Path(p) if p.path.get_ident().is_some() => p.path.get_ident().cloned(),
        _ => None,
    }
    .ok_or_else(|| syn::Error::new(b.left.span(), format!("expected a coordinate: `{form}`")))?;
    let mut options = Options::default();
    while content.parse::<Option<Token![,]>>()?.is_some() && !content.is_empty() {
        options.parse_one(&content, &name)?;
    }
    if let Some(key) = options.only_contact {
        return Err(syn::Error::new(
            key.span(),
            format!("`{key}` is an option of `contact`; a stop takes `restitution = e` alone"),
        ));
    }
    let restitution = options.restitution.ok_or_else(|| {
        syn::Error::new(
            name.span(),
            format!("stop `{name}` needs `restitution = e`: write `{form}`"),
        )
    })?;
    Ok(Contact {
        name,
        geometry: ContactGeometry::Stop {
            coordinate,
            lower,
            bound: (*b.right).clone(),
        },
        restitution,
        friction: 0.0,
    })
}

/// The options as written.
#[derive(Default)]
struct Options {
    on: Option<Ident>,
    radius: Option<Expr>,
    normal: Option<[f64; 3]>,
    offset: Option<Expr>,
    restitution: Option<f64>,
    friction: Option<f64>,
    against: Option<Ident>,
    against_radius: Option<Expr>,
    /// Where `normal`, `offset` and `friction` were written, for the errors
    /// of a contact between two spheres.
    normal_key: Option<Ident>,
    offset_key: Option<Ident>,
    friction_key: Option<Ident>,
    /// The first option written that a stop does not take.
    only_contact: Option<Ident>,
}

impl Options {
    /// One `key = value`.
    fn parse_one(&mut self, input: ParseStream, name: &Ident) -> syn::Result<()> {
        let key: Ident = input.parse()?;
        let word = key.to_string();
        let Some(option) = CONTACT_OPTIONS.find(&word) else {
            let expected = CONTACT_OPTIONS.alternatives();
            return Err(syn::Error::new(
                key.span(),
                match CONTACT_OPTIONS.closest(&word) {
                    Some(w) => format!(
                        "unknown option `{word}` of contact `{name}`; did you mean `{w}`? (expected {expected})"
                    ),
                    None => format!(
                        "unknown option `{word}` of contact `{name}`; expected {expected}:\n{}",
                        CONTACT_OPTIONS.described()
                    ),
                },
            ));
        };
        input.parse::<Token![=]>()?;
        if option != ContactOption::Restitution && self.only_contact.is_none() {
            self.only_contact = Some(key.clone());
        }
        match option {
            ContactOption::On => self.on = Some(input.parse()?),
            ContactOption::Radius => self.radius = Some(input.parse()?),
            ContactOption::Against => self.against = Some(input.parse()?),
            ContactOption::AgainstRadius => self.against_radius = Some(input.parse()?),
            ContactOption::Offset => {
                self.offset_key = Some(key);
                self.offset = Some(input.parse()?);
            }
            ContactOption::Normal => {
                self.normal_key = Some(key);
                self.normal = Some(normal(&input.parse()?)?);
            }
            ContactOption::Restitution => {
                let value: Expr = input.parse()?;
                let e = number(&value, "restitution")?;
                if !(0.0..=1.0).contains(&e) {
                    return Err(syn::Error::new(
                        value.span(),
                        format!(
                            "restitution = {e}: Newton's coefficient lies in [0, 1] (0 plastic, 1 elastic)"
                        ),
                    ));
                }
                self.restitution = Some(e);
            }
            ContactOption::Friction => {
                let value: Expr = input.parse()?;
                let mu = number(&value, "friction")?;
                if mu < 0.0 {
                    return Err(syn::Error::new(
                        value.span(),
                        format!(
                            "friction = {mu}: Coulomb's coefficient is ≥ 0 (0 for no friction)"
                        ),
                    ));
                }
                self.friction = Some(mu);
                self.friction_key = Some(key);
            }
        }
        Ok(())
    }
}

/// A number written as a literal, possibly negated.
pub(super) fn number(e: &Expr, what: &str) -> syn::Result<f64> {
    let value = match e {
        Expr::Lit(l) => match &l.lit {
            syn::Lit::Int(i) => i.base10_parse::<f64>().ok(),
            syn::Lit::Float(f) => f.base10_parse::<f64>().ok(),
            _ => None,
        },
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => number(&u.expr, what).ok().map(|x| -x),
        Expr::Paren(p) => number(&p.expr, what).ok(),
        _ => None,
    };
    value.filter(|x| x.is_finite()).ok_or_else(|| {
        syn::Error::new(
            e.span(),
            format!(
                "`{what}` takes a number written out (e.g. `0.5`), read when the code is derived"
            ),
        )
    })
}

/// `[nx, ny, nz]`, three numbers not all zero, made a unit vector.
fn normal(e: &Expr) -> syn::Result<[f64; 3]> {
    let wrong = || {
        syn::Error::new(
            e.span(),
            "`normal` takes three numbers, not all zero: `normal = [0, 0, 1]`",
        )
    };
    let Expr::Array(a) = e else {
        return Err(wrong());
    };
    if a.elems.len() != 3 {
        return Err(wrong());
    }
    let mut n = [0.0; 3];
    for (slot, x) in n.iter_mut().zip(&a.elems) {
        *slot = number(x, "normal")?;
    }
    let size = n.iter().map(|x| x * x).sum::<f64>().sqrt();
    if size == 0.0 {
        return Err(wrong());
    }
    Ok(n.map(|x| x / size))
}
