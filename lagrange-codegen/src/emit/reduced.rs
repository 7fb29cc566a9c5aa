//! `impl Reduced`: the reduced form's speeds and stacked rows.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::mechanics::Model;

/// `impl Reduced`: the speeds, the stacked rows A = [U; G] with b, and their
/// rates c; the runtime solves them (W, κ, M*, F*) with pivoting. With free
/// orientations q has Q entries (`Reduced<T, N, K, Q>`) and the rows are read
/// in v, as the multiplier form's are.
pub(super) fn impl_reduced(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(r) = &model.constraints.reduced else {
        return quote!();
    };
    let n = model.dof();
    let kl = Literal::usize_unsuffixed(r.names.len());
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let vec_k = f.vec(&kl);
    let mat_nn = f.mat(nl, nl);
    let qvec = f.qvec();
    let sizes = f.sizes_after(&kl);

    let (u_lets, u_outs) = e.program(&r.speeds);
    let mut rows: Vec<Sym> = r.matrix.iter().flatten().copied().collect();
    rows.extend(&r.free);
    let (row_lets, row_outs) = e.program(&rows);
    let (a_outs, b_outs) = row_outs.split_at(n * n);
    let a_fill = e.fill_dense(&quote!(a), a_outs, n);
    let (rate_lets, rate_outs) = e.program(&r.rates);
    let derivatives = match &r.derivatives {
        None => quote!(),
        Some(d) => {
            let body = e.dense_matrices(&[
                ("danu", &d.force_q, mat_nn.clone()),
                ("dres", &d.acceleration_q, mat_nn.clone()),
                ("drate", &d.gamma_v, mat_nn.clone()),
                ("dvel", &d.velocity_q, mat_nn.clone()),
            ]);
            quote! {
                #[inline]
                fn row_derivatives(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, nu: &#vec_n, t: #s) -> ::core::option::Option<(#mat_nn, #mat_nn, #mat_nn, #mat_nn)> {
                    #body
                    ::core::option::Option::Some((danu, dres, drate, dvel))
                }
            }
        }
    };
    let positions = holonomic_positions(e, f, &r.positions);
    let names = &r.names;
    let row_names = &r.rows;
    let free = r.free_speeds;
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Reduced<#s, #sizes> for #ident #tg #wc {
            const SPEEDS: [&'static str; #kl] = [#(#names),*];
            const ROWS: [&'static str; #nl] = [#(#row_names),*];
            const FREE_SPEEDS: bool = #free;

            #[inline]
            fn velocity_rows(&self, q: &#qvec, t: #s) -> (#mat_nn, #vec_n) {
                #row_lets
                let mut a = <#mat_nn>::zeros();
                #a_fill
                (a, <#vec_n>::from([#(#b_outs),*]))
            }

            #[inline]
            fn row_rates(&self, q: &#qvec, v: &#vec_n, t: #s) -> #vec_n {
                #rate_lets
                <#vec_n>::from([#(#rate_outs),*])
            }

            #[inline]
            fn speeds(&self, q: &#qvec, v: &#vec_n, t: #s) -> #vec_k {
                #u_lets
                <#vec_k>::from([#(#u_outs),*])
            }

            #derivatives
            #positions
        }
    }
}

/// `Reduced::HOLONOMIC` and `holonomic_positions`: Φ(q, t) of the holonomic
/// constraints (nothing for a description without them: the defaults say none).
fn holonomic_positions(e: &Emitter, f: &Frame, positions: &[Sym]) -> TokenStream {
    if positions.is_empty() {
        return quote!();
    }
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let qvec = f.qvec();
    let h = Literal::usize_unsuffixed(positions.len());
    let (lets, outs) = e.program(positions);
    let index = (0..positions.len()).map(Literal::usize_unsuffixed);
    quote! {
        const HOLONOMIC: usize = #h;

        #[inline]
        fn holonomic_positions(&self, q: &#qvec, t: #s) -> #vec_n {
            #lets
            let mut phi = <#vec_n>::zeros();
            #(phi[#index] = #outs;)*
            phi
        }
    }
}
