//! q̈ and its derivatives as one program (`emit(jacobians)` on a system
//! without constraints): `impl Differentiable`, whose
//! `acceleration_derivatives_unchecked` also returns M's pivot ratio for the
//! singularity check. Above [`FACTORED_ABOVE_OPS`] operations the impl
//! factorises M at run time instead (`factored_derivatives`), around the
//! emitted M, Q − h and ∂(Q − h)/∂(q, q̇).

use quote::quote;

use super::Pieces;
use super::jacobians::JACOBIAN_CHUNK_OPS;
use crate::ast::{Extra, System};
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

/// The one program's size above which its solves run at run time: M = L D Lᵀ,
/// M⁻¹ = L⁻ᵀ D⁻¹ L⁻¹, q̈ and M⁻¹'s products with the right-hand side's
/// Jacobians (`factored_derivatives`), around the emitted
/// `mass_matrix_and_rhs` and `rhs_jacobians`. A straight-line program this
/// long is tens of kilobytes of code, beyond an instruction cache, and its
/// symbolic solves thousands of operations that the loops do from a few
/// hundred bytes. Measured (BENCHMARKS, "The derivatives factored at run
/// time" and "Solo 12 beside the traced C"), the factored form against the
/// one program: the Z1's (8,591 operations) 1.9× as fast, the xArm7's
/// (9,389) 1.15×, the Panda's 1.2×, Solo 12's (36,807, a branched M with
/// 114 zeros of 324) 1.2×; the Kinova's (6,311) 0.9× and the UR5's (3,671)
/// 0.7×, so these stay one program. Not beside `emit(batched)`, whose lanes
/// run the one program.
pub const FACTORED_ABOVE_OPS: usize = 8000;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, system: &System) -> Pieces {
    let Some(d) = &model.outputs.solved else {
        return Pieces::default();
    };
    // `emit(batched)` runs the one program in lanes, bit for bit the scalar
    // one: beside it the scalar form stays that program.
    let batched = system.extras.iter().any(|(_, x)| *x == Extra::Batched);
    // Counted only where it can decide: the program is lowered again below.
    let long = || {
        let ops = lagrange_symbolic::Program::new(&model.ctx, &outputs(d)).op_count();
        ops.total() > FACTORED_ABOVE_OPS
    };
    if !batched && long() {
        return factored(f);
    }
    let Frame { s, n, .. } = f;
    let dof = model.dof();
    let p = quote!(::lagrange::__private);
    let vec_n = quote!(#p::SVector<#s, #n>);
    let mat = quote!(#p::SMatrix<#s, #n, #n>);
    let qvec = f.qvec();
    let sizes = f.sizes();
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let all = outputs(d);
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
    Pieces {
        lagrangian: reached_generically(f),
        items,
        // Beside M's pieces, in the impl that allows generated code's lints.
        hoisted: chunks,
        ..Pieces::default()
    }
}

/// q̈, ∂q̈/∂q, ∂q̈/∂q̇, M⁻¹ and the pivots, in the program's order.
fn outputs(d: &crate::mechanics::SolvedDerivatives) -> Vec<lagrange_symbolic::Expr> {
    let mut all: Vec<lagrange_symbolic::Expr> = d.acceleration.clone();
    for m in [&d.position, &d.velocity, &d.inverse_mass] {
        all.extend(m.iter().flatten());
    }
    all.extend(&d.pivots);
    all
}

/// `impl Differentiable` by M's factorisation at run time, for a program
/// above [`FACTORED_ABOVE_OPS`].
fn factored(f: &Frame) -> Pieces {
    let Frame { s, n, .. } = f;
    let p = quote!(::lagrange::__private);
    let vec_n = quote!(#p::SVector<#s, #n>);
    let qvec = f.qvec();
    let sizes = f.sizes();
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let lagrangian_trait = quote!(#p::Lagrangian<#s, #sizes>);
    let items = quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #p::Differentiable<#s, #sizes> for #ident #tg #wc {
            fn acceleration_derivatives_unchecked(&self, q: &#qvec, v: &#vec_n, tau: &#vec_n, t: #s) -> (#p::AccelerationDerivatives<#s, #n>, #s) {
                let (m, rhs) = <Self as #lagrangian_trait>::mass_matrix_and_rhs(self, q, v, t);
                #p::factored_derivatives(m, rhs + tau, |a| {
                    <Self as #lagrangian_trait>::rhs_jacobians(self, q, v, a, t)
                })
            }
        }
    };
    Pieces {
        lagrangian: reached_generically(f),
        items,
        ..Pieces::default()
    }
}

/// `Lagrangian::emitted_derivatives`: the impl reached from code generic
/// over any system.
fn reached_generically(f: &Frame) -> proc_macro2::TokenStream {
    let Frame { s, n, .. } = f;
    let p = quote!(::lagrange::__private);
    let vec_n = quote!(#p::SVector<#s, #n>);
    let (qvec, sizes) = (f.qvec(), f.sizes());
    quote! {
        fn emitted_derivatives(&self, q: &#qvec, v: &#vec_n, tau: &#vec_n, t: #s) -> ::core::option::Option<(#p::AccelerationDerivatives<#s, #n>, #s)> {
            ::core::option::Option::Some(<Self as #p::Differentiable<#s, #sizes>>::acceleration_derivatives_unchecked(self, q, v, tau, t))
        }
    }
}
