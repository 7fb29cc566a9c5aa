//! The articulated-body q̈ (`emit(articulated)`):
//! `Lagrangian::forward_dynamics`, with the smallest-to-largest pivot ratio
//! for the singularity check, over the hoisted parameter terms `p`.

use proc_macro2::Literal;
use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(a) = &model.outputs.articulated else {
        return Pieces::default();
    };
    let Frame { s, n, .. } = f;
    let vec_t = quote!(::lagrange::__private::SVector<#s, #n>);
    let qvec = f.qvec();
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let outputs = model.hoisted_articulated().unwrap_or_default();
    let (lets, outs) = e.program(outputs);
    let (acc, pivots) = outs.split_at(a.accelerations.len());
    let lagrangian = quote! {
        #[inline]
        fn forward_dynamics(&self, q: &#qvec, v: &#vec_t, tau: &#vec_t, t: #s) -> ::core::option::Option<(#vec_t, #s)> {
            ::core::option::Option::Some(self.__lagrange_forward_dynamics(&self.__lagrange_parameter_terms(), q, v, tau, t))
        }

        #[inline]
        fn forward_dynamics_with(&self, terms: &[#s], q: &#qvec, v: &#vec_t, tau: &#vec_t, t: #s) -> ::core::option::Option<(#vec_t, #s)> {
            match <&[#s; #h_len]>::try_from(terms) {
                ::core::result::Result::Ok(p) => ::core::option::Option::Some(self.__lagrange_forward_dynamics(p, q, v, tau, t)),
                ::core::result::Result::Err(_) => self.forward_dynamics(q, v, tau, t),
            }
        }
    };
    let hoisted = quote! {
        #[doc(hidden)]
        pub fn __lagrange_forward_dynamics(&self, p: &[#s; #h_len], q: &#qvec, v: &#vec_t, tau: &#vec_t, t: #s) -> (#vec_t, #s) {
            #lets
            let ratio = ::lagrange::__private::func::pivot_ratio(&[#(#pivots),*]);
            (<#vec_t>::from([#(#acc),*]), ratio)
        }
    };
    Pieces {
        lagrangian,
        hoisted,
        ..Pieces::default()
    }
}
