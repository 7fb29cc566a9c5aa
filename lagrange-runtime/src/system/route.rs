//! Which derivation a system's M and h come from ([`Route`]).

/// How a system's mass matrix M and bias h are computed
/// ([`Lagrangian::ROUTE`](crate::Lagrangian::ROUTE); also the `route:` line of a derived system's
/// `EQUATIONS`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// Composite rigid bodies for M and recursive Newton–Euler for h over the
    /// kinematic tree the description spans: O(n²) and O(n) operations.
    Recursive,
    /// Differentiating the positions ξ(q, t) (M = Σ Jᵀ m J, h by projection
    /// or Christoffel symbols), and why the recursive route was not taken.
    Generic {
        /// Which body or point, and what about it, keeps the description
        /// from being a tree; or that the generic program was the cheaper
        /// one on a small tree.
        reason: &'static str,
    },
    /// Not derived: the system's impl was written by hand.
    HandWritten,
}
