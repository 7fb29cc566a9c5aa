//! Trigonometric rewriting: the Pythagorean identity (applied by every sum)
//! and the expansion of sines and cosines of sums.

use std::collections::{HashMap, HashSet};

use crate::context::Context;
use crate::node::{Expr, Func, Node};
use crate::rational::Num;

/// One `sin(u)^k` or `cos(u)^k` (k ≥ 2) factor found in a term.
struct Square {
    term: usize,
    func: Func,
    arg: Expr,
    factor: Expr,
    exp: i64,
}

/// Largest `n` for which `sin(n·x)` / `cos(n·x)` are expanded; beyond that
/// the expansion costs more than the call it replaces.
const MAX_MULTIPLE: i64 = 6;

impl Context {
    /// Find `c·R·sin²u + c·R·cos²u` pairs among the terms of a sum and
    /// replace each pair by `c·R` (also for higher even-or-odd powers:
    /// `sin^k u = sin^(k-2) u · sin² u`). Returns `None` if nothing applies.
    pub(crate) fn pythagorean(&mut self, items: &[(Num, Expr)]) -> Option<Vec<(Num, Expr)>> {
        let mut squares = Vec::new();
        for (i, &(_, m)) in items.iter().enumerate() {
            self.find_squares(i, m, &mut squares);
        }
        // Only build cofactors when some argument has both a sine and a
        // cosine square, which is rare; this keeps ordinary sums cheap.
        let sin_args: HashSet<Expr> = squares
            .iter()
            .filter(|s| s.func == Func::Sin)
            .map(|s| s.arg)
            .collect();
        let both: HashSet<Expr> = squares
            .iter()
            .filter(|s| s.func == Func::Cos && sin_args.contains(&s.arg))
            .map(|s| s.arg)
            .collect();
        if both.is_empty() {
            return None;
        }
        let mut cos_index: HashMap<(Expr, Expr, Num), usize> = HashMap::new();
        let mut sin_keys = Vec::new();
        for s in squares.iter().filter(|s| both.contains(&s.arg)) {
            let cof = self.cofactor(items[s.term].1, s.factor, s.func, s.arg, s.exp);
            let key = (s.arg, cof, items[s.term].0);
            if s.func == Func::Cos {
                cos_index.entry(key).or_insert(s.term);
            } else {
                sin_keys.push((key, s.term));
            }
        }
        let mut used = vec![false; items.len()];
        let mut merged = Vec::new();
        for (key, i) in sin_keys {
            if let Some(&j) = cos_index.get(&key)
                && i != j
                && !used[i]
                && !used[j]
            {
                used[i] = true;
                used[j] = true;
                merged.push((key.2, key.1));
            }
        }
        if merged.is_empty() {
            return None;
        }
        let mut out: Vec<(Num, Expr)> = items
            .iter()
            .zip(&used)
            .filter(|(_, u)| !**u)
            .map(|(t, _)| *t)
            .collect();
        out.extend(merged);
        Some(out)
    }

    fn find_squares(&self, term: usize, m: Expr, out: &mut Vec<Square>) {
        let factors: &[Expr] = match self.node(m) {
            Node::Mul(fs) => fs,
            _ => std::slice::from_ref(&m),
        };
        for &factor in factors {
            if let Node::Pow(b, x) = *self.node(factor)
                && let Node::Call(func @ (Func::Sin | Func::Cos), arg) = *self.node(b)
                && let Some(exp) = self.as_rational(x).filter(|r| r.is_integer() && r.num >= 2)
            {
                out.push(Square {
                    term,
                    func,
                    arg,
                    factor,
                    exp: exp.num,
                });
            }
        }
    }

    /// The monomial `m` with its factor `f(arg)^exp` lowered to `f(arg)^(exp-2)`.
    fn cofactor(&mut self, m: Expr, factor: Expr, func: Func, arg: Expr, exp: i64) -> Expr {
        let call = self.func(func, arg);
        let reduced = self.powi(call, exp - 2);
        let rest: Vec<Expr> = match self.node(m) {
            Node::Mul(fs) => fs.iter().copied().filter(|&f| f != factor).collect(),
            _ => Vec::new(),
        };
        let mut all = rest;
        all.push(reduced);
        self.product(&all)
    }

    /// Expand sines and cosines of sums, `sin(a + b) = sin a cos b + cos a sin b`,
    /// and of small integer multiples `n·x`, recursively, so that only sines and
    /// cosines of single terms remain.
    ///
    /// A sum is split as (last term) + (the rest); with coordinates declared
    /// in chain order the rest is the previous link's angle, so the expansions
    /// of `θ1 + … + θk` share their subexpressions through the DAG and the
    /// result stays linear in size. Memoised.
    pub fn expand_trig(&mut self, e: Expr) -> Expr {
        if let Some(&r) = self.trig_memo.get(&e) {
            return r;
        }
        let r = match *self.node(e) {
            Node::Call(f @ (Func::Sin | Func::Cos), arg) => {
                let arg = self.expand_trig(arg);
                self.expand_sin_cos(f, arg)
            }
            _ => self.rebuild(e, Self::expand_trig),
        };
        self.trig_memo.insert(e, r);
        r
    }

    /// `f(arg)` expanded, for `f` sine or cosine and an already expanded `arg`.
    fn expand_sin_cos(&mut self, f: Func, arg: Expr) -> Expr {
        if self.is_negative_term(arg) {
            let (c, m) = self.split_coeff(arg);
            let pos = self.with_coeff(c.neg(), m);
            let inner = self.expand_sin_cos(f, pos);
            return if f == Func::Sin {
                self.neg(inner)
            } else {
                inner
            };
        }
        let call = self.func(f, arg);
        if !matches!(self.node(call), Node::Call(..)) {
            return call;
        }
        // Shared with `expand_trig`: the key is the (canonical) call node.
        if let Some(&r) = self.trig_memo.get(&call) {
            return r;
        }
        let r = match self.split_angle(arg) {
            None => call,
            Some((a, b)) => {
                let (sa, ca) = (
                    self.expand_sin_cos(Func::Sin, a),
                    self.expand_sin_cos(Func::Cos, a),
                );
                let (sb, cb) = (
                    self.expand_sin_cos(Func::Sin, b),
                    self.expand_sin_cos(Func::Cos, b),
                );
                if f == Func::Sin {
                    let l = self.mul(sa, cb);
                    let r = self.mul(ca, sb);
                    self.add(l, r)
                } else {
                    let l = self.mul(ca, cb);
                    let r = self.mul(sa, sb);
                    self.sub(l, r)
                }
            }
        };
        self.trig_memo.insert(call, r);
        r
    }

    /// `arg = a + b` with both parts simpler, or `None` if `arg` is atomic.
    fn split_angle(&mut self, arg: Expr) -> Option<(Expr, Expr)> {
        match self.node(arg) {
            Node::Add(terms) => {
                let terms = terms.clone();
                let (last, rest) = terms.split_last()?;
                let rest = self.sum(rest);
                Some((*last, rest))
            }
            Node::Mul(_) => {
                let (c, m) = self.split_coeff(arg);
                let n = c.as_integer().filter(|n| (2..=MAX_MULTIPLE).contains(n))?;
                let rest = self.with_coeff(Num::Rat(crate::Rational::integer(n - 1)), m);
                Some((m, rest))
            }
            _ => None,
        }
    }
}
