//! Straight-line programs: many outputs lowered together into a list of
//! binary operations, each computed once, in dependency order.
//!
//! Lowering applies the cost model the generated code relies on: integer
//! powers become multiplications (`x^4 = (x·x)·(x·x)`), negative powers a
//! single division, `x^(1/2)` a `sqrt`, terms with negative coefficients a
//! subtraction, a coefficient `-1` a negation and any other coefficient one
//! multiplication by a literal. The operations themselves are hash-consed
//! too, so e.g. `x·y` is shared between `x·y·z` and `x·y·w`, and a term that
//! appears once added and once subtracted is computed once.

use std::collections::{HashMap, HashSet};

use crate::context::Context;
use crate::node::{Expr, Func, Node, Symbol};
use crate::rational::Num;
use crate::subsums;

/// Operation counts of a [`Program`], matching what [`Program::emit`] writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions, subtractions and negations.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Function calls: sin, cos, sqrt, exp, atan2, powf, powi, ...
    pub call: usize,
}

impl OpCount {
    /// `add + mul + div + call`.
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.call
    }

    /// A rough latency model: a call costs about 20 additions, a division 4.
    pub fn weighted(&self) -> usize {
        self.add + self.mul + 4 * self.div + 20 * self.call
    }
}

/// A value in a program: an index into its operation list.
pub(crate) type Value = u32;

/// One operation. Operands always refer to earlier operations.
#[derive(Copy, Clone, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Op {
    Sym(Symbol),
    /// Constant as `f64` bits (not an operation; emitted inline).
    Const(u64),
    Add(Value, Value),
    Sub(Value, Value),
    Mul(Value, Value),
    Div(Value, Value),
    Neg(Value),
    Call(Func, Value),
    Atan2(Value, Value),
    Powf(Value, Value),
    Powi(Value, i32),
    /// `if test > 0 { a } else { b }`.
    Select(Value, Value, Value),
}

impl Op {
    /// The values this operation reads.
    pub(crate) fn operands(&self) -> impl Iterator<Item = Value> {
        let (a, b, c) = match *self {
            Op::Sym(_) | Op::Const(_) => (None, None, None),
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => {
                (Some(a), Some(b), None)
            }
            Op::Atan2(a, b) | Op::Powf(a, b) => (Some(a), Some(b), None),
            Op::Neg(a) | Op::Call(_, a) | Op::Powi(a, _) => (Some(a), None, None),
            Op::Select(t, a, b) => (Some(t), Some(a), Some(b)),
        };
        a.into_iter().chain(b).chain(c)
    }
}

/// Integer powers above this use `powi` instead of a multiplication chain.
const MAX_UNROLLED_POWER: u64 = 64;

/// A straight-line program computing several expressions at once.
///
/// Built from a [`Context`] and a list of outputs; only nodes reachable from
/// the outputs are lowered, shared subexpressions are computed once, and the
/// operation order is a deterministic function of the outputs (a depth-first
/// walk in output order), so emitted code is byte-identical across runs.
#[derive(Clone, Debug)]
pub struct Program {
    pub(crate) ops: Vec<Op>,
    pub(crate) outputs: Vec<Value>,
}

struct Lowering<'a> {
    cx: &'a Context,
    ops: Vec<Op>,
    dedup: HashMap<Op, Value>,
    /// Each expression's value and whether it holds the negation.
    memo: HashMap<Expr, (Value, bool)>,
    /// Sums by (added terms, subtracted terms, constant bits), sorted.
    sums: HashMap<(Vec<Value>, Vec<Value>, u64), Value>,
    /// Each sum's largest part that is a reachable sum of its own
    /// ([`subsums::bases`]): lowered, the sum starts from that part's value.
    bases: HashMap<Expr, Expr>,
}

