//! `#[lagrange(...)]` attributes and struct fields → [`crate::ast::System`].
//!
//! Parsing is syntactic only: names are not resolved here (that is `lower`'s job),
//! but every item keeps its tokens so later errors can point at them.

use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::spanned::Spanned;
use syn::{Data, DeriveInput, Expr, Fields, GenericParam, Ident, Token, Type};

use crate::ast::{
    Body, Constraint, Definition, Extra, Force, Formulation, GeneralizedForce, Parameter, Point,
    Scalar, Shape, System, Torque,
};
use crate::ctxt::Ctxt;
use crate::loads;
use keyword::{FORMULATIONS, KEYS, Key, OUTPUTS, Words};

mod contact;
mod joint;
mod keyword;

/// One top-level item of the attribute.
enum Item {
    Coordinates(Vec<Ident>),
    Orientations(Vec<Ident>),
    Inputs(Vec<Ident>),
    Define(Vec<Definition>),
    Point(Point),
    Body(Box<Body>),
    Holonomic(Vec<Constraint>),
    Nonholonomic(Vec<Constraint>),
    Speeds(Vec<Definition>),
    Formulation(Vec<(Ident, Formulation)>),
    Emit(Vec<(Ident, Extra)>),
    Gravity(Ident, Expr),
    Potential(Ident, Expr),
    Dissipation(Ident, Expr),
    Force(Force),
    Torque(Torque),
    GeneralizedForce(Vec<GeneralizedForce>),
    /// The path, and the tolerance within which angles snap to multiples of π/2.
    Urdf(syn::LitStr, crate::urdf::Options),
    Shape(Shape),
    Contact(crate::ast::Contact),
    Joint(Box<crate::ast::Joint>),
}

impl Parse for Item {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let key: Ident = input.parse()?;
        let Some(which) = KEYS.find(&key.to_string()) else {
            return Err(unknown_key(&key));
        };
        expect_list(input, &key, which.list_form())?;
        let definition = |(name, value)| Definition { name, value };
        let constraint = |(name, value)| Constraint { name, value };
        match which {
            Key::Coordinates => parse_coordinates(input, &key).map(Item::Coordinates),
            Key::Orientation => parse_names(input).map(Item::Orientations),
            Key::Inputs => parse_names(input).map(Item::Inputs),
            Key::Define => Ok(Item::Define(
                parse_name_values(input)?.map(definition).collect(),
            )),
            Key::Point => parse_point(input).map(Item::Point),
            Key::Body => parse_body(input).map(|b| Item::Body(Box::new(b))),
            Key::Holonomic => Ok(Item::Holonomic(
                parse_name_values(input)?.map(constraint).collect(),
            )),
            Key::Nonholonomic => Ok(Item::Nonholonomic(
                parse_name_values(input)?.map(constraint).collect(),
            )),
            Key::Speeds => Ok(Item::Speeds(
                parse_name_values(input)?.map(definition).collect(),
            )),
            Key::Formulation => {
                parse_keywords(input, "formulation", &FORMULATIONS).map(Item::Formulation)
            }
            Key::Emit => parse_keywords(input, "output", &OUTPUTS).map(Item::Emit),
            Key::Gravity | Key::Potential | Key::Dissipation => {
                input.parse::<Token![=]>()?;
                let value: Expr = input.parse()?;
                Ok(match which {
                    Key::Gravity => Item::Gravity(key, value),
                    Key::Potential => Item::Potential(key, value),
                    _ => Item::Dissipation(key, value),
                })
            }
            Key::Urdf => {
                crate::urdf::parse_attribute(input).map(|(path, options)| Item::Urdf(path, options))
            }
            Key::Force => loads::parse_force(input).map(Item::Force),
            Key::Torque => loads::parse_torque(input).map(Item::Torque),
            Key::GeneralizedForce => {
                loads::parse_generalized_forces(input).map(Item::GeneralizedForce)
            }
            Key::Shape => crate::shape::parse(input).map(Item::Shape),
            Key::Contact => contact::parse_contact(input).map(Item::Contact),
            Key::Stop => contact::parse_stop(input).map(Item::Contact),
            Key::Joint => joint::parse_joint(input).map(|j| Item::Joint(Box::new(j))),
        }
    }
}

