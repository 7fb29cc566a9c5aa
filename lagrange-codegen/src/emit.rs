//! [`Model`] → the `impl Lagrangian` tokens.
//!
//! Every method is one straight-line program: the outputs it returns are built
//! together so that shared subexpressions (sin/cos of coordinates, Jacobian entries,
//! partial sums of masses) are computed once. Generated code uses absolute paths
//! through `::lagrange::__private`, allocates nothing and is deterministic.

use lagrange_symbolic::{EmitConfig, Expr as Sym, Program, Symbol, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use crate::ast::{Extra, Formulation, Scalar, System};
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

/// Above this many operations M and Q − h are emitted as several functions
/// passing values through an array: LLVM's time grows faster than linearly
/// with one function's size (the spatial 30-link arm built in 16.8 s of CPU in
/// one piece, 14.4 s in pieces), and the pieces also run faster where one
/// function outgrew the instruction cache (the planar 30-link chain 1.59 →
/// 1.13 µs; the spatial 30-link arm 4 % slower). Smaller pieces (1,000) built
/// little faster and ran 12 % slower on the arm.
const CHUNK_OPS: usize = 4000;

struct Emitter<'a> {
    model: &'a Model,
    scalar: &'a Scalar,
    /// The free symbols that reach emission and what they are in the generated
    /// method: the weights the linearisation methods hold fixed, `nu[k]` (the
    /// multipliers' and the reduced rows' symbols are distinct).
    free: Vec<(Symbol, TokenStream)>,
}

