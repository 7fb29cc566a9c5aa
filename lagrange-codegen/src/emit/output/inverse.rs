//! The inverse dynamics (`emit(inverse_dynamics)`):
//! `Lagrangian::inverse_dynamics` and `gravity_torques`.

use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(inverse) = &model.outputs.inverse else {
        return Pieces::default();
    };
    let s = &f.s;
    let vec_n = f.vec(&f.n);
    let qvec = f.qvec();
    let (lets, outs) = e.program(&inverse.torques);
    let (g_lets, g_outs) = e.program(&inverse.gravity);
    let lagrangian = quote! {
        #[inline]
        fn inverse_dynamics(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s) -> #vec_n {
            #lets
            <#vec_n>::from([#(#outs),*])
        }

        #[inline]
        fn gravity_torques(&self, q: &#qvec, t: #s) -> ::core::option::Option<#vec_n> {
            #g_lets
            ::core::option::Option::Some(<#vec_n>::from([#(#g_outs),*]))
        }
    };
    Pieces {
        lagrangian,
        ..Pieces::default()
    }
}
