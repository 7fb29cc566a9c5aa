//! Rust tokens for a [`Program`]: one assignment per operation, symbols and
//! constants inlined where they are used.
//!
//! Temporaries live in a small set of reused variables (registers allocated by
//! liveness: a value's variable is free again after its last use), declared
//! once at the top. One `let` per operation would nest one lexical scope per
//! operation, and rustc walks those scopes recursively when it emits debug
//! information: the ~6,000 temporaries of a bicycle's right-hand-side Jacobians
//! overflowed its stack in a debug build. The optimiser sees the same SSA values
//! either way.

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
    /// The program as Rust: the declarations and assignments, and one expression
    /// per output (a variable, or an inlined symbol or constant).
    pub fn emit(&self, _ctx: &Context, cfg: &EmitConfig) -> (TokenStream, Vec<TokenStream>) {
        let last_use = self.last_uses();
        let mut registers = Registers::default();
        // For each value: how it is read (an inlined symbol or constant, or the
        // register holding it) and, for temporaries, the register index.
        let mut operand: Vec<TokenStream> = Vec::with_capacity(self.ops.len());
        let mut register_of: Vec<Option<usize>> = Vec::with_capacity(self.ops.len());
        let mut body = TokenStream::new();
        for (i, op) in self.ops.iter().enumerate() {
            let expr = match self.expression(op, &|v| operand[v as usize].clone(), cfg) {
                Ok(expr) => expr,
                Err(inline) => {
                    operand.push(inline);
                    register_of.push(None);
                    continue;
                }
            };
            // Operands read here for the last time give their registers back
            // before the result takes one: `_t3 = _t3 * _t5` is fine.
            for v in op.operands() {
                if last_use[v as usize] == i
                    && let Some(r) = register_of[v as usize]
                {
                    registers.release(r);
                }
            }
            let r = registers.take();
            let name = register_name(cfg, r);
            body.extend(quote!(#name = #expr;));
            operand.push(quote!(#name));
            register_of.push(Some(r));
        }
        let declarations = (0..registers.count).map(|r| {
            let name = register_name(cfg, r);
            quote!(let mut #name;)
        });
        let outputs = self
            .outputs
            .iter()
            .map(|&v| operand[v as usize].clone())
            .collect();
        (quote!(#(#declarations)* #body), outputs)
    }

    /// The program split into pieces of at most `max_ops` operations, for
    /// separate functions: LLVM's time grows faster than linearly with the
    /// size of one function, so a model of tens of thousands of operations
    /// builds several times faster in pieces. Values a later piece reads (and
    /// the outputs) pass through the array `state`, one slot each; symbols and
    /// constants are spelled inline as usual. `None` if one piece would do.
    pub fn emit_chunked(
        &self,
        _ctx: &Context,
        cfg: &EmitConfig,
        max_ops: usize,
        state: &TokenStream,
    ) -> Option<Chunked> {
        let inline = |op: &Op| matches!(op, Op::Sym(_) | Op::Const(_));
        let computed = self.ops.iter().filter(|op| !inline(op)).count();
        if computed <= max_ops {
            return None;
        }
        let mut piece = vec![0usize; self.ops.len()];
        let (mut count, mut current) = (0, 0);
        for (i, op) in self.ops.iter().enumerate() {
            if !inline(op) {
                if count == max_ops {
                    current += 1;
                    count = 0;
                }
                count += 1;
            }
            piece[i] = current;
        }
        let mut slot: Vec<Option<usize>> = vec![None; self.ops.len()];
        let mut slots = 0;
        let mut give_slot = |v: usize, slot: &mut Vec<Option<usize>>| {
            if slot[v].is_none() {
                slot[v] = Some(slots);
                slots += 1;
            }
        };
        for (i, op) in self.ops.iter().enumerate() {
            for v in op.operands() {
                let v = v as usize;
                if !inline(&self.ops[v]) && piece[v] < piece[i] {
                    give_slot(v, &mut slot);
                }
            }
        }
        for &o in &self.outputs {
            if !inline(&self.ops[o as usize]) {
                give_slot(o as usize, &mut slot);
            }
        }
        // Reads within a piece; a value read only later needs no register
        // after its slot is written.
        let mut last = vec![0usize; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            for v in op.operands() {
                if piece[v as usize] == piece[i] {
                    last[v as usize] = i;
                }
            }
        }
        let mut operand: Vec<TokenStream> = Vec::with_capacity(self.ops.len());
        let mut register_of: Vec<Option<usize>> = vec![None; self.ops.len()];
        let mut chunks = Vec::new();
        let mut body = TokenStream::new();
        let mut registers = Registers::default();
        let mut finish = |body: &mut TokenStream, registers: &mut Registers| {
            let declarations = (0..registers.count).map(|r| {
                let name = register_name(cfg, r);
                quote!(let mut #name;)
            });
            chunks.push(quote!(#(#declarations)* #body));
            *body = TokenStream::new();
            *registers = Registers::default();
        };
        for (i, op) in self.ops.iter().enumerate() {
            if i > 0 && piece[i] != piece[i - 1] {
                finish(&mut body, &mut registers);
            }
            // Operands from earlier pieces are read from their slots.
            let spell = |v: Value| -> TokenStream {
                let v = v as usize;
                match slot[v] {
                    Some(k) if piece[v] < piece[i] => quote!(#state[#k]),
                    _ => operand[v].clone(),
                }
            };
            let expr = match self.expression(op, &spell, cfg) {
                Ok(expr) => expr,
                Err(inline) => {
                    operand.push(inline);
                    continue;
                }
            };
            for v in op.operands() {
                let v = v as usize;
                if piece[v] == piece[i]
                    && last[v] == i
                    && let Some(r) = register_of[v]
                {
                    registers.release(r);
                }
            }
            let r = registers.take();
            let name = register_name(cfg, r);
            body.extend(quote!(#name = #expr;));
            if let Some(k) = slot[i] {
                body.extend(quote!(#state[#k] = #name;));
            }
            operand.push(quote!(#name));
            register_of[i] = Some(r);
        }
        finish(&mut body, &mut registers);
        let outputs = self
            .outputs
            .iter()
            .map(|&v| match slot[v as usize] {
                Some(k) => quote!(#state[#k]),
                None => operand[v as usize].clone(),
            })
            .collect();
        Some(Chunked {
            slots,
            chunks,
            outputs,
        })
    }

    /// The index of the last operation reading each value (`usize::MAX` for
    /// outputs, which are read after the program).
    fn last_uses(&self) -> Vec<usize> {
        let mut last = vec![0usize; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            for v in op.operands() {
                last[v as usize] = i;
            }
        }
        for &v in &self.outputs {
            last[v as usize] = usize::MAX;
        }
        last
    }

    /// The expression computing `op`, or `Err` with the inlined spelling of a
    /// symbol or constant (which need no temporary).
    fn expression(
        &self,
        op: &Op,
        operand: &dyn Fn(Value) -> TokenStream,
        cfg: &EmitConfig,
    ) -> Result<TokenStream, TokenStream> {
        let o = |v: Value| operand(v);
        let f = cfg.function;
        Ok(match *op {
            Op::Sym(s) => return Err((cfg.symbol)(s)),
            Op::Const(b) => return Err((cfg.constant)(f64::from_bits(b))),
            Op::Add(a, b) => binary(&o(a), quote!(+), &o(b)),
            Op::Sub(a, b) => binary(&o(a), quote!(-), &o(b)),
            Op::Mul(a, b) => binary(&o(a), quote!(*), &o(b)),
            Op::Div(a, b) => binary(&o(a), quote!(/), &o(b)),
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
            Op::Select(t, a, b) => {
                let (t, a, b) = (o(t), o(a), o(b));
                quote!(#f::select(#t, #a, #b))
            }
        })
    }
}

/// A program emitted in pieces (see [`Program::emit_chunked`]).
pub struct Chunked {
    /// Length of the state array the pieces share.
    pub slots: usize,
    /// Each piece's declarations and assignments, to run in order.
    pub chunks: Vec<TokenStream>,
    /// One expression per output, read after the last piece.
    pub outputs: Vec<TokenStream>,
}

/// Free registers, lowest first, so the output is deterministic.
#[derive(Default)]
struct Registers {
    count: usize,
    free: std::collections::BTreeSet<usize>,
}

impl Registers {
    fn take(&mut self) -> usize {
        match self.free.pop_first() {
            Some(r) => r,
            None => {
                self.count += 1;
                self.count - 1
            }
        }
    }

    fn release(&mut self, r: usize) {
        self.free.insert(r);
    }
}

fn register_name(cfg: &EmitConfig, r: usize) -> Ident {
    Ident::new(&format!("{}{r}", cfg.temp_prefix), Span::call_site())
}

fn binary(a: &TokenStream, op: TokenStream, b: &TokenStream) -> TokenStream {
    quote!(#a #op #b)
}