impl Lowering<'_> {
    fn push(&mut self, op: Op) -> Value {
        // Addition and multiplication commute exactly in IEEE arithmetic, so
        // ordering their operands only improves sharing.
        // Literals go first (`0.5 * x` reads better than `x * 0.5`).
        let key = |v: Value| (!matches!(self.ops[v as usize], Op::Const(_)), v);
        let op = match op {
            Op::Add(a, b) if key(b) < key(a) => Op::Add(b, a),
            Op::Mul(a, b) if key(b) < key(a) => Op::Mul(b, a),
            other => other,
        };
        if let Some(&v) = self.dedup.get(&op) {
            return v;
        }
        let v = self.ops.len() as Value;
        self.ops.push(op);
        self.dedup.insert(op, v);
        v
    }

    fn constant(&mut self, v: f64) -> Value {
        self.push(Op::Const(v.to_bits()))
    }

    fn lower(&mut self, e: Expr) -> Value {
        match self.lower_signed(e) {
            (v, true) => self.push(Op::Neg(v)),
            (v, false) => v,
        }
    }

    /// `e` as a value and whether that value is −e. A sum whose negation was
    /// already computed (`c·d − a·b` after `a·b − c·d`, as sin(θⱼ − θᵢ) after
    /// sin(θᵢ − θⱼ)) is that value negated, and the sign travels up through
    /// products into the sum that uses them, where it becomes a subtraction
    /// instead of a negation, so the products are shared as well.
    fn lower_signed(&mut self, e: Expr) -> (Value, bool) {
        if let Some(&v) = self.memo.get(&e) {
            return v;
        }
        let cx = self.cx;
        let v = match cx.node(e) {
            Node::Const(_) | Node::Float(_) => {
                (self.constant(cx.as_f64(e).unwrap_or(f64::NAN)), false)
            }
            Node::Sym(s) => (self.push(Op::Sym(*s)), false),
            Node::Add(terms) => self.lower_sum(e, terms),
            Node::Mul(fs) => match cx.num(fs[0]) {
                Some(c) => self.lower_product(c, &fs[1..]),
                None => self.lower_product(Num::ONE, fs),
            },
            Node::Pow(..) => self.lower_product(Num::ONE, &[e]),
            &Node::Call(f, a) => {
                let a = self.lower(a);
                (self.push(Op::Call(f, a)), false)
            }
            &Node::Atan2(y, x) => {
                let y = self.lower(y);
                let x = self.lower(x);
                (self.push(Op::Atan2(y, x)), false)
            }
            &Node::Select(t, a, b) => {
                let t = self.lower(t);
                let a = self.lower(a);
                let b = self.lower(b);
                (self.push(Op::Select(t, a, b)), false)
            }
        };
        self.memo.insert(e, v);
        v
    }

    fn lower_sum(&mut self, e: Expr, terms: &[Expr]) -> (Value, bool) {
        let cx = self.cx;
        let mut constant = 0.0;
        let mut pos = Vec::new();
        let mut neg = Vec::new();
        // Start from the part that is a sum of its own, already computed or
        // computed now for this sum and any other that holds it.
        let mut held: HashSet<Expr> = HashSet::new();
        if let Some(&b) = self.bases.get(&e)
            && let Node::Add(base_terms) = cx.node(b)
        {
            held.extend(base_terms.iter());
            let (v, negated) = self.lower_signed(b);
            if negated { neg.push(v) } else { pos.push(v) }
        }
        for &t in terms {
            if held.contains(&t) {
                continue;
            }
            if let Some(n) = cx.num(t) {
                constant += n.to_f64();
                continue;
            }
            let (v, negated) = if cx.is_negative_term(t) {
                let Node::Mul(fs) = cx.node(t) else { continue };
                let c = cx.num(fs[0]).unwrap_or(Num::MINUS_ONE);
                let (v, negated) = self.lower_product(c.neg(), &fs[1..]);
                (v, !negated)
            } else {
                self.lower_signed(t)
            };
            if negated { neg.push(v) } else { pos.push(v) }
        }
        // The same sum with every sign flipped, if it was computed already.
        let key = |a: &[Value], b: &[Value], c: f64| {
            let mut a = a.to_vec();
            let mut b = b.to_vec();
            a.sort_unstable();
            b.sort_unstable();
            (a, b, (c + 0.0).to_bits())
        };
        if let Some(&v) = self.sums.get(&key(&neg, &pos, -constant)) {
            return (v, true);
        }
        let mine = key(&pos, &neg, constant);
        if let Some(&v) = self.sums.get(&mine) {
            return (v, false);
        }
        // All terms subtracted and no positive constant: the sum of the
        // subtracted terms, negated (the sign goes to the user).
        let (v, negated) = if pos.is_empty() && constant <= 0.0 && !neg.is_empty() {
            (self.build_sum(&neg, &[], -constant), true)
        } else {
            (self.build_sum(&pos, &neg, constant), false)
        };
        let stored = if negated {
            key(&neg, &pos, -constant)
        } else {
            mine
        };
        self.sums.insert(stored, v);
        (v, negated)
    }

    /// Σ pos − Σ neg + constant, `pos` non-empty or `constant` non-zero.
    fn build_sum(&mut self, pos: &[Value], neg: &[Value], mut constant: f64) -> Value {
        let mut neg = neg.iter().copied();
        let mut acc = if let Some(&p) = pos.first() {
            p
        } else if constant > 0.0 {
            // `c - a - b` rather than `-a - b + c`.
            let c = self.constant(constant);
            constant = 0.0;
            c
        } else if let Some(n) = neg.next() {
            self.push(Op::Neg(n))
        } else {
            return self.constant(constant);
        };
        for &p in pos.iter().skip(1) {
            acc = self.push(Op::Add(acc, p));
        }
        for n in neg {
            acc = self.push(Op::Sub(acc, n));
        }
        if constant > 0.0 {
            let c = self.constant(constant);
            acc = self.push(Op::Add(acc, c));
        } else if constant < 0.0 {
            let c = self.constant(-constant);
            acc = self.push(Op::Sub(acc, c));
        }
        acc
    }

    fn lower_product(&mut self, coeff: Num, factors: &[Expr]) -> (Value, bool) {
        let cx = self.cx;
        let mut num = Vec::new();
        let mut den = Vec::new();
        let mut flipped = false;
        for &f in factors {
            let Node::Pow(b, x) = *cx.node(f) else {
                let (v, negated) = self.lower_signed(f);
                flipped ^= negated;
                num.push(v);
                continue;
            };
            let base = self.lower(b);
            match cx.num(x) {
                Some(Num::Rat(r)) if r.den == 1 || r.den == 2 => {
                    let root = if r.den == 2 {
                        self.push(Op::Call(Func::Sqrt, base))
                    } else {
                        base
                    };
                    let v = self.powi(root, r.num.unsigned_abs());
                    if r.num < 0 { den.push(v) } else { num.push(v) }
                }
                Some(n) => {
                    let e = self.constant(n.abs().to_f64());
                    let v = self.push(Op::Powf(base, e));
                    if n.is_negative() {
                        den.push(v)
                    } else {
                        num.push(v)
                    }
                }
                None => {
                    let e = self.lower(x);
                    num.push(self.push(Op::Powf(base, e)));
                }
            }
        }
        let coeff = if flipped { coeff.neg() } else { coeff };
        let magnitude = coeff.abs().to_f64();
        let mut negate = false;
        let mut v = match self.chain(&num) {
            Some(t) if magnitude != 1.0 => {
                let c = self.constant(coeff.to_f64());
                self.push(Op::Mul(c, t))
            }
            Some(t) => {
                negate = coeff.is_negative();
                t
            }
            None => self.constant(coeff.to_f64()),
        };
        if let Some(d) = self.chain(&den) {
            v = self.push(Op::Div(v, d));
        }
        (v, negate)
    }

    /// Left-to-right product of `vs` (`None` if empty).
    fn chain(&mut self, vs: &[Value]) -> Option<Value> {
        let (&first, rest) = vs.split_first()?;
        Some(
            rest.iter()
                .fold(first, |acc, &v| self.push(Op::Mul(acc, v))),
        )
    }

    /// `v^n` by squaring; intermediate powers are shared through `push`.
    fn powi(&mut self, v: Value, n: u64) -> Value {
        match n {
            0 => self.constant(1.0),
            1 => v,
            n if n > MAX_UNROLLED_POWER => {
                self.push(Op::Powi(v, i32::try_from(n).unwrap_or(i32::MAX)))
            }
            n if n % 2 == 0 => {
                let h = self.powi(v, n / 2);
                self.push(Op::Mul(h, h))
            }
            n => {
                let p = self.powi(v, n - 1);
                self.push(Op::Mul(p, v))
            }
        }
    }
}

