//! The contract between `#[derive(Lagrangian)]` and the runtime.
//!
//! The derive macro implements [`Lagrangian`] for the annotated struct; everything
//! in the runtime (forward dynamics, integrators, diagnostics) is written against
//! this trait only, so a hand-written implementation is a first-class citizen too
//! (the benchmarks compare exactly that).

use crate::error::IdentifyError;
use crate::numeric::Real;
use crate::numeric::orientation::Orientation;
use nalgebra::{DMatrix, DMatrixViewMut, DVector, SMatrix, SVector};

mod atlas;
mod configuration;
mod constrained;
mod contact;
mod derivatives;
mod driven;
mod form;
pub mod physical;
mod route;

pub use atlas::{Atlas, DrivenAtlas, EulerRotation, FreeVisitor};
pub use configuration::Configuration;
pub use constrained::{Constrained, Reduced};
pub use contact::{ContactKind, ContactLaw, ContactRows, Contacts};
pub use derivatives::AccelerationDerivatives;
pub use driven::Driven;
pub use form::FormVisitor;
pub use route::{ForwardRoute, Route};

/// A coordinate's position limits, watched by the runs (see
/// [`Lagrangian::position_limits`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimit {
    /// The joint's name (its coordinate's).
    pub joint: &'static str,
    /// The coordinate's index in q.
    pub coordinate: usize,
    /// The lower limit (−∞ for none).
    pub lower: f64,
    /// The upper limit (+∞ for none).
    pub upper: f64,
}

/// A holonomic system in minimal coordinates q ∈ Rᴺ, with equations of motion
///
/// ```text
/// M(q,t) q̈ + h(q,q̇,t) = Q(q,q̇,t)
/// ```
///
/// `T` is the scalar the parameters are stored in (f64, f32, or any [`Real`]);
/// `N` is the number of degrees of freedom, a type-level constant so that every
/// state is a stack-allocated [`SVector`].
///
/// The evaluation methods check nothing (they are called at every stage of
/// a run): at a quaternion off the unit sphere they answer for a scaled
/// rotation, at a NaN with NaN. [`Configuration`] evaluates at q checked as
/// a run checks its initial state, with typed errors.
pub trait Lagrangian<T: Real, const N: usize, const Q: usize = N> {
    /// Names of the numbers in q, in order: a coordinate's name, and for an
    /// orientation its quaternion's four components (`body.w`, `body.x`, …).
    const COORDINATES: [&'static str; Q];
    /// Names of the velocities, in order: a coordinate's own name (its rate),
    /// and for an orientation the body-axis angular velocity's components
    /// (`body.wx`, …). Without orientations, the coordinates' names.
    const VELOCITIES: [&'static str; N] = {
        let mut names = [""; N];
        let mut i = 0;
        while i < N && i < Q {
            names[i] = Self::COORDINATES[i];
            i += 1;
        }
        names
    };
    /// Where unit quaternions sit in q and their angular velocities in v (see
    /// [`orientation`](crate::numeric::orientation)): none by default, and then
    /// Q = N. `#[derive(Lagrangian)]` sets it for free bodies and spherical
    /// joints.
    const ORIENTATIONS: &'static [Orientation] = &[];
    /// Whether a position map depends explicitly on time. When it does, the
    /// conserved quantity (if any) is the Jacobi integral T2 − T0 + V, not T + V.
    const RHEONOMIC: bool;
    /// Whether the system has constraints (holonomic or nonholonomic) that its
    /// equations in these coordinates do not contain. Such a system must be run
    /// with its constraints ([`Simulation::run_constrained`](crate::Simulation::run_constrained)
    /// or [`run_reduced`](crate::Simulation::run_reduced)): integrating
    /// M q̈ + h = Q alone would let it move as if unconstrained, so the
    /// unconstrained forward dynamics ([`Dynamics`](crate::Dynamics), hence
    /// `Simulation::run`, the integrators' `integrate` on it, and unconstrained
    /// linearisation) refuse it at compile time. `#[derive(Lagrangian)]` sets it;
    /// a hand-written [`Constrained`] or [`Reduced`] system should set it too.
    const CONSTRAINED: bool = false;
    /// Which coordinates are cyclic (ignorable): no equation of motion reads
    /// their value, so q_j enters M, h, Q and the constraint rows only through
    /// its rate (a wheel's angle, a rolling body's position on the plane).
    /// `#[derive(Lagrangian)]` finds them from the derived expressions; the
    /// default, none, is always safe. Plots show them apart (they grow without
    /// bound while the motion they belong to stays bounded), and an
    /// eigen-analysis knows their zero eigenvalues are structural.
    const CYCLIC: [bool; N] = [false; N];
    /// How M and h are computed: by the recursive algorithms over a kinematic
    /// tree, or by differentiating the positions (with the reason the
    /// recursive route was not taken: which body, and what about it).
    /// `#[derive(Lagrangian)]` sets it; the default is [`Route::HandWritten`].
    const ROUTE: Route = Route::HandWritten;
    /// How [`forward_dynamics`](Self::forward_dynamics) computes q̈, and the
    /// operation counts `emit(articulated)` chose it by. `#[derive(Lagrangian)]`
    /// sets it; the default is [`ForwardRoute::MassMatrix`].
    const FORWARD_ROUTE: ForwardRoute = ForwardRoute::MassMatrix;
    /// Whether the description has `emit(atlas)` (an [`Atlas`]): a run that
    /// meets a singular M then says to call
    /// [`run_atlas`](crate::Simulation::run_atlas), which runs through its
    /// Euler charts' singular sets. `#[derive(Lagrangian)]` sets it.
    const ATLAS: bool = false;
    /// The names of the description's unilateral contacts and stops, in the
    /// order of their rows ([`Contacts`](crate::Contacts)): none by default.
    /// Only [`run_contacts`](crate::Simulation::run_contacts) honours them,
    /// so every other run of a [`Simulation`](crate::Simulation) refuses a
    /// system that lists some ([`ContactFault::NeedsContactRun`](crate::ContactFault::NeedsContactRun)).
    /// `#[derive(Lagrangian)]` sets it; a hand-written system with contacts
    /// should set it too.
    const CONTACTS: &'static [&'static str] = &[];

