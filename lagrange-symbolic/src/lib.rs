//! The expression engine of `lagrange`.
//!
//! A [`Context`] is an arena of hash-consed expression nodes; an [`Expr`] is
//! an id into it. Smart constructors keep every node in a canonical form
//! (exact rational constants, flattened and sorted sums and products, like
//! terms merged, `sin²+cos²=1`) without ever distributing products over
//! sums, so derivatives of large mechanical expressions stay compact.
//!
//! On top of the arena sit differentiation ([`Context::diff`],
//! [`Context::time_derivative`]), rewriting ([`Context::expand_trig`],
//! [`Context::collect`], [`Context::simplify`]), evaluation, text and LaTeX
//! display, and [`Program`]: a straight-line program over many outputs that
//! computes every shared subexpression once and emits Rust tokens with a
//! cost model tuned for generated mechanics code.
//!
//! ```
//! use lagrange_symbolic::Context;
//! let mut cx = Context::new();
//! let (theta, l) = (cx.coordinate("theta"), cx.parameter("l"));
//! let s = cx.sin(theta);
//! let x = cx.mul(l, s);
//! let v = cx.time_derivative(x);
//! assert_eq!(cx.display(v), "l*dot(theta)*cos(theta)");
//! ```

#![warn(missing_docs)]

mod collect;
mod construct;
mod context;
mod diff;
mod display;
mod emit;
mod eval;
mod fold;
mod hoist;
mod listing;
mod node;
mod program;
mod rational;
mod reduce;
mod subsums;
mod trig;

pub use context::Context;
pub use emit::{Chunked, EmitConfig};
pub use hoist::Hoisted;
pub use listing::ListingStyle;
pub use node::{Expr, Func, Node, Symbol, SymbolKind};
pub use program::{OpCount, Program};
pub use rational::Rational;
