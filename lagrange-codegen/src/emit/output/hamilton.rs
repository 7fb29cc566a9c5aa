//! Hamilton's form (`emit(hamiltonian)`, and the momentum alone of a
//! rheonomic system): `Lagrangian::momentum` and `kinetic_gradient`.

use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(hamilton) = &model.outputs.hamilton else {
        return Pieces::default();
    };
    let s = &f.s;
    let vec_n = f.vec(&f.n);
    let qvec = f.qvec();
    let (lets, outs) = e.program(&hamilton.momentum);
    let mut lagrangian = quote! {
        #[inline]
        fn momentum(&self, q: &#qvec, v: &#vec_n, t: #s) -> #vec_n {
            #lets
            <#vec_n>::from([#(#outs),*])
        }
    };
    if let Some(g) = &hamilton.kinetic_gradient {
        let (lets, outs) = e.program(g);
        lagrangian.extend(quote! {
            #[inline]
            fn kinetic_gradient(&self, q: &#qvec, v: &#vec_n, t: #s) -> ::core::option::Option<#vec_n> {
                #lets
                ::core::option::Option::Some(<#vec_n>::from([#(#outs),*]))
            }
        });
    }
    Pieces {
        lagrangian,
        ..Pieces::default()
    }
}
