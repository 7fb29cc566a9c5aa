//! The emitter: straight-line programs over the model's context, with the free
//! symbols each generated method names (`p`, `nu`, `tau`), and the fills of the
//! matrices they return.

use lagrange_symbolic::{EmitConfig, Expr as Sym, Program, Symbol, SymbolKind};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::constant;
use crate::ast::Scalar;
use crate::mechanics::Model;

/// Above this many operations M and Q − h are emitted as several functions
/// passing values through an array: LLVM's time grows faster than linearly
/// with one function's size (the spatial 30-link arm built in 16.8 s of CPU in
/// one piece, 14.4 s in pieces), and the pieces also run faster where one
/// function outgrew the instruction cache (the planar 30-link chain 1.59 →
/// 1.13 µs; the spatial 30-link arm 4 % slower). Smaller pieces (1,000) built
/// little faster and ran 12 % slower on the arm.
pub(super) const CHUNK_OPS: usize = 4000;

pub(super) struct Emitter<'a> {
    model: &'a Model,
    scalar: &'a Scalar,
    /// The free symbols that reach emission and what they are in the generated
    /// method: the weights the linearisation methods hold fixed, `nu[k]` (the
    /// multipliers' and the reduced rows' symbols are distinct); and whether
    /// each is one value for every state (the parameter terms `p`), which a
    /// batched program splats.
    free: Vec<(Symbol, TokenStream, bool)>,
    /// Whether programs are emitted over four states at once
    /// (`emit(batched)`): the scalar spelled `F64x4`, the states' symbols read
    /// as lanes, parameters and constants splatted, the functions those of
    /// `lanes::func`.
    lanes: bool,
}

