//! `#[derive(Lagrangian)]` as an ordinary library: `DeriveInput` → `TokenStream`.
//!
//! The pipeline, one representation per stage:
//!
//! 1. [`attr`]: attributes and fields → [`ast::System`] (syntax, spans kept);
//! 2. [`check`]: structural rules (names, dimensions, targets);
//! 3. [`lower`]: `syn::Expr` → symbolic expressions (names resolved, velocity rules);
//! 4. [`mechanics`]: M, h, Q, energies as expressions ([`mechanics::Model`]);
//! 5. [`emit`]: straight-line Rust for each method of the runtime's trait.
//!
//! Errors are collected in a [`ctxt::Ctxt`] across stages; on error the output is
//! `compile_error!`s plus a stub impl, never a panic.

pub mod ast;
pub mod attr;
pub mod chain;
pub mod check;
pub mod ctxt;
pub mod doc;
pub mod emit;
pub mod lower;
pub mod mechanics;

use proc_macro2::TokenStream;
use syn::DeriveInput;

use ctxt::Ctxt;
use lower::{Lowerer, Mode};
use mechanics::{Lowered, Model, PointModel};

/// Parses and expands; the entry point of the proc macro.
pub fn derive(input: TokenStream) -> TokenStream {
    match syn::parse2::<DeriveInput>(input) {
        Ok(input) => expand(&input),
        Err(e) => e.to_compile_error(),
    }
}

/// Expands a parsed derive input into the trait impl (or errors plus a stub impl).
pub fn expand(input: &DeriveInput) -> TokenStream {
    let cx = Ctxt::new();
    let Some(system) = attr::parse(&cx, input) else {
        return cx.to_compile_errors();
    };
    match build(&cx, &system) {
        Some(model) => {
            let body = emit::impl_lagrangian(&system, &model);
            quote::quote!(const _: () = { #body };)
        }
        None => {
            let errors = cx.to_compile_errors();
            let stub = emit::stub_impl(&system);
            quote::quote!(#errors const _: () = { #stub };)
        }
    }
}

/// Runs the stages up to the symbolic model, for tools and benchmarks that want the
/// equations (and their operation counts) rather than tokens.
pub fn model(input: &DeriveInput) -> Result<Model, syn::Error> {
    let cx = Ctxt::new();
    let system = attr::parse(&cx, input);
    let model = system.as_ref().and_then(|s| build(&cx, s));
    match (model, cx.take()) {
        (Some(m), None) => Ok(m),
        (_, Some(e)) => Err(e),
        (None, None) => Err(syn::Error::new(
            input.ident.span(),
            "could not derive the equations",
        )),
    }
}

fn build(cx: &Ctxt, system: &ast::System) -> Option<Model> {
    check::check(cx, system);
    let lowered = lower_system(cx, system);
    if cx.has_errors() {
        return None;
    }
    lowered.map(mechanics::derive)
}

fn lower_system(cx: &Ctxt, system: &ast::System) -> Option<Lowered> {
    let mut lw = Lowerer::new(cx);
    for p in &system.parameters {
        lw.declare_parameter(&p.name);
    }
    for q in &system.coordinates {
        lw.declare_coordinate(q);
    }
    for d in &system.definitions {
        lw.declare_definition(&d.name, &d.value);
    }
    let mut points = Vec::new();
    for p in &system.points {
        let (Some(mass), Some(at)) = (&p.mass, &p.at) else {
            continue;
        };
        let mass = lw.expr(mass, Mode::Constant);
        let position = lw.vector(at, Mode::Configuration);
        if let (Some(mass), Some(position)) = (mass, position) {
            points.push(PointModel {
                name: p.name.to_string(),
                mass,
                position,
            });
        }
    }
    let gravity = system
        .gravity
        .as_ref()
        .and_then(|g| lw.vector(g, Mode::Configuration));
    let potential = system
        .potential
        .as_ref()
        .and_then(|v| lw.expr(v, Mode::Configuration));
    let dissipation = system
        .dissipation
        .as_ref()
        .and_then(|d| lw.expr(d, Mode::State));
    let mut forces = Vec::new();
    for f in &system.forces {
        let target = system.points.iter().position(|p| p.name == f.point);
        if let (Some(i), Some(v)) = (target, lw.vector(&f.value, Mode::State)) {
            forces.push((i, v));
        }
    }
    let mut generalized_forces = Vec::new();
    for g in &system.generalized_forces {
        let target = system.coordinates.iter().position(|c| *c == g.coordinate);
        if let (Some(i), Some(v)) = (target, lw.expr(&g.value, Mode::State)) {
            generalized_forces.push((i, v));
        }
    }
    if cx.has_errors() {
        return None;
    }
    Some(Lowered {
        ctx: lw.ctx,
        coordinates: system.coordinates.iter().map(|c| c.to_string()).collect(),
        parameters: system
            .parameters
            .iter()
            .map(|p| p.name.to_string())
            .collect(),
        points,
        gravity,
        potential,
        dissipation,
        forces,
        generalized_forces,
    })
}
