//! The right-hand side's Jacobians (`emit(jacobians)`):
//! `Lagrangian::rhs_jacobians`, at the current q̈ `a`.

use lagrange_symbolic::Expr as Sym;
use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(j) = &model.outputs.jacobians else {
        return Pieces::default();
    };
    let s = &f.s;
    let nl = &f.n;
    let n = model.dof();
    let vec_n = f.vec(nl);
    let mat = f.mat(nl, nl);
    let qvec = f.qvec();
    let mut all: Vec<Sym> = j.position.iter().flatten().copied().collect();
    all.extend(j.velocity.iter().flatten());
    let (lets, outs) = e.program(&all);
    let fq = e.fill_dense(&quote!(jq), &outs[..n * n], n);
    let fv = e.fill_dense(&quote!(jv), &outs[n * n..], n);
    let lagrangian = quote! {
        #[inline]
        fn rhs_jacobians(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s) -> ::core::option::Option<(#mat, #mat)> {
            #lets
            let mut jq = <#mat>::zeros();
            #fq
            let mut jv = <#mat>::zeros();
            #fv
            ::core::option::Option::Some((jq, jv))
        }
    };
    Pieces {
        lagrangian,
        ..Pieces::default()
    }
}
