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

mod angles;

use crate::context::Context;
use crate::node::Symbol;
use crate::program::{Op, Program, Value};
use angles::Angles;

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
    /// tanh, exp, ln, sqrt, abs, atan2(y, x), powi(x, i32), powf(x, y)`, and
    /// `sin_cos_many([x; K]) -> ([sin; K], [cos; K])`, which a piece calls
    /// once for the arguments of its sines and cosines that are known before
    /// its first one (see [`Program::emit`]).
    pub function: &'a TokenStream,
    /// Prefix of temporaries: `_t` gives `_t0`, `_t1`, ...
    pub temp_prefix: &'a str,
    /// Whether a product read once, by a sum, is spelled with that sum as
    /// `function::mul_add(x, y, c)` (x y + c): the module's `mul_add` may
    /// fuse it where the target has fused multiply–add, and is `x * y + c`
    /// otherwise, which is what the two operations compute apart.
    pub fused_multiply_add: bool,
}

impl Program {
    /// The program as Rust: the declarations and assignments, and one expression
    /// per output (a variable, or an inlined symbol or constant).
    ///
    /// Sines and cosines whose arguments are known before the first of them
    /// (the joint angles, read as symbols) are computed together, where that
    /// first one was, by one `sin_cos_many` call over at least two distinct
    /// arguments, each giving both its sine and its cosine: one SIMD kernel
    /// for all the angles instead of a library call each.
    pub fn emit(&self, _ctx: &Context, cfg: &EmitConfig) -> (TokenStream, Vec<TokenStream>) {
        let piece = vec![0; self.ops.len()];
        let slot = vec![None; self.ops.len()];
        let (mut bodies, outputs) = self.emit_pieces(cfg, &piece, &slot, &TokenStream::new());
        (bodies.pop().unwrap_or_default(), outputs)
    }

    /// The program split into pieces of at most `max_ops` operations, for
    /// separate functions: LLVM's time grows faster than linearly with the
    /// size of one function, so a model of tens of thousands of operations
    /// builds faster in pieces. Values a later piece reads (and the outputs)
    /// pass through the array `state`, one slot each; symbols and constants
    /// are spelled inline as usual. `None` if one piece would do.
    pub fn emit_chunked(
        &self,
        _ctx: &Context,
        cfg: &EmitConfig,
        max_ops: usize,
        state: &TokenStream,
    ) -> Option<Chunked> {
        let piece = self.pieces(max_ops)?;
        let (slot, slots) = self.slots(&piece);
        let (chunks, outputs) = self.emit_pieces(cfg, &piece, &slot, state);
        Some(Chunked {
            slots,
            chunks,
            outputs,
        })
    }

    /// Each operation's piece, cutting after every `max_ops` computed ones
    /// (symbols and constants cost nothing); `None` if there is one piece.
    fn pieces(&self, max_ops: usize) -> Option<Vec<usize>> {
        let mut piece = vec![0usize; self.ops.len()];
        let mut count = 0;
        let mut current = 0;
        for (i, op) in self.ops.iter().enumerate() {
            if !is_inline(op) {
                if count == max_ops {
                    current += 1;
                    count = 0;
                }
                count += 1;
            }
            piece[i] = current;
        }
        (current > 0).then_some(piece)
    }

    /// A slot in the state array for every value a later piece reads and for
    /// every computed output; the number of slots.
    fn slots(&self, piece: &[usize]) -> (Vec<Option<usize>>, usize) {
        let mut slot: Vec<Option<usize>> = vec![None; self.ops.len()];
        let mut slots = 0;
        let crossing = self.ops.iter().enumerate().flat_map(|(i, op)| {
            op.operands()
                .map(|v| v as usize)
                .filter(move |&v| piece[v] < piece[i])
        });
        let outputs = self.outputs.iter().map(|&o| o as usize);
        for v in crossing.chain(outputs) {
            if !is_inline(&self.ops[v]) && slot[v].is_none() {
                slot[v] = Some(slots);
                slots += 1;
            }
        }
        (slot, slots)
    }

