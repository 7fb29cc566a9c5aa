//! q̈ and its derivatives as one program (`emit(jacobians)` on a system
//! without constraints): `impl Differentiable`, whose
//! `acceleration_derivatives_unchecked` also returns M's pivot ratio for the
//! singularity check.

use quote::quote;

use super::Pieces;
use super::jacobians::JACOBIAN_CHUNK_OPS;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
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
    // One program, in pieces when it is large (see `emitter::CHUNK_OPS`).
    let params = quote!(q: &#qvec, v: &#vec_n, tau: &#vec_n, t: #s);
    let (lets, outs, chunks) = e.program_in_pieces(
        &all,
        ("__lagrange_acceleration_derivatives", JACOBIAN_CHUNK_OPS),
        (&params, &quote!(q, v, tau, t)),
    );
    let (acc, rest) = outs.split_at(dof);
    let (dq, rest) = rest.split_at(dof * dof);
    let (dv, rest) = rest.split_at(dof * dof);
    let (minv, pivots) = rest.split_at(dof * dof);
    let fq = e.fill_dense(&quote!(dq), dq, dof);
    let fv = e.fill_dense(&quote!(dv), dv, dof);
    let fm = e.fill_dense(&quote!(dtau), minv, dof);
    let items = quote! {
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
    // The same program reached from code generic over any system.
    let lagrangian = quote! {
        fn emitted_derivatives(&self, q: &#qvec, v: &#vec_n, tau: &#vec_n, t: #s) -> ::core::option::Option<(#p::AccelerationDerivatives<#s, #n>, #s)> {
            ::core::option::Option::Some(<Self as #p::Differentiable<#s, #sizes>>::acceleration_derivatives_unchecked(self, q, v, tau, t))
        }
    };
    Pieces {
        lagrangian,
        items,
        // Beside M's pieces, in the impl that allows generated code's lints.
        hoisted: chunks,
        ..Pieces::default()
    }
}
