//! Handles (`Expr`, `Symbol`) and the node representation stored in the arena.

use crate::rational::Rational;

/// An expression: an id into a [`Context`](crate::Context) arena.
///
/// Because the arena hash-conses, two `Expr`s from the same context are equal
/// exactly when the expressions are structurally equal (after the smart
/// constructors' canonicalisation). Children always have smaller ids than
/// their parents, so id order is a topological order.
#[derive(Copy, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Expr(pub(crate) u32);

impl Expr {
    /// The position of this node in its context's arena.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A symbol: an id into the context's symbol table.
#[derive(Copy, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Symbol(pub(crate) u32);

impl Symbol {
    /// The position of this symbol in its context's symbol table.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The role a symbol plays; indices count declarations of that role.
#[derive(Copy, Clone, PartialEq, Eq, Hash, Debug)]
pub enum SymbolKind {
    /// Generalized coordinate `q_i`.
    Coordinate(usize),
    /// Generalized velocity `q̇_i` (declared together with `q_i`).
    Velocity(usize),
    /// Generalized acceleration `q̈_i` (declared together with `q_i`).
    Acceleration(usize),
    /// Time `t`.
    Time,
    /// Physical parameter (a field of the user's struct).
    Parameter(usize),
    /// Input signal `u_i` supplied at run time (a force, a torque, a set-point).
    /// Its time derivative is unknown, so [`Context::time_derivative`]
    /// treats it as having no rate: an input must not reach an expression
    /// that is differentiated in time.
    ///
    /// [`Context::time_derivative`]: crate::Context::time_derivative
    Input(usize),
    /// Any other symbol (scratch variables, multipliers, ...).
    Free,
}

/// Elementary functions of one argument. `atan2` and powers are separate
/// nodes; `Sqrt` is accepted by [`Context::func`](crate::Context::func) but
/// stored as the power `x^(1/2)` so that `sqrt(x)^2 = x` simplifies.
#[derive(Copy, Clone, PartialEq, Eq, Hash, Debug)]
pub enum Func {
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
    /// Arc sine.
    Asin,
    /// Arc cosine.
    Acos,
    /// Arc tangent.
    Atan,
    /// Hyperbolic sine.
    Sinh,
    /// Hyperbolic cosine.
    Cosh,
    /// Hyperbolic tangent.
    Tanh,
    /// Natural exponential.
    Exp,
    /// Natural logarithm.
    Ln,
    /// Square root.
    Sqrt,
    /// Absolute value.
    Abs,
}

impl Func {
    /// The function's name as used in text display and in emitted code
    /// (`#function::name(x)`).
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Sqrt => "sqrt",
            Func::Abs => "abs",
        }
    }

    /// Evaluate in `f64`.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Sqrt => x.sqrt(),
            Func::Abs => x.abs(),
        }
    }

    /// `f(-x) = -f(x)`.
    pub(crate) fn is_odd(self) -> bool {
        matches!(
            self,
            Func::Sin | Func::Tan | Func::Asin | Func::Atan | Func::Sinh | Func::Tanh
        )
    }

    /// `f(-x) = f(x)`.
    pub(crate) fn is_even(self) -> bool {
        matches!(self, Func::Cos | Func::Cosh | Func::Abs)
    }
}

/// One node of the expression DAG, as stored in the arena.
///
/// Canonical forms maintained by the smart constructors:
/// - `Add`: at least two children, the numeric constant (if nonzero) first,
///   the other terms sorted by id, no two terms differing only by their
///   numeric coefficient, no `Add` child.
/// - `Mul`: at least two children (or a coefficient and one factor), the
///   numeric coefficient (if not one) first, then factors sorted by id with
///   pairwise distinct bases, no `Mul` or numeric factor.
/// - `Pow`: exponent not 0 or 1.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// Exact rational constant.
    Const(Rational),
    /// Float constant (bit pattern) that is not a small exact rational.
    Float(u64),
    /// A symbol.
    Sym(Symbol),
    /// n-ary sum.
    Add(Box<[Expr]>),
    /// n-ary product.
    Mul(Box<[Expr]>),
    /// `base ^ exponent`.
    Pow(Expr, Expr),
    /// `f(arg)`.
    Call(Func, Expr),
    /// `atan2(y, x)`.
    Atan2(Expr, Expr),
    /// `if test > 0 { positive } else { otherwise }`: the one piecewise form;
    /// comparisons, `sign`, `min`, `max` and `clamp` are built from it.
    Select(Expr, Expr, Expr),
}

impl Node {
    /// The direct children, in stored order.
    pub fn children(&self) -> Vec<Expr> {
        let mut out = Vec::new();
        self.for_each_child(|c| out.push(c));
        out
    }

    /// Call `f` on each direct child, in stored order, without allocating.
    pub fn for_each_child(&self, mut f: impl FnMut(Expr)) {
        match self {
            Node::Const(_) | Node::Float(_) | Node::Sym(_) => {}
            Node::Add(c) | Node::Mul(c) => c.iter().copied().for_each(f),
            Node::Pow(a, b) | Node::Atan2(a, b) => {
                f(*a);
                f(*b);
            }
            Node::Call(_, a) => f(*a),
            Node::Select(t, a, b) => {
                f(*t);
                f(*a);
                f(*b);
            }
        }
    }
}
