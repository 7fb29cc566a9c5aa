//! Cost-reducing rewrites that never change the value: factoring of sums
//! (greedy multivariate Horner), bounded expansion, and `simplify`.

use std::collections::HashMap;

use crate::context::Context;
use crate::node::{Expr, Node};
use crate::rational::Num;

/// Expansion gives up on a node whose expanded form would exceed this many
/// terms; `simplify` only ever keeps an expansion if it is smaller.
const EXPAND_TERM_LIMIT: usize = 64;

impl Context {
    /// Factor sums to reduce evaluation cost: pull out the factor common to
    /// the most terms, recurse on the cofactor and on the remaining terms,
    /// repeat (greedy multivariate Horner). Factors may be symbols, calls,
    /// reciprocals, or whole subexpressions (including sums), so
    /// `m1·X + m2·X` becomes `X·(m1 + m2)` for a shared `X`. Memoised.
    pub fn collect(&mut self, e: Expr) -> Expr {
        if let Some(&r) = self.collect_memo.get(&e) {
            return r;
        }
        let inner = self.rebuild(e, Self::collect);
        let r = match self.node(inner) {
            Node::Add(terms) => {
                let terms = terms.to_vec();
                self.factor_terms(terms)
            }
            _ => inner,
        };
        self.collect_memo.insert(e, r);
        self.collect_memo.insert(r, r);
        r
    }

    /// The factors of a term that can be pulled out of a sum: for `x^n` with
    /// integer `n` one power of `x` (or of `1/x`), otherwise the whole factor.
    fn units(&mut self, term: Expr) -> Vec<Expr> {
        let factors: Vec<Expr> = match self.node(term) {
            Node::Const(_) | Node::Float(_) => return Vec::new(),
            Node::Mul(fs) => fs
                .iter()
                .copied()
                .filter(|&f| self.num(f).is_none())
                .collect(),
            _ => vec![term],
        };
        factors
            .into_iter()
            .map(|f| {
                let (b, x) = self.base_exp(f);
                match self.num(x).and_then(Num::as_integer) {
                    Some(n) if n > 0 => b,
                    Some(_) => self.powi(b, -1),
                    None => f,
                }
            })
            .collect()
    }

    fn factor_terms(&mut self, terms: Vec<Expr>) -> Expr {
        if terms.len() < 2 {
            return self.sum(&terms);
        }
        let Some(best) = self.most_common_unit(&terms) else {
            return self.common_coefficient(terms);
        };
        let inv = self.powi(best, -1);
        let mut with = Vec::new();
        let mut without = Vec::new();
        for t in terms {
            if self.units(t).contains(&best) {
                with.push(self.mul(t, inv));
            } else {
                without.push(t);
            }
        }
        let inner = self.factor_terms(with);
        let pulled = self.mul(best, inner);
        if without.is_empty() {
            return pulled;
        }
        // `pulled` may share a factor with the rest (`m1·X + m2·X`); the
        // term count strictly decreased, so this recursion terminates.
        without.insert(0, pulled);
        self.factor_terms(without)
    }

    /// The unit factor occurring in the most terms (at least two); ties go to
    /// the first one seen, which is deterministic.
    fn most_common_unit(&mut self, terms: &[Expr]) -> Option<Expr> {
        let mut order = Vec::new();
        let mut counts: HashMap<Expr, usize> = HashMap::new();
        for &t in terms {
            for u in self.units(t) {
                let c = counts.entry(u).or_insert_with(|| {
                    order.push(u);
                    0
                });
                *c += 1;
            }
        }
        let mut best: Option<(usize, Expr)> = None;
        for u in order {
            let c = counts[&u];
            if c >= 2 && best.is_none_or(|(bc, _)| c > bc) {
                best = Some((c, u));
            }
        }
        best.map(|(_, u)| u)
    }