/// `coordinates(q1, q2, ...)`, which must name at least one.
fn parse_coordinates(input: ParseStream, key: &Ident) -> syn::Result<Vec<Ident>> {
    let content;
    syn::parenthesized!(content in input);
    let names = Punctuated::<Ident, Token![,]>::parse_terminated(&content)?;
    if names.is_empty() {
        return Err(syn::Error::new(
            key.span(),
            "`coordinates()` lists no coordinate: name them, `coordinates(q1, q2, ...)`",
        ));
    }
    Ok(names.into_iter().collect())
}

/// `(name = value, ...)`, the shape of `define`, the constraints, `speeds` and
/// `generalized_force`.
fn parse_name_values(input: ParseStream) -> syn::Result<impl Iterator<Item = (Ident, Expr)>> {
    let content;
    syn::parenthesized!(content in input);
    let items = Punctuated::<NameValue, Token![,]>::parse_terminated(&content)?;
    Ok(items.into_iter().map(|NameValue(n, v)| (n, v)))
}

/// `(word, ...)` where each word is one of `words` (`what` names them in
/// the error, which suggests the word a typo meant or lists them all).
fn parse_keywords<T: Copy + PartialEq>(
    input: ParseStream,
    what: &str,
    words: &Words<T>,
) -> syn::Result<Vec<(Ident, T)>> {
    let names = parse_names(input)?;
    let mut out = Vec::new();
    for n in names {
        let word = n.to_string();
        let Some(value) = words.find(&word) else {
            let expected = words.alternatives();
            let message = match words.closest(&word) {
                Some(w) => {
                    format!("unknown {what} `{word}`; did you mean `{w}`? (expected {expected})")
                }
                None => format!(
                    "unknown {what} `{word}`; expected {expected}:\n{}",
                    words.described()
                ),
            };
            return Err(syn::Error::new(n.span(), message));
        };
        out.push((n, value));
    }
    Ok(out)
}

/// The error for a key that is none of [`KEYS`], with the likely one if the key
/// is a typo of it.
fn unknown_key(key: &Ident) -> syn::Error {
    let other = key.to_string();
    let keys = KEYS.joined(", ");
    syn::Error::new(
        key.span(),
        match KEYS.closest(&other) {
            Some(k) => format!(
                "unknown key `{other}` in #[lagrange(...)]; did you mean `{k}`? (keys: {keys})"
            ),
            None => {
                format!("unknown key `{other}` in #[lagrange(...)]; expected one of: {keys}")
            }
        },
    )
}

/// A list key written as an assignment (`coordinates = [x, y]`) is one error
/// at the `=` that shows the list form.
fn expect_list(input: ParseStream, key: &Ident, form: Option<String>) -> syn::Result<()> {
    let Some(form) = form else {
        return Ok(());
    };
    if input.peek(Token![=]) {
        let eq: Token![=] = input.parse()?;
        return Err(syn::Error::new(
            eq.span,
            format!("`{key}` takes its entries in parentheses, not `=`: write `{form}`"),
        ));
    }
    Ok(())
}

/// `name = expr`
struct NameValue(Ident, Expr);

impl Parse for NameValue {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let name: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value: Expr = input.parse()?;
        Ok(NameValue(name, value))
    }
}

/// `(a, b, c)`: a parenthesised list of names.
fn parse_names(input: ParseStream) -> syn::Result<Vec<Ident>> {
    let content;
    syn::parenthesized!(content in input);
    let names = Punctuated::<Ident, Token![,]>::parse_terminated(&content)?;
    Ok(names.into_iter().collect())
}