impl Program {
    /// Lower `outputs` (all from `ctx`) into one program.
    pub fn new(ctx: &Context, outputs: &[Expr]) -> Program {
        let mut lw = Lowering {
            cx: ctx,
            ops: Vec::new(),
            dedup: HashMap::new(),
            memo: HashMap::new(),
            sums: HashMap::new(),
            bases: subsums::bases(ctx, outputs),
        };
        let outs: Vec<Value> = outputs.iter().map(|&o| lw.lower(o)).collect();
        Program {
            ops: lw.ops,
            outputs: outs,
        }
        .without_dead_code()
        .with_shared_reciprocals()
    }

    /// Every divisor that divides more than once divided into 1 once, and
    /// the divisions by it made multiplications by that reciprocal: a
    /// division costs several multiplications, and a factorisation's pivot
    /// divides every entry of its column and every solve (one a/d costs what
    /// it did, within an ulp of a · (1/d)).
    fn with_shared_reciprocals(self) -> Program {
        let mut uses = vec![0usize; self.ops.len()];
        for op in &self.ops {
            if let Op::Div(_, d) = op {
                uses[*d as usize] += 1;
            }
        }
        if uses.iter().all(|&n| n < 2) {
            return self;
        }
        let mut ops: Vec<Op> = Vec::with_capacity(self.ops.len());
        let mut renumber = vec![0 as Value; self.ops.len()];
        let mut reciprocal: HashMap<Value, Value> = HashMap::new();
        let mut one = None;
        for (i, &original) in self.ops.iter().enumerate() {
            let shared = matches!(original, Op::Div(_, d) if uses[d as usize] >= 2);
            let op = match map_operands(original, |v| renumber[v as usize]) {
                Op::Div(a, d) if shared => {
                    let r = *reciprocal.entry(d).or_insert_with(|| {
                        let c = *one.get_or_insert_with(|| {
                            ops.push(Op::Const(1f64.to_bits()));
                            (ops.len() - 1) as Value
                        });
                        ops.push(Op::Div(c, d));
                        (ops.len() - 1) as Value
                    });
                    Op::Mul(a, r)
                }
                other => other,
            };
            renumber[i] = ops.len() as Value;
            ops.push(op);
        }
        let outputs = self.outputs.iter().map(|&o| renumber[o as usize]).collect();
        Program { ops, outputs }
    }

