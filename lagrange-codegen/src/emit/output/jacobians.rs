//! The right-hand side's Jacobians (`emit(jacobians)`):
//! `Lagrangian::rhs_jacobians`, at the current q̈ `a`, a large program in
//! pieces.

use lagrange_symbolic::Expr as Sym;
use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

/// Above this many operations the Jacobians run in pieces. Pieces of 4,000
/// (as M's) built the Panda's 10,633 in 3.7 s of CPU instead of 8.0 s, but
/// ran the floating bases' 10–20 % slower (values crossing between pieces go
/// through memory).
pub(super) const JACOBIAN_CHUNK_OPS: usize = 6000;

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
    // Both Jacobians are one program (they share the forward pass), run in
    // pieces when it is large: the Panda's 10,633 operations in one function
    // cost LLVM twice as much per operation as in pieces.
    let params = quote!(q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s);
    let (lets, outs, pieces) = e.program_in_pieces(
        &all,
        ("__lagrange_rhs_jacobians", JACOBIAN_CHUNK_OPS),
        (&params, &quote!(q, v, a, t)),
    );
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
        // Beside M's pieces, in the impl that allows generated code's lints.
        hoisted: pieces,
        ..Pieces::default()
    }
}