/// `(name, key = value, ...)` with keys from `keys`, each at most once, in any order.
fn parse_keyed(
    input: ParseStream,
    what: &str,
    keys: &[&str],
) -> syn::Result<(Ident, Vec<Option<Expr>>)> {
    let content;
    syn::parenthesized!(content in input);
    let name: Ident = content.parse()?;
    let mut slots: Vec<Option<Expr>> = vec![None; keys.len()];
    while !content.is_empty() {
        content.parse::<Token![,]>()?;
        if content.is_empty() {
            break;
        }
        let NameValue(k, v) = content.parse()?;
        let Some(i) = keys.iter().position(|key| k == key) else {
            let expected: Vec<String> = keys.iter().map(|k| format!("`{k} = ...`")).collect();
            return Err(syn::Error::new(
                k.span(),
                format!(
                    "unknown key `{k}` in {what} `{name}`; expected {}",
                    expected.join(", ")
                ),
            ));
        };
        if slots[i].is_some() {
            return Err(syn::Error::new(
                k.span(),
                format!("`{k}` given twice for {what} `{name}`"),
            ));
        }
        slots[i] = Some(v);
    }
    Ok((name, slots))
}

/// `point(name, mass = m, at = [x, y, z])` or `point(name, on = body, at = [..])`.
fn parse_point(input: ParseStream) -> syn::Result<Point> {
    let (name, mut s) = parse_keyed(input, "point", &["mass", "at", "on"])?;
    let on = match s[2].take() {
        None => None,
        Some(Expr::Path(p)) if p.path.get_ident().is_some() => p.path.get_ident().cloned(),
        Some(other) => {
            return Err(syn::Error::new_spanned(
                other,
                "`on = ...` names the body the point is fixed in",
            ));
        }
    };
    Ok(Point {
        name,
        mass: s[0].take(),
        at: s[1].take(),
        on,
    })
}

/// `body(name, mass = m, inertia = [..], at = [..], rotation = R, com = [..])`.
fn parse_body(input: ParseStream) -> syn::Result<Body> {
    let keys = ["mass", "inertia", "at", "rotation", "com", "about"];
    let (name, mut s) = parse_keyed(input, "body", &keys)?;
    Ok(Body {
        name,
        mass: s[0].take(),
        inertia: s[1].take(),
        at: s[2].take(),
        rotation: s[3].take(),
        com: s[4].take(),
        about: s[5].take(),
        inertia_unchecked: false,
    })
}

/// Reads the struct and its `#[lagrange(...)]` attributes. Returns `None` only when
/// the input is not something we can describe at all (not a struct with named fields).
pub fn parse(cx: &Ctxt, input: &DeriveInput) -> Option<System> {
    let fields = match &input.data {
        Data::Struct(s) => match &s.fields {
            Fields::Named(named) => Some(named),
            Fields::Unit => None,
            Fields::Unnamed(_) => {
                cx.error_spanned_by(
                    &s.fields,
                    "#[derive(Lagrangian)] needs named fields (the parameters are referred to by name)",
                );
                return None;
            }
        },
        _ => {
            cx.error_at(
                input.ident.span(),
                "#[derive(Lagrangian)] applies to structs whose fields are the physical parameters",
            );
            return None;
        }
    };

    let (scalar, parameters) = parse_fields(cx, input, fields);
    let mut system = System {
        ident: input.ident.clone(),
        generics: input.generics.clone(),
        scalar,
        parameters,
        coordinates: Vec::new(),
        orientations: Vec::new(),
        inputs: Vec::new(),
        definitions: Vec::new(),
        points: Vec::new(),
        bodies: Vec::new(),
        holonomic: Vec::new(),
        nonholonomic: Vec::new(),
        speeds: Vec::new(),
        formulations: Vec::new(),
        extras: Vec::new(),
        gravity: None,
        potential: None,
        dissipation: None,
        forces: Vec::new(),
        torques: Vec::new(),
        generalized_forces: Vec::new(),
        shapes: Vec::new(),
        contacts: Vec::new(),
        joints: Vec::new(),
        span: input.ident.span(),
        urdf: None,
    };

    let mut seen_attr = false;
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("lagrange")) {
        seen_attr = true;
        let tokens = match &attr.meta {
            syn::Meta::List(list) => list.tokens.clone(),
            other => {
                cx.error_spanned_by(other, "expected #[lagrange(...)]");
                continue;
            }
        };
        // Each top-level item is parsed on its own, so one malformed item is one
        // error and the rest of the description is still checked.
        for chunk in split_top_level_commas(tokens) {
            match syn::parse2::<Item>(chunk) {
                Ok(item) => add_item(cx, &mut system, item),
                Err(e) => cx.syn_error(e),
            }
        }
    }
    let misplaced = misplaced_attributes(cx, input, fields);
    if !seen_attr && !misplaced {
        cx.error_at(
            input.ident.span(),
            "missing #[lagrange(coordinates(...), point(...), ...)] describing the system",
        );
    }
    Some(system)
}

