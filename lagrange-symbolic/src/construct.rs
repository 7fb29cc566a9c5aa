//! Smart constructors: every node enters the arena through these, already in
//! canonical form (see [`Node`]).
//!
//! They fold constants, flatten and sort n-ary sums and products, merge like
//! terms and like bases, and apply the Pythagorean identity. They deliberately
//! never distribute a product over a sum: the derivative of a product of sums
//! must stay factored, or expressions grow exponentially. The one exception
//! is an *exact* numeric multiple of a sum appearing inside a sum, which is
//! flattened (`a + 2(b + c) = a + 2b + 2c`) so that cancellations are found;
//! that is linear in size. A float multiple stays one product: its
//! cancellations would not be exact anyway, and a float coefficient (a mass, a
//! link length) times a sum of k terms costs one multiplication where its k
//! distributed copies cost k (the recursive dynamics' I a, m v and d × f).

use std::collections::HashMap;

use crate::context::Context;
use crate::node::{Expr, Func, Node};
use crate::rational::{Num, Rational};

/// Accumulates `coefficient × monomial` pairs, merging equal monomials while
/// keeping first-seen order (deterministic, independent of hashing).
#[derive(Default)]
struct TermSet {
    constant: Option<Num>,
    order: Vec<Expr>,
    coeffs: HashMap<Expr, Num>,
}

impl TermSet {
    fn push(&mut self, coeff: Num, monomial: Expr) {
        match self.coeffs.get_mut(&monomial) {
            Some(c) => *c = c.add(coeff),
            None => {
                self.order.push(monomial);
                self.coeffs.insert(monomial, coeff);
            }
        }
    }

    fn push_constant(&mut self, c: Num) {
        self.constant = Some(self.constant.map_or(c, |k| k.add(c)));
    }

    fn into_terms(self) -> (Num, Vec<(Num, Expr)>) {
        let terms = self
            .order
            .iter()
            .map(|m| (self.coeffs[m], *m))
            .filter(|(c, _)| !c.is_zero())
            .collect();
        (self.constant.unwrap_or(Num::ZERO), terms)
    }
}

