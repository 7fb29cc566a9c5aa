//! `impl Constrained`: the multiplier form's rows.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::constraint::ConstraintSet;
use crate::mechanics::Model;

/// `impl Constrained`: Φ, (G, g), γ and all of them with M and Q − h in one pass.
pub(super) fn impl_constrained(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(c) = &model.constraints.multipliers else {
        return quote!();
    };
    let n = model.dof();
    let k = c.names.len();
    let kl = Literal::usize_unsuffixed(k);
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let vec_k = f.vec(&kl);
    let qvec = f.qvec();
    let mat_nn = f.mat(nl, nl);
    let mat_kn = f.mat(&kl, nl);
    let sizes = f.sizes_after(&kl);
    let g_flat: Vec<Sym> = c.jacobian.iter().flatten().copied().collect();

    let (phi_lets, phi_outs) = e.program(&c.phi);
    let mut jac = g_flat.clone();
    jac.extend(&c.velocity_term);
    let (jac_lets, jac_outs) = e.program(&jac);
    let g_fill = e.fill_dense(&quote!(g), &jac_outs[..n * k], n);
    let g0 = &jac_outs[n * k..];
    let (gamma_lets, gamma_outs) = e.program(&c.gamma);

    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let system = constrained_system(e, f, model, &kl);
    let derivatives = derivatives(e, f, c, &kl);
    let names = &c.names;
    let holonomic = c.holonomic;
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Constrained<#s, #sizes> for #ident #tg #wc {
            const CONSTRAINTS: [&'static str; #kl] = [#(#names),*];
            const HOLONOMIC: usize = #holonomic;

            #[inline]
            fn constraint_positions(&self, q: &#qvec, t: #s) -> #vec_k {
                #phi_lets
                <#vec_k>::from([#(#phi_outs),*])
            }

            #[inline]
            fn constraint_jacobian(&self, q: &#qvec, t: #s) -> (#mat_kn, #vec_k) {
                #jac_lets
                let mut g = <#mat_kn>::zeros();
                #g_fill
                (g, <#vec_k>::from([#(#g0),*]))
            }

            #[inline]
            fn constraint_rhs(&self, q: &#qvec, v: &#vec_n, t: #s) -> #vec_k {
                #gamma_lets
                <#vec_k>::from([#(#gamma_outs),*])
            }

            #[inline]
            fn constrained_system(&self, q: &#qvec, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) {
                self.__lagrange_constrained_system(&self.__lagrange_parameter_terms(), q, v, t)
            }

            #[inline]
            fn constrained_system_with(&self, terms: &[#s], q: &#qvec, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) {
                match <&[#s; #h_len]>::try_from(terms) {
                    ::core::result::Result::Ok(p) => self.__lagrange_constrained_system(p, q, v, t),
                    ::core::result::Result::Err(_) => self.constrained_system(q, v, t),
                }
            }

            #derivatives
        }

        #system
    }
}

/// `constraint_derivatives`, when the Jacobians were asked for.
fn derivatives(e: &Emitter, f: &Frame, c: &ConstraintSet, kl: &Literal) -> TokenStream {
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let vec_k = f.vec(kl);
    let mat_nn = f.mat(nl, nl);
    let mat_kn = f.mat(kl, nl);
    match &c.derivatives {
        None => quote!(),
        Some(d) => {
            let body = e.dense_matrices(&[
                ("dgnu", &d.force_q, mat_nn.clone()),
                ("dres", &d.acceleration_q, mat_kn.clone()),
                ("dgamma", &d.gamma_v, mat_kn.clone()),
                ("dvel", &d.velocity_q, mat_kn.clone()),
            ]);
            quote! {
                #[inline]
                fn constraint_derivatives(&self, q: &#vec_n, v: &#vec_n, a: &#vec_n, nu: &#vec_k, t: #s) -> ::core::option::Option<(#mat_nn, #mat_kn, #mat_kn, #mat_kn)> {
                    #body
                    ::core::option::Option::Some((dgnu, dres, dgamma, dvel))
                }
            }
        }
    }
}

/// The inherent `__lagrange_constrained_system`: M, Q − h, G and γ in one
/// program over the hoisted parameter terms `p`.
fn constrained_system(e: &Emitter, f: &Frame, model: &Model, kl: &Literal) -> TokenStream {
    let n = model.dof();
    let k = model
        .constraints
        .multipliers
        .as_ref()
        .map_or(0, |c| c.names.len());
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let vec_k = f.vec(kl);
    let qvec = f.qvec();
    let mat_nn = f.mat(nl, nl);
    let mat_kn = f.mat(kl, nl);
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let mut all = model.hoisted_upper_and_rhs();
    let upper_len = all.len() - n;
    all.extend(model.hoisted_constraints().unwrap_or_default());
    let (all_lets, all_outs) = e.program(&all);
    let (mu, rest) = all_outs.split_at(upper_len);
    let (rhs, rest) = rest.split_at(n);
    let (gs, gamma) = rest.split_at(n * k);
    let m_fill = e.symmetric_matrix(mu, n);
    let g_fill_all = e.fill_dense(&quote!(g), gs, n);

    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig #ident #tg #wc {
            #[doc(hidden)]
            pub fn __lagrange_constrained_system(&self, p: &[#s; #h_len], q: &#qvec, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) {
                #all_lets
                let m = <#mat_nn>::from(#m_fill);
                let mut g = <#mat_kn>::zeros();
                #g_fill_all
                (m, <#vec_n>::from([#(#rhs),*]), g, <#vec_k>::from([#(#gamma),*]))
            }
        }
    }
}