/// `#[lagrange(...)]` on a field, where the derive (which registers it as a
/// helper attribute of the whole item) accepts it silently: an error at the
/// attribute. Returns whether there was one.
fn misplaced_attributes(cx: &Ctxt, input: &DeriveInput, fields: Option<&syn::FieldsNamed>) -> bool {
    let mut found = false;
    for field in fields.into_iter().flat_map(|f| f.named.iter()) {
        for attr in field.attrs.iter().filter(|a| a.path().is_ident("lagrange")) {
            found = true;
            let name = field
                .ident
                .as_ref()
                .map(ToString::to_string)
                .unwrap_or_default();
            cx.error_spanned_by(
                attr,
                format!(
                    "#[lagrange(...)] belongs on the struct, not on field `{name}`: move it above \
                     `struct {}` (the fields are the parameters and take no attribute)",
                    input.ident
                ),
            );
        }
    }
    found
}

/// Splits `a, b(c, d), e` into `a`, `b(c, d)`, `e`: commas inside groups are
/// inside one token tree, so only the top-level ones separate items.
fn split_top_level_commas(tokens: proc_macro2::TokenStream) -> Vec<proc_macro2::TokenStream> {
    let mut items = Vec::new();
    let mut current = proc_macro2::TokenStream::new();
    for tt in tokens {
        match &tt {
            proc_macro2::TokenTree::Punct(p) if p.as_char() == ',' => {
                items.push(std::mem::take(&mut current));
            }
            _ => current.extend([tt]),
        }
    }
    if !current.is_empty() {
        items.push(current);
    }
    items.into_iter().filter(|c| !c.is_empty()).collect()
}

fn add_item(cx: &Ctxt, system: &mut System, item: Item) {
    match item {
        Item::Coordinates(names) => system.coordinates.extend(names),
        Item::Orientations(names) => system.orientations.extend(names),
        Item::Inputs(names) => system.inputs.extend(names),
        Item::Define(defs) => system.definitions.extend(defs),
        Item::Point(p) => system.points.push(p),
        Item::Body(b) => system.bodies.push(*b),
        Item::Holonomic(c) => system.holonomic.extend(c),
        Item::Nonholonomic(c) => system.nonholonomic.extend(c),
        Item::Speeds(s) => system.speeds.extend(s),
        Item::Formulation(f) => system.formulations.extend(f),
        Item::Emit(e) => system.extras.extend(e),
        Item::Force(f) => system.forces.push(f),
        Item::Torque(t) => system.torques.push(t),
        Item::GeneralizedForce(g) => system.generalized_forces.extend(g),
        Item::Shape(s) => system.shapes.push(s),
        Item::Contact(c) => system.contacts.push(c),
        Item::Joint(j) => system.joints.push(*j),
        Item::Gravity(k, v) => set_once(cx, &mut system.gravity, k, v),
        Item::Potential(k, v) => set_once(cx, &mut system.potential, k, v),
        Item::Dissipation(k, v) => set_once(cx, &mut system.dissipation, k, v),
        Item::Urdf(path, options) => add_urdf(cx, system, &path, options),
    }
}

