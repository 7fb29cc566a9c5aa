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

/// How a system's unconstrained q̈ is computed
/// ([`Lagrangian::FORWARD_ROUTE`](crate::Lagrangian::FORWARD_ROUTE); also a
/// line of a derived system's `EQUATIONS`).
///
/// With `emit(articulated)` the derive builds q̈ both ways and emits the one
/// with fewer operations (weighted as the expression engine's cost model
/// counts them: an addition or a multiplication one, a division four, a
/// call twenty); the two counts are kept here, so the
/// distance between the routes is visible. Either way the runtime's
/// [`Dynamics::acceleration`](crate::Dynamics::acceleration) calls the
/// emitted program, and
/// [`Dynamics::acceleration_from_mass_matrix`](crate::Dynamics::acceleration_from_mass_matrix)
/// the route through M and the runtime's Cholesky factorisation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForwardRoute {
    /// M and Q − h from the system, M factorised at run time (Cholesky): no
    /// `emit(articulated)`, or a hand-written system.
    MassMatrix,
    /// Featherstone's articulated-body algorithm, emitted.
    ArticulatedBody {
        /// The articulated-body program's weighted operations.
        articulated_body: usize,
        /// The factored program's, not emitted.
        factored_mass: usize,
    },
    /// M and Q − h with M = Lᵀ D L factorised in the emitted program
    /// (Featherstone's LTDL, which fills in nothing on a kinematic tree) and
    /// two triangular solves.
    FactoredMass {
        /// The articulated-body program's, not emitted; `None` where the
        /// algorithm does not apply (a coordinate driving two joints, as a
        /// URDF's `<mimic>` finger).
        articulated_body: Option<usize>,
        /// The factored program's weighted operations.
        factored_mass: usize,
    },
}
