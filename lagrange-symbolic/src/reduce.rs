//! Reduction modulo a quadratic relation x² = s: the canonical form of a
//! polynomial on the set where the relation holds.
//!
//! A unit quaternion satisfies w² = 1 − x² − y² − z². Expressions built from
//! its rotation matrix carry that identity hidden (a column's squared norm is
//! (w² + x² + y² + z²)², which is 1 only there); expanded, with every power
//! of w above the first rewritten through the relation and expanded again,
//! each is a polynomial of degree at most one in w, which is canonical: equal
//! functions on the relation's set give the same form, so the hidden 1s and
//! 0s appear.

use std::collections::HashMap;

use crate::Context;
use crate::node::{Expr, Node};

impl Context {
    /// `e` with every power xᵏ (k ≥ 2 an integer) written as x^(k mod 2) ·
    /// s^(k div 2), then expanded and collected: `e` reduced modulo x² = s.
    /// `x` must be a symbol; `s` must not contain it.
    pub fn reduce_square(&mut self, e: Expr, x: Expr, s: Expr) -> Expr {
        let expanded = self.expand(e);
        let mut memo = HashMap::new();
        let reduced = self.rewrite_powers(expanded, x, s, &mut memo);
        let expanded = self.expand(reduced);
        self.collect(expanded)
    }

    fn rewrite_powers(
        &mut self,
        e: Expr,
        x: Expr,
        s: Expr,
        memo: &mut HashMap<Expr, Expr>,
    ) -> Expr {
        let Some(sym) = self.as_symbol(x) else {
            return e;
        };
        if self.free_slice(e).binary_search(&sym).is_err() {
            return e;
        }
        if let Some(&r) = memo.get(&e) {
            return r;
        }
        let r = match self.node(e).clone() {
            Node::Pow(b, k) if b == x => match self.num(k).and_then(|n| n.as_integer()) {
                Some(k) if k >= 2 => {
                    let odd = self.powi(x, k % 2);
                    let even = self.powi(s, k / 2);
                    self.mul(odd, even)
                }
                _ => e,
            },
            _ => self.rebuild(e, |cx, c| cx.rewrite_powers(c, x, s, memo)),
        };
        memo.insert(e, r);
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_quaternion_s_column_norm_reduces_to_one() {
        let mut cx = Context::new();
        let [w, x, y, z] = ["w", "x", "y", "z"].map(|n| cx.free_symbol(n));
        let sq = |cx: &mut Context, a| cx.powi(a, 2);
        let x2 = sq(&mut cx, x);
        let y2 = sq(&mut cx, y);
        let z2 = sq(&mut cx, z);
        let one = cx.one();
        let sum = cx.sum(&[x2, y2, z2]);
        let s = cx.sub(one, sum);
        // (w² + x² + y² + z²)² on the set w² = 1 − x² − y² − z² is 1.
        let w2 = sq(&mut cx, w);
        let norm = cx.sum(&[w2, x2, y2, z2]);
        let squared = cx.powi(norm, 2);
        assert_eq!(cx.reduce_square(squared, w, s), one);
        // w³ = w (1 − x² − y² − z²) stays of degree one in w.
        let cube = cx.powi(w, 3);
        let r = cx.reduce_square(cube, w, s);
        assert_eq!(cx.degree_in(r, &[w]), Some(1));
    }
}