    /// Drop operations no output depends on and renumber (order preserved).
    fn without_dead_code(self) -> Program {
        let mut live = vec![false; self.ops.len()];
        for &o in &self.outputs {
            live[o as usize] = true;
        }
        for i in (0..self.ops.len()).rev() {
            if live[i] {
                for_each_operand(self.ops[i], |v| live[v as usize] = true);
            }
        }
        let mut renumber = vec![0 as Value; self.ops.len()];
        let mut ops = Vec::new();
        for (i, op) in self.ops.iter().enumerate() {
            if live[i] {
                renumber[i] = ops.len() as Value;
                ops.push(map_operands(*op, |v| renumber[v as usize]));
            }
        }
        let outputs = self.outputs.iter().map(|&o| renumber[o as usize]).collect();
        Program { ops, outputs }
    }

    /// Number of outputs.
    pub fn output_count(&self) -> usize {
        self.outputs.len()
    }

    /// Operation counts (constants and symbol reads are free).
    pub fn op_count(&self) -> OpCount {
        let mut c = OpCount::default();
        for op in &self.ops {
            match op {
                Op::Sym(_) | Op::Const(_) => {}
                Op::Add(..) | Op::Sub(..) | Op::Neg(_) => c.add += 1,
                Op::Mul(..) => c.mul += 1,
                Op::Div(..) => c.div += 1,
                Op::Call(..) | Op::Atan2(..) | Op::Powf(..) | Op::Powi(..) => c.call += 1,
                // A comparison and a branch-free choice: counted as one addition.
                Op::Select(..) => c.add += 1,
            }
        }
        c
    }

