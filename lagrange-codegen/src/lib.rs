//! `#[derive(Lagrangian)]` as an ordinary library: `DeriveInput` → `TokenStream`.
//!
//! The pipeline, one representation per stage:
//!
//! 1. [`attr`]: attributes and fields → [`ast::System`] (syntax, spans kept), with
//!    [`shape`] for the `shape(...)` items;
//! 2. [`check`] and [`shape::check`]: structural rules (names, dimensions, targets);
//! 3. [`scene`] (with [`lower`] for expressions and [`lower::rotation`] for bodies):
//!    `syn::Expr` → symbolic expressions (names resolved, velocity and linearity rules),
//!    handed on as a [`lowered::Lowered`], whose [`lowered::Poses`] ([`pose`]) hold
//!    the bodies' poses, the points' positions and the shapes for the scene;
//! 4. [`mechanics`]: M, h, Q, energies as expressions ([`mechanics::Model`]), with
//!    [`tree`] for the recursive route and [`constraint`] for the multiplier and
//!    reduced forms;
//! 5. [`emit`] (with [`doc`] for the `EQUATIONS` texts): straight-line Rust for
//!    each method of the runtime's traits, `Posed` (the scene's poses) among them.
//!
//! A module imports only from its own stage or the ones before it; [`mat3`],
//! [`ctxt`] and [`spelling`] are shared by all.
//!
//! Errors are collected in a [`ctxt::Ctxt`] across stages, consumed before
//! anything is emitted; on error the output is `compile_error!`s plus a stub
//! impl, never a panic.

#![warn(missing_docs)]

pub mod ast;
pub mod atlas;
pub mod attr;
pub mod chain;
pub mod check;
pub mod constraint;
pub mod ctxt;
pub mod doc;
pub mod emit;
pub mod loads;
pub mod lower;
pub mod lowered;
pub mod mat3;
pub mod mechanics;
pub mod order;
pub mod physical;
pub mod pose;
pub mod scene;
pub mod shape;
pub mod spelling;
pub mod tree;
pub mod urdf;

use proc_macro2::TokenStream;
use syn::DeriveInput;

use ctxt::Ctxt;
use mechanics::Model;

/// Parses and expands; the entry point of the proc macro.
///
/// A panic anywhere in the pipeline is a bug, but it must not surface as rustc's
/// bare "proc-macro derive panicked": it is caught and turned into an error at the
/// struct's name that says what happened.
pub fn derive(input: TokenStream) -> TokenStream {
    let input = match syn::parse2::<DeriveInput>(input) {
        Ok(input) => input,
        Err(e) => return e.to_compile_error(),
    };
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| expand(&input))) {
        Ok(tokens) => tokens,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            syn::Error::new(
                input.ident.span(),
                format!("internal error in #[derive(Lagrangian)] ({what}); this is a bug in lagrange, please report it with this description"),
            )
            .to_compile_error()
        }
    }
}