    /// Mass matrix M(q,t): symmetric, positive definite where the chart is regular.
    fn mass_matrix(&self, q: &SVector<T, Q>, t: T) -> SMatrix<T, N, N>;

    /// Bias h(q,q̇,t): Coriolis/centrifugal terms plus the rheonomic terms from T1, T0.
    fn bias(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> SVector<T, N>;

    /// Generalized forces Q(q,q̇,t): −∂V/∂q, Σ Jᵀ F, −∂D/∂q̇ and explicit generalized forces.
    fn generalized_forces(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> SVector<T, N>;

    /// M and the right-hand side Q − h, computed in one pass so that subexpressions
    /// shared between them (sines and cosines of the coordinates, Jacobian entries)
    /// are evaluated once. This is what the integrators call.
    fn mass_matrix_and_rhs(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> (SMatrix<T, N, N>, SVector<T, N>);

    /// Kinetic energy T = T2 + T1 + T0.
    fn kinetic_energy(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> T;

    /// Potential energy V(q,t), gravity included.
    fn potential_energy(&self, q: &SVector<T, Q>, t: T) -> T;

    /// The quantity conserved when the forces are conservative: T + V for a
    /// scleronomic system, the Jacobi integral T2 − T0 + V for a rheonomic one.
    /// It is the runtime's accuracy diagnostic.
    fn integral(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> T;

    /// The generalized momentum p = ∂L/∂q̇ = M(q,t) q̇ + a(q,t), with a the
    /// coefficient of T1 = aᵀq̇. The default, M q̇, is right for scleronomic
    /// systems (a = 0); a rheonomic implementation must override it.
    fn momentum(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> SVector<T, N> {
        self.mass_matrix(q, t) * v
    }

    /// The kinetic-energy gradient ∂T/∂q at fixed q̇, or `None` if the
    /// implementation does not provide it (the default).
    ///
    /// With it the equations of motion take Hamilton's form in (q, p):
    /// ṗ = ∂T/∂q + Q, q̇ = M⁻¹(p − a), which is what the symplectic
    /// [`Gauss`](crate::Gauss) integrator needs for a configuration-dependent
    /// mass matrix. (∂T/∂q rather than ∂L/∂q = ∂T/∂q − ∂V/∂q: −∂V/∂q is already
    /// part of [`generalized_forces`](Self::generalized_forces), and the form
    /// ṗ = ∂T/∂q + Q also covers forces that have no potential.)
    ///
    /// For a free orientation the entries are T's derivative along turns of
    /// the body about its own axes, q ⊕ δθ, at fixed ω (not at fixed θ̇ of a
    /// chart): with π its entries of p, the body angular momentum,
    /// π̇ = π × ω + ∂T/∂θ + Q (Hamel's form; Euler's equations for a lone
    /// body, where ∂T/∂θ = 0).
    fn kinetic_gradient(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> Option<SVector<T, N>> {
        let _ = (q, v, t);
        None
    }

    /// Inverse dynamics: the generalized forces τ = M a + h − Q that give the
    /// accelerations `a` at (q, q̇, t), every input at zero (the torques a
    /// computed-torque controller applies). The default computes M and Q − h;
    /// `#[derive(Lagrangian)]` with `emit(inverse_dynamics)` emits recursive
    /// Newton–Euler on a kinematic tree (O(n), no mass matrix), else one
    /// straight-line program. Constraint forces are not included.
    fn inverse_dynamics(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
        t: T,
    ) -> SVector<T, N> {
        let (m, f) = self.mass_matrix_and_rhs(q, v, t);
        m * a - f
    }

    /// The generalized forces that hold the system still against gravity alone
    /// at q, ∂V_gravity/∂q (Pinocchio's generalized gravity). `None` unless the
    /// description asks for it with `emit(inverse_dynamics)`.
    fn gravity_torques(&self, q: &SVector<T, Q>, t: T) -> Option<SVector<T, N>> {
        let _ = (q, t);
        None
    }

    /// The inertial parameters π's names, in the order of
    /// [`regressor`](Self::regressor)'s columns: per body `body.m`,
    /// `body.mx`, `body.my`, `body.mz` (the first moments m c),
    /// `body.Ixx`, `body.Ixy`, `body.Iyy`, `body.Ixz`, `body.Iyz`,
    /// `body.Izz` (the inertia about the body's reference point), c and I in
    /// the body's axes (Pinocchio's `Inertia::toDynamicParameters`), and per
    /// point mass `point.m`, in the description's order once its items are
    /// put in dependency order (a mass placed at another comes after it);
    /// then per `joint(q, ..)` item its coefficients, `q.damping` (b),
    /// `q.friction` (fc) and `q.armature` (Ia + n² Ir), those it has.
    /// Empty unless the description asks for `emit(regressor)`.
    const REGRESSOR_PARAMETERS: &'static [&'static str] = &[];

    /// The dynamics regressor Y(q, q̇, q̈, t), N × π's length: M q̈ + h −
    /// Q_gravity = Y π, the generalized forces the masses need for the
    /// accelerations `a` (with no other force, the
    /// [`inverse_dynamics`](Self::inverse_dynamics)); π as
    /// [`REGRESSOR_PARAMETERS`](Self::REGRESSOR_PARAMETERS) names it. `None`
    /// unless the description asks for it with `emit(regressor)`. On a
    /// kinematic tree Y is built from each joint's axis carried outward to
    /// the bodies below it, where it meets their body regressors; on any other
    /// description by the Euler–Lagrange operator on each parameter's share
    /// of the Lagrangian (the same π). A joint's coefficients are columns
    /// with one entry on its row: q̇ for its damping, q̈ for its armature
    /// (both in the inverse dynamics too) and sign(q̇) for its Coulomb
    /// friction (the torque a slipping joint's friction takes, which the
    /// inverse dynamics leaves out: Y π is then τ + fc sign q̇). The
    /// constraints' reactions and Q's other forces (the user's potential,
    /// springs, dissipation function, forces, inputs) are not in Y π.
    /// Allocates its matrix; [`regressor_into`](Self::regressor_into)
    /// writes into one the caller holds.
    fn regressor(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
        t: T,
    ) -> Option<DMatrix<T>> {
        let _ = (q, v, a, t);
        None
    }

    /// [`regressor`](Self::regressor)'s Y written into `y`, every entry set,
    /// allocating nothing: `y` may be a block of a larger matrix (a
    /// regressor stacked over samples, `w.view_mut((k * N, 0), (N, p))`).
    ///
    /// The derive writes it without allocating; the default copies what a
    /// hand-written [`regressor`](Self::regressor) returns, so a system that
    /// implements that one method has both.
    ///
    /// # Errors
    /// [`IdentifyError::NoRegressor`] unless the description asks for
    /// `emit(regressor)` (or `regressor` is implemented);
    /// [`IdentifyError::Lengths`] when `y` is not N × π's length (`y` is
    /// then left as it was).
    fn regressor_into(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
        t: T,
        mut y: DMatrixViewMut<'_, T>,
    ) -> Result<(), IdentifyError> {
        let values = (self.regressor(q, v, a, t)).ok_or(IdentifyError::NoRegressor {
            method: "regressor",
        })?;
        for (what, got, expected) in [
            (
                "rows of the matrix regressor_into writes",
                y.nrows(),
                values.nrows(),
            ),
            (
                "columns of the matrix regressor_into writes",
                y.ncols(),
                values.ncols(),
            ),
        ] {
            if got != expected {
                return Err(IdentifyError::Lengths {
                    what,
                    got,
                    expected,
                });
            }
        }
        y.copy_from(&values);
        Ok(())
    }

    /// The energy regressor Y_E(q, q̇, t), one entry per parameter of π:
    /// T + V_gravity = Y_E · π, the kinetic energy (an armature's ½ Ia q̇²
    /// included) and gravity's potential (the user's potential is not in
    /// it; a joint's damping and friction have zero entries). `None` unless the description
    /// asks for `emit(regressor)`. Allocates its vector.
    fn energy_regressor(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> Option<DVector<T>> {
        let _ = (q, v, t);
        None
    }

    /// The momentum regressor Y_p(q, q̇, t), N × π's length: the generalized
    /// momentum p = ∂T/∂q̇ = M q̇ (+ the share of T linear in q̇, where the
    /// description moves with time) = Y_p π, column k being ∂T_k/∂q̇ for
    /// parameter k's share T_k of T; π as
    /// [`REGRESSOR_PARAMETERS`](Self::REGRESSOR_PARAMETERS) names it.
    ///
    /// Row i is the momentum conjugate to velocity i. For a free
    /// orientation, whose velocities are its body's ω in the body's axes,
    /// its three rows are the angular momentum of everything whose motion
    /// the orientation carries, about the point its body turns about (the
    /// body's reference point), in the body's axes. So for a floating base
    /// (`urdf(.., base = floating)`, whose velocities are (ẋ, ẏ, ż) of the
    /// base's reference point in world axes, the joints' rates, then ω of
    /// the base in its axes, at [`ORIENTATIONS`](Self::ORIENTATIONS)`[0].v`)
    /// rows 0–2 are the robot's total linear momentum Σ m v_com in world
    /// axes and the base's ω rows its total angular momentum about the
    /// base's reference point (moving with it), Σ (c − o) × m v_c + R I ω
    /// over the bodies, in the base's axes. `None` unless the description
    /// asks for `emit(regressor)`. Allocates its matrix.
    fn momentum_regressor(&self, q: &SVector<T, Q>, v: &SVector<T, N>, t: T) -> Option<DMatrix<T>> {
        let _ = (q, v, t);
        None
    }

    /// π from the system's parameters (its fields): each body's mass, first
    /// moments and inertia about its reference point, each point mass's
    /// mass, in [`REGRESSOR_PARAMETERS`](Self::REGRESSOR_PARAMETERS)' order,
    /// so that [`regressor`](Self::regressor) times it is the masses' share of
    /// τ. `None` unless the description asks for `emit(regressor)`.
    fn inertial_parameters(&self) -> Option<DVector<T>> {
        None
    }

    /// q̈ as one emitted program, with the extra generalized forces `tau`
    /// added to Q, and the ratio of the smallest to the largest pivot of M's
    /// LᵀDL factorisation. `None` unless the description asks for it with
    /// `emit(articulated)` (a kinematic tree); then the unconstrained
    /// dynamics use it in place of M and the runtime's Cholesky
    /// factorisation. The derive builds it by the articulated-body algorithm
    /// and by M factorised in the program (no fill-in on a tree) and keeps
    /// the one with fewer operations ([`FORWARD_ROUTE`](Self::FORWARD_ROUTE)).
    fn forward_dynamics(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: &SVector<T, N>,
        t: T,
    ) -> Option<(SVector<T, N>, T)> {
        let _ = (q, v, tau, t);
        None
    }

    /// The parameter-only terms of [`mass_matrix_and_rhs`](Self::mass_matrix_and_rhs)
    /// and [`forward_dynamics`](Self::forward_dynamics): composite masses,
    /// products of lengths and inertia sums that `#[derive(Lagrangian)]` splits
    /// off so they are computed once per parameter set instead of at every call.
    /// Empty for a hand-written system.
    ///
    /// The runs of [`Simulation`](crate::Simulation) compute them once per run
    /// (the system is borrowed for the run, so its parameters cannot change
    /// under it). A loop of its own — a controller, an optimiser — does the
    /// same with the `_with` methods; compute the terms again after changing a
    /// parameter (with stale terms the results are those of the old parameters):
    ///
    /// ```
    /// # use lagrange_runtime::Lagrangian;
    /// # use nalgebra::{Matrix1, Vector1};
    /// # struct Spring { k: f64 }
    /// # impl Lagrangian<f64, 1> for Spring {
    /// #     const COORDINATES: [&'static str; 1] = ["x"];
    /// #     const RHEONOMIC: bool = false;
    /// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
    /// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
    /// #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { -q * self.k }
    /// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
    /// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    /// #     }
    /// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
    /// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { 0.5 * self.k * q[0] * q[0] }
    /// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
    /// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    /// #     }
    /// # }
    /// # let sys = Spring { k: 4.0 };
    /// # let states = [(Vector1::new(0.5), Vector1::new(0.0)), (Vector1::new(-0.2), Vector1::new(1.0))];
    /// let terms = sys.parameter_terms();
    /// for (q, v) in states {
    ///     let (m, rhs) = sys.mass_matrix_and_rhs_with(&terms, &q, &v, 0.0);
    ///     assert_eq!((m, rhs), sys.mass_matrix_and_rhs(&q, &v, 0.0));
    /// }
    /// ```
    fn parameter_terms(&self) -> Vec<T> {
        Vec::new()
    }

    /// [`mass_matrix_and_rhs`](Self::mass_matrix_and_rhs) over terms from
    /// [`parameter_terms`](Self::parameter_terms) of this same system (terms of
    /// the wrong length are ignored and recomputed).
    #[allow(clippy::type_complexity)]
    fn mass_matrix_and_rhs_with(
        &self,
        terms: &[T],
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> (SMatrix<T, N, N>, SVector<T, N>) {
        let _ = terms;
        self.mass_matrix_and_rhs(q, v, t)
    }

    /// [`forward_dynamics`](Self::forward_dynamics) over terms from
    /// [`parameter_terms`](Self::parameter_terms) of this same system.
    fn forward_dynamics_with(
        &self,
        terms: &[T],
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: &SVector<T, N>,
        t: T,
    ) -> Option<(SVector<T, N>, T)> {
        let _ = terms;
        self.forward_dynamics(q, v, tau, t)
    }

    /// The Jacobians of the right-hand side at the acceleration `a` = q̈:
    ///
    /// ```text
    /// J_q = ∂(Q − h)/∂q − [∂M/∂q_1 a, …, ∂M/∂q_N a],    J_v = ∂(Q − h)/∂q̇
    /// ```
    ///
    /// so that ∂q̈/∂q = M⁻¹ J_q and ∂q̈/∂q̇ = M⁻¹ J_v. `None` (the default) makes the
    /// implicit integrators fall back to finite differences; `#[derive(Lagrangian)]`
    /// emits them with `emit(jacobians)`.
    #[allow(clippy::type_complexity)]
    fn rhs_jacobians(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        a: &SVector<T, N>,
        t: T,
    ) -> Option<(SMatrix<T, N, N>, SMatrix<T, N, N>)> {
        let _ = (q, v, a, t);
        None
    }

    /// q̈ = M⁻¹(Q − h + τ), its derivatives and M's pivot ratio from the one
    /// program `emit(jacobians)` emits, unchecked: the
    /// [`Differentiable`](crate::Differentiable) trait's, reached from code
    /// generic over any system (a `Transition`'s stages). `None` (the
    /// default) where the system does not emit it.
    #[doc(hidden)]
    fn emitted_derivatives(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: &SVector<T, N>,
        t: T,
    ) -> Option<(AccelerationDerivatives<T, N>, T)> {
        let _ = (q, v, tau, t);
        None
    }

    /// Checks that the parameters describe a physical system: non-negative
    /// masses, principal moments that are non-negative and satisfy the triangle
    /// inequalities, inertia tensors whose second-moment matrix is positive
    /// semidefinite (see [`physical`](crate::physical)). `#[derive(Lagrangian)]`
    /// refuses literal values at compile time and overrides this method when a
    /// mass or an inertia is computed from the struct's fields; the runs of
    /// [`Simulation`](crate::Simulation) call it before they start. The
    /// default, for a hand-written system, checks nothing.
    ///
    /// # Errors
    /// [`Error::NonPhysicalParameter`](crate::Error::NonPhysicalParameter)
    /// naming the body, the entry and the rule.
    fn check_parameters(&self) -> Result<(), crate::error::Error> {
        Ok(())
    }

    /// The coordinates' position limits a run watches: a run stops with
    /// [`Error::JointLimit`](crate::Error::JointLimit) when one leaves them
    /// (unless [`Simulation::joint_limits`](crate::Simulation::joint_limits)
    /// says otherwise). `#[derive(Lagrangian)]` overrides it for a robot read
    /// from URDF with the file's finite `<limit>`s; the default, for a
    /// hand-written system, has none.
    fn position_limits(&self) -> &'static [JointLimit] {
        &[]
    }

    /// Hands `form` the equations this system runs in: the unconstrained
    /// dynamics here; `#[derive(Lagrangian)]` overrides it for a constrained
    /// description to choose the multiplier form (or the reduced form when only
    /// that is emitted), so that [`Simulation::run`](crate::Simulation::run) is
    /// the one way to run any derived system. The contract names no runner:
    /// the runner is the visitor. Not meant to be called directly.
    #[doc(hidden)]
    fn visit_form<F: FormVisitor<T, N, Self, Q>>(&self, form: F) -> F::Output
    where
        Self: Sized,
    {
        form.unconstrained(self)
    }
}