/// Reads the URDF file and adds its description's items, each spanned at the
/// path so that any error they raise points at `urdf = "..."`.
fn add_urdf(cx: &Ctxt, system: &mut System, path: &syn::LitStr, options: crate::urdf::Options) {
    if system.urdf.is_some() {
        cx.error_at(
            path.span(),
            "`urdf` given twice; a description reads one robot",
        );
        return;
    }
    let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
    let fields: Vec<String> = system
        .parameters
        .iter()
        .map(|p| p.name.to_string())
        .collect();
    let urdf = match crate::urdf::load(&manifest, &path.value(), &fields, options) {
        Ok(urdf) => urdf,
        Err(message) => return cx.error_at(path.span(), message),
    };
    let first_body = system.bodies.len();
    for tokens in urdf.items_at(path.span()) {
        match syn::parse2::<Item>(tokens.clone()) {
            Ok(item) => add_item(cx, system, item),
            Err(e) => cx.error_at(
                path.span(),
                format!("{}: generated `{tokens}`: {e}", path.value()),
            ),
        }
    }
    if options.inertia == crate::urdf::InertiaRule::AsWritten {
        for body in &mut system.bodies[first_body..] {
            body.inertia_unchecked = true;
        }
    }
    system.urdf = Some(crate::ast::UrdfSource {
        path: urdf.path,
        robot: urdf.name,
        coordinates: urdf.coordinates,
        limits: urdf.limits,
        efforts: urdf.efforts,
        velocities: urdf.velocities,
        snapped: urdf.snapped,
        repaired: urdf.repaired,
    });
}

fn set_once(cx: &Ctxt, slot: &mut Option<Expr>, key: Ident, value: Expr) {
    if slot.is_some() {
        cx.error_at(
            key.span(),
            format!("`{key}` given twice; write it once (sums are allowed)"),
        );
    } else {
        *slot = Some(value);
    }
}

/// The fields must all be of one float type: `f64`, `f32`, or a type parameter of
/// the struct. That type is the scalar of the generated code.
fn parse_fields(
    cx: &Ctxt,
    input: &DeriveInput,
    fields: Option<&syn::FieldsNamed>,
) -> (Scalar, Vec<Parameter>) {
    let type_params: Vec<&Ident> = input
        .generics
        .params
        .iter()
        .filter_map(|p| match p {
            GenericParam::Type(t) => Some(&t.ident),
            _ => None,
        })
        .collect();
    let mut scalar: Option<(Scalar, Span)> = None;
    let mut parameters = Vec::new();
    for field in fields.into_iter().flat_map(|f| f.named.iter()) {
        let Some(name) = field.ident.clone() else {
            continue;
        };
        let Some(this) = scalar_of(&field.ty, &type_params) else {
            cx.error_spanned_by(
                &field.ty,
                format!(
                    "parameter field `{name}` must be a float (f64, f32, or the struct's scalar type parameter)"
                ),
            );
            continue;
        };
        match &scalar {
            None => scalar = Some((this, field.ty.span())),
            Some((s, _)) if *s != this => cx.error_spanned_by(
                &field.ty,
                format!("parameter field `{name}` has a different float type from the first field; use one scalar type for all parameters"),
            ),
            Some(_) => {}
        }
        parameters.push(Parameter { name });
    }
    let scalar = match scalar {
        Some((s, _)) => s,
        // No fields: a single type parameter is the scalar, otherwise f64.
        None => match type_params.as_slice() {
            [t] => Scalar::Generic((*t).clone()),
            _ => Scalar::F64,
        },
    };
    (scalar, parameters)
}

fn scalar_of(ty: &Type, type_params: &[&Ident]) -> Option<Scalar> {
    let Type::Path(p) = ty else { return None };
    if p.qself.is_some() {
        return None;
    }
    let ident = p.path.get_ident()?;
    if ident == "f64" {
        Some(Scalar::F64)
    } else if ident == "f32" {
        Some(Scalar::F32)
    } else if type_params.contains(&ident) {
        Some(Scalar::Generic(ident.clone()))
    } else {
        None
    }
}