impl Context {
    /// `a + b`.
    pub fn add(&mut self, a: Expr, b: Expr) -> Expr {
        self.sum(&[a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Expr, b: Expr) -> Expr {
        let nb = self.neg(b);
        self.sum(&[a, nb])
    }

    /// `-a`.
    pub fn neg(&mut self, a: Expr) -> Expr {
        self.scale(Num::MINUS_ONE, a)
    }

    /// `c · e` for a numeric `c`.
    pub(crate) fn scale(&mut self, c: Num, e: Expr) -> Expr {
        let c = self.num_expr(c);
        self.product(&[c, e])
    }

    /// Split a term into its numeric coefficient and the rest (the monomial).
    /// `3·x·y -> (3, x·y)`, `x -> (1, x)`, `5 -> (5, 1)`.
    pub(crate) fn split_coeff(&mut self, e: Expr) -> (Num, Expr) {
        if let Some(n) = self.num(e) {
            return (n, self.int(1));
        }
        if let Node::Mul(children) = self.node(e)
            && let Some(c) = self.num(children[0])
        {
            let rest: Vec<Expr> = children[1..].to_vec();
            let m = if rest.len() == 1 {
                rest[0]
            } else {
                self.intern(Node::Mul(rest.into()))
            };
            return (c, m);
        }
        (Num::ONE, e)
    }

    /// Whether a term would print with a leading minus (negative coefficient).
    pub(crate) fn is_negative_term(&self, e: Expr) -> bool {
        if let Some(n) = self.num(e) {
            return n.is_negative();
        }
        if let Node::Mul(children) = self.node(e) {
            return self.num(children[0]).is_some_and(Num::is_negative);
        }
        false
    }

    fn accumulate(&mut self, set: &mut TermSet, scale: Num, e: Expr) {
        if let Some(n) = self.num(e) {
            set.push_constant(scale.mul(n));
            return;
        }
        if let Node::Add(children) = self.node(e) {
            for c in children.clone() {
                self.accumulate(set, scale, c);
            }
            return;
        }
        let (c, m) = self.split_coeff(e);
        // Exact multiples only (see the module docs): a float one stays a
        // product.
        let exact = matches!(c, Num::Rat(r) if r != Rational::ONE);
        if exact && matches!(self.node(m), Node::Add(_)) {
            self.accumulate(set, scale.mul(c), m);
            return;
        }
        set.push(scale.mul(c), m);
    }

    /// The sum of `terms`, canonicalised.
    pub fn sum(&mut self, terms: &[Expr]) -> Expr {
        let mut set = TermSet::default();
        for &t in terms {
            self.accumulate(&mut set, Num::ONE, t);
        }
        let (mut constant, mut items) = set.into_terms();
        // Each successful Pythagorean rewrite removes a term, so this loop
        // runs at most `items.len()` times.
        while let Some(rewritten) = self.pythagorean(&items) {
            let mut set = TermSet::default();
            set.push_constant(constant);
            for (c, m) in rewritten {
                self.accumulate(&mut set, c, m);
            }
            (constant, items) = set.into_terms();
        }
        let mut out: Vec<Expr> = items
            .into_iter()
            .map(|(c, m)| self.with_coeff(c, m))
            .collect();
        out.sort_unstable();
        if !constant.is_zero() {
            out.insert(0, self.num_expr(constant));
        }
        match out.len() {
            0 => self.int(0),
            1 => out[0],
            _ => self.intern(Node::Add(out.into())),
        }
    }

    /// `c · m` for a monomial `m` (no coefficient, not a sum), built directly.
    pub(crate) fn with_coeff(&mut self, c: Num, m: Expr) -> Expr {
        if c.is_one() {
            return m;
        }
        if c.is_zero() {
            return self.int(0);
        }
        if let Some(n) = self.num(m) {
            return self.num_expr(c.mul(n));
        }
        let ce = self.num_expr(c);
        let children: Vec<Expr> = match self.node(m) {
            Node::Mul(fs) => std::iter::once(ce).chain(fs.iter().copied()).collect(),
            _ => vec![ce, m],
        };
        self.intern(Node::Mul(children.into()))
    }

    /// `a · b`.
    pub fn mul(&mut self, a: Expr, b: Expr) -> Expr {
        self.product(&[a, b])
    }

    /// `a / b`.
    pub fn div(&mut self, a: Expr, b: Expr) -> Expr {
        let m1 = self.int(-1);
        let inv = self.pow(b, m1);
        self.product(&[a, inv])
    }

    /// Split a factor into base and exponent: `x^e -> (x, e)`, `x -> (x, 1)`.
    pub(crate) fn base_exp(&mut self, f: Expr) -> (Expr, Expr) {
        match *self.node(f) {
            Node::Pow(b, e) => (b, e),
            _ => (f, self.int(1)),
        }
    }

    fn flatten_factors(
        &mut self,
        e: Expr,
        coeff: &mut Num,
        bases: &mut Vec<Expr>,
        exps: &mut HashMap<Expr, Vec<Expr>>,
    ) {
        if let Some(n) = self.num(e) {
            *coeff = coeff.mul(n);
            return;
        }
        if let Node::Mul(children) = self.node(e) {
            for c in children.clone() {
                self.flatten_factors(c, coeff, bases, exps);
            }
            return;
        }
        let (b, x) = self.base_exp(e);
        exps.entry(b)
            .or_insert_with(|| {
                bases.push(b);
                Vec::new()
            })
            .push(x);
    }

    /// The product of `factors`, canonicalised.
    pub fn product(&mut self, factors: &[Expr]) -> Expr {
        let mut coeff = Num::ONE;
        let mut bases = Vec::new();
        let mut exps: HashMap<Expr, Vec<Expr>> = HashMap::new();
        for &f in factors {
            self.flatten_factors(f, &mut coeff, &mut bases, &mut exps);
        }
        if coeff.is_zero() {
            return self.int(0);
        }
        let mut out = Vec::with_capacity(bases.len());
        let mut reflatten = Vec::new();
        for b in bases {
            let list = &exps[&b];
            let x = if list.len() == 1 {
                list[0]
            } else {
                self.sum(&list.clone())
            };
            let f = self.pow(b, x);
            if let Some(n) = self.num(f) {
                coeff = coeff.mul(n);
            } else if matches!(self.node(f), Node::Mul(_)) {
                // e.g. sqrt(x·y)·sqrt(x·y) = x·y: merge its factors again.
                reflatten.push(f);
            } else {
                out.push(f);
            }
        }
        if !reflatten.is_empty() {
            let c = self.num_expr(coeff);
            out.push(c);
            out.extend(reflatten);
            return self.product(&out);
        }
        if coeff.is_zero() {
            return self.int(0);
        }
        out.sort_unstable();
        if out.is_empty() {
            return self.num_expr(coeff);
        }
        if out.len() == 1 && coeff.is_one() {
            return out[0];
        }
        if !coeff.is_one() {
            out.insert(0, self.num_expr(coeff));
        }
        self.intern(Node::Mul(out.into()))
    }

    /// `base ^ exp`.
    pub fn pow(&mut self, base: Expr, exp: Expr) -> Expr {
        let one = self.int(1);
        if exp == one {
            return base;
        }
        if let Some(x) = self.num(exp) {
            if x.is_zero() {
                return one;
            }
            if let Some(b) = self.num(base)
                && let Some(v) = b.pow(x)
            {
                return self.num_expr(v);
            }
            // (b^e)^n = b^(e·n) and (a·b)^n = a^n·b^n hold for integral n only
            // ((x^2)^(1/2) = |x|).
            if x.as_integer().is_some() {
                match self.node(base).clone() {
                    Node::Pow(b, e) => {
                        let ex = self.mul(e, exp);
                        return self.pow(b, ex);
                    }
                    Node::Mul(children) => {
                        let powered: Vec<Expr> =
                            children.iter().map(|&c| self.pow(c, exp)).collect();
                        return self.product(&powered);
                    }
                    _ => {}
                }
            }
        }
        if base == one {
            return one;
        }
        self.intern(Node::Pow(base, exp))
    }

    /// `base ^ n`.
    pub fn powi(&mut self, base: Expr, n: i64) -> Expr {
        let e = self.int(n);
        self.pow(base, e)
    }

    /// `sqrt(a)`, stored as `a^(1/2)`.
    pub fn sqrt(&mut self, a: Expr) -> Expr {
        let half = self.rational(1, 2);
        self.pow(a, half)
    }

    /// `sin(a)`.
    pub fn sin(&mut self, a: Expr) -> Expr {
        self.func(Func::Sin, a)
    }

    /// `cos(a)`.
    pub fn cos(&mut self, a: Expr) -> Expr {
        self.func(Func::Cos, a)
    }

    /// `f(arg)`, with constant folding at exact special values, float
    /// evaluation of float arguments and parity (`sin(-x) = -sin(x)`).
    pub fn func(&mut self, f: Func, arg: Expr) -> Expr {
        if f == Func::Sqrt {
            return self.sqrt(arg);
        }
        if let Some(n) = self.num(arg) {
            if let Num::Float(v) = n {
                return self.float(f.apply(v));
            }
            if let Some(v) = exact_value(f, n) {
                return self.num_expr(v);
            }
        }
        if self.is_negative_term(arg) {
            let (c, m) = self.split_coeff(arg);
            let pos = self.with_coeff(c.neg(), m);
            if f.is_odd() {
                let inner = self.func(f, pos);
                return self.neg(inner);
            }
            if f.is_even() {
                return self.func(f, pos);
            }
        }
        match (f, self.node(arg)) {
            (Func::Ln, &Node::Call(Func::Exp, x)) => return x,
            (Func::Abs, &Node::Call(Func::Abs, _)) => return arg,
            _ => {}
        }
        self.intern(Node::Call(f, arg))
    }

    /// `atan2(y, x)`.
    pub fn atan2(&mut self, y: Expr, x: Expr) -> Expr {
        if let (Some(a), Some(b)) = (self.num(y), self.num(x)) {
            if a.is_zero() && !b.is_negative() && !b.is_zero() {
                return self.int(0);
            }
            if matches!(a, Num::Float(_)) || matches!(b, Num::Float(_)) {
                return self.float(a.to_f64().atan2(b.to_f64()));
            }
        }
        self.intern(Node::Atan2(y, x))
    }

    /// `if test > 0 { positive } else { otherwise }`. Folds a constant test and
    /// equal branches.
    pub fn select(&mut self, test: Expr, positive: Expr, otherwise: Expr) -> Expr {
        if positive == otherwise {
            return positive;
        }
        if let Some(t) = self.num(test) {
            return if t.to_f64() > 0.0 {
                positive
            } else {
                otherwise
            };
        }
        self.intern(Node::Select(test, positive, otherwise))
    }

    /// `a > b`, as the test of a [`select`](Self::select): `a − b`.
    pub fn greater(&mut self, a: Expr, b: Expr) -> Expr {
        self.sub(a, b)
    }

    /// sign(x): 1, 0 or −1 (0 at 0).
    pub fn sign(&mut self, x: Expr) -> Expr {
        let one = self.int(1);
        let zero = self.int(0);
        let minus = self.int(-1);
        let neg = self.neg(x);
        let below = self.select(neg, minus, zero);
        self.select(x, one, below)
    }

    /// min(a, b) (a when equal).
    pub fn min(&mut self, a: Expr, b: Expr) -> Expr {
        let t = self.greater(a, b);
        self.select(t, b, a)
    }

    /// max(a, b) (a when equal).
    pub fn max(&mut self, a: Expr, b: Expr) -> Expr {
        let t = self.greater(b, a);
        self.select(t, b, a)
    }
}

impl Context {
    /// Rebuild `e` through the smart constructors after mapping each child
    /// with `f`; returns `e` itself when no child changed (it is canonical).
    pub(crate) fn rebuild(&mut self, e: Expr, mut f: impl FnMut(&mut Self, Expr) -> Expr) -> Expr {
        match self.node(e).clone() {
            Node::Const(_) | Node::Float(_) | Node::Sym(_) => e,
            Node::Add(cs) | Node::Mul(cs) => {
                let mapped: Vec<Expr> = cs.iter().map(|&c| f(self, c)).collect();
                if *mapped == *cs {
                    e
                } else if matches!(self.node(e), Node::Add(_)) {
                    self.sum(&mapped)
                } else {
                    self.product(&mapped)
                }
            }
            Node::Pow(b, x) => {
                let nb = f(self, b);
                let nx = f(self, x);
                if (nb, nx) == (b, x) {
                    e
                } else {
                    self.pow(nb, nx)
                }
            }
            Node::Call(func, a) => {
                let na = f(self, a);
                if na == a { e } else { self.func(func, na) }
            }
            Node::Atan2(y, x) => {
                let ny = f(self, y);
                let nx = f(self, x);
                if (ny, nx) == (y, x) {
                    e
                } else {
                    self.atan2(ny, nx)
                }
            }
            Node::Select(t, a, b) => {
                let nt = f(self, t);
                let na = f(self, a);
                let nb = f(self, b);
                if (nt, na, nb) == (t, a, b) {
                    e
                } else {
                    self.select(nt, na, nb)
                }
            }
        }
    }
}

/// Exactly known values of `f` at rational points (only the trivial ones;
/// anything else stays symbolic so no precision is lost).
fn exact_value(f: Func, n: Num) -> Option<Num> {
    let zero = n.is_zero();
    let one = n.is_one();
    match f {
        Func::Sin | Func::Tan | Func::Asin | Func::Atan | Func::Sinh | Func::Tanh if zero => {
            Some(Num::ZERO)
        }
        Func::Cos | Func::Cosh | Func::Exp if zero => Some(Num::ONE),
        Func::Ln | Func::Acos if one => Some(Num::ZERO),
        Func::Abs => Some(n.abs()),
        _ => None,
    }
}

/// Convenience used by several modules.
pub(crate) fn rat(n: i64, d: i64) -> Num {
    Rational::new(n, d).map_or(Num::float(n as f64 / d as f64), Num::Rat)
}