    /// `2x + 2y -> 2·(x + y)` when all terms share one coefficient other than ±1.
    fn common_coefficient(&mut self, terms: Vec<Expr>) -> Expr {
        let split: Vec<(Num, Expr)> = terms.iter().map(|&t| self.split_coeff(t)).collect();
        let c = split[0].0;
        let all_same = split.iter().all(|(k, m)| *k == c && self.num(*m).is_none());
        if !all_same || c.abs().is_one() {
            return self.sum(&terms);
        }
        let monomials: Vec<Expr> = split.into_iter().map(|(_, m)| m).collect();
        let s = self.sum(&monomials);
        let ce = self.num_expr(c);
        // Built directly: the smart `sum` would flatten `c·(x + y)` back
        // into a sum the moment it is added to something else, but here it is
        // a product in its own right.
        self.intern(Node::Mul(vec![ce, s].into()))
    }

    /// Distribute products over sums and expand positive integer powers of
    /// sums, bottom-up. A node whose expansion would exceed a fixed term
    /// limit is left factored, so this never blows up.
    pub fn expand(&mut self, e: Expr) -> Expr {
        let mut memo = HashMap::new();
        self.expand_in(e, &mut memo)
    }

    fn expand_in(&mut self, e: Expr, memo: &mut HashMap<Expr, Expr>) -> Expr {
        if let Some(&r) = memo.get(&e) {
            return r;
        }
        let inner = self.rebuild(e, |cx, c| cx.expand_in(c, memo));
        let r = match self.node(inner).clone() {
            Node::Mul(fs) => self.distribute(&fs).unwrap_or(inner),
            Node::Pow(b, x) => match (self.node(b), self.num(x).and_then(Num::as_integer)) {
                (Node::Add(_), Some(n)) if (2..=8).contains(&n) => {
                    let fs = vec![b; n as usize];
                    self.distribute(&fs).unwrap_or(inner)
                }
                _ => inner,
            },
            _ => inner,
        };
        memo.insert(e, r);
        r
    }

    /// The product of `factors` as a sum of products, or `None` if there is
    /// no sum to distribute or the result would be too large.
    fn distribute(&mut self, factors: &[Expr]) -> Option<Expr> {
        let mut terms = vec![self.int(1)];
        let mut any_sum = false;
        for &f in factors {
            let parts: Vec<Expr> = match self.node(f) {
                Node::Add(ts) => {
                    any_sum = true;
                    ts.to_vec()
                }
                _ => vec![f],
            };
            if terms.len() * parts.len() > EXPAND_TERM_LIMIT {
                return None;
            }
            let mut next = Vec::with_capacity(terms.len() * parts.len());
            for &t in &terms {
                for &p in &parts {
                    next.push(self.mul(t, p));
                }
            }
            terms = next;
        }
        any_sum.then(|| self.sum(&terms))
    }

    /// Rebuild `e` bottom-up through the smart constructors (re-applying
    /// every canonicalisation, e.g. after substitution), and at each sum
    /// with a product-of-sum term try distributing those terms one level
    /// (capped at a fixed term count), kept only when the node gets smaller.
    /// This is what finds cancellations such as `(x + 1)·y - x·y = y`.
    /// The result is never larger than the input. Memoised.
    pub fn simplify(&mut self, e: Expr) -> Expr {
        if let Some(&r) = self.simplify_memo.get(&e) {
            return r;
        }
        let inner = self.rebuild(e, Self::simplify);
        let r = match self.distribute_terms(inner) {
            Some(expanded) if self.node_count(expanded) < self.node_count(inner) => expanded,
            _ => inner,
        };
        // Cheap in the common case: canonical input rebuilds to itself.
        let r = if r != e && self.node_count(r) > self.node_count(e) {
            e
        } else {
            r
        };
        self.simplify_memo.insert(e, r);
        self.simplify_memo.insert(r, r);
        r
    }

    /// The sum `e` with its product-of-sum terms distributed one level, or
    /// `None` if `e` is not such a sum or a term would exceed the limit.
    fn distribute_terms(&mut self, e: Expr) -> Option<Expr> {
        let Node::Add(terms) = self.node(e) else {
            return None;
        };
        let terms = terms.to_vec();
        let mut out = Vec::with_capacity(terms.len());
        let mut changed = false;
        for t in terms {
            let factors = match self.node(t) {
                Node::Mul(fs) if fs.iter().any(|&f| matches!(self.node(f), Node::Add(_))) => {
                    fs.to_vec()
                }
                _ => {
                    out.push(t);
                    continue;
                }
            };
            out.push(self.distribute(&factors)?);
            changed = true;
        }
        changed.then(|| self.sum(&out))
    }
}