    /// The longest chain of dependent operations, each weighted by a
    /// typical latency in cycles (addition and multiplication 4, division 14,
    /// a function call 40): a lower bound on the program's time however wide
    /// the processor, beside [`Program::op_count`], which bounds it by
    /// throughput. As the emitted code fuses (where the target has FMA), a
    /// product read once, by a sum, adds no latency of its own to that sum,
    /// one product per sum.
    pub fn latency_depth(&self) -> usize {
        let mut reads = vec![0usize; self.ops.len()];
        for v in self
            .ops
            .iter()
            .flat_map(Op::operands)
            .chain(self.outputs.iter().copied())
        {
            reads[v as usize] += 1;
        }
        let mut depth = vec![0usize; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            let cost = match op {
                Op::Sym(_) | Op::Const(_) => 0,
                Op::Add(..) | Op::Sub(..) | Op::Mul(..) | Op::Neg(_) | Op::Select(..) => 4,
                Op::Div(..) => 14,
                Op::Call(..) | Op::Atan2(..) | Op::Powf(..) | Op::Powi(..) => 40,
            };
            let ready = op.operands().map(|v| depth[v as usize]).max().unwrap_or(0);
            // The best one product to fuse: the sum waits for the product's
            // operands instead of the product.
            let fused = match *op {
                Op::Add(a, b) | Op::Sub(a, b) => [(a, b), (b, a)]
                    .into_iter()
                    .filter(|&(p, _)| {
                        matches!(self.ops[p as usize], Op::Mul(..)) && reads[p as usize] == 1
                    })
                    .map(|(p, other)| (depth[p as usize] - 4).max(depth[other as usize]))
                    .min(),
                _ => None,
            };
            depth[i] = fused.unwrap_or(ready) + cost;
        }
        self.outputs
            .iter()
            .map(|&o| depth[o as usize])
            .max()
            .unwrap_or(0)
    }

    /// Run the program in `f64`; one value per output.
    pub fn eval(&self, _ctx: &Context, env: &dyn Fn(Symbol) -> f64) -> Vec<f64> {
        let mut vals: Vec<f64> = Vec::with_capacity(self.ops.len());
        for op in &self.ops {
            let g = |v: Value| vals[v as usize];
            let x = match *op {
                Op::Sym(s) => env(s),
                Op::Const(b) => f64::from_bits(b),
                Op::Add(a, b) => g(a) + g(b),
                Op::Sub(a, b) => g(a) - g(b),
                Op::Mul(a, b) => g(a) * g(b),
                Op::Div(a, b) => g(a) / g(b),
                Op::Neg(a) => -g(a),
                Op::Call(f, a) => f.apply(g(a)),
                Op::Atan2(y, x) => g(y).atan2(g(x)),
                Op::Powf(a, b) => g(a).powf(g(b)),
                Op::Powi(a, n) => g(a).powi(n),
                Op::Select(t, a, b) => {
                    if g(t) > 0.0 {
                        g(a)
                    } else {
                        g(b)
                    }
                }
            };
            vals.push(x);
        }
        self.outputs.iter().map(|&o| vals[o as usize]).collect()
    }
}

pub(crate) fn for_each_operand(op: Op, mut f: impl FnMut(Value)) {
    match op {
        Op::Sym(_) | Op::Const(_) => {}
        Op::Neg(a) | Op::Call(_, a) | Op::Powi(a, _) => f(a),
        Op::Add(a, b)
        | Op::Sub(a, b)
        | Op::Mul(a, b)
        | Op::Div(a, b)
        | Op::Atan2(a, b)
        | Op::Powf(a, b) => {
            f(a);
            f(b);
        }
        Op::Select(t, a, b) => {
            f(t);
            f(a);
            f(b);
        }
    }
}

fn map_operands(op: Op, f: impl Fn(Value) -> Value) -> Op {
    match op {
        Op::Sym(_) | Op::Const(_) => op,
        Op::Add(a, b) => Op::Add(f(a), f(b)),
        Op::Sub(a, b) => Op::Sub(f(a), f(b)),
        Op::Mul(a, b) => Op::Mul(f(a), f(b)),
        Op::Div(a, b) => Op::Div(f(a), f(b)),
        Op::Neg(a) => Op::Neg(f(a)),
        Op::Call(func, a) => Op::Call(func, f(a)),
        Op::Atan2(a, b) => Op::Atan2(f(a), f(b)),
        Op::Powf(a, b) => Op::Powf(f(a), f(b)),
        Op::Powi(a, n) => Op::Powi(f(a), n),
        Op::Select(t, a, b) => Op::Select(f(t), f(a), f(b)),
    }
}
