//! Calculus and structural queries: partial and total time derivatives,
//! substitution, polynomial degree.

use std::collections::HashMap;

use crate::context::Context;
use crate::node::{Expr, Func, Node, SymbolKind};
use crate::rational::Num;

impl Context {
    /// `∂e/∂wrt`. `wrt` must be a symbol expression (otherwise the result is
    /// zero). Memoised per `(e, wrt)`; subtrees not containing `wrt` are
    /// skipped in O(log n). Products stay factored (product rule, no
    /// expansion).
    pub fn diff(&mut self, e: Expr, wrt: Expr) -> Expr {
        if !self.depends_on(e, wrt) {
            return self.int(0);
        }
        if let Some(&d) = self.diff_memo.get(&(e, wrt)) {
            return d;
        }
        let d = self.diff_node(e, wrt);
        self.diff_memo.insert((e, wrt), d);
        d
    }

    fn diff_node(&mut self, e: Expr, wrt: Expr) -> Expr {
        match self.node(e) {
            Node::Sym(_) => self.int(if e == wrt { 1 } else { 0 }),
            _ => self.chain_rule(e, &mut |cx, x| cx.diff(x, wrt)),
        }
    }

    /// The derivative along `direction` (pairs of a symbol expression and its
    /// rate): `Σ ∂e/∂x · ẋ` over the pairs, in one forward pass over `e`
    /// instead of one partial derivative per symbol. Symbols not listed have
    /// rate zero. With `(q_k, q̇_k)` this is d/dt at q̈ = 0, and applied twice
    /// the second derivative along the motion (J̇ q̇ from a position).
    pub fn directional(&mut self, e: Expr, direction: &[(Expr, Expr)]) -> Expr {
        let rates: HashMap<crate::Symbol, Expr> = direction
            .iter()
            .filter_map(|&(x, v)| Some((self.as_symbol(x)?, v)))
            .collect();
        let mut keys: Vec<_> = rates.keys().copied().collect();
        keys.sort_unstable();
        let mut memo = HashMap::new();
        self.directional_in(e, &rates, &keys, &mut memo)
    }

    fn directional_in(
        &mut self,
        e: Expr,
        rates: &HashMap<crate::Symbol, Expr>,
        keys: &[crate::Symbol],
        memo: &mut HashMap<Expr, Expr>,
    ) -> Expr {
        let free = self.free_slice(e);
        if !keys.iter().any(|k| free.binary_search(k).is_ok()) {
            return self.int(0);
        }
        if let Some(&d) = memo.get(&e) {
            return d;
        }
        let d = match self.as_symbol(e) {
            Some(s) => rates[&s],
            None => self.chain_rule(e, &mut |cx, x| cx.directional_in(x, rates, keys, memo)),
        };
        memo.insert(e, d);
        d
    }

    /// One step of the chain rule at the non-symbol node `e`, its children's
    /// derivatives from `d` (a partial derivative or a directional one).
    /// Products stay factored (product rule, no expansion).
    fn chain_rule(&mut self, e: Expr, d: &mut dyn FnMut(&mut Context, Expr) -> Expr) -> Expr {
        match self.node(e).clone() {
            Node::Const(_) | Node::Float(_) | Node::Sym(_) => self.int(0),
            Node::Add(terms) => {
                let ds: Vec<Expr> = terms.iter().map(|&t| d(self, t)).collect();
                self.sum(&ds)
            }
            Node::Mul(factors) => {
                let mut terms = Vec::new();
                for (i, &f) in factors.iter().enumerate() {
                    let df = d(self, f);
                    if self.is_zero(df) {
                        continue;
                    }
                    let mut parts = factors.to_vec();
                    parts[i] = df;
                    terms.push(self.product(&parts));
                }
                self.sum(&terms)
            }
            Node::Pow(b, x) => {
                let db = d(self, b);
                let dx = d(self, x);
                self.pow_rule(b, x, db, dx)
            }
            Node::Call(f, u) => {
                let du = d(self, u);
                let outer = self.func_derivative(f, u);
                self.mul(outer, du)
            }
            Node::Atan2(y, x) => {
                // d atan2(y, x) = (x dy - y dx) / (x² + y²)
                let dy = d(self, y);
                let dx = d(self, x);
                let a = self.mul(x, dy);
                let b = self.mul(y, dx);
                let num = self.sub(a, b);
                let x2 = self.powi(x, 2);
                let y2 = self.powi(y, 2);
                let den = self.add(x2, y2);
                self.div(num, den)
            }
            // Piecewise: the derivative of the branch taken (the switching
            // surface itself has measure zero; there the else branch's).
            Node::Select(t, a, b) => {
                let da = d(self, a);
                let db = d(self, b);
                self.select(t, da, db)
            }
        }
    }