/// Expands a parsed derive input into the trait impl (or errors plus a stub impl).
///
/// The stages record their errors in one [`Ctxt`], consumed ([`Ctxt::finish`])
/// before anything is emitted: code comes out only for a description without
/// errors, and every error recorded comes out.
pub fn expand(input: &DeriveInput) -> TokenStream {
    let cx = Ctxt::new();
    let Some(system) = attr::parse(&cx, input) else {
        // Not a struct with named fields, as the errors say: nothing to stub.
        let nothing: Option<TokenStream> = None;
        return cx
            .finish(nothing, input.ident.span())
            .unwrap_or_else(|e| e.to_compile_error());
    };
    let derived = derive_models(&cx, &system);
    match cx.finish(derived, system.span) {
        Ok(derived) => derived.emit(&system),
        Err(errors) => {
            let errors = errors.to_compile_error();
            let stub = emit::stub_impl(&system);
            quote::quote!(#errors const _: () = { #stub };)
        }
    }
}

/// The models a description's code is emitted from, derived while its errors
/// are still being collected and emitted only once none was.
struct Derived {
    model: Model,
    /// `emit(atlas)`'s free twin: its description, its model, and the Euler
    /// rotations it replaces.
    atlas: Option<(ast::System, Model, Vec<atlas::EulerTriple>)>,
}

impl Derived {
    fn emit(&self, system: &ast::System) -> TokenStream {
        let body = emit::impl_lagrangian(system, &self.model);
        let atlas = self.atlas.as_ref().map(|(twin, twin_model, triples)| {
            emit::impl_atlas(system, &self.model, twin, twin_model, triples)
        });
        quote::quote!(const _: () = { #body #atlas };)
    }
}

/// The user's model and, if `emit(atlas)` asks for them, the free twin's:
/// the twin's description goes through the same stages as the user's.
fn derive_models(cx: &Ctxt, system: &ast::System) -> Option<Derived> {
    let model = build(cx, system, mechanics::Route::Auto)?;
    let asked = system.extras.iter().find(|(_, e)| *e == ast::Extra::Atlas);
    let atlas = match asked {
        None => None,
        Some((at, _)) => {
            let (twin, triples) = atlas::twin(cx, system, at)?;
            let twin_model = build(cx, &twin, mechanics::Route::Auto)?;
            Some((twin, twin_model, triples))
        }
    };
    Some(Derived { model, atlas })
}

/// Runs the stages up to the symbolic model, for tools and benchmarks that want the
/// equations (and their operation counts) rather than tokens.
pub fn model(input: &DeriveInput) -> Result<Model, syn::Error> {
    model_by(input, mechanics::Route::Auto)
}

/// [`model`] by a chosen derivation route, for tests and benchmarks that compare
/// the recursive and generic routes on one description.
pub fn model_by(input: &DeriveInput, route: mechanics::Route) -> Result<Model, syn::Error> {
    let cx = Ctxt::new();
    let system = attr::parse(&cx, input);
    let model = system.as_ref().and_then(|s| build(&cx, s, route));
    cx.finish(model, input.ident.span())
}

fn build(cx: &Ctxt, system: &ast::System, route: mechanics::Route) -> Option<Model> {
    // An item that did not parse may have declared names (a misspelt
    // `coordinates`, a malformed `define`): checking the rest would report
    // every use of those names as well, so parse errors are reported alone.
    if cx.has_errors() {
        return None;
    }
    let names_unique = check::check(cx, system);
    shape::check(cx, system);
    if !names_unique {
        return None;
    }
    let lowered = scene::lower(cx, system);
    if cx.has_errors() {
        return None;
    }
    match mechanics::derive_with(lowered?, route) {
        Ok(model) => {
            let zero_rows: Vec<bool> = (model.motion.mass.iter())
                .map(|row| row.iter().all(|&e| model.ctx.is_zero(e)))
                .collect();
            check::mass_rows(cx, system, &zero_rows);
            if let Some(inputs) = &model.inputs {
                let moves: Vec<bool> = (inputs.symbols.iter())
                    .map(|&u| inputs.forces.iter().any(|&f| model.ctx.depends_on(f, u)))
                    .collect();
                check::inputs_move(cx, system, &moves);
            }
            (!cx.has_errors()).then_some(model)
        }
        Err(
            e @ (mechanics::DeriveError::ArticulatedNeedsTree(_)
            | mechanics::DeriveError::JacobiansNeedTree(_)),
        ) => {
            let wanted = match e {
                mechanics::DeriveError::ArticulatedNeedsTree(_) => ast::Extra::Articulated,
                _ => ast::Extra::Jacobians,
            };
            let at = system.extras.iter().find(|(_, e)| *e == wanted);
            cx.error_at(at.map_or(system.span, |(name, _)| name.span()), e);
            None
        }
        Err(e) => {
            let span = system.speeds.first().map_or(system.span, |u| u.name.span());
            cx.error_at(span, e);
            None
        }
    }
}
