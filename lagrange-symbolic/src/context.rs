//! The arena: hash-consed nodes, the symbol table, constants and queries.

use std::collections::{BTreeSet, HashMap};
use std::sync::Arc;

use crate::node::{Expr, Node, Symbol, SymbolKind};
use crate::rational::{Num, Rational};

#[derive(Clone)]
struct SymbolInfo {
    name: String,
    kind: SymbolKind,
    expr: Expr,
}

/// The three symbols that belong to one generalized coordinate.
#[derive(Copy, Clone)]
struct CoordinateSymbols {
    q: Expr,
    dq: Expr,
    ddq: Expr,
}

/// The expression arena. Every expression lives here; [`Expr`] is an id.
///
/// Nodes are hash-consed: constructing a structurally equal node twice yields
/// the same id, so common subexpressions are shared for free and equality is
/// an integer comparison. Alongside each node the arena keeps its sorted set of
/// free symbols, which makes `depends_on` a binary search and lets every
/// traversal skip subtrees that cannot matter.
#[derive(Clone)]
pub struct Context {
    nodes: Vec<Node>,
    free: Vec<Arc<[Symbol]>>,
    interner: HashMap<Node, Expr>,
    symbols: Vec<SymbolInfo>,
    coords: Vec<CoordinateSymbols>,
    params: Vec<Expr>,
    inputs: Vec<Expr>,
    time: Option<Expr>,
    pub(crate) diff_memo: HashMap<(Expr, Expr), Expr>,
    pub(crate) trig_memo: HashMap<Expr, Expr>,
    pub(crate) collect_memo: HashMap<Expr, Expr>,
    pub(crate) simplify_memo: HashMap<Expr, Expr>,
}

impl Default for Context {
    fn default() -> Self {
        Self::new()
    }
}

impl Context {
    /// An empty context.
    pub fn new() -> Self {
        Context {
            nodes: Vec::new(),
            free: Vec::new(),
            interner: HashMap::new(),
            symbols: Vec::new(),
            coords: Vec::new(),
            params: Vec::new(),
            inputs: Vec::new(),
            time: None,
            diff_memo: HashMap::new(),
            trig_memo: HashMap::new(),
            collect_memo: HashMap::new(),
            simplify_memo: HashMap::new(),
        }
    }

    /// The node behind an expression.
    pub fn node(&self, e: Expr) -> &Node {
        &self.nodes[e.index()]
    }

    /// Number of nodes in the arena (all expressions ever built).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the arena is empty.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Store `node` unless an equal node exists. Callers guarantee canonical
    /// form; this is the only place that grows the arena.
    pub(crate) fn intern(&mut self, node: Node) -> Expr {
        if let Some(&e) = self.interner.get(&node) {
            return e;
        }
        let free = match &node {
            Node::Sym(s) => Arc::from([*s]),
            _ => self.union_free(&node),
        };
        let e =
            Expr(u32::try_from(self.nodes.len()).expect("expression arena exceeds u32::MAX nodes"));
        self.nodes.push(node.clone());
        self.free.push(free);
        self.interner.insert(node, e);
        e
    }

    fn union_free(&self, node: &Node) -> Arc<[Symbol]> {
        let mut best: Option<&Arc<[Symbol]>> = None;
        let mut all: Vec<Symbol> = Vec::new();
        let mut distinct = 0;
        node.for_each_child(|c| {
            let f = &self.free[c.index()];
            if f.is_empty() {
                return;
            }
            distinct += 1;
            if best.is_none_or(|b| f.len() > b.len()) {
                best = Some(f);
            }
            all.extend_from_slice(f);
        });
        // Reuse the largest child's set when it already covers everything,
        // which is the common case and keeps memory linear in practice.
        all.sort_unstable();
        all.dedup();
        match best {
            Some(b) if distinct == 1 || b.len() == all.len() => b.clone(),
            _ => Arc::from(all),
        }
    }

    fn new_symbol(&mut self, name: &str, kind: SymbolKind) -> Expr {
        let s = Symbol(u32::try_from(self.symbols.len()).expect("too many symbols"));
        let expr = self.intern(Node::Sym(s));
        self.symbols.push(SymbolInfo {
            name: name.to_owned(),
            kind,
            expr,
        });
        expr
    }

    fn find_symbol(&self, name: &str, matches: impl Fn(SymbolKind) -> bool) -> Option<Expr> {
        self.symbols
            .iter()
            .find(|s| s.name == name && matches(s.kind))
            .map(|s| s.expr)
    }

    /// Declare (or look up) the generalized coordinate `name`; this also
    /// declares its velocity `dot(name)` and acceleration `ddot(name)`.
    /// Indices follow declaration order.
    pub fn coordinate(&mut self, name: &str) -> Expr {
        self.coordinate_with_rates(name, &format!("dot({name})"), &format!("ddot({name})"))
    }