    /// d(b^x) from db and dx.
    fn pow_rule(&mut self, b: Expr, x: Expr, db: Expr, dx: Expr) -> Expr {
        if self.is_zero(dx) {
            // d b^x = x b^(x-1) db
            let one = self.int(1);
            let xm1 = self.sub(x, one);
            let p = self.pow(b, xm1);
            return self.product(&[x, p, db]);
        }
        // d b^x = b^x (dx ln b + x db / b)
        let ln_b = self.func(Func::Ln, b);
        let t1 = self.mul(dx, ln_b);
        let q = self.div(db, b);
        let t2 = self.mul(x, q);
        let s = self.add(t1, t2);
        let p = self.pow(b, x);
        self.mul(p, s)
    }

    /// `f'(u)` as an expression in `u`.
    fn func_derivative(&mut self, f: Func, u: Expr) -> Expr {
        let one = self.int(1);
        let half = self.rational(1, 2);
        let m_half = self.rational(-1, 2);
        match f {
            Func::Sin => self.cos(u),
            Func::Cos => {
                let s = self.sin(u);
                self.neg(s)
            }
            Func::Tan => {
                let t = self.func(Func::Tan, u);
                let t2 = self.powi(t, 2);
                self.add(one, t2)
            }
            Func::Asin | Func::Acos => {
                let u2 = self.powi(u, 2);
                let r = self.sub(one, u2);
                let d = self.pow(r, m_half);
                if f == Func::Asin { d } else { self.neg(d) }
            }
            Func::Atan => {
                let u2 = self.powi(u, 2);
                let r = self.add(one, u2);
                self.powi(r, -1)
            }
            Func::Sinh => self.func(Func::Cosh, u),
            Func::Cosh => self.func(Func::Sinh, u),
            Func::Tanh => {
                let t = self.func(Func::Tanh, u);
                let t2 = self.powi(t, 2);
                self.sub(one, t2)
            }
            Func::Exp => self.func(Func::Exp, u),
            Func::Ln => self.powi(u, -1),
            Func::Sqrt => {
                let p = self.pow(u, m_half);
                self.mul(half, p)
            }
            // sign(u): ±1, and 0 at u = 0 (a subgradient there, not a NaN).
            Func::Abs => self.sign(u),
        }
    }

    /// The total time derivative `d/dt = ∂/∂t + Σ q̇ ∂/∂q + Σ q̈ ∂/∂q̇`.
    ///
    /// Accelerations are treated as having zero derivative (there is no jerk
    /// symbol); mechanics never differentiates an expression containing `q̈`.
    /// Inputs ([`SymbolKind::Input`]) have no known rate either and are
    /// treated the same way, which is why the description language forbids
    /// them wherever the derivation differentiates in time.
    pub fn time_derivative(&mut self, e: Expr) -> Expr {
        let syms: Vec<_> = self.free_slice(e).to_vec();
        let mut terms = Vec::new();
        for s in syms {
            let x = self.symbol_expr(s);
            let rate = match self.symbol_kind(s) {
                SymbolKind::Time => Some(self.int(1)),
                SymbolKind::Coordinate(_) => self.velocity(x),
                SymbolKind::Velocity(i) => self.accelerations().get(i).copied(),
                _ => None,
            };
            if let Some(rate) = rate {
                let d = self.diff(e, x);
                terms.push(self.mul(rate, d));
            }
        }
        self.sum(&terms)
    }

