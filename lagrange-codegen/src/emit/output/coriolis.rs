//! The Coriolis matrix (`emit(coriolis)`): the inherent `coriolis_matrix`.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::TokenStream;
use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(c) = &model.outputs.coriolis else {
        return Pieces::default();
    };
    Pieces {
        inherent: coriolis(e, f, model, &c.matrix),
        ..Pieces::default()
    }
}

/// `coriolis_matrix`: C(q, q̇, t).
fn coriolis(e: &Emitter, f: &Frame, model: &Model, cm: &[Vec<Sym>]) -> TokenStream {
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let vec_q = f.qvec();
    let n = model.dof();
    let flat: Vec<Sym> = cm.iter().flatten().copied().collect();
    let (lets, outs) = e.program(&flat);
    let fill = e.fill_dense(&quote!(c), &outs, n);
    let mat = f.mat(nl, nl);
    quote! {
        /// The Coriolis matrix C(q, q̇, t), C_ij = Σ_k Γ_ijk q̇_k, with Γ the Christoffel
        /// symbols of M: Ṁ − 2C is skew-symmetric, and C q̇ is the quadratic part of h.
        /// With free orientations, v holds their body-axis ω and Γ is taken in the
        /// chart that moves with each body, at its centre (Ṁ along the motion).
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        pub fn coriolis_matrix(&self, q: &#vec_q, v: &#vec_n, t: #s) -> #mat {
            #lets
            let mut c = <#mat>::zeros();
            #fill
            c
        }
    }
}