impl<'a> Emitter<'a> {
    fn new(model: &'a Model, scalar: &'a Scalar) -> Self {
        let mut free = Vec::new();
        let mut add = |symbols: &[Sym], array: &str| {
            let array = format_ident!("{array}");
            for (i, &e) in symbols.iter().enumerate() {
                if let Some(s) = model.ctx.as_symbol(e) {
                    let i = Literal::usize_unsuffixed(i);
                    free.push((s, quote!(#array[#i])));
                }
            }
        };
        if let Some(d) = model.reduced.as_ref().and_then(|r| r.derivatives.as_ref()) {
            add(&d.nu_symbols, "nu");
        }
        if let Some(a) = &model.articulated {
            add(&a.extra, "tau");
        }
        add(&model.hoisted.symbols, "p");
        if let Some(d) = model
            .constraints
            .as_ref()
            .and_then(|c| c.derivatives.as_ref())
        {
            add(&d.nu_symbols, "nu");
        }
        Emitter {
            model,
            scalar,
            free,
        }
    }

    /// `let` statements and output expressions for a set of outputs.
    fn program(&self, outputs: &[Sym]) -> (TokenStream, Vec<TokenStream>) {
        self.with_config(outputs, |program, ctx, cfg| program.emit(ctx, cfg))
    }

    /// The program for `outputs` in pieces of at most [`CHUNK_OPS`] operations
    /// sharing the array `s`, or `None` when it is small enough for one function.
    fn program_chunked(&self, outputs: &[Sym]) -> Option<lagrange_symbolic::Chunked> {
        self.with_config(outputs, |program, ctx, cfg| {
            program.emit_chunked(ctx, cfg, CHUNK_OPS, &quote!(s))
        })
    }

    fn with_config<R>(
        &self,
        outputs: &[Sym],
        f: impl FnOnce(&Program, &lagrange_symbolic::Context, &EmitConfig) -> R,
    ) -> R {
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
            // Inputs reach only the `Driven` methods, which take them as `u`.
            SymbolKind::Input(i) => {
                let i = Literal::usize_unsuffixed(i);
                quote!(u[#i])
            }
            SymbolKind::Free => match self.free.iter().find(|(f, _)| *f == s) {
                Some((_, tokens)) => tokens.clone(),
                None => quote!(::core::compile_error!(
                    "internal: unexpected symbol in generated code"
                )),
            },
            // Accelerations appear only in the Jacobians, which take the
            // current q̈ as `a`.
            SymbolKind::Acceleration(i) => {
                let i = Literal::usize_unsuffixed(i);
                quote!(a[#i])
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
        f(&program, ctx, &cfg)
    }

    /// `let mut <name> = zeros; <name>[(i, j)] = ...;` for a dense matrix whose
    /// entries are `outs` in row-major order.
    /// Whether an output is the literal zero: the matrices start as zeros, so
    /// those entries are not written again.
    fn is_zero(&self, o: &TokenStream) -> bool {
        o.to_string() == constant(self.scalar, 0.0).to_string()
    }

    fn fill_dense(&self, name: &TokenStream, outs: &[TokenStream], cols: usize) -> TokenStream {
        let sets = outs
            .iter()
            .enumerate()
            .filter(|(_, o)| !self.is_zero(o))
            .map(|(k, o)| {
                let (i, j) = (
                    Literal::usize_unsuffixed(k / cols),
                    Literal::usize_unsuffixed(k % cols),
                );
                quote!(#name[(#i, #j)] = #o;)
            });
        quote!(#(#sets)*)
    }

    /// The symmetric N×N matrix from its upper triangle, row by row, as one
    /// array literal (columns; M is symmetric): no indexing, so no bounds
    /// checks, whose thousands of branches slowed the optimiser on large models.
    fn symmetric_matrix(&self, outs: &[TokenStream], n: usize) -> TokenStream {
        let zero = constant(self.scalar, 0.0);
        let at = |i: usize, j: usize| {
            let (r, c) = if i <= j { (i, j) } else { (j, i) };
            // Index of (r, c) in the row-major upper triangle.
            let k = r * n - r * (r + 1) / 2 + c;
            let o = &outs[k];
            if self.is_zero(o) {
                zero.clone()
            } else {
                o.clone()
            }
        };
        let columns = (0..n).map(|j| {
            let column = (0..n).map(|i| at(i, j));
            quote!([#(#column),*])
        });
        quote!([#(#columns),*])
    }

    fn upper(&self) -> Vec<Sym> {
        let n = self.model.dof();
        (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| self.model.mass[i][j])
            .collect()
    }

    /// One program for several dense matrices: `let mut <name> = zeros;` and
    /// the nonzero entries of each, sharing subexpressions across all of them.
    /// Each matrix is (name, rows, type); rows may be empty for a zero-row matrix.
    fn dense_matrices(&self, mats: &[(&str, &[Vec<Sym>], TokenStream)]) -> TokenStream {
        let all: Vec<Sym> = mats
            .iter()
            .flat_map(|(_, rows, _)| rows.iter().flatten().copied())
            .collect();
        let (lets, outs) = self.program(&all);
        let mut rest = &outs[..];
        let mut fills = TokenStream::new();
        for (name, rows, ty) in mats {
            let cols = rows.first().map_or(0, Vec::len);
            let (mine, tail) = rest.split_at(rows.len() * cols);
            rest = tail;
            let name = format_ident!("{name}");
            let fill = self.fill_dense(&quote!(#name), mine, cols.max(1));
            fills.extend(quote! {
                let mut #name = <#ty>::zeros();
                #fill
            });
        }
        quote!(#lets #fills)
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
    let e = Emitter::new(model, &system.scalar);
    let s = scalar_tokens(&system.scalar);
    let n = model.dof();
    let nl = Literal::usize_unsuffixed(n);
    let upper = e.upper();

    let (m_lets, m_outs) = e.program(&upper);
    let m_fill = e.symmetric_matrix(&m_outs, n);

    let bias = e.vector_body(&model.bias, &s, &nl);
    let forces = e.vector_body(&model.forces, &s, &nl);

    // M and Q − h over the hoisted parameter terms `p`.
    let hoisted = &model.hoisted;
    let joint = model.hoisted_upper_and_rhs();
    let upper_len = joint.len() - n;
    // A large program runs as pieces, each its own function, passing values
    // through the array `s`.
    let (j_lets, j_outs, j_pieces) = match e.program_chunked(&joint) {
        None => {
            let (lets, outs) = e.program(&joint);
            (lets, outs, TokenStream::new())
        }
        Some(chunked) => {
            let slots = Literal::usize_unsuffixed(chunked.slots);
            let zero = constant(&system.scalar, 0.0);
            let names: Vec<syn::Ident> = (0..chunked.chunks.len())
                .map(|k| format_ident!("__lagrange_mass_matrix_and_rhs_{k}"))
                .collect();
            let bodies = &chunked.chunks;
            let h_len = Literal::usize_unsuffixed(hoisted.terms.len());
            let vec_t = quote!(::lagrange::__private::SVector<#s, #nl>);
            let lets = quote! {
                let mut s = [#zero; #slots];
                #(self.#names(p, q, v, t, &mut s);)*
            };
            let pieces = quote! {
                #(
                    #[doc(hidden)]
                    #[inline(never)]
                    pub fn #names(&self, p: &[#s; #h_len], q: &#vec_t, v: &#vec_t, t: #s, s: &mut [#s; #slots]) {
                        #bodies
                    }
                )*
            };
            (lets, chunked.outputs, pieces)
        }
    };
    let j_fill = e.symmetric_matrix(&j_outs[..upper_len], n);
    let j_rhs = &j_outs[upper_len..];

    let (k_lets, k_out) = e.program(&[model.kinetic]);
    let (p_lets, p_out) = e.program(&[model.potential]);
    let (i_lets, i_out) = e.program(&[model.integral]);
    let (k_out, p_out, i_out) = (&k_out[0], &p_out[0], &i_out[0]);

    let names = &model.coordinates;
    let rheonomic = model.rheonomic;
    let has_constraints = !(system.holonomic.is_empty() && system.nonholonomic.is_empty());
    let ident = &system.ident;
    let (impl_generics, ty_generics, where_clause) = system.generics.split_for_impl();
    let where_clause = real_bound(system, where_clause);
    // The text is emitted once, in a macro both the rustdoc and `EQUATIONS`
    // expand (a summary replaces it in the rustdoc beyond the cap).
    let doc::Texts {
        equations: docs,
        latex,
    } = doc::texts(model);
    let docs_macro = format_ident!("__lagrange_equations_{}", system.ident);
    let impl_doc = match doc::rustdoc(&docs, &system.ident.to_string()) {
        Some(summary) => quote!(#[doc = #summary]),
        None => quote! {
            #[doc = "Equations of motion derived by `#[derive(Lagrangian)]`.\n\n```text"]
            #[doc = #docs_macro!()]
            #[doc = "```"]
        },
    };

    let vec_t = quote!(::lagrange::__private::SVector<#s, #nl>);
    let mat_t = quote!(::lagrange::__private::SMatrix<#s, #nl, #nl>);
    let frame = Frame::new(system, n);
    let hamiltonian = optional_methods(&e, &frame, model);
    let run_in = run_in(&frame, model);
    let (forward_dynamics, articulated_inner) = forward_dynamics(&e, &frame, model);
    let h_len = Literal::usize_unsuffixed(hoisted.terms.len());
    let (t_lets, t_outs) = e.program(&hoisted.terms);
    let constrained = impl_constrained(&e, &frame, model);
    let extras = extras(&e, &frame, model, system);
    let reduced = impl_reduced(&e, &frame, model);
    let driven = impl_driven(&e, &frame, model);
    quote! {
        macro_rules! #docs_macro {
            () => {
                #docs
            };
        }

        /// The system as `#[derive(Lagrangian)]` derived it; the equations are
        /// on the type's inherent impl (`EQUATIONS`).
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #impl_generics ::lagrange::__private::Lagrangian<#s, #nl> for #ident #ty_generics #where_clause {
            const COORDINATES: [&'static str; #nl] = [#(#names),*];
            const RHEONOMIC: bool = #rheonomic;
            const CONSTRAINED: bool = #has_constraints;

            #[inline]
            fn mass_matrix(&self, q: &#vec_t, t: #s) -> #mat_t {
                #m_lets
                <#mat_t>::from(#m_fill)
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
                self.__lagrange_mass_matrix_and_rhs(&self.__lagrange_parameter_terms(), q, v, t)
            }

            fn parameter_terms(&self) -> ::std::vec::Vec<#s> {
                self.__lagrange_parameter_terms().to_vec()
            }

            #[inline]
            fn mass_matrix_and_rhs_with(&self, terms: &[#s], q: &#vec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) {
                match <&[#s; #h_len]>::try_from(terms) {
                    ::core::result::Result::Ok(p) => self.__lagrange_mass_matrix_and_rhs(p, q, v, t),
                    ::core::result::Result::Err(_) => self.mass_matrix_and_rhs(q, v, t),
                }
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

            #hamiltonian
            #forward_dynamics
            #run_in
        }

        #impl_doc
        #[automatically_derived]
        impl #impl_generics #ident #ty_generics #where_clause {
            /// The derived equations of motion as text: M, h, Q, the energies
            /// and the constraint rows, as one listing with shared
            /// intermediates named.
            pub const EQUATIONS: &'static str = #docs_macro!();
            /// The same equations as LaTeX: the lines of an `aligned` block
            /// (`M_{0 1} &= …`, `h_{0}`, `Q_{0}`, `T`, `V`, and `\Phi`, `G`, `g`,
            /// `\gamma`, `A`, `b`, `c` per constraint or speed row), ready for
            /// `$$ … $$` in a document or a notebook.
            pub const EQUATIONS_LATEX: &'static str = #latex;
            #extras
        }

        /// The parameter-only terms and the programs over them.
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #impl_generics #ident #ty_generics #where_clause {
            #[doc(hidden)]
            #[inline(never)]
            pub fn __lagrange_parameter_terms(&self) -> [#s; #h_len] {
                #t_lets
                [#(#t_outs),*]
            }

            // Not `#[inline]`: two trait methods call it, and one copy of a
            // large straight-line program is what keeps model crates quick to
            // build (the call costs nothing beside the body).
            #[doc(hidden)]
            pub fn __lagrange_mass_matrix_and_rhs(&self, p: &[#s; #h_len], q: &#vec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) {
                #j_lets
                (<#mat_t>::from(#j_fill), <#vec_t>::from([#(#j_rhs),*]))
            }

            #j_pieces

            #articulated_inner
        }

        #constrained
        #reduced
        #driven
    }
}

/// The pieces every impl block needs: scalar, sizes, generics.
struct Frame<'a> {
    s: TokenStream,
    n: Literal,
    ident: &'a syn::Ident,
    impl_generics: syn::ImplGenerics<'a>,
    ty_generics: syn::TypeGenerics<'a>,
    where_clause: TokenStream,
}

impl<'a> Frame<'a> {
    fn new(system: &'a System, n: usize) -> Self {
        let (impl_generics, ty_generics, where_clause) = system.generics.split_for_impl();
        Frame {
            s: scalar_tokens(&system.scalar),
            n: Literal::usize_unsuffixed(n),
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

    fn mat(&self, r: &Literal, c: &Literal) -> TokenStream {
        let s = &self.s;
        quote!(::lagrange::__private::SMatrix<#s, #r, #c>)
    }
}

/// The optional `Lagrangian` methods: momentum and ∂T/∂q (Hamilton's form) and
/// the right-hand-side Jacobians, when the model has them.
fn optional_methods(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let (s, nl) = (&f.s, &f.n);
    let n = model.dof();
    let (vec_n, mat) = (f.vec(nl), f.mat(nl, nl));
    let mut out = TokenStream::new();
    if let Some(p) = &model.momentum {
        let (lets, outs) = e.program(p);
        out.extend(quote! {
            #[inline]
            fn momentum(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #vec_n {
                #lets
                <#vec_n>::from([#(#outs),*])
            }
        });
    }
    if let Some(g) = &model.kinetic_gradient {
        let (lets, outs) = e.program(g);
        out.extend(quote! {
            #[inline]
            fn kinetic_gradient(&self, q: &#vec_n, v: &#vec_n, t: #s) -> ::core::option::Option<#vec_n> {
                #lets
                ::core::option::Option::Some(<#vec_n>::from([#(#outs),*]))
            }
        });
    }
    if let Some([jq, jv]) = &model.jacobians {
        let mut all: Vec<Sym> = jq.iter().flatten().copied().collect();
        all.extend(jv.iter().flatten());
        let (lets, outs) = e.program(&all);
        let fq = e.fill_dense(&quote!(jq), &outs[..n * n], n);
        let fv = e.fill_dense(&quote!(jv), &outs[n * n..], n);
        out.extend(quote! {
            #[inline]
            fn rhs_jacobians(&self, q: &#vec_n, v: &#vec_n, a: &#vec_n, t: #s) -> ::core::option::Option<(#mat, #mat)> {
                #lets
                let mut jq = <#mat>::zeros();
                #fq
                let mut jv = <#mat>::zeros();
                #fv
                ::core::option::Option::Some((jq, jv))
            }
        });
    }
    out
}

/// `impl Constrained`: Φ, (G, g), γ and all of them with M and Q − h in one pass.
fn impl_constrained(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(c) = &model.constraints else {
        return quote!();
    };
    let n = model.dof();
    let k = c.names.len();
    let kl = Literal::usize_unsuffixed(k);
    let (s, nl) = (&f.s, &f.n);
    let (vec_n, vec_k) = (f.vec(nl), f.vec(&kl));
    let (mat_nn, mat_kn) = (f.mat(nl, nl), f.mat(&kl, nl));
    let g_flat: Vec<Sym> = c.jacobian.iter().flatten().copied().collect();

    let (phi_lets, phi_outs) = e.program(&c.phi);
    let mut jac = g_flat.clone();
    jac.extend(&c.velocity_term);
    let (jac_lets, jac_outs) = e.program(&jac);
    let g_fill = e.fill_dense(&quote!(g), &jac_outs[..n * k], n);
    let g0 = &jac_outs[n * k..];
    let (gamma_lets, gamma_outs) = e.program(&c.gamma);

    // M, Q − h, G and γ over the hoisted parameter terms `p`.
    let mut all = model.hoisted_upper_and_rhs();
    let upper_len = all.len() - n;
    all.extend(model.hoisted_constraints().unwrap_or_default());
    let (all_lets, all_outs) = e.program(&all);
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let (mu, rest) = all_outs.split_at(upper_len);
    let (rhs, rest) = rest.split_at(n);
    let (gs, gamma) = rest.split_at(n * k);
    let m_fill = e.symmetric_matrix(mu, n);
    let g_fill_all = e.fill_dense(&quote!(g), gs, n);

    let derivatives = match &c.derivatives {
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
    };
    let names = &c.names;
    let holonomic = c.holonomic;
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Constrained<#s, #nl, #kl> for #ident #tg #wc {
            const CONSTRAINTS: [&'static str; #kl] = [#(#names),*];
            const HOLONOMIC: usize = #holonomic;

            #[inline]
            fn constraint_positions(&self, q: &#vec_n, t: #s) -> #vec_k {
                #phi_lets
                <#vec_k>::from([#(#phi_outs),*])
            }

            #[inline]
            fn constraint_jacobian(&self, q: &#vec_n, t: #s) -> (#mat_kn, #vec_k) {
                #jac_lets
                let mut g = <#mat_kn>::zeros();
                #g_fill
                (g, <#vec_k>::from([#(#g0),*]))
            }

            #[inline]
            fn constraint_rhs(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #vec_k {
                #gamma_lets
                <#vec_k>::from([#(#gamma_outs),*])
            }

            #[inline]
            fn constrained_system(&self, q: &#vec_n, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) {
                self.__lagrange_constrained_system(&self.__lagrange_parameter_terms(), q, v, t)
            }

            #[inline]
            fn constrained_system_with(&self, terms: &[#s], q: &#vec_n, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) {
                match <&[#s; #h_len]>::try_from(terms) {
                    ::core::result::Result::Ok(p) => self.__lagrange_constrained_system(p, q, v, t),
                    ::core::result::Result::Err(_) => self.constrained_system(q, v, t),
                }
            }

            #derivatives
        }

        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig #ident #tg #wc {
            #[doc(hidden)]
            pub fn __lagrange_constrained_system(&self, p: &[#s; #h_len], q: &#vec_n, v: &#vec_n, t: #s) -> (#mat_nn, #vec_n, #mat_kn, #vec_k) {
                #all_lets
                let m = <#mat_nn>::from(#m_fill);
                let mut g = <#mat_kn>::zeros();
                #g_fill_all
                (m, <#vec_n>::from([#(#rhs),*]), g, <#vec_k>::from([#(#gamma),*]))
            }
        }
    }
}

/// `Lagrangian::forward_dynamics` by the articulated-body algorithm, with the
/// smallest-to-largest pivot ratio for the singularity check: the trait methods
/// and the inherent program over the hoisted parameter terms `p`.
fn forward_dynamics(e: &Emitter, f: &Frame, model: &Model) -> (TokenStream, TokenStream) {
    let Some(a) = &model.articulated else {
        return (TokenStream::new(), TokenStream::new());
    };
    let Frame { s, n, .. } = f;
    let vec_t = quote!(::lagrange::__private::SVector<#s, #n>);
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let outputs = model.hoisted_articulated().unwrap_or_default();
    let (lets, outs) = e.program(outputs);
    let (acc, pivots) = outs.split_at(a.accelerations.len());
    let methods = quote! {
        #[inline]
        fn forward_dynamics(&self, q: &#vec_t, v: &#vec_t, tau: &#vec_t, t: #s) -> ::core::option::Option<(#vec_t, #s)> {
            ::core::option::Option::Some(self.__lagrange_forward_dynamics(&self.__lagrange_parameter_terms(), q, v, tau, t))
        }

        #[inline]
        fn forward_dynamics_with(&self, terms: &[#s], q: &#vec_t, v: &#vec_t, tau: &#vec_t, t: #s) -> ::core::option::Option<(#vec_t, #s)> {
            match <&[#s; #h_len]>::try_from(terms) {
                ::core::result::Result::Ok(p) => ::core::option::Option::Some(self.__lagrange_forward_dynamics(p, q, v, tau, t)),
                ::core::result::Result::Err(_) => self.forward_dynamics(q, v, tau, t),
            }
        }
    };
    let inner = quote! {
        #[doc(hidden)]
        pub fn __lagrange_forward_dynamics(&self, p: &[#s; #h_len], q: &#vec_t, v: &#vec_t, tau: &#vec_t, t: #s) -> (#vec_t, #s) {
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

/// The override of `Lagrangian::visit_form` that makes `Simulation::run` run
/// a constrained description in its form: the multiplier form when it is
/// emitted, else the reduced form; nothing for an unconstrained one.
fn run_in(f: &Frame, model: &Model) -> TokenStream {
    let (s, nl) = (&f.s, &f.n);
    let (method, k) = match (&model.constraints, &model.reduced) {
        (Some(c), _) => (quote!(multipliers), c.names.len()),
        (None, Some(r)) => (quote!(reduced), r.names.len()),
        (None, None) => return quote!(),
    };
    let kl = Literal::usize_unsuffixed(k);
    let p = quote!(::lagrange::__private);
    quote! {
        fn visit_form<F: #p::FormVisitor<#s, #nl, Self>>(&self, form: F) -> F::Output {
            form.#method::<#kl>(self)
        }
    }
}

/// `impl Reduced`: the speeds, the stacked rows A = [U; G] with b, and their
/// rates c; the runtime solves them (W, κ, M*, F*) with pivoting.
fn impl_reduced(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(r) = &model.reduced else {
        return quote!();
    };
    let n = model.dof();
    let kl = Literal::usize_unsuffixed(r.names.len());
    let (s, nl) = (&f.s, &f.n);
    let (vec_n, vec_k, mat_nn) = (f.vec(nl), f.vec(&kl), f.mat(nl, nl));

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
                fn row_derivatives(&self, q: &#vec_n, v: &#vec_n, a: &#vec_n, nu: &#vec_n, t: #s) -> ::core::option::Option<(#mat_nn, #mat_nn, #mat_nn, #mat_nn)> {
                    #body
                    ::core::option::Option::Some((danu, dres, drate, dvel))
                }
            }
        }
    };
    let (names, row_names, free) = (&r.names, &r.rows, r.free_speeds);
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Reduced<#s, #nl, #kl> for #ident #tg #wc {
            const SPEEDS: [&'static str; #kl] = [#(#names),*];
            const ROWS: [&'static str; #nl] = [#(#row_names),*];
            const FREE_SPEEDS: bool = #free;

            #[inline]
            fn velocity_rows(&self, q: &#vec_n, t: #s) -> (#mat_nn, #vec_n) {
                #row_lets
                let mut a = <#mat_nn>::zeros();
                #a_fill
                (a, <#vec_n>::from([#(#b_outs),*]))
            }

            #[inline]
            fn row_rates(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #vec_n {
                #rate_lets
                <#vec_n>::from([#(#rate_outs),*])
            }

            #[inline]
            fn speeds(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #vec_k {
                #u_lets
                <#vec_k>::from([#(#u_outs),*])
            }

            #derivatives
        }
    }
}

/// `Driven` with no inputs, for a description without them: the runtime's
/// defaults (ΔQ = 0). Every derived system is `Driven` exactly once, so the
/// number of inputs is inferred wherever one is needed.
fn driven_by_nothing(f: &Frame) -> TokenStream {
    let (s, nl) = (&f.s, &f.n);
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    quote! {
        #[automatically_derived]
        impl #ig ::lagrange::__private::Driven<#s, #nl, 0> for #ident #tg #wc {}
    }
}

/// `impl Driven` for a description with inputs: ΔQ and its Jacobians, with the
/// inputs taken as `u`.
fn impl_driven(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(inputs) = &model.inputs else {
        return driven_by_nothing(f);
    };
    let p = inputs.names.len();
    let pl = Literal::usize_unsuffixed(p);
    let (s, nl) = (&f.s, &f.n);
    let (vec_n, vec_p) = (f.vec(nl), f.vec(&pl));
    let (mat_np, mat_nn) = (f.mat(nl, &pl), f.mat(nl, nl));
    let forces = e.vector_body(&inputs.forces, s, nl);
    let body = e.dense_matrices(&[
        ("du", &inputs.jacobian_u, mat_np.clone()),
        ("dq", &inputs.jacobian_q, mat_nn.clone()),
        ("dv", &inputs.jacobian_v, mat_nn.clone()),
    ]);
    let names = &inputs.names;
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Driven<#s, #nl, #pl> for #ident #tg #wc {
            const INPUTS: [&'static str; #pl] = [#(#names),*];

            #[inline]
            fn input_forces(&self, q: &#vec_n, v: &#vec_n, u: &#vec_p, t: #s) -> #vec_n {
                #forces
            }

            #[inline]
            fn input_jacobians(&self, q: &#vec_n, v: &#vec_n, u: &#vec_p, t: #s) -> (#mat_np, #mat_nn, #mat_nn) {
                #body
                (du, dq, dv)
            }
        }
    }
}

/// Inherent methods for the optional outputs: reactions and the Coriolis matrix.
fn extras(e: &Emitter, f: &Frame, model: &Model, system: &System) -> TokenStream {
    let mut out = TokenStream::new();
    let (s, nl) = (&f.s, &f.n);
    let vec_n = f.vec(nl);
    let wants = |x: Extra| system.extras.iter().any(|(_, e)| *e == x);
    if wants(Extra::Reactions)
        && let Some(c) = &model.constraints
    {
        let k = c.names.len();
        let kl = Literal::usize_unsuffixed(k);
        let p = c.reactions.len();
        let pl = Literal::usize_unsuffixed(p);
        let dim = c.reactions.first().map_or(3, |(_, r)| r.len());
        let dl = Literal::usize_unsuffixed(dim);
        let vec_k = f.vec(&kl);
        let vec_d = f.vec(&dl);
        let coeffs: Vec<Sym> = c
            .reactions
            .iter()
            .flat_map(|(_, r)| r.iter().flatten().copied())
            .collect();
        let (lets, outs) = e.program(&coeffs);
        let zero = constant(&system.scalar, 0.0);
        let mut it = outs.iter();
        let mut idx = 0;
        let vectors: Vec<TokenStream> = c
            .reactions
            .iter()
            .map(|(_, r)| {
                let comps: Vec<TokenStream> = r
                    .iter()
                    .map(|row| {
                        let terms: Vec<TokenStream> = row
                            .iter()
                            .enumerate()
                            .filter_map(|(j, &coef)| {
                                let o = it.next();
                                idx += 1;
                                let o = o?;
                                if model.ctx.is_zero(coef) {
                                    return None;
                                }
                                let j = Literal::usize_unsuffixed(j);
                                Some(quote!(#o * nu[#j]))
                            })
                            .collect();
                        if terms.is_empty() {
                            zero.clone()
                        } else {
                            quote!(#(#terms)+*)
                        }
                    })
                    .collect();
                quote!(<#vec_d>::from([#(#comps),*]))
            })
            .collect();
        let names: Vec<&String> = c.reactions.iter().map(|(n, _)| n).collect();
        out.extend(quote! {
            /// Points and bodies that constraints act on, in the order of [`Self::reactions`].
            pub const REACTION_POINTS: [&'static str; #pl] = [#(#names),*];

            /// Cartesian constraint reactions R = Σ_α ν_α ∂f_α/∂ξ on each of
            /// [`Self::REACTION_POINTS`], from the multipliers ν the constrained
            /// dynamics compute. Constraints written in generalized coordinates only
            /// do not act on a point and do not appear here.
            #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
            pub fn reactions(&self, q: &#vec_n, v: &#vec_n, t: #s, nu: &#vec_k) -> [#vec_d; #pl] {
                #lets
                [#(#vectors),*]
            }
        });
    }
    if let Some(cm) = &model.coriolis {
        let n = model.dof();
        let flat: Vec<Sym> = cm.iter().flatten().copied().collect();
        let (lets, outs) = e.program(&flat);
        let fill = e.fill_dense(&quote!(c), &outs, n);
        let mat = f.mat(nl, nl);
        out.extend(quote! {
            /// The Coriolis matrix C(q, q̇, t), C_ij = Σ_k Γ_ijk q̇_k, with Γ the Christoffel
            /// symbols of M: Ṁ − 2C is skew-symmetric, and C q̇ is the quadratic part of h.
            #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
            pub fn coriolis_matrix(&self, q: &#vec_n, v: &#vec_n, t: #s) -> #mat {
                #lets
                let mut c = <#mat>::zeros();
                #fill
                c
            }
        });
    }
    out
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
    let constrained = stub_constraint_impls(system);
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
        #constrained
    }
}

/// Stub impls of the constraint traits the description asks for (and of
/// `Driven` when it declares inputs), so that a `run_constrained`,
/// `run_reduced` or `input_forces` call site does not add a cascade of errors.
fn stub_constraint_impls(system: &System) -> TokenStream {
    let n = system.coordinates.len();
    let m = system.holonomic.len() + system.nonholonomic.len();
    let f = Frame::new(system, n);
    let (s, nl) = (&f.s, &f.n);
    let vec_n = f.vec(nl);
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let mut out = TokenStream::new();
    if !system.inputs.is_empty() {
        let p = system.inputs.len();
        let pl = Literal::usize_unsuffixed(p);
        let (vec_p, mat_np, mat_nn) = (f.vec(&pl), f.mat(nl, &pl), f.mat(nl, nl));
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
        let (vec_k, mat_kn, mat_nn) = (f.vec(&kl), f.mat(&kl, nl), f.mat(nl, nl));
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
