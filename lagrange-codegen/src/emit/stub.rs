//! The impls emitted on error: bodies that are unreachable, so that the user sees
//! the one real error and not a cascade at every use site.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{Frame, real_bound, scalar_tokens};
use crate::ast::{Formulation, System};

/// On error, an impl whose bodies are unreachable, so that the user sees the one real
/// error and not a cascade of "trait not implemented" at every use site.
pub fn stub_impl(system: &System) -> TokenStream {
    let n = system.coordinates.len();
    if n == 0 {
        return quote!();
    }
    let s = scalar_tokens(&system.scalar);
    let nl = Literal::usize_unsuffixed(n);
    let ident = &system.ident;
    let (impl_generics, ty_generics, where_clause) = system.generics.split_for_impl();
    let where_clause = real_bound(system, where_clause);
    let names: Vec<String> = system.coordinates.iter().map(|c| c.to_string()).collect();
    let vec_t = quote!(::lagrange::__private::SVector<#s, #nl>);
    let mat_t = quote!(::lagrange::__private::SMatrix<#s, #nl, #nl>);
    let constrained = stub_constraint_impls(system);
    let p = quote!(::lagrange::__private);
    quote! {
        #[allow(unused_variables)]
        impl #impl_generics ::lagrange::__private::Lagrangian<#s, #nl> for #ident #ty_generics #where_clause {
            const COORDINATES: [&'static str; #nl] = [#(#names),*];
            const RHEONOMIC: bool = false;
            fn mass_matrix(&self, q: &#vec_t, t: #s) -> #mat_t { ::core::unreachable!() }
            fn bias(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #vec_t { ::core::unreachable!() }
            fn generalized_forces(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #vec_t { ::core::unreachable!() }
            fn mass_matrix_and_rhs(&self, q: &#vec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) { ::core::unreachable!() }
            fn kinetic_energy(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #s { ::core::unreachable!() }
            fn potential_energy(&self, q: &#vec_t, t: #s) -> #s { ::core::unreachable!() }
            fn integral(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #s { ::core::unreachable!() }
        }
        #[allow(unused_variables)]
        impl #impl_generics #p::Posed<#s, #nl> for #ident #ty_generics #where_clause {
            const BODIES: &'static [&'static str] = &[];
            const POINTS: &'static [&'static str] = &[];
            const POINT_BODIES: &'static [::core::option::Option<usize>] = &[];
            fn poses(&self, q: &#vec_t, t: #s, bodies: &mut [#p::BodyPose<#s>], points: &mut [#p::Vector3<#s>]) { ::core::unreachable!() }
            fn inertias(&self, out: &mut [#p::BodyInertia<#s>]) { ::core::unreachable!() }
            fn shapes(&self, out: &mut dyn FnMut(#p::Shape<#s>)) { ::core::unreachable!() }
        }
        #constrained
    }
}

/// Stub impls of the constraint traits the description asks for (and of
/// `Driven` when it declares inputs), so that a `run_constrained`,
/// `run_reduced` or `input_forces` call site does not add a cascade of errors.
fn stub_constraint_impls(system: &System) -> TokenStream {
    let n = system.coordinates.len();
    let m = system.holonomic.len() + system.nonholonomic.len();
    let f = Frame::new(system, n, n);
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    let mut out = TokenStream::new();
    if !system.inputs.is_empty() {
        let p = system.inputs.len();
        let pl = Literal::usize_unsuffixed(p);
        let vec_p = f.vec(&pl);
        let mat_np = f.mat(nl, &pl);
        let mat_nn = f.mat(nl, nl);
        let names: Vec<String> = system.inputs.iter().map(|u| u.to_string()).collect();
        out.extend(quote! {
            #[allow(unused_variables)]
            impl #ig ::lagrange::__private::Driven<#s, #nl, #pl> for #ident #tg #wc {
                const INPUTS: [&'static str; #pl] = [#(#names),*];
                fn input_forces(&self, q: &#vec_n, v: &#vec_n, u: &#vec_p, t: #s) -> #vec_n { ::core::unreachable!() }
                fn input_jacobians(&self, q: &#vec_n, v: &#vec_n, u: &#vec_p, t: #s) -> (#mat_np, #mat_nn, #mat_nn) { ::core::unreachable!() }
            }
        });
    }
    let chosen = crate::check::formulations(system);
    if chosen.contains(&Formulation::Multipliers) && m > 0 {
        let kl = Literal::usize_unsuffixed(m);
        let vec_k = f.vec(&kl);
        let mat_kn = f.mat(&kl, nl);
        let mat_nn = f.mat(nl, nl);
        let names: Vec<String> = system
            .holonomic
            .iter()
            .chain(&system.nonholonomic)
            .map(|c| c.name.to_string())
            .collect();
        let h = system.holonomic.len();
        out.extend(quote! {
            #[allow(unused_variables)]
            impl #ig ::lagrange::__private::Constrained<#s, #nl, #kl> for #ident #tg #wc {
                const CONSTRAINTS: [&'static str; #kl] = [#(#names),*];
                const HOLONOMIC: usize = #h;
                fn constraint_positions(&self, q: &#vec_n, t: #s) -> #vec_k { ::core::unreachable!() }
                fn constraint_jacobian(&self, q: &#vec_n, t: #s) -> (#mat_kn, #vec_k) { ::core::unreachable!() }
                fn constraint_rhs(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #vec_k { ::core::unreachable!() }
                fn constrained_system(&self, q: &#vec_n, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) { ::core::unreachable!() }
            }
        });
    }
    if chosen.contains(&Formulation::Reduced) {
        let k = if system.speeds.is_empty() {
            n.saturating_sub(m)
        } else {
            system.speeds.len()
        };
        let kl = Literal::usize_unsuffixed(k);
        let names: Vec<String> = (0..k).map(|i| format!("u{i}")).collect();
        let rows: Vec<String> = (0..n).map(|i| format!("r{i}")).collect();
        let mat_nn = f.mat(nl, nl);
        out.extend(quote! {
            #[allow(unused_variables)]
            impl #ig ::lagrange::__private::Reduced<#s, #nl, #kl> for #ident #tg #wc {
                const SPEEDS: [&'static str; #kl] = [#(#names),*];
                const ROWS: [&'static str; #nl] = [#(#rows),*];
                fn velocity_rows(&self, q: &#vec_n, t: #s) -> (#mat_nn, #vec_n) { ::core::unreachable!() }
                fn row_rates(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #vec_n { ::core::unreachable!() }
            }
        });
    }
    out
}