    /// Replace symbols: each `(symbol expr, replacement)` pair in `map`.
    /// Non-symbol keys are ignored. Subtrees without any mapped symbol are
    /// returned as they are.
    pub fn substitute(&mut self, e: Expr, map: &[(Expr, Expr)]) -> Expr {
        self.substitute_all(&[e], map)[0]
    }

    /// [`substitute`](Self::substitute) on many expressions with one memo,
    /// so the subtrees they share are rebuilt once.
    pub fn substitute_all(&mut self, es: &[Expr], map: &[(Expr, Expr)]) -> Vec<Expr> {
        let table: HashMap<Expr, Expr> = map
            .iter()
            .filter(|(k, _)| self.as_symbol(*k).is_some())
            .copied()
            .collect();
        if table.is_empty() {
            return es.to_vec();
        }
        let keys: Vec<_> = table.keys().filter_map(|&k| self.as_symbol(k)).collect();
        let mut memo = HashMap::new();
        es.iter()
            .map(|&e| self.substitute_in(e, &table, &keys, &mut memo))
            .collect()
    }

    fn substitute_in(
        &mut self,
        e: Expr,
        table: &HashMap<Expr, Expr>,
        keys: &[crate::Symbol],
        memo: &mut HashMap<Expr, Expr>,
    ) -> Expr {
        if let Some(&r) = table.get(&e) {
            return r;
        }
        let free = self.free_slice(e);
        if !keys.iter().any(|k| free.binary_search(k).is_ok()) {
            return e;
        }
        if let Some(&r) = memo.get(&e) {
            return r;
        }
        let r = self.rebuild(e, |cx, c| cx.substitute_in(c, table, keys, memo));
        memo.insert(e, r);
        r
    }

    /// Total polynomial degree of `e` in the symbols `syms`; `None` if `e` is
    /// not a polynomial in them (a symbol under a function, a negative or
    /// fractional power, or a symbolic exponent).
    pub fn degree_in(&self, e: Expr, syms: &[Expr]) -> Option<u32> {
        let wanted: Vec<_> = syms.iter().filter_map(|&s| self.as_symbol(s)).collect();
        let mut memo = HashMap::new();
        self.degree(e, &wanted, &mut memo)
    }

    fn degree(
        &self,
        e: Expr,
        wanted: &[crate::Symbol],
        memo: &mut HashMap<Expr, Option<u32>>,
    ) -> Option<u32> {
        let free = self.free_slice(e);
        if !wanted.iter().any(|s| free.binary_search(s).is_ok()) {
            return Some(0);
        }
        if let Some(&d) = memo.get(&e) {
            return d;
        }
        let d = match self.node(e) {
            Node::Const(_) | Node::Float(_) => Some(0),
            Node::Sym(_) => Some(1),
            Node::Add(ts) => ts
                .iter()
                .try_fold(0u32, |acc, &t| Some(acc.max(self.degree(t, wanted, memo)?))),
            Node::Mul(fs) => fs.iter().try_fold(0u32, |acc, &f| {
                acc.checked_add(self.degree(f, wanted, memo)?)
            }),
            &Node::Pow(b, x) => {
                let n = self.num(x).and_then(Num::as_integer).filter(|n| *n >= 0)?;
                self.degree(b, wanted, memo)?
                    .checked_mul(u32::try_from(n).ok()?)
            }
            Node::Call(..) | Node::Atan2(..) | Node::Select(..) => None,
        };
        memo.insert(e, d);
        d
    }
}
