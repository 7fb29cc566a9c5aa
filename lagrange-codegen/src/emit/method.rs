//! The `Lagrangian` methods a description has only sometimes: Hamilton's form,
//! the right-hand-side Jacobians, the articulated-body q̈ and `visit_form` for a
//! constrained description.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::lowered::PhysicalCheck;
use crate::mechanics::Model;

/// The optional `Lagrangian` methods: momentum and ∂T/∂q (Hamilton's form) and
/// the right-hand-side Jacobians, when the model has them.
pub(super) fn optional_methods(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let (s, nl) = (&f.s, &f.n);
    let n = model.dof();
    let (vec_n, mat, qvec) = (f.vec(nl), f.mat(nl, nl), f.qvec());
    let mut out = TokenStream::new();
    let hamilton = model.outputs.hamilton.as_ref();
    if let Some(p) = hamilton.map(|h| &h.momentum) {
        let (lets, outs) = e.program(p);
        out.extend(quote! {
            #[inline]
            fn momentum(&self, q: &#qvec, v: &#vec_n, t: #s) -> #vec_n {
                #lets
                <#vec_n>::from([#(#outs),*])
            }
        });
    }
    if let Some(g) = hamilton.and_then(|h| h.kinetic_gradient.as_ref()) {
        let (lets, outs) = e.program(g);
        out.extend(quote! {
            #[inline]
            fn kinetic_gradient(&self, q: &#qvec, v: &#vec_n, t: #s) -> ::core::option::Option<#vec_n> {
                #lets
                ::core::option::Option::Some(<#vec_n>::from([#(#outs),*]))
            }
        });
    }
    if let Some(j) = &model.outputs.jacobians {
        let mut all: Vec<Sym> = j.position.iter().flatten().copied().collect();
        all.extend(j.velocity.iter().flatten());
        let (lets, outs) = e.program(&all);
        let fq = e.fill_dense(&quote!(jq), &outs[..n * n], n);
        let fv = e.fill_dense(&quote!(jv), &outs[n * n..], n);
        out.extend(quote! {
            #[inline]
            fn rhs_jacobians(&self, q: &#qvec, v: &#vec_n, a: &#vec_n, t: #s) -> ::core::option::Option<(#mat, #mat)> {
                #lets
                let mut jq = <#mat>::zeros();
                #fq
                let mut jv = <#mat>::zeros();
                #fv
                ::core::option::Option::Some((jq, jv))
            }
        });
    }
    out.extend(inverse_dynamics(e, f, model));
    out.extend(check_parameters(e, model));
    out
}

/// `Lagrangian::check_parameters` for the masses and inertias computed from
/// parameters (nothing when every one is a literal, checked at compile time).
fn check_parameters(e: &Emitter, model: &Model) -> TokenStream {
    if model.masses.checks.is_empty() {
        return TokenStream::new();
    }
    let mut values: Vec<Sym> = Vec::new();
    for c in &model.masses.checks {
        match c {
            PhysicalCheck::Mass(_, m) => values.push(*m),
            PhysicalCheck::Principal(_, m) => values.extend(m),
            PhysicalCheck::Tensor(_, m) => values.extend(m),
            PhysicalCheck::Moments(_, _, m) => values.extend(m),
        }
    }
    let (lets, outs) = e.program(&values);
    let mut outs = outs.into_iter();
    let p = quote!(::lagrange::__private);
    let calls = model.masses.checks.iter().map(|c| {
        let (rule, name, k) = match c {
            PhysicalCheck::Mass(n, _) => (quote!(mass), n, 1),
            PhysicalCheck::Principal(n, _) => (quote!(principal), n, 3),
            PhysicalCheck::Tensor(n, _) => (quote!(tensor), n, 6),
            PhysicalCheck::Moments(n, _, _) => (quote!(moments), n, 3),
        };
        let args: Vec<TokenStream> = outs.by_ref().take(k).collect();
        let arg = match c {
            PhysicalCheck::Mass(..) => quote!(#(#args)*),
            PhysicalCheck::Moments(_, names, _) => quote!([#(#names),*], [#(#args),*]),
            _ => quote!([#(#args),*]),
        };
        quote!(#p::physical::#rule(#name, #arg)?;)
    });
    quote! {
        fn check_parameters(&self) -> ::core::result::Result<(), #p::Error> {
            #lets
            #(#calls)*
            ::core::result::Result::Ok(())
        }
    }
}

/// `Lagrangian::forward_dynamics` by the articulated-body algorithm, with the
/// smallest-to-largest pivot ratio for the singularity check: the trait methods
/// and the inherent program over the hoisted parameter terms `p`.
pub(super) fn forward_dynamics(
    e: &Emitter,
    f: &Frame,
    model: &Model,
) -> (TokenStream, TokenStream) {
    let Some(a) = &model.outputs.articulated else {
        return (TokenStream::new(), TokenStream::new());
    };
    let Frame { s, n, .. } = f;
    let vec_t = quote!(::lagrange::__private::SVector<#s, #n>);
    let qvec = f.qvec();
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let outputs = model.hoisted_articulated().unwrap_or_default();
    let (lets, outs) = e.program(outputs);
    let (acc, pivots) = outs.split_at(a.accelerations.len());
    let methods = quote! {
        #[inline]
        fn forward_dynamics(&self, q: &#qvec, v: &#vec_t, tau: &#vec_t, t: #s) -> ::core::option::Option<(#vec_t, #s)> {
            ::core::option::Option::Some(self.__lagrange_forward_dynamics(&self.__lagrange_parameter_terms(), q, v, tau, t))
        }

        #[inline]
        fn forward_dynamics_with(&self, terms: &[#s], q: &#qvec, v: &#vec_t, tau: &#vec_t, t: #s) -> ::core::option::Option<(#vec_t, #s)> {
            match <&[#s; #h_len]>::try_from(terms) {
                ::core::result::Result::Ok(p) => ::core::option::Option::Some(self.__lagrange_forward_dynamics(p, q, v, tau, t)),
                ::core::result::Result::Err(_) => self.forward_dynamics(q, v, tau, t),
            }
        }
    };
    let inner = quote! {
        #[doc(hidden)]
        pub fn __lagrange_forward_dynamics(&self, p: &[#s; #h_len], q: &#qvec, v: &#vec_t, tau: &#vec_t, t: #s) -> (#vec_t, #s) {
            #lets
            let pivots: [#s; #n] = [#(#pivots),*];
            let (mut lo, mut hi) = (pivots[0], pivots[0]);
            for &d in &pivots[1..] {
                if d < lo { lo = d; }
                if d > hi { hi = d; }
            }
            (<#vec_t>::from([#(#acc),*]), lo / hi)
        }
    };
    (methods, inner)
}

/// `inverse_dynamics` and `gravity_torques`, with `emit(inverse_dynamics)`.
fn inverse_dynamics(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(inverse) = &model.outputs.inverse else {
        return TokenStream::new();
    };
    let (s, vec_n, qvec) = (&f.s, f.vec(&f.n), f.qvec());
    let (lets, outs) = e.program(&inverse.torques);
    let (g_lets, g_outs) = e.program(&inverse.gravity);
    quote! {
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
    }
}

/// The override of `Lagrangian::visit_form` that makes `Simulation::run` run
/// a constrained description in its form: the multiplier form when it is
/// emitted, else the reduced form; nothing for an unconstrained one.
pub(super) fn visit_form(f: &Frame, model: &Model) -> TokenStream {
    let (s, nl) = (&f.s, &f.n);
    let (method, k) = match (&model.constraints.multipliers, &model.constraints.reduced) {
        (Some(c), _) => (quote!(multipliers), c.names.len()),
        (None, Some(r)) => (quote!(reduced), r.names.len()),
        (None, None) => return quote!(),
    };
    let kl = Literal::usize_unsuffixed(k);
    let p = quote!(::lagrange::__private);
    let q = f.configuration_after_self();
    quote! {
        fn visit_form<F: #p::FormVisitor<#s, #nl, Self #q>>(&self, form: F) -> F::Output {
            form.#method::<#kl>(self)
        }
    }
}
