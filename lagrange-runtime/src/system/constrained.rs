//! The constrained forms a description can have: multipliers
//! ([`Constrained`]) and independent speeds ([`Reduced`]).

use super::Lagrangian;
use crate::numeric::Real;
use nalgebra::{SMatrix, SVector};

/// Constraints kept with multipliers: K rows of
///
/// ```text
/// G(q,t) q̇ + g(q,t) = 0,        G = [Φ_q; A],  g = [Φ_t; b]
/// ```
///
/// The first [`HOLONOMIC`](Self::HOLONOMIC) rows are holonomic, Φ(q,t) = 0 at the
/// position level; the rest are nonholonomic, linear in the velocities. The
/// equations of motion become
///
/// ```text
/// M q̈ + h = Q + Gᵀ ν,     G q̈ = γ(q,q̇,t)
/// ```
///
/// with γ = −(Ġ q̇ + ġ) and the multipliers ν = [λ; μ].
///
/// With free orientations (Q = N + 1 per orientation, see
/// [`Lagrangian::ORIENTATIONS`]) q holds the quaternions and v the body-axis
/// angular velocities: G's columns are the tangent space's (an orientation's
/// three are ∂/∂θ of q ⊗ exp(θ) at θ = 0, i.e. the coefficients of ω), so
/// G is K × N and G v + g = 0, G v̇ = γ read in v as they do without.
///
/// A hand-written implementation also sets [`Lagrangian::CONSTRAINED`] and
/// overrides [`Lagrangian::visit_form`] with `form.multipliers::<K>(self)`,
/// as the derive does, so that `Simulation::run` and `complete_state` use
/// this form.
#[diagnostic::on_unimplemented(
    message = "`{Self}` has no multiplier form with these constraint rows: `run_constrained` and the constrained linearisation need constraints (`holonomic(...)`, `nonholonomic(...)`) in the `multipliers` formulation",
    label = "needs the multiplier form",
    note = "the multiplier form is the default when a description has constraints and no `speeds(...)`; `formulation(multipliers, reduced)` emits both; a system with free orientations (quaternions in q) linearises with `Linearizer::constrained_tangent`"
)]
pub trait Constrained<T: Real, const N: usize, const K: usize, const Q: usize = N>:
    Lagrangian<T, N, Q>
{
    /// Names of the constraints, in row order.
    const CONSTRAINTS: [&'static str; K];
    /// How many of the K rows (the first ones) are holonomic.
    const HOLONOMIC: usize;

    /// Φ(q,t) in the holonomic rows, zero in the nonholonomic rows.
    fn constraint_positions(&self, q: &SVector<T, Q>, t: T) -> SVector<T, K>;

    /// G(q,t) = [Φ_q; A] and g(q,t) = [Φ_t; b].
    fn constraint_jacobian(&self, q: &SVector<T, Q>, t: T) -> (SMatrix<T, K, N>, SVector<T, K>);

    /// γ(q,q̇,t) = −(Ġ q̇ + ġ), the right-hand side of G q̈ = γ.
    fn constraint_rhs(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> SVector<T, K>;

    /// M, Q − h, G and γ in one pass (shared subexpressions evaluated once): what
    /// the constrained dynamics call.
    #[allow(clippy::type_complexity)]
    fn constrained_system(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> (
        SMatrix<T, N, N>,
        SVector<T, N>,
        SMatrix<T, K, N>,
        SVector<T, K>,
    );

    /// [`constrained_system`](Self::constrained_system) over terms from
    /// [`Lagrangian::parameter_terms`] of this same system (terms of the wrong
    /// length are ignored and recomputed).
    #[allow(clippy::type_complexity)]
    fn constrained_system_with(
        &self,
        terms: &[T],
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> (
        SMatrix<T, N, N>,
        SVector<T, N>,
        SMatrix<T, K, N>,
        SVector<T, K>,
    ) {
        let _ = terms;
        self.constrained_system(q, v, t)
    }

    /// Derivatives of the constraint terms at the accelerations `a` = q̈ and the
    /// multipliers `nu` = ν, for linearising the constrained dynamics:
    ///
    /// ```text
    /// ( ∂(Gᵀν)/∂q   (N × N),
    ///   ∂(γ − G a)/∂q (K × N),
    ///   ∂γ/∂q̇        (K × N),
    ///   ∂(G q̇ + g)/∂q (K × N) )
    /// ```
    ///
    /// with a and ν held fixed. Differentiating M q̈ + h = Q + Gᵀν and G q̈ = γ
    /// then gives the first-order change of q̈ and ν from the saddle-point matrix
    /// alone. `None` (the default) means the system does not provide them;
    /// `#[derive(Lagrangian)]` emits them with `emit(jacobians)`.
    #[allow(clippy::type_complexity)]
    fn constraint_derivatives(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
        nu: &SVector<T, K>,
        t: T,
    ) -> Option<(
        SMatrix<T, N, N>,
        SMatrix<T, K, N>,
        SMatrix<T, K, N>,
        SMatrix<T, K, N>,
    )> {
        let _ = (q, v, a, nu, t);
        None
    }
}

/// A nonholonomic system reduced to K independent speeds u (independent
/// velocities or quasi-velocities; Maggi, Voronets, Gibbs–Appell).
///
/// The speeds u = U(q,t) q̇ + u₀(q,t) and the velocity constraints
/// G(q,t) q̇ + g(q,t) = 0 stack into N rows
///
/// ```text
/// A q̇ + b = (u, 0),    A = [U; G],  b = [u₀; g]
/// A q̈ = (u̇, 0) + c,    c = −(Ȧ q̇ + ḃ)
/// ```
///
/// and the runtime ([`ReducedDynamics`](crate::ReducedDynamics)) solves them with
/// pivoting at each state: q̇ = W u + w with W = A⁻¹[I; 0], q̈ = W u̇ + κ with
/// κ = A⁻¹ c, and
///
/// ```text
/// M* u̇ = F*,    M* = Wᵀ M W,   F* = Wᵀ (Q − h − M κ)
/// ```
///
/// The velocity constraints hold identically for every u (G W = 0), so there are
/// no multipliers and no velocity drift. The form is finite wherever A is
/// regular; where it is not, the speeds do not determine the velocities and the
/// runtime names the dependent rows. The state the integrators carry is still
/// (q, q̇); along the motion the dynamics solve with the velocities the
/// constraints leave free at each state (any independent speeds give the same
/// q̈) and project q̇ back onto the constraints after each step.
///
/// A hand-written implementation that runs only in this form sets
/// [`Lagrangian::CONSTRAINED`] and overrides [`Lagrangian::visit_form`] with
/// `form.reduced::<K>(self)`, as the derive does.
///
/// With free orientations (Q = N + 1 per orientation, see
/// [`Lagrangian::ORIENTATIONS`]) q holds the quaternions and v the body-axis
/// angular velocities, as in [`Constrained`]: A's columns are the tangent
/// space's (an orientation's three are the coefficients of ω), so A is N × N
/// and A v + b = (u, 0), A v̇ = (u̇, 0) + c read in v as they do without.
#[diagnostic::on_unimplemented(
    message = "`{Self}` has no reduced form: `run_reduced` and the reduced linearisation need `formulation(reduced)` in its #[lagrange(...)]",
    label = "needs the reduced form",
    note = "add `formulation(reduced)` (with `speeds(...)` to choose the independent speeds, or let the macro pick velocities); `formulation(multipliers, reduced)` emits both"
)]
pub trait Reduced<T: Real, const N: usize, const K: usize, const Q: usize = N>:
    Lagrangian<T, N, Q>
{
    /// Names of the independent speeds.
    const SPEEDS: [&'static str; K];

    /// Names of the N stacked rows: the speeds, then the constraints.
    const ROWS: [&'static str; N];

    /// Whether the speeds are velocities picked for you (no `speeds(...)`), so
    /// that any other velocities the constraints leave free serve as well: the
    /// runtime then keeps those where the constraints fix the picked ones (a
    /// knife edge heading north fixes ẋ). Speeds you name are kept or refused.
    const FREE_SPEEDS: bool = false;

    /// How many constraint rows are holonomic: the rows right after the K
    /// speed rows are Φ_q of Φ(q, t) = 0 for that many constraints. Zero (the
    /// default) when the description has none.
    const HOLONOMIC: usize = 0;

    /// Φ(q, t) of the holonomic constraints in the first
    /// [`HOLONOMIC`](Self::HOLONOMIC) entries, zero in the others: what
    /// [`complete_state`](crate::linear::complete_state) projects a starting
    /// state onto. `#[derive(Lagrangian)]` emits it; the default has none.
    fn holonomic_positions(&self, q: &SVector<T, Q>, t: T) -> SVector<T, N> {
        let _ = (q, t);
        SVector::zeros()
    }

    /// A = [U; G] and b = [u₀; g], so that A q̇ + b = (u, 0).
    fn velocity_rows(&self, q: &SVector<T, Q>, t: T) -> (SMatrix<T, N, N>, SVector<T, N>);

    /// c = −(Ȧ q̇ + ḃ), so that A q̈ = (u̇, 0) + c.
    fn row_rates(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> SVector<T, N>;

    /// u = U(q,t) q̇ + u₀(q,t): the first K rows of A q̇ + b.
    fn speeds(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> SVector<T, K> {
        let (a, b) = self.velocity_rows(q, t);
        (a * v + b).fixed_rows::<K>(0).into_owned()
    }

    /// Derivatives of the stacked rows at the accelerations `a` = q̈ and the
    /// weights `nu`, for linearising the reduced form:
    ///
    /// ```text
    /// ( ∂(Aᵀν)/∂q, ∂(c − A a)/∂q, ∂c/∂q̇, ∂(A q̇ + b)/∂q )    (each N × N)
    /// ```
    ///
    /// with a and ν held fixed; the runtime composes them with W and M. `None`
    /// (the default) means the system does not provide them;
    /// `#[derive(Lagrangian)]` emits them with `emit(jacobians)`.
    #[allow(clippy::type_complexity)]
    fn row_derivatives(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
        nu: &SVector<T, N>,
        t: T,
    ) -> Option<(
        SMatrix<T, N, N>,
        SMatrix<T, N, N>,
        SMatrix<T, N, N>,
        SMatrix<T, N, N>,
    )> {
        let _ = (q, v, a, nu, t);
        None
    }
}