    /// Declare (or look up) the generalized coordinate `name` whose velocity
    /// and acceleration are shown as `velocity` and `acceleration`: a chart
    /// coordinate whose rate has a name of its own (a free orientation's
    /// rotation vector `turn.θx`, whose rate at the chart's centre is the
    /// angular velocity `turn.wx`, and its rate `dot(turn.wx)`).
    pub fn coordinate_with_rates(
        &mut self,
        name: &str,
        velocity: &str,
        acceleration: &str,
    ) -> Expr {
        if let Some(e) = self.find_symbol(name, |k| matches!(k, SymbolKind::Coordinate(_))) {
            return e;
        }
        let i = self.coords.len();
        let q = self.new_symbol(name, SymbolKind::Coordinate(i));
        let dq = self.new_symbol(velocity, SymbolKind::Velocity(i));
        let ddq = self.new_symbol(acceleration, SymbolKind::Acceleration(i));
        self.coords.push(CoordinateSymbols { q, dq, ddq });
        q
    }

    fn coordinate_index(&self, e: Expr) -> Option<usize> {
        match self.symbol_kind(self.as_symbol(e)?) {
            SymbolKind::Coordinate(i) => Some(i),
            _ => None,
        }
    }

    /// The velocity `q̇` of a coordinate `q`; `None` if `coordinate` is not one.
    pub fn velocity(&self, coordinate: Expr) -> Option<Expr> {
        Some(self.coords[self.coordinate_index(coordinate)?].dq)
    }

    /// The acceleration `q̈` of a coordinate `q`; `None` if `coordinate` is not one.
    pub fn acceleration(&self, coordinate: Expr) -> Option<Expr> {
        Some(self.coords[self.coordinate_index(coordinate)?].ddq)
    }

    /// All coordinates in declaration order.
    pub fn coordinates(&self) -> Vec<Expr> {
        self.coords.iter().map(|c| c.q).collect()
    }

    /// All velocities, in coordinate order.
    pub fn velocities(&self) -> Vec<Expr> {
        self.coords.iter().map(|c| c.dq).collect()
    }

    /// All accelerations, in coordinate order.
    pub fn accelerations(&self) -> Vec<Expr> {
        self.coords.iter().map(|c| c.ddq).collect()
    }

    /// The time symbol `t` (created on first use).
    pub fn time(&mut self) -> Expr {
        if let Some(t) = self.time {
            return t;
        }
        let t = self.new_symbol("t", SymbolKind::Time);
        self.time = Some(t);
        t
    }

    /// Declare (or look up) the parameter `name`; indices follow declaration order.
    pub fn parameter(&mut self, name: &str) -> Expr {
        if let Some(e) = self.find_symbol(name, |k| matches!(k, SymbolKind::Parameter(_))) {
            return e;
        }
        let e = self.new_symbol(name, SymbolKind::Parameter(self.params.len()));
        self.params.push(e);
        e
    }

    /// All parameters in declaration order.
    pub fn parameters(&self) -> Vec<Expr> {
        self.params.clone()
    }

    /// Declare (or look up) the input `name`, a signal supplied at run time;
    /// indices follow declaration order. Inputs have no known rate: see
    /// [`time_derivative`](Self::time_derivative).
    pub fn input(&mut self, name: &str) -> Expr {
        if let Some(e) = self.find_symbol(name, |k| matches!(k, SymbolKind::Input(_))) {
            return e;
        }
        let e = self.new_symbol(name, SymbolKind::Input(self.inputs.len()));
        self.inputs.push(e);
        e
    }

    /// All inputs in declaration order.
    pub fn inputs(&self) -> Vec<Expr> {
        self.inputs.clone()
    }

    /// Declare (or look up) a free symbol `name`.
    pub fn free_symbol(&mut self, name: &str) -> Expr {
        if let Some(e) = self.find_symbol(name, |k| k == SymbolKind::Free) {
            return e;
        }
        self.new_symbol(name, SymbolKind::Free)
    }

    /// The symbol `e` is, if it is a bare symbol.
    pub fn as_symbol(&self, e: Expr) -> Option<Symbol> {
        match self.node(e) {
            Node::Sym(s) => Some(*s),
            _ => None,
        }
    }

    /// The expression of a symbol.
    pub fn symbol_expr(&self, s: Symbol) -> Expr {
        self.symbols[s.index()].expr
    }

    /// A symbol's name (`dot(theta)` for velocities).
    pub fn symbol_name(&self, s: Symbol) -> &str {
        &self.symbols[s.index()].name
    }

    /// A symbol's role.
    pub fn symbol_kind(&self, s: Symbol) -> SymbolKind {
        self.symbols[s.index()].kind
    }

    /// The integer constant `v`.
    pub fn int(&mut self, v: i64) -> Expr {
        self.intern(Node::Const(Rational::integer(v)))
    }

    /// The rational constant `num / den` (`den == 0` gives a float ±inf/NaN).
    pub fn rational(&mut self, num: i64, den: i64) -> Expr {
        match Rational::new(num, den) {
            Some(r) => self.intern(Node::Const(r)),
            None => self.float(num as f64 / den as f64),
        }
    }

