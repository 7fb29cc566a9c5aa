//! Rust tokens for a [`Program`]: one `let` per operation, symbols and
//! constants inlined where they are used.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use crate::context::Context;
use crate::node::Symbol;
use crate::program::{Op, Program, Value};

/// How [`Program::emit`] spells the pieces that depend on the generated code.
///
/// The `symbol` and `constant` closures must produce expressions that can be
/// used directly as operands of binary operators (paths, field accesses,
/// indexing, calls, literals; a leading minus on a literal is fine).
pub struct EmitConfig<'a> {
    /// How to read a symbol, e.g. `q[0]`, `self.m`, `t`.
    pub symbol: &'a dyn Fn(Symbol) -> TokenStream,
    /// How to write a numeric literal in the target scalar type.
    pub constant: &'a dyn Fn(f64) -> TokenStream,
    /// Path of a module with `sin, cos, tan, asin, acos, atan, sinh, cosh,
    /// tanh, exp, ln, sqrt, abs, atan2(y, x), powi(x, i32), powf(x, y)`.
    pub function: &'a TokenStream,
    /// Prefix of temporaries: `_t` gives `_t0`, `_t1`, ...
    pub temp_prefix: &'a str,
}

impl Program {
    /// The program as Rust: the `let` statements, and one expression per
    /// output (a temporary, or an inlined symbol or constant).
    pub fn emit(&self, _ctx: &Context, cfg: &EmitConfig) -> (TokenStream, Vec<TokenStream>) {
        let mut operand: Vec<TokenStream> = Vec::with_capacity(self.ops.len());
        let mut body = TokenStream::new();
        let mut temps = 0usize;
        for op in &self.ops {
            let o = |v: Value| &operand[v as usize];
            let f = cfg.function;
            let expr = match *op {
                Op::Sym(s) => {
                    operand.push((cfg.symbol)(s));
                    continue;
                }
                Op::Const(b) => {
                    operand.push((cfg.constant)(f64::from_bits(b)));
                    continue;
                }
                Op::Add(a, b) => binary(o(a), quote!(+), o(b)),
                Op::Sub(a, b) => binary(o(a), quote!(-), o(b)),
                Op::Mul(a, b) => binary(o(a), quote!(*), o(b)),
                Op::Div(a, b) => binary(o(a), quote!(/), o(b)),
                Op::Neg(a) => {
                    let a = o(a);
                    quote!(-#a)
                }
                Op::Call(func, a) => {
                    let name = Ident::new(func.name(), Span::call_site());
                    let a = o(a);
                    quote!(#f::#name(#a))
                }
                Op::Atan2(y, x) => {
                    let (y, x) = (o(y), o(x));
                    quote!(#f::atan2(#y, #x))
                }
                Op::Powf(a, b) => {
                    let (a, b) = (o(a), o(b));
                    quote!(#f::powf(#a, #b))
                }
                Op::Powi(a, n) => {
                    let a = o(a);
                    quote!(#f::powi(#a, #n))
                }
            };
            let name = Ident::new(&format!("{}{temps}", cfg.temp_prefix), Span::call_site());
            temps += 1;
            body.extend(quote!(let #name = #expr;));
            operand.push(quote!(#name));
        }
        let outputs = self
            .outputs
            .iter()
            .map(|&v| operand[v as usize].clone())
            .collect();
        (body, outputs)
    }
}

fn binary(a: &TokenStream, op: TokenStream, b: &TokenStream) -> TokenStream {
    quote!(#a #op #b)
}
