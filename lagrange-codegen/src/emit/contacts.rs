//! `impl Contacts`: the contacts' laws, and each contact's rows as one
//! program in (q, q̇, t). Emitted only for a description with contacts.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::mechanics::{ContactRowsModel, Model};

pub(super) fn impl_contacts(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    if model.contacts.is_empty() {
        return quote!();
    }
    let n = model.dof();
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let p = quote!(::lagrange::__private);
    let zero_row = quote!(<#vec_n>::zeros());
    let zero = e.constant(0.0);
    let laws = model.contacts.iter().map(|c| law(&p, c));
    let arms = model.contacts.iter().enumerate().map(|(i, c)| {
        let (lets, outs) = e.program(&c.outputs());
        let row = |k: usize| {
            let entries = &outs[k..k + n];
            quote!(<#vec_n>::from([#(#entries),*]))
        };
        let gap = &outs[0];
        let normal = row(1);
        let normal_bias = &outs[n + 1];
        let (tangents, biases) = match c.tangents.len() {
            2 => {
                let (a, b) = (row(n + 2), row(2 * n + 3));
                let (ba, bb) = (&outs[2 * n + 2], &outs[3 * n + 3]);
                (quote!([#a, #b]), quote!([#ba, #bb]))
            }
            1 => {
                let (a, ba) = (row(n + 2), &outs[2 * n + 2]);
                (quote!([#a, #zero_row]), quote!([#ba, #zero]))
            }
            _ => (quote!([#zero_row, #zero_row]), quote!([#zero, #zero])),
        };
        let il = Literal::usize_unsuffixed(i);
        quote! {
            #il => {
                #lets
                ::core::option::Option::Some(#p::ContactRows {
                    gap: #gap,
                    normal: #normal,
                    normal_bias: #normal_bias,
                    tangents: #tangents,
                    tangent_bias: #biases,
                })
            }
        }
    });
    let approach = approach_method(e, f, model);
    let ident = f.ident;
    let (sizes, vec_q) = (f.sizes(), f.qvec());
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig #p::Contacts<#s, #sizes> for #ident #tg #wc {
            fn contact_laws(&self) -> ::std::vec::Vec<#p::ContactLaw> {
                ::std::vec![#(#laws),*]
            }

            #[inline]
            fn contact_rows(&self, index: usize, q: &#vec_q, v: &#vec_n, t: #s) -> ::core::option::Option<#p::ContactRows<#s, #nl>> {
                match index {
                    #(#arms)*
                    _ => ::core::option::Option::None,
                }
            }

            #approach
        }
    }
}

/// One contact's `ContactLaw`.
fn law(p: &TokenStream, c: &ContactRowsModel) -> TokenStream {
    let (name, e, mu) = (&c.name, c.restitution, c.friction);
    match c.dry {
        true => quote!(#p::ContactLaw::dry_friction(#name, #mu)),
        false => quote!(#p::ContactLaw::unilateral(#name, #e, #mu)),
    }
}

/// `contact_approach`, for the contacts whose touch event is not their gap
/// (two spheres); nothing when every contact's is.
fn approach_method(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let arms: Vec<TokenStream> = (model.contacts.iter().enumerate())
        .filter_map(|(i, c)| {
            let (lets, outs) = e.program(&[c.approach?]);
            let value = &outs[0];
            let il = Literal::usize_unsuffixed(i);
            Some(quote!(#il => { #lets ::core::option::Option::Some(#value) }))
        })
        .collect();
    if arms.is_empty() {
        return quote!();
    }
    let (s, vec_n, vec_q) = (&f.s, f.vec(&f.n), f.qvec());
    quote! {
        #[inline]
        fn contact_approach(&self, index: usize, q: &#vec_q, v: &#vec_n, t: #s) -> ::core::option::Option<#s> {
            match index {
                #(#arms)*
                _ => ::core::option::Option::None,
            }
        }
    }
}
