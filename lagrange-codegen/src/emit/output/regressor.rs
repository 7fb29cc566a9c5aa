//! The dynamics regressor (`emit(regressor)`): `Lagrangian::regressor`,
//! `energy_regressor`, `inertial_parameters` and `REGRESSOR_PARAMETERS`.

use proc_macro2::Literal;
use quote::quote;

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(regressor) = &model.outputs.regressor else {
        return Pieces::default();
    };
    let s = &f.s;
    let vec_n = f.vec(&f.n);
    let qvec = f.qvec();
    let p = quote!(::lagrange::__private);
    let names = &regressor.names;
    let columns = Literal::usize_unsuffixed(names.len());
    // Most of Y is structurally zero (a joint feels no body above it): only
    // the other entries are computed, and Y is built from them in one pass,
    // column-major, with no zeroing before and no indexing after.
    let mut entries = Vec::new();
    let mut at = Vec::new();
    for k in 0..names.len() {
        for row in &regressor.rows {
            let y = row[k];
            at.push((!model.ctx.is_zero(y)).then_some(entries.len()));
            if at.last().is_some_and(Option::is_some) {
                entries.push(y);
            }
        }
    }
    let (lets, outs) = e.program(&entries);
    let zero = e.constant(0.0);
    let column_major = at.iter().map(|slot| match slot {
        Some(j) => outs[*j].clone(),
        None => zero.clone(),
    });
    let (p_lets, p_outs) = e.program(&regressor.parameters);
    let (e_lets, e_outs) = e.program(&regressor.energy);
    let n = &f.n;
    let lagrangian = quote! {
        const REGRESSOR_PARAMETERS: &'static [&'static str] = &[#(#names),*];

        #[inline]
        fn regressor(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s) -> ::core::option::Option<#p::DMatrix<#s>> {
            #lets
            ::core::option::Option::Some(<#p::DMatrix<#s>>::from_vec(#n, #columns, ::std::vec![#(#column_major),*]))
        }

        #[inline]
        fn energy_regressor(&self, q: &#qvec, v: &#vec_n, t: #s) -> ::core::option::Option<#p::DVector<#s>> {
            #e_lets
            ::core::option::Option::Some(<#p::DVector<#s>>::from_column_slice(&[#(#e_outs),*]))
        }

        #[inline]
        fn inertial_parameters(&self) -> ::core::option::Option<#p::DVector<#s>> {
            #p_lets
            ::core::option::Option::Some(<#p::DVector<#s>>::from_column_slice(&[#(#p_outs),*]))
        }
    };
    Pieces {
        lagrangian,
        ..Pieces::default()
    }
}