impl<'a> Emitter<'a> {
    pub(super) fn new(model: &'a Model, scalar: &'a Scalar) -> Self {
        let mut free = Vec::new();
        // The quaternions follow the coordinates in q.
        let first = model.variables.coordinates.len();
        for (k, o) in model.variables.orientations.iter().enumerate() {
            for (c, &e) in o.quaternion.iter().enumerate() {
                if let Some(s) = model.ctx.as_symbol(e) {
                    let i = Literal::usize_unsuffixed(first + 4 * k + c);
                    free.push((s, quote!(q[#i]), false));
                }
            }
        }
        let mut add = |symbols: &[Sym], array: &str| {
            let shared = array == "p";
            let array = format_ident!("{array}");
            for (i, &e) in symbols.iter().enumerate() {
                if let Some(s) = model.ctx.as_symbol(e) {
                    let i = Literal::usize_unsuffixed(i);
                    free.push((s, quote!(#array[#i]), shared));
                }
            }
        };
        if let Some(d) = model
            .constraints
            .reduced
            .as_ref()
            .and_then(|r| r.derivatives.as_ref())
        {
            add(&d.nu_symbols, "nu");
        }
        if let Some(a) = &model.outputs.articulated {
            add(&a.extra, "tau");
        }
        if let Some(d) = &model.outputs.solved {
            add(&d.extra, "tau");
        }
        add(&model.hoisted.symbols, "p");
        let multipliers = model.constraints.multipliers.as_ref();
        if let Some(d) = multipliers.and_then(|c| c.derivatives.as_ref()) {
            add(&d.nu_symbols, "nu");
        }
        Emitter {
            model,
            scalar,
            free,
            lanes: false,
        }
    }

    /// The same emitter writing programs over four states at once (see
    /// [`Emitter::lanes`]); only for an `f64` system.
    pub(super) fn batched(&self) -> Emitter<'a> {
        Emitter {
            model: self.model,
            scalar: self.scalar,
            free: self.free.clone(),
            lanes: true,
        }
    }

    /// The scalar of the emitted programs: the system's, or `F64x4`.
    pub(super) fn scalar_type(&self) -> TokenStream {
        if self.lanes {
            quote!(::lagrange::__private::lanes::F64x4)
        } else {
            super::scalar_tokens(self.scalar)
        }
    }

    /// A literal in the emitted programs' scalar.
    pub(super) fn constant(&self, v: f64) -> TokenStream {
        let c = constant(self.scalar, v);
        if self.lanes {
            quote!(::lagrange::__private::lanes::func::splat(#c))
        } else {
            c
        }
    }

    /// `value`, one for every state, as the programs' scalar.
    fn shared(&self, value: TokenStream) -> TokenStream {
        if self.lanes {
            quote!(::lagrange::__private::lanes::func::splat(#value))
        } else {
            value
        }
    }

    /// `let` statements and output expressions for a set of outputs.
    pub(super) fn program(&self, outputs: &[Sym]) -> (TokenStream, Vec<TokenStream>) {
        self.with_config(outputs, |program, ctx, cfg| program.emit(ctx, cfg))
    }

    /// The program for `outputs` in pieces of at most `max_ops` operations
    /// sharing the array `s`, or `None` when it is small enough for one function.
    pub(super) fn program_chunked(
        &self,
        outputs: &[Sym],
        max_ops: usize,
    ) -> Option<lagrange_symbolic::Chunked> {
        self.with_config(outputs, |program, ctx, cfg| {
            program.emit_chunked(ctx, cfg, max_ops, &quote!(s))
        })
    }

    /// A program as `let`s and outputs, the `let`s of one of more than
    /// `max_ops` operations (see [`CHUNK_OPS`]) calls to its pieces: hidden `#[inline(never)]` methods
    /// `<name>_<k>(&self, <params>, s)`, called with `args`, passing values
    /// through the array `s`, returned last.
    pub(super) fn program_in_pieces(
        &self,
        outputs: &[Sym],
        (name, max_ops): (&str, usize),
        (params, args): (&TokenStream, &TokenStream),
    ) -> (TokenStream, Vec<TokenStream>, TokenStream) {
        let Some(chunked) = self.program_chunked(outputs, max_ops) else {
            let (lets, outs) = self.program(outputs);
            return (lets, outs, TokenStream::new());
        };
        let slots = Literal::usize_unsuffixed(chunked.slots);
        let zero = self.constant(0.0);
        let names: Vec<syn::Ident> = (0..chunked.chunks.len())
            .map(|k| format_ident!("{name}_{k}"))
            .collect();
        let bodies = &chunked.chunks;
        let s = self.scalar_type();
        let lets = quote! {
            let mut s = [#zero; #slots];
            #(self.#names(#args, &mut s);)*
        };
        let pieces = quote! {
            #(
                #[doc(hidden)]
                #[inline(never)]
                pub fn #names(&self, #params, s: &mut [#s; #slots]) {
                    #bodies
                }
            )*
        };
        (lets, chunked.outputs, pieces)
    }

    pub(super) fn with_config<R>(
        &self,
        outputs: &[Sym],
        f: impl FnOnce(&Program, &lagrange_symbolic::Context, &EmitConfig) -> R,
    ) -> R {
        let ctx = &self.model.ctx;
        let program = Program::new(ctx, outputs);
        let params = &self.model.variables.parameters;
        let symbol = |s| match ctx.symbol_kind(s) {
            SymbolKind::Coordinate(i) if !self.lanes => {
                let i = Literal::usize_unsuffixed(i);
                quote!(::lagrange::__private::func::apart(q[#i]))
            }
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
                self.shared(quote!(self.#f))
            }
            // Inputs reach only the `Driven` methods, which take them as `u`.
            SymbolKind::Input(i) => {
                let i = Literal::usize_unsuffixed(i);
                quote!(u[#i])
            }
            SymbolKind::Free => match self.free.iter().find(|(f, ..)| *f == s) {
                Some((_, tokens, true)) => self.shared(tokens.clone()),
                Some((_, tokens, false)) => tokens.clone(),
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
        let constant = |v: f64| self.constant(v);
        let function = if self.lanes {
            quote!(::lagrange::__private::lanes::func)
        } else {
            quote!(::lagrange::__private::func)
        };
        let cfg = EmitConfig {
            symbol: &symbol,
            constant: &constant,
            function: &function,
            temp_prefix: "_t",
            fused_multiply_add: true,
        };
        f(&program, ctx, &cfg)
    }

    /// `let mut <name> = zeros; <name>[(i, j)] = ...;` for a dense matrix whose
    /// entries are `outs` in row-major order.
    /// Whether an output is the literal zero: the matrices start as zeros, so
    /// those entries are not written again.
    pub(super) fn is_zero(&self, o: &TokenStream) -> bool {
        o.to_string() == self.constant(0.0).to_string()
    }

    pub(super) fn fill_dense(
        &self,
        name: &TokenStream,
        outs: &[TokenStream],
        cols: usize,
    ) -> TokenStream {
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
    pub(super) fn symmetric_matrix(&self, outs: &[TokenStream], n: usize) -> TokenStream {
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

    pub(super) fn upper(&self) -> Vec<Sym> {
        let n = self.model.dof();
        (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| self.model.motion.mass[i][j])
            .collect()
    }

    /// One program for several dense matrices: `let mut <name> = zeros;` and
    /// the nonzero entries of each, sharing subexpressions across all of them.
    /// Each matrix is (name, rows, type); rows may be empty for a zero-row matrix.
    pub(super) fn dense_matrices(&self, mats: &[(&str, &[Vec<Sym>], TokenStream)]) -> TokenStream {
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

    pub(super) fn vector_body(&self, outputs: &[Sym], s: &TokenStream, n: &Literal) -> TokenStream {
        let (lets, outs) = self.program(outputs);
        quote! {
            #lets
            <::lagrange::__private::SVector::<#s, #n>>::from([#(#outs),*])
        }
    }
}