    /// Each piece's declarations and assignments (registers reused by
    /// liveness within the piece; a value with a slot is written to it when
    /// computed and read from it in later pieces), and the outputs' spellings.
    fn emit_pieces(
        &self,
        cfg: &EmitConfig,
        piece: &[usize],
        slot: &[Option<usize>],
        state: &TokenStream,
    ) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let fused = self.fused(cfg, piece, slot);
        let last_use = self.last_uses(piece, slot, &fused);
        let angles = Angles::new(self, piece, cfg);
        let mut operand: Vec<TokenStream> = Vec::with_capacity(self.ops.len());
        let mut register_of: Vec<Option<usize>> = vec![None; self.ops.len()];
        let mut bodies = Vec::new();
        let mut body = TokenStream::new();
        let mut registers = Registers::default();
        for (i, op) in self.ops.iter().enumerate() {
            if i > 0 && piece[i] != piece[i - 1] {
                bodies.push(registers.declare(cfg, std::mem::take(&mut body)));
                registers = Registers::default();
            }
            let spell = |v: Value| -> TokenStream {
                let v = v as usize;
                match slot[v] {
                    Some(k) if piece[v] < piece[i] => quote!(#state[#k]),
                    _ => operand[v].clone(),
                }
            };
            if fused[i] {
                // Spelled by the sum that reads it.
                operand.push(TokenStream::new());
                continue;
            }
            body.extend(angles.call_before(i, self, cfg, &spell));
            let expr = match angles.read(i) {
                Some(expr) => expr,
                None => match self.expression(op, &spell, cfg, &fused) {
                    Ok(expr) => expr,
                    Err(inline) => {
                        operand.push(inline);
                        continue;
                    }
                },
            };
            // Operands read here for the last time give their registers back
            // before the result takes one: `_t3 = _t3 * _t5` is fine. A fused
            // product's operands are read here too.
            let fused_operands = op
                .operands()
                .filter(|&v| fused[v as usize])
                .flat_map(|m| self.ops[m as usize].operands());
            for v in op.operands().chain(fused_operands) {
                if last_use[v as usize] == i
                    && piece[v as usize] == piece[i]
                    && let Some(r) = register_of[v as usize]
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
        bodies.push(registers.declare(cfg, body));
        let outputs = self
            .outputs
            .iter()
            .map(|&v| match slot[v as usize] {
                Some(k) => quote!(#state[#k]),
                None => operand[v as usize].clone(),
            })
            .collect();
        (bodies, outputs)
    }

    /// Which products are spelled inside the one sum that reads them (see
    /// [`EmitConfig::fused_multiply_add`]): read once, by an addition or
    /// subtraction of the same piece, neither an output nor in a slot.
    fn fused(&self, cfg: &EmitConfig, piece: &[usize], slot: &[Option<usize>]) -> Vec<bool> {
        let mut fused = vec![false; self.ops.len()];
        if !cfg.fused_multiply_add {
            return fused;
        }
        let mut reads = vec![0usize; self.ops.len()];
        let mut reader = vec![0usize; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            for v in op.operands() {
                reads[v as usize] += 1;
                reader[v as usize] = i;
            }
        }
        for &o in &self.outputs {
            reads[o as usize] += 1;
        }
        for (v, op) in self.ops.iter().enumerate() {
            let sum = matches!(self.ops[reader[v]], Op::Add(..) | Op::Sub(..));
            let mut claimed = false;
            if let (Op::Mul(..), true, 1, None) = (op, sum, reads[v], slot[v]) {
                claimed = piece[reader[v]] == piece[v];
            }
            fused[v] = claimed;
        }
        // A sum of two products fuses one of them: the first.
        for op in &self.ops {
            if let Op::Add(a, b) | Op::Sub(a, b) = *op
                && fused[a as usize]
            {
                fused[b as usize] = false;
            }
        }
        fused
    }

    /// The index of the last operation of the same piece reading each value
    /// (`usize::MAX` for an output without a slot, read after the program);
    /// a fused product's operands are read where its sum is.
    fn last_uses(&self, piece: &[usize], slot: &[Option<usize>], fused: &[bool]) -> Vec<usize> {
        let mut last = vec![0usize; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            for v in op.operands() {
                if piece[v as usize] != piece[i] {
                    continue;
                }
                last[v as usize] = i;
                if fused[v as usize] {
                    for w in self.ops[v as usize].operands() {
                        if piece[w as usize] == piece[i] {
                            last[w as usize] = i;
                        }
                    }
                }
            }
        }
        for &v in &self.outputs {
            if slot[v as usize].is_none() {
                last[v as usize] = usize::MAX;
            }
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
        fused: &[bool],
    ) -> Result<TokenStream, TokenStream> {
        let o = |v: Value| operand(v);
        let f = cfg.function;
        // x y + c, with x y a fused product and `negate` on x.
        let fma = |m: Value, negate: bool, c: TokenStream| -> TokenStream {
            let Op::Mul(x, y) = self.ops[m as usize] else {
                return c;
            };
            let (x, y) = (o(x), o(y));
            let x = if negate { quote!(-#x) } else { x };
            quote!(#f::mul_add(#x, #y, #c))
        };
        Ok(match *op {
            Op::Sym(s) => return Err((cfg.symbol)(s)),
            Op::Const(b) => return Err((cfg.constant)(f64::from_bits(b))),
            Op::Add(a, b) if fused[a as usize] => fma(a, false, o(b)),
            Op::Add(a, b) if fused[b as usize] => fma(b, false, o(a)),
            Op::Sub(a, b) if fused[a as usize] => {
                let b = o(b);
                fma(a, false, quote!(-#b))
            }
            Op::Sub(a, b) if fused[b as usize] => fma(b, true, o(a)),
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
                let y = o(y);
                let x = o(x);
                quote!(#f::atan2(#y, #x))
            }
            Op::Powf(a, b) => {
                let a = o(a);
                let b = o(b);
                quote!(#f::powf(#a, #b))
            }
            Op::Powi(a, n) => {
                let a = o(a);
                quote!(#f::powi(#a, #n))
            }
            Op::Select(t, a, b) => {
                let t = o(t);
                let a = o(a);
                let b = o(b);
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

    /// `let mut` for every register used, then `body`.
    fn declare(&self, cfg: &EmitConfig, body: TokenStream) -> TokenStream {
        let declarations = (0..self.count).map(|r| {
            let name = register_name(cfg, r);
            quote!(let mut #name;)
        });
        quote!(#(#declarations)* #body)
    }
}

fn is_inline(op: &Op) -> bool {
    matches!(op, Op::Sym(_) | Op::Const(_))
}

fn register_name(cfg: &EmitConfig, r: usize) -> Ident {
    Ident::new(&format!("{}{r}", cfg.temp_prefix), Span::call_site())
}

fn binary(a: &TokenStream, op: TokenStream, b: &TokenStream) -> TokenStream {
    quote!(#a #op #b)
}
