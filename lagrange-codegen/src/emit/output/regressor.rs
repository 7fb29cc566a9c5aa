//! The dynamics regressor (`emit(regressor)`): `Lagrangian::regressor`,
//! `energy_regressor`, `momentum_regressor`, `inertial_parameters` and
//! `REGRESSOR_PARAMETERS`.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
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
    let writes = written_column_major(e, model, &regressor.rows);
    let (m_lets, y_p) = column_major(e, model, &regressor.momentum);
    let (p_lets, p_outs) = e.program(&regressor.parameters);
    let (e_lets, e_outs) = e.program(&regressor.energy);
    let n = &f.n;
    let lagrangian = quote! {
        const REGRESSOR_PARAMETERS: &'static [&'static str] = &[#(#names),*];

        #[inline]
        fn regressor(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s) -> ::core::option::Option<#p::DMatrix<#s>> {
            let mut y = <#p::DMatrix<#s>>::zeros(#n, #columns);
            self.__lagrange_regressor(q, v, a, t, &mut y.as_view_mut());
            ::core::option::Option::Some(y)
        }

        #[inline]
        fn regressor_into(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s, mut y: #p::DMatrixViewMut<'_, #s>) -> ::core::result::Result<(), ::lagrange::IdentifyError> {
            if y.nrows() != #n {
                return ::core::result::Result::Err(::lagrange::IdentifyError::Lengths { what: "rows of the matrix regressor_into writes", got: y.nrows(), expected: #n });
            }
            if y.ncols() != #columns {
                return ::core::result::Result::Err(::lagrange::IdentifyError::Lengths { what: "columns of the matrix regressor_into writes", got: y.ncols(), expected: #columns });
            }
            self.__lagrange_regressor(q, v, a, t, &mut y);
            ::core::result::Result::Ok(())
        }

        #[inline]
        fn energy_regressor(&self, q: &#qvec, v: &#vec_n, t: #s) -> ::core::option::Option<#p::DVector<#s>> {
            #e_lets
            ::core::option::Option::Some(<#p::DVector<#s>>::from_column_slice(&[#(#e_outs),*]))
        }

        #[inline]
        fn momentum_regressor(&self, q: &#qvec, v: &#vec_n, t: #s) -> ::core::option::Option<#p::DMatrix<#s>> {
            #m_lets
            ::core::option::Option::Some(<#p::DMatrix<#s>>::from_vec(#n, #columns, ::std::vec![#(#y_p),*]))
        }

        #[inline]
        fn inertial_parameters(&self) -> ::core::option::Option<#p::DVector<#s>> {
            #p_lets
            ::core::option::Option::Some(<#p::DVector<#s>>::from_column_slice(&[#(#p_outs),*]))
        }
    };
    // Y written into the caller's matrix (N × π's length, checked), once,
    // for both methods, entry by entry, column-major: no array returned
    // and copied over. The writes are indexed, and so checked: the checks
    // cut the program into a block per column, the compiler moves each
    // column's arithmetic down into its block, and far fewer of Y's values
    // are live at once. Through a view of fixed size instead (no checks,
    // each entry stored as soon as it is computed) the program stayed one
    // block of 2,300 instructions whose schedule spilled a third more: the
    // UR5's Y took 214–237 ns against 169–178 in alternated runs (the array
    // returned and copied: 252–279 against 173–186).
    let hoisted = quote! {
        #[doc(hidden)]
        #[inline]
        fn __lagrange_regressor(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s, y: &mut #p::DMatrixViewMut<'_, #s>) {
            #writes
        }
    };
    Pieces {
        lagrangian,
        hoisted,
        ..Pieces::default()
    }
}

/// The program of a matrix's entries and each entry written into `y`,
/// column-major, by an indexed write (see `__lagrange_regressor`).
fn written_column_major(e: &Emitter, model: &Model, rows: &[Vec<Sym>]) -> TokenStream {
    let (lets, y) = column_major(e, model, rows);
    let n = rows.len();
    let writes = (y.iter().enumerate()).map(|(k, value)| {
        let (i, j) = (
            Literal::usize_unsuffixed(k % n),
            Literal::usize_unsuffixed(k / n),
        );
        quote!(y[(#i, #j)] = #value;)
    });
    quote!(#lets #(#writes)*)
}

/// The program of a matrix's entries that are not structurally zero, and
/// every entry column-major, a literal zero where it is structurally zero:
/// most of Y and Y_p is zero (a joint feels no body above it), so only the
/// other entries are computed, and the matrix is filled from the list in
/// one pass (Y_p built from it, Y written entry by entry).
fn column_major(e: &Emitter, model: &Model, rows: &[Vec<Sym>]) -> (TokenStream, Vec<TokenStream>) {
    let columns = rows.first().map_or(0, Vec::len);
    let mut at = Vec::new();
    let mut entries = Vec::new();
    for k in 0..columns {
        for row in rows {
            let y = row[k];
            if model.ctx.is_zero(y) {
                at.push(None);
            } else {
                at.push(Some(entries.len()));
                entries.push(y);
            }
        }
    }
    let (lets, outs) = e.program(&entries);
    let zero = e.constant(0.0);
    let all = (at.iter())
        .map(|slot| slot.map_or_else(|| zero.clone(), |j| outs[j].clone()))
        .collect();
    (lets, all)
}
