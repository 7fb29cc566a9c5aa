//! [`Model`](crate::mechanics::Model) → the `impl Lagrangian` tokens.
//!
//! Every method is one straight-line program: the outputs it returns are built
//! together so that shared subexpressions (sin/cos of coordinates, Jacobian entries,
//! partial sums of masses) are computed once. Generated code uses absolute paths
//! through `::lagrange::__private`, allocates nothing and is deterministic.

mod atlas;
mod constrained;
mod contacts;
mod driven;
mod emitter;
mod lagrangian;
mod method;
mod output;
mod posed;
mod reduced;
mod stub;

pub use atlas::impl_atlas;
pub use lagrangian::impl_lagrangian;
pub use stub::stub_impl;

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use crate::ast::{Scalar, System};

/// The scalar type as tokens, e.g. `f64` or `T`.
pub fn scalar_tokens(scalar: &Scalar) -> TokenStream {
    match scalar {
        Scalar::F64 => quote!(f64),
        Scalar::F32 => quote!(f32),
        Scalar::Generic(t) => quote!(#t),
    }
}

/// A numeric literal in the target scalar.
pub(crate) fn constant(scalar: &Scalar, v: f64) -> TokenStream {
    if !v.is_finite() {
        let s = scalar_tokens(scalar);
        return quote!(::lagrange::__private::func::lit::<#s>(::core::f64::NAN));
    }
    match scalar {
        Scalar::F64 => {
            let l = Literal::f64_suffixed(v);
            quote!(#l)
        }
        Scalar::F32 => {
            let l = Literal::f32_suffixed(v as f32);
            quote!(#l)
        }
        Scalar::Generic(t) => {
            let l = Literal::f64_suffixed(v);
            quote!(::lagrange::__private::func::lit::<#t>(#l))
        }
    }
}

/// The pieces every impl block needs: scalar, sizes, generics.
struct Frame<'a> {
    s: TokenStream,
    n: Literal,
    /// The length of q: `n` plus one per free orientation.
    nq: Literal,
    ident: &'a syn::Ident,
    impl_generics: syn::ImplGenerics<'a>,
    ty_generics: syn::TypeGenerics<'a>,
    where_clause: TokenStream,
}

impl<'a> Frame<'a> {
    fn new(system: &'a System, n: usize, nq: usize) -> Self {
        let (impl_generics, ty_generics, where_clause) = system.generics.split_for_impl();
        Frame {
            s: scalar_tokens(&system.scalar),
            n: Literal::usize_unsuffixed(n),
            nq: Literal::usize_unsuffixed(nq),
            ident: &system.ident,
            impl_generics,
            ty_generics,
            where_clause: real_bound(system, where_clause),
        }
    }

    fn vec(&self, k: &Literal) -> TokenStream {
        let s = &self.s;
        quote!(::lagrange::__private::SVector<#s, #k>)
    }

    /// The type of q.
    fn qvec(&self) -> TokenStream {
        self.vec(&self.nq)
    }

    /// The trait arguments after the scalar: `N`, or `N, Q` with orientations.
    fn sizes(&self) -> TokenStream {
        let n = &self.n;
        let nq = &self.nq;
        if n.to_string() == nq.to_string() {
            quote!(#n)
        } else {
            quote!(#n, #nq)
        }
    }

    /// The trait arguments after the scalar of a trait with one more size
    /// `k` after N (`Constrained<T, N, K, Q>`): `N, K`, or `N, K, Q` with
    /// orientations.
    fn sizes_after(&self, k: &Literal) -> TokenStream {
        let n = &self.n;
        let nq = &self.nq;
        if n.to_string() == nq.to_string() {
            quote!(#n, #k)
        } else {
            quote!(#n, #k, #nq)
        }
    }

    /// The arguments after `Self` of the form visitor: none, or `Q` with
    /// orientations.
    fn configuration_after_self(&self) -> TokenStream {
        let n = &self.n;
        let nq = &self.nq;
        if n.to_string() == nq.to_string() {
            quote!()
        } else {
            quote!(, #nq)
        }
    }

    fn mat(&self, r: &Literal, c: &Literal) -> TokenStream {
        let s = &self.s;
        quote!(::lagrange::__private::SMatrix<#s, #r, #c>)
    }
}

/// The where clause with `T: Real` added for a generic scalar.
fn real_bound(system: &System, where_clause: Option<&syn::WhereClause>) -> TokenStream {
    let preds = where_clause.map(|w| {
        let p = &w.predicates;
        quote!(#p)
    });
    match &system.scalar {
        Scalar::Generic(t) => {
            let sep = preds
                .as_ref()
                .map(|p| if p.is_empty() { quote!() } else { quote!(,) });
            quote!(where #preds #sep #t: ::lagrange::__private::Real)
        }
        _ => match where_clause {
            Some(w) => quote!(#w),
            None => quote!(),
        },
    }
}
