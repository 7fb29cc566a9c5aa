//! The joint angles' sines and cosines, computed together: one
//! `sin_cos_many` call per piece of a program for the arguments of its sines
//! and cosines that are known before the first of them, in place of a
//! library call each (see `lagrange_runtime::numeric::sincos` for why).

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use super::EmitConfig;
use crate::node::Func;
use crate::program::{Op, Program, Value};

/// Where each piece computes its sines and cosines together, and where each
/// sine or cosine reads its value.
pub(super) struct Angles {
    /// Per op: its place in its piece's call (the argument's index, and 0
    /// for a sine, 1 for a cosine), or `None` if it is computed alone.
    taken: Vec<Option<(usize, usize)>>,
    /// Per call: the op it precedes (its piece's first sine or cosine) and
    /// the distinct arguments, in order.
    calls: Vec<(usize, Vec<Value>)>,
    /// The two arrays the calls bind: `_tsin` and `_tcos`.
    names: [Ident; 2],
}

impl Angles {
    /// An argument qualifies if it is a symbol or a value of the same piece
    /// computed before the piece's first sine or cosine; a piece with fewer
    /// than two qualifying arguments keeps its calls one by one.
    pub(super) fn new(program: &Program, piece: &[usize], cfg: &EmitConfig) -> Angles {
        let ops = &program.ops;
        let trig = |op: &Op| match *op {
            Op::Call(Func::Sin, a) => Some((a, 0)),
            Op::Call(Func::Cos, a) => Some((a, 1)),
            _ => None,
        };
        let mut first = std::collections::BTreeMap::new();
        for (i, op) in ops.iter().enumerate() {
            if trig(op).is_some() {
                first.entry(piece[i]).or_insert(i);
            }
        }
        let mut taken = vec![None; ops.len()];
        let mut calls = Vec::new();
        for (&p, &at) in &first {
            let mut args: Vec<Value> = Vec::new();
            let mut places = Vec::new();
            for (i, op) in ops.iter().enumerate().filter(|&(i, _)| piece[i] == p) {
                let Some((a, which)) = trig(op) else { continue };
                let known = match ops[a as usize] {
                    Op::Sym(_) => true,
                    Op::Const(_) => false,
                    _ => piece[a as usize] == p && (a as usize) < at,
                };
                if known {
                    let k = args.iter().position(|&x| x == a).unwrap_or_else(|| {
                        args.push(a);
                        args.len() - 1
                    });
                    places.push((i, k, which));
                }
            }
            if args.len() >= 2 {
                for (i, k, which) in places {
                    taken[i] = Some((k, which));
                }
                calls.push((at, args));
            }
        }
        let name = |what| Ident::new(&format!("{}{what}", cfg.temp_prefix), Span::call_site());
        Angles {
            taken,
            calls,
            names: [name("sin"), name("cos")],
        }
    }

    /// `let (_tsin, _tcos) = f::sin_cos_many([..]);` if a call goes before
    /// op `i`, its computed arguments spelled by `spell`.
    pub(super) fn call_before(
        &self,
        i: usize,
        program: &Program,
        cfg: &EmitConfig,
        spell: &dyn Fn(Value) -> TokenStream,
    ) -> Option<TokenStream> {
        let (_, args) = self.calls.iter().find(|(at, _)| *at == i)?;
        // A symbol's op may come after the first sine: spelled here.
        let args = args.iter().map(|&a| match program.ops[a as usize] {
            Op::Sym(s) => (cfg.symbol)(s),
            _ => spell(a),
        });
        let (f, [s, c]) = (cfg.function, &self.names);
        Some(quote!(let (#s, #c) = #f::sin_cos_many([#(#args),*]);))
    }

    /// `_tsin[k]` or `_tcos[k]` for a sine or cosine taken from a call.
    pub(super) fn read(&self, i: usize) -> Option<TokenStream> {
        let (k, which) = self.taken[i]?;
        let (name, k) = (&self.names[which], Literal::usize_unsuffixed(k));
        Some(quote!(#name[#k]))
    }
}
