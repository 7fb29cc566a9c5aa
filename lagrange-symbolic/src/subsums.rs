//! Sums that hold other sums whole. The canonical form flattens every sum, so
//! a sum built as `B + x + y` from a sum `B` is stored as B's terms and x and
//! y side by side: lowered term by term it adds B's terms all over again.
//! That is the shape of every composite quantity of a tree gathered leaves
//! first (a subtree's inertia, force or Coriolis matrix in world axes is its
//! root body's terms plus its children's composites): flattened, the root's
//! composite re-adds the whole tree, O(n²) additions where the recursion does
//! O(n).
//!
//! [`bases`] finds, for each sum a program reaches, the largest other sum
//! among them whose terms are a subset of its own, so that lowering can start
//! from that sum's value and add only the rest. Nothing is rewritten in the
//! context: the canonical form (on which cancellation and `sin² + cos² = 1`
//! depend) stays as it is; only the order of the additions changes, which is
//! round-off.

use std::collections::{HashMap, HashSet};

use crate::context::Context;
use crate::node::{Expr, Node};

/// One reachable sum: its terms other than a number, sorted, and its number
/// (a canonical sum has at most one).
struct Sum {
    expr: Expr,
    terms: Vec<Expr>,
    constant: Option<Expr>,
}

/// For each sum reachable from `outputs`, the largest other reachable sum of
/// two or more terms whose terms it holds (and whose constant is zero or its
/// own), when there is one.
pub(crate) fn bases(cx: &Context, outputs: &[Expr]) -> HashMap<Expr, Expr> {
    let sums = reachable_sums(cx, outputs);
    // A subset's rarest term is in its superset, so each sum is indexed under
    // that term alone and a superset looks only in its own terms' buckets.
    let mut occurrences: HashMap<Expr, usize> = HashMap::new();
    for s in &sums {
        for &t in &s.terms {
            *occurrences.entry(t).or_default() += 1;
        }
    }
    let mut bucket: HashMap<Expr, Vec<usize>> = HashMap::new();
    for (i, s) in sums.iter().enumerate() {
        if s.terms.len() < 2 {
            continue;
        }
        let rarest = s.terms.iter().min_by_key(|t| (occurrences[*t], **t));
        if let Some(&t) = rarest {
            bucket.entry(t).or_default().push(i);
        }
    }
    let mut out = HashMap::new();
    for s in &sums {
        let mut best: Option<&Sum> = None;
        for t in &s.terms {
            for &c in bucket.get(t).map_or(&[][..], Vec::as_slice) {
                let b = &sums[c];
                let larger = best.is_none_or(|x| b.terms.len() > x.terms.len());
                if larger && holds(s, b) {
                    best = Some(b);
                }
            }
        }
        if let Some(b) = best {
            out.insert(s.expr, b.expr);
        }
    }
    out
}

/// Whether `b` is a proper part of `a`: fewer terms, each of them `a`'s, and
/// a constant that is zero or `a`'s (so the rest's constant is exact).
fn holds(a: &Sum, b: &Sum) -> bool {
    let constant = b.constant.is_none() || b.constant == a.constant;
    if b.terms.len() >= a.terms.len() || !constant {
        return false;
    }
    let mut rest = a.terms.iter();
    b.terms.iter().all(|t| rest.any(|x| x == t))
}

/// The sums reachable from `outputs`, each once, in the order a depth-first
/// walk first meets them (so the choice of bases is deterministic).
fn reachable_sums(cx: &Context, outputs: &[Expr]) -> Vec<Sum> {
    let mut seen: HashSet<Expr> = HashSet::new();
    let mut stack: Vec<Expr> = outputs.iter().rev().copied().collect();
    let mut sums = Vec::new();
    while let Some(e) = stack.pop() {
        if !seen.insert(e) {
            continue;
        }
        let node = cx.node(e);
        if let Node::Add(children) = node {
            let mut terms = Vec::with_capacity(children.len());
            let mut constant = None;
            for &c in children.iter() {
                match cx.num(c) {
                    Some(_) => constant = Some(c),
                    None => terms.push(c),
                }
            }
            terms.sort_unstable();
            sums.push(Sum {
                expr: e,
                terms,
                constant,
            });
        }
        node.for_each_child(|c| {
            if !seen.contains(&c) {
                stack.push(c);
            }
        });
    }
    sums
}
