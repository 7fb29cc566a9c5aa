//! Angle sums folded back for display: sin a cos b ± cos a sin b = sin(a ± b)
//! and cos a cos b ∓ sin a sin b = cos(a ± b), between the terms of a sum that
//! share every other factor.
//!
//! The derivation expands sines and cosines of sums into products of those of
//! the coordinates (2n calls for an n-link chain, and products are cheaper than
//! calls), so emitted code keeps the products; printed equations read better as
//! the closed forms the texts write, e.g. M₁₂ = m₂ l₁ l₂ cos(θ₁ − θ₂).

use std::collections::HashMap;

use crate::context::Context;
use crate::node::{Expr, Func, Node};

/// Which product of a sine or cosine of `lo` and of `hi` (lo < hi) a term holds.
#[derive(Copy, Clone, PartialEq, Eq)]
enum Pair {
    SinCos,
    CosSin,
    CosCos,
    SinSin,
}

/// A term's candidate pair: its index, coefficient and kind.
struct Candidate {
    term: usize,
    coefficient: Expr,
    pair: Pair,
}

impl Context {
    /// `e` with angle sums folded wherever two terms of a sum allow it.
    pub fn fold_angle_sums(&mut self, e: Expr) -> Expr {
        let mut memo = HashMap::new();
        self.fold_in(e, &mut memo)
    }

    fn fold_in(&mut self, e: Expr, memo: &mut HashMap<Expr, Expr>) -> Expr {
        if let Some(&r) = memo.get(&e) {
            return r;
        }
        let mut r = self.rebuild(e, |cx, c| cx.fold_in(c, memo));
        // A fold can expose another (sin(a + b) cos c + cos(a + b) sin c).
        for _ in 0..4 {
            match self.fold_sum(r) {
                Some(next) => r = next,
                None => break,
            }
        }
        memo.insert(e, r);
        r
    }

    /// (coefficient, other factors) of a term.
    fn split_coefficient(&mut self, term: Expr) -> (Expr, Vec<Expr>) {
        let factors: Vec<Expr> = match self.node(term) {
            Node::Mul(fs) => fs.to_vec(),
            _ => vec![term],
        };
        let (consts, rest): (Vec<Expr>, Vec<Expr>) =
            factors.into_iter().partition(|&f| self.num(f).is_some());
        (self.product(&consts), rest)
    }

    /// One pass of folding over the terms of the sum `s`; `None` if no pair folds.
    fn fold_sum(&mut self, s: Expr) -> Option<Expr> {
        let Node::Add(ts) = self.node(s).clone() else {
            return None;
        };
        let mut buckets: HashMap<(Expr, Expr, Expr), Vec<Candidate>> = HashMap::new();
        for (i, &t) in ts.iter().enumerate() {
            let (coefficient, factors) = self.split_coefficient(t);
            let trig: Vec<(usize, Func, Expr)> = factors
                .iter()
                .enumerate()
                .filter_map(|(k, &f)| match self.node(f) {
                    &Node::Call(func @ (Func::Sin | Func::Cos), a) => Some((k, func, a)),
                    _ => None,
                })
                .collect();
            for (x, &(kx, fx, ax)) in trig.iter().enumerate() {
                for &(ky, fy, ay) in &trig[x + 1..] {
                    if ax == ay {
                        continue;
                    }
                    let ((flo, lo), (fhi, hi)) = if ax < ay {
                        ((fx, ax), (fy, ay))
                    } else {
                        ((fy, ay), (fx, ax))
                    };
                    let pair = match (flo, fhi) {
                        (Func::Sin, Func::Cos) => Pair::SinCos,
                        (Func::Cos, Func::Sin) => Pair::CosSin,
                        (Func::Cos, Func::Cos) => Pair::CosCos,
                        _ => Pair::SinSin,
                    };
                    let rest: Vec<Expr> = factors
                        .iter()
                        .enumerate()
                        .filter(|&(k, _)| k != kx && k != ky)
                        .map(|(_, &f)| f)
                        .collect();
                    let rest = self.product(&rest);
                    buckets.entry((rest, lo, hi)).or_default().push(Candidate {
                        term: i,
                        coefficient,
                        pair,
                    });
                }
            }
        }
        let mut used = vec![false; ts.len()];
        let mut folded = Vec::new();
        let mut keys: Vec<(Expr, Expr, Expr)> = buckets.keys().copied().collect();
        keys.sort_unstable();
        for key in keys {
            let (rest, lo, hi) = key;
            let candidates = &buckets[&key];
            for (x, a) in candidates.iter().enumerate() {
                for b in &candidates[x + 1..] {
                    if used[a.term] || used[b.term] || a.term == b.term {
                        continue;
                    }
                    let Some(angle) = self.angle_of(a, b, lo, hi) else {
                        continue;
                    };
                    used[a.term] = true;
                    used[b.term] = true;
                    folded.push(self.product(&[angle, rest]));
                }
            }
        }
        if folded.is_empty() {
            return None;
        }
        let mut terms: Vec<Expr> = (0..ts.len()).filter(|&i| !used[i]).map(|i| ts[i]).collect();
        terms.extend(folded);
        Some(self.sum(&terms))
    }

    /// c·sin(lo ± hi) or c·cos(lo ± hi) from two candidates, if they pair.
    fn angle_of(&mut self, a: &Candidate, b: &Candidate, lo: Expr, hi: Expr) -> Option<Expr> {
        let (a, b) = match (a.pair, b.pair) {
            (Pair::SinCos, Pair::CosSin) | (Pair::CosCos, Pair::SinSin) => (a, b),
            (Pair::CosSin, Pair::SinCos) | (Pair::SinSin, Pair::CosCos) => (b, a),
            _ => return None,
        };
        let same = self.sub(a.coefficient, b.coefficient);
        let opposite = self.add(a.coefficient, b.coefficient);
        let plus = self.add(lo, hi);
        let minus = self.sub(lo, hi);
        let (func, angle) = match a.pair {
            // c sin lo cos hi ± c cos lo sin hi = c sin(lo ± hi)
            Pair::SinCos if self.is_zero(same) => (Func::Sin, plus),
            Pair::SinCos if self.is_zero(opposite) => (Func::Sin, minus),
            // c cos lo cos hi ∓ c sin lo sin hi = c cos(lo ± hi)
            Pair::CosCos if self.is_zero(opposite) => (Func::Cos, plus),
            Pair::CosCos if self.is_zero(same) => (Func::Cos, minus),
            _ => return None,
        };
        let call = self.func(func, angle);
        Some(self.mul(a.coefficient, call))
    }
}
