//! q̈ and its derivatives over four states per call (`emit(batched)`): the
//! programs of `articulated` (else of `jacobians`' q̈) and of `solved`, with
//! `F64x4` for `f64` (see `Emitter::batched`): `impl Batched` and, with
//! `jacobians`, `impl BatchedDifferentiable`.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::Pieces;
use super::jacobians::JACOBIAN_CHUNK_OPS;
use crate::ast::{Extra, System};
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, system: &System) -> Pieces {
    if !system.extras.iter().any(|(_, x)| *x == Extra::Batched) {
        return Pieces::default();
    }
    let lanes = e.batched();
    let mut pieces = acceleration(&lanes, f, model);
    pieces.extend(derivatives(&lanes, f, model));
    pieces
}

/// The arguments every batched program takes: the states in lanes.
fn parameters(f: &Frame) -> TokenStream {
    let (n, nq) = (&f.n, &f.nq);
    let l = quote!(::lagrange::__private::lanes::F64x4);
    quote!(q: &[#l; #nq], v: &[#l; #n], tau: &[#l; #n], t: #l)
}

/// `impl Batched`: `articulated`'s q̈ program (the route it chose) over the
/// hoisted terms, or
/// the q̈ and pivots of the derivatives' program (the rest of it unread, so
/// not emitted).
fn acceleration(e: &Emitter, f: &Frame, model: &Model) -> Pieces {
    let p = quote!(::lagrange::__private);
    let l = quote!(#p::lanes::F64x4);
    let n = &f.n;
    let params = parameters(f);
    let ratio = |pivots: &[TokenStream]| quote!(#p::lanes::func::pivot_ratio(&[#(#pivots),*]));
    let (body, hoisted) = if let Some(a) = &model.outputs.articulated {
        let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
        let (lets, outs) = e.program(model.hoisted_articulated().unwrap_or_default());
        let (acc, pivots) = outs.split_at(a.accelerations.len());
        let ratio = ratio(pivots);
        let hoisted = quote! {
            #[doc(hidden)]
            pub fn __lagrange_forward_dynamics_lanes(&self, p: &[f64; #h_len], #params) -> ([#l; #n], #l) {
                #lets
                ([#(#acc),*], #ratio)
            }
        };
        let body = quote!(self.__lagrange_forward_dynamics_lanes(
            &self.__lagrange_parameter_terms(),
            q,
            v,
            tau,
            t
        ));
        (body, hoisted)
    } else if let Some(d) = &model.outputs.solved {
        let all: Vec<Sym> = d.acceleration.iter().chain(&d.pivots).copied().collect();
        let (lets, outs) = e.program(&all);
        let (acc, pivots) = outs.split_at(d.acceleration.len());
        let ratio = ratio(pivots);
        (quote!(#lets ([#(#acc),*], #ratio)), TokenStream::new())
    } else {
        return Pieces::default();
    };
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let sizes = f.sizes();
    let items = quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #p::Batched<#sizes> for #ident #tg #wc {
            fn acceleration_lanes_unchecked(&self, #params) -> ([#l; #n], #l) {
                #body
            }
        }
    };
    Pieces {
        items,
        hoisted,
        ..Pieces::default()
    }
}

/// `impl BatchedDifferentiable`: the derivatives' program, in pieces where
/// the scalar one is.
fn derivatives(e: &Emitter, f: &Frame, model: &Model) -> Pieces {
    let Some(d) = &model.outputs.solved else {
        return Pieces::default();
    };
    let p = quote!(::lagrange::__private);
    let l = quote!(#p::lanes::F64x4);
    let dof = model.dof();
    let params = parameters(f);
    let mut all: Vec<Sym> = d.acceleration.clone();
    for m in [&d.position, &d.velocity, &d.inverse_mass] {
        all.extend(m.iter().flatten());
    }
    all.extend(&d.pivots);
    let (lets, outs, chunks) = e.program_in_pieces(
        &all,
        (
            "__lagrange_acceleration_derivatives_lanes",
            JACOBIAN_CHUNK_OPS,
        ),
        (&params, &quote!(q, v, tau, t)),
    );
    let (acc, rest) = outs.split_at(dof);
    let (dq, rest) = rest.split_at(dof * dof);
    let (dv, rest) = rest.split_at(dof * dof);
    let (minv, pivots) = rest.split_at(dof * dof);
    let columns = |name: &str, entries: &[TokenStream]| columns(e, dof, name, entries);
    let (fq, fv, fm) = (columns("dq", dq), columns("dv", dv), columns("dtau", minv));
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let (n, sizes) = (&f.n, f.sizes());
    let items = quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #p::BatchedDifferentiable<#sizes> for #ident #tg #wc {
            fn acceleration_derivatives_lanes_unchecked(&self, #params) -> (#p::LaneDerivatives<#n>, #l) {
                #lets
                #fq
                #fv
                #fm
                let ratio = #p::lanes::func::pivot_ratio(&[#(#pivots),*]);
                (#p::LaneDerivatives { acceleration: [#(#acc),*], dq, dv, dtau }, ratio)
            }
        }
    };
    Pieces {
        items,
        hoisted: chunks,
        ..Pieces::default()
    }
}

/// `let mut <name> = [[0; dof]; dof];` and its nonzero entries, `entries` in
/// row-major order, stored by columns (`name[j][i]`).
fn columns(e: &Emitter, dof: usize, name: &str, entries: &[TokenStream]) -> TokenStream {
    let name = format_ident!("{name}");
    let zero = e.constant(0.0);
    let n = Literal::usize_unsuffixed(dof);
    let sets = (entries.iter().enumerate())
        .filter(|(_, o)| !e.is_zero(o))
        .map(|(k, o)| {
            let (i, j) = (k / dof, k % dof);
            let (i, j) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(j));
            quote!(#name[#j][#i] = #o;)
        });
    quote! {
        let mut #name = [[#zero; #n]; #n];
        #(#sets)*
    }
}
