//! `impl Driven`: the inputs' generalized forces and their Jacobians.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::mechanics::Model;

/// `Driven` with no inputs, for a description without them: the runtime's
/// defaults (ΔQ = 0). Every derived system is `Driven` exactly once, so the
/// number of inputs is inferred wherever one is needed.
fn driven_by_nothing(f: &Frame) -> TokenStream {
    let s = &f.s;
    let sizes = f.sizes_after(&Literal::usize_unsuffixed(0));
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #[automatically_derived]
        impl #ig ::lagrange::__private::Driven<#s, #sizes> for #ident #tg #wc {}
    }
}

/// `impl Driven` for a description with inputs: ΔQ and its Jacobians, with the
/// inputs taken as `u`.
pub(super) fn impl_driven(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(inputs) = &model.inputs else {
        return driven_by_nothing(f);
    };
    let p = inputs.names.len();
    let pl = Literal::usize_unsuffixed(p);
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let vec_p = f.vec(&pl);
    let qvec = f.qvec();
    let sizes = f.sizes_after(&pl);
    let mat_np = f.mat(nl, &pl);
    let mat_nn = f.mat(nl, nl);
    let forces = e.vector_body(&inputs.forces, s, nl);
    let body = e.dense_matrices(&[
        ("du", &inputs.jacobian_u, mat_np.clone()),
        ("dq", &inputs.jacobian_q, mat_nn.clone()),
        ("dv", &inputs.jacobian_v, mat_nn.clone()),
    ]);
    let names = &inputs.names;
    let affine = inputs.affine;
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Driven<#s, #sizes> for #ident #tg #wc {
            const INPUTS: [&'static str; #pl] = [#(#names),*];
            const INPUTS_AFFINE: bool = #affine;

            #[inline]
            fn input_forces(&self, q: &#qvec, v: &#vec_n, u: &#vec_p, t: #s) -> #vec_n {
                #forces
            }

            #[inline]
            fn input_jacobians(&self, q: &#qvec, v: &#vec_n, u: &#vec_p, t: #s) -> (#mat_np, #mat_nn, #mat_nn) {
                #body
                (du, dq, dv)
            }
        }
    }
}