    /// A float constant; exact small dyadic values (`0.5`, `2.0`) become rationals.
    pub fn float(&mut self, v: f64) -> Expr {
        self.num_expr(Num::float(v))
    }

    /// The constant zero.
    pub fn zero(&mut self) -> Expr {
        self.int(0)
    }

    /// The constant one.
    pub fn one(&mut self) -> Expr {
        self.int(1)
    }

    pub(crate) fn num_expr(&mut self, n: Num) -> Expr {
        match n {
            Num::Rat(r) => self.intern(Node::Const(r)),
            Num::Float(v) => match Rational::from_f64(v) {
                Some(r) => self.intern(Node::Const(r)),
                None => self.intern(Node::Float(v.to_bits())),
            },
        }
    }

    /// The numeric value of a constant node.
    pub(crate) fn num(&self, e: Expr) -> Option<Num> {
        match self.node(e) {
            Node::Const(r) => Some(Num::Rat(*r)),
            Node::Float(b) => Some(Num::Float(f64::from_bits(*b))),
            _ => None,
        }
    }

    /// The exact value of a rational constant.
    pub fn as_rational(&self, e: Expr) -> Option<Rational> {
        match self.node(e) {
            Node::Const(r) => Some(*r),
            _ => None,
        }
    }

    /// The value of any numeric constant (rational or float).
    pub fn as_f64(&self, e: Expr) -> Option<f64> {
        self.num(e).map(Num::to_f64)
    }

    /// Whether `e` is the constant zero.
    pub fn is_zero(&self, e: Expr) -> bool {
        self.as_rational(e) == Some(Rational::ZERO)
    }

    /// Whether `e` contains the symbol `sym` (a symbol expression). O(log n).
    pub fn depends_on(&self, e: Expr, sym: Expr) -> bool {
        match self.as_symbol(sym) {
            Some(s) => self.free[e.index()].binary_search(&s).is_ok(),
            None => false,
        }
    }

    /// Whether `e` contains any symbol at all.
    pub fn is_constant(&self, e: Expr) -> bool {
        self.free[e.index()].is_empty()
    }

    /// The symbols `e` contains.
    pub fn free_symbols(&self, e: Expr) -> BTreeSet<Symbol> {
        self.free[e.index()].iter().copied().collect()
    }

    pub(crate) fn free_slice(&self, e: Expr) -> &[Symbol] {
        &self.free[e.index()]
    }

    /// Number of distinct nodes reachable from `e` (the DAG size).
    pub fn node_count(&self, e: Expr) -> usize {
        let mut seen = vec![false; e.index() + 1];
        let mut stack = vec![e];
        let mut count = 0;
        while let Some(x) = stack.pop() {
            if std::mem::replace(&mut seen[x.index()], true) {
                continue;
            }
            count += 1;
            self.node(x).for_each_child(|c| stack.push(c));
        }
        count
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_bring_velocity_and_acceleration() {
        let mut cx = Context::new();
        let a = cx.coordinate("theta");
        let b = cx.coordinate("phi");
        assert_eq!(cx.coordinate("theta"), a);
        let da = cx.velocity(a).unwrap();
        assert_eq!(cx.symbol_name(cx.as_symbol(da).unwrap()), "dot(theta)");
        assert_eq!(
            cx.symbol_kind(cx.as_symbol(b).unwrap()),
            SymbolKind::Coordinate(1)
        );
        let ddb = cx.acceleration(b).unwrap();
        assert_eq!(
            cx.symbol_kind(cx.as_symbol(ddb).unwrap()),
            SymbolKind::Acceleration(1)
        );
        assert_eq!(cx.velocities(), vec![da, cx.velocity(b).unwrap()]);
        assert_eq!(cx.velocity(da), None);
        let t = cx.time();
        assert_eq!(cx.time(), t);
        let m = cx.parameter("m");
        assert_eq!(
            cx.symbol_kind(cx.as_symbol(m).unwrap()),
            SymbolKind::Parameter(0)
        );
        assert_ne!(cx.free_symbol("m"), m);
        let u = cx.input("u");
        assert_eq!(cx.input("u"), u);
        assert_eq!(
            cx.symbol_kind(cx.as_symbol(u).unwrap()),
            SymbolKind::Input(0)
        );
        assert_eq!(cx.inputs(), vec![u]);
        assert_ne!(cx.parameter("u"), u);
        // No rate: d/dt (u q) = u q̇, not u q̇ + u̇ q.
        let uq = cx.mul(u, a);
        let d = cx.time_derivative(uq);
        assert_eq!(d, cx.mul(u, da));
    }

    #[test]
    fn constants() {
        let mut cx = Context::new();
        assert_eq!(cx.float(0.5), cx.rational(2, 4));
        assert_eq!(cx.float(3.0), cx.int(3));
        let tenth = cx.float(0.1);
        assert!(cx.as_rational(tenth).is_none());
        let zero = cx.zero();
        assert!(cx.is_zero(zero));
        let inf = cx.rational(1, 0);
        assert_eq!(cx.as_f64(inf), Some(f64::INFINITY));
    }
}
