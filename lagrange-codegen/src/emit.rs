//! [`Model`] → the `impl Lagrangian` tokens.
//!
//! Every method is one straight-line program: the outputs it returns are built
//! together so that shared subexpressions (sin/cos of coordinates, Jacobian entries,
//! partial sums of masses) are computed once. Generated code uses absolute paths
//! through `::lagrange::__private`, allocates nothing and is deterministic.

use lagrange_symbolic::{EmitConfig, Expr as Sym, Program, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use crate::ast::{Scalar, System};
use crate::doc;
use crate::mechanics::Model;

/// The scalar type as tokens, e.g. `f64` or `T`.
pub fn scalar_tokens(scalar: &Scalar) -> TokenStream {
    match scalar {
        Scalar::F64 => quote!(f64),
        Scalar::F32 => quote!(f32),
        Scalar::Generic(t) => quote!(#t),
    }
}

/// A numeric literal in the target scalar.
fn constant(scalar: &Scalar, v: f64) -> TokenStream {
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

struct Emitter<'a> {
    model: &'a Model,
    scalar: &'a Scalar,
}

impl Emitter<'_> {
    /// `let` statements and output expressions for a set of outputs.
    fn program(&self, outputs: &[Sym]) -> (TokenStream, Vec<TokenStream>) {
        let ctx = &self.model.ctx;
        let program = Program::new(ctx, outputs);
        let params = &self.model.parameters;
        let symbol = |s| match ctx.symbol_kind(s) {
            SymbolKind::Coordinate(i) => {
                let i = Literal::usize_unsuffixed(i);
                quote!(q[#i])
            }
            SymbolKind::Velocity(i) => {
                let i = Literal::usize_unsuffixed(i);
                quote!(v[#i])
            }
            SymbolKind::Time => quote!(t),
            SymbolKind::Parameter(i) => {
                let f = format_ident!("{}", params[i]);
                quote!(self.#f)
            }
            // Lowering never lets accelerations or free symbols into the model.
            SymbolKind::Acceleration(_) | SymbolKind::Free => {
                quote!(::core::compile_error!(
                    "internal: unexpected symbol in generated code"
                ))
            }
        };
        let scalar = self.scalar;
        let constant = |v: f64| constant(scalar, v);
        let function = quote!(::lagrange::__private::func);
        let cfg = EmitConfig {
            symbol: &symbol,
            constant: &constant,
            function: &function,
            temp_prefix: "_t",
        };
        program.emit(ctx, &cfg)
    }

    fn fill_matrix(&self, outs: &[TokenStream], n: usize) -> TokenStream {
        let mut k = 0;
        let mut sets = Vec::new();
        for i in 0..n {
            for j in i..n {
                let o = &outs[k];
                k += 1;
                let (li, lj) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(j));
                if i == j {
                    sets.push(quote!(m[(#li, #lj)] = #o;));
                } else {
                    sets.push(quote!(let _m = #o; m[(#li, #lj)] = _m; m[(#lj, #li)] = _m;));
                }
            }
        }
        quote!(#(#sets)*)
    }

    fn upper(&self) -> Vec<Sym> {
        let n = self.model.dof();
        (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| self.model.mass[i][j])
            .collect()
    }

    fn vector_body(&self, outputs: &[Sym], s: &TokenStream, n: &Literal) -> TokenStream {
        let (lets, outs) = self.program(outputs);
        quote! {
            #lets
            <::lagrange::__private::SVector::<#s, #n>>::from([#(#outs),*])
        }
    }
}

pub fn impl_lagrangian(system: &System, model: &Model) -> TokenStream {
    let e = Emitter {
        model,
        scalar: &system.scalar,
    };
    let s = scalar_tokens(&system.scalar);
    let n = model.dof();
    let nl = Literal::usize_unsuffixed(n);
    let upper = e.upper();

    let (m_lets, m_outs) = e.program(&upper);
    let m_fill = e.fill_matrix(&m_outs, n);

    let bias = e.vector_body(&model.bias, &s, &nl);
    let forces = e.vector_body(&model.forces, &s, &nl);

    let mut joint = upper.clone();
    joint.extend(&model.rhs);
    let (j_lets, j_outs) = e.program(&joint);
    let j_fill = e.fill_matrix(&j_outs[..upper.len()], n);
    let j_rhs = &j_outs[upper.len()..];

    let (k_lets, k_out) = e.program(&[model.kinetic]);
    let (p_lets, p_out) = e.program(&[model.potential]);
    let (i_lets, i_out) = e.program(&[model.integral]);
    let (k_out, p_out, i_out) = (&k_out[0], &p_out[0], &i_out[0]);

    let names = &model.coordinates;
    let rheonomic = model.rheonomic;
    let ident = &system.ident;
    let (impl_generics, ty_generics, where_clause) = system.generics.split_for_impl();
    let where_clause = real_bound(system, where_clause);
    let docs = doc::equations(model);
    let impl_doc =
        format!("Equations of motion derived by `#[derive(Lagrangian)]`.\n\n```text\n{docs}```");

    let vec_t = quote!(::lagrange::__private::SVector<#s, #nl>);
    let mat_t = quote!(::lagrange::__private::SMatrix<#s, #nl, #nl>);
    quote! {
        #[doc = #impl_doc]
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #impl_generics ::lagrange::__private::Lagrangian<#s, #nl> for #ident #ty_generics #where_clause {
            const COORDINATES: [&'static str; #nl] = [#(#names),*];
            const RHEONOMIC: bool = #rheonomic;

            #[inline]
            fn mass_matrix(&self, q: &#vec_t, t: #s) -> #mat_t {
                #m_lets
                let mut m = <#mat_t>::zeros();
                #m_fill
                m
            }

            #[inline]
            fn bias(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #vec_t {
                #bias
            }

            #[inline]
            fn generalized_forces(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #vec_t {
                #forces
            }

            #[inline]
            fn mass_matrix_and_rhs(&self, q: &#vec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) {
                #j_lets
                let mut m = <#mat_t>::zeros();
                #j_fill
                (m, <#vec_t>::from([#(#j_rhs),*]))
            }

            #[inline]
            fn kinetic_energy(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #s {
                #k_lets
                #k_out
            }

            #[inline]
            fn potential_energy(&self, q: &#vec_t, t: #s) -> #s {
                #p_lets
                #p_out
            }

            #[inline]
            fn integral(&self, q: &#vec_t, v: &#vec_t, t: #s) -> #s {
                #i_lets
                #i_out
            }
        }

        #[automatically_derived]
        impl #impl_generics #ident #ty_generics #where_clause {
            /// The derived equations of motion as text: M, h, Q and the energies.
            pub const EQUATIONS: &'static str = #docs;
        }
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
    }
}
