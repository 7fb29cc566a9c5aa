//! The `Lagrangian` methods a description has only sometimes, beside the
//! optional outputs (`super::output`): `check_parameters` for masses computed
//! from parameters and `visit_form` for a constrained description.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::lowered::PhysicalCheck;
use crate::mechanics::Model;

/// `Lagrangian::check_parameters` for the masses and inertias computed from
/// parameters (nothing when every one is a literal, checked at compile time).
pub(super) fn check_parameters(e: &Emitter, model: &Model) -> TokenStream {
    if model.masses.checks.is_empty() {
        return TokenStream::new();
    }
    let mut values: Vec<Sym> = Vec::new();
    for c in &model.masses.checks {
        match c {
            PhysicalCheck::Mass(_, m) => values.push(*m),
            PhysicalCheck::Principal(_, m) => values.extend(m),
            PhysicalCheck::Tensor(_, m) => values.extend(m),
            PhysicalCheck::Moments(_, _, m) => values.extend(m),
            PhysicalCheck::Joint(_, _, m) | PhysicalCheck::Gear(_, m) => values.push(*m),
        }
    }
    let (lets, outs) = e.program(&values);
    let mut outs = outs.into_iter();
    let p = quote!(::lagrange::__private);
    let calls = model.masses.checks.iter().map(|c| {
        let (rule, name, k) = match c {
            PhysicalCheck::Mass(n, _) => (quote!(mass), n, 1),
            PhysicalCheck::Principal(n, _) => (quote!(principal), n, 3),
            PhysicalCheck::Tensor(n, _) => (quote!(tensor), n, 6),
            PhysicalCheck::Moments(n, _, _) => (quote!(moments), n, 3),
            PhysicalCheck::Joint(n, _, _) => (quote!(joint), n, 1),
            PhysicalCheck::Gear(n, _) => (quote!(gear_ratio), n, 1),
        };
        let args: Vec<TokenStream> = outs.by_ref().take(k).collect();
        let arg = match c {
            PhysicalCheck::Mass(..) | PhysicalCheck::Gear(..) => quote!(#(#args)*),
            PhysicalCheck::Joint(_, what, _) => quote!(#what, #(#args)*),
            PhysicalCheck::Moments(_, names, _) => quote!([#(#names),*], [#(#args),*]),
            _ => quote!([#(#args),*]),
        };
        quote!(#p::physical::#rule(#name, #arg)?;)
    });
    quote! {
        fn check_parameters(&self) -> ::core::result::Result<(), #p::Error> {
            #lets
            #(#calls)*
            ::core::result::Result::Ok(())
        }
    }
}

/// The override of `Lagrangian::visit_form` that makes `Simulation::run` run
/// a constrained description in its form: the multiplier form when it is
/// emitted, else the reduced form; nothing for an unconstrained one.
pub(super) fn visit_form(f: &Frame, model: &Model) -> TokenStream {
    let s = &f.s;
    let nl = &f.n;
    let (method, k) = match (&model.constraints.multipliers, &model.constraints.reduced) {
        (Some(c), _) => (quote!(multipliers), c.names.len()),
        (None, Some(r)) => (quote!(reduced), r.names.len()),
        (None, None) => return quote!(),
    };
    let kl = Literal::usize_unsuffixed(k);
    let p = quote!(::lagrange::__private);
    let q = f.configuration_after_self();
    quote! {
        fn visit_form<F: #p::FormVisitor<#s, #nl, Self #q>>(&self, form: F) -> F::Output {
            form.#method::<#kl>(self)
        }
    }
}
