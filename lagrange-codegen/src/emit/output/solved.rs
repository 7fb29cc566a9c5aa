//! q̈ and its derivatives as one program (`emit(jacobians)` on a system
//! without constraints): `impl Differentiable`, whose
//! `acceleration_derivatives_unchecked` also returns M's pivot ratio for the
//! singularity check.

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::constant;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, system: &System) -> Pieces {
    let Some(d) = &model.outputs.solved else {
        return Pieces::default();
    };
    let Frame { s, n, .. } = f;
    let dof = model.dof();
    let p = quote!(::lagrange::__private);
    let vec_n = quote!(#p::SVector<#s, #n>);
    let mat = quote!(#p::SMatrix<#s, #n, #n>);
    let qvec = f.qvec();
    let sizes = f.sizes();
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let mut all: Vec<lagrange_symbolic::Expr> = d.acceleration.clone();
    for m in [&d.position, &d.velocity, &d.inverse_mass] {
        all.extend(m.iter().flatten());
    }
    all.extend(&d.pivots);
    let (lets, outs, chunks) = chunked(e, f, &all, &system.scalar);
    let (acc, rest) = outs.split_at(dof);
    let (dq, rest) = rest.split_at(dof * dof);
    let (dv, rest) = rest.split_at(dof * dof);
    let (minv, pivots) = rest.split_at(dof * dof);
    let fq = e.fill_dense(&quote!(dq), dq, dof);
    let fv = e.fill_dense(&quote!(dv), dv, dof);
    let fm = e.fill_dense(&quote!(dtau), minv, dof);
    let items = quote! {
        #chunks

        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #p::Differentiable<#s, #sizes> for #ident #tg #wc {
            fn acceleration_derivatives_unchecked(&self, q: &#qvec, v: &#vec_n, tau: &#vec_n, t: #s) -> (#p::AccelerationDerivatives<#s, #n>, #s) {
                #lets
                let mut dq = <#mat>::zeros();
                #fq
                let mut dv = <#mat>::zeros();
                #fv
                let mut dtau = <#mat>::zeros();
                #fm
                let ratio = #p::func::pivot_ratio(&[#(#pivots),*]);
                let acceleration = <#vec_n>::from([#(#acc),*]);
                (#p::AccelerationDerivatives { acceleration, dq, dv, dtau }, ratio)
            }
        }
    };
    Pieces {
        items,
        ..Pieces::default()
    }
}

/// The program's statements and outputs; a large one runs as pieces, each
/// its own function (an inherent method, the third part), passing values
/// through the array `s` (see `emitter::CHUNK_OPS`).
fn chunked(
    e: &Emitter,
    f: &Frame,
    all: &[lagrange_symbolic::Expr],
    scalar: &crate::ast::Scalar,
) -> (TokenStream, Vec<TokenStream>, TokenStream) {
    let Some(chunked) = e.program_chunked(all) else {
        let (lets, outs) = e.program(all);
        return (lets, outs, TokenStream::new());
    };
    let Frame { s, n, .. } = f;
    let vec_n = quote!(::lagrange::__private::SVector<#s, #n>);
    let qvec = f.qvec();
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let slots = Literal::usize_unsuffixed(chunked.slots);
    let zero = constant(scalar, 0.0);
    let names: Vec<syn::Ident> = (0..chunked.chunks.len())
        .map(|k| format_ident!("__lagrange_acceleration_derivatives_{k}"))
        .collect();
    let bodies = &chunked.chunks;
    let lets = quote! {
        let mut s = [#zero; #slots];
        #(Self::#names(self, q, v, tau, t, &mut s);)*
    };
    let chunks = quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #ident #tg #wc {
            #(
                #[doc(hidden)]
                #[inline(never)]
                pub fn #names(&self, q: &#qvec, v: &#vec_n, tau: &#vec_n, t: #s, s: &mut [#s; #slots]) {
                    #bodies
                }
            )*
        }
    };
    (lets, chunked.outputs, chunks)
}
