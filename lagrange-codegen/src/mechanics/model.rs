//! The equations of motion M q̈ + h = Q and the energies, as the derivation hands
//! them to `emit` and `doc`.

use lagrange_symbolic::{Context, Expr as Sym};

use crate::constraint::{ConstraintSet, Reduction};

/// Which derivation of h the emitted code uses.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum BiasRoute {
    /// h = Σ_ν m_ν J_νᵀ κ_ν (d'Alembert's principle).
    Projection,
    /// h = d/dt ∂T/∂q̇ − ∂T/∂q with q̈ = 0 (Christoffel symbols, rheonomic terms).
    Christoffel,
    /// Recursive Newton–Euler over the kinematic tree, with M by composite rigid
    /// bodies ([`crate::tree`]).
    Recursive,
    /// h_i = Σ_jk (∂M_ij/∂q_k − ½ ∂M_jk/∂q_i) q̇_j q̇_k, the Christoffel symbols of
    /// the derived M (scleronomic systems only).
    MassMatrix,
}

/// How the inputs u enter: Q(q, q̇, u, t) = Q(q, q̇, 0, t) + ΔQ.
pub struct InputModel {
    pub names: Vec<String>,
    /// The input symbols, in order (emitted as `u[i]`).
    pub symbols: Vec<Sym>,
    /// ΔQ = Q(q, q̇, u, t) − Q(q, q̇, 0, t).
    pub forces: Vec<Sym>,
    /// ∂Q/∂u (N × P), row-major.
    pub jacobian_u: Vec<Vec<Sym>>,
    /// ∂ΔQ/∂q (N × N).
    pub jacobian_q: Vec<Vec<Sym>>,
    /// ∂ΔQ/∂q̇ (N × N).
    pub jacobian_v: Vec<Vec<Sym>>,
}

/// q̈(q, q̇, τ) by the articulated-body algorithm (`emit(articulated)`).
pub struct Articulation {
    /// q̈, with the extra generalized forces as the free symbols `extra`.
    pub accelerations: Vec<Sym>,
    /// The articulated pivots D_i, for the singularity check.
    pub pivots: Vec<Sym>,
    /// Free symbols for the extra generalized forces (emitted as `tau[i]`).
    pub extra: Vec<Sym>,
}

/// The equations of motion M q̈ + h = Q and the energies, as expressions.
///
/// With inputs, everything here but [`Model::inputs`] is the unforced system
/// (every input at zero); the inputs' share of Q is in [`InputModel`].
pub struct Model {
    pub ctx: Context,
    pub coordinates: Vec<String>,
    /// Free orientations: their θ coordinates follow `coordinates` (and are
    /// zero in every output), their quaternions follow the coordinates in q.
    pub orientations: Vec<crate::lowered::OrientationModel>,
    pub parameters: Vec<String>,
    pub rheonomic: bool,
    /// Row-major N×N, symmetric (the same `Sym` at (i,j) and (j,i)).
    pub mass: Vec<Vec<Sym>>,
    pub bias: Vec<Sym>,
    pub forces: Vec<Sym>,
    /// Q − h, the right-hand side the integrators need.
    pub rhs: Vec<Sym>,
    pub kinetic: Sym,
    pub potential: Sym,
    pub integral: Sym,
    pub bias_route: BiasRoute,
    /// Why M and h are not by the recursive route: which body or point, and
    /// what about it (`None` when they are).
    pub route_reason: Option<String>,
    /// τ = M q̈ + h − Q and the gravity torques, if asked for
    /// (`emit(inverse_dynamics)`).
    pub inverse: Option<super::InverseDynamics>,
    /// The frames' Jacobians and the centre of mass, if asked for
    /// (`emit(kinematics)`).
    pub frames: Option<super::Frames>,
    /// The route not chosen, kept so tests can check the two agree (empty when
    /// only the recursive route was derived).
    pub bias_other: Vec<Sym>,
    /// The inputs' generalized forces and their Jacobians, if inputs were declared.
    pub inputs: Option<InputModel>,
    /// Constraint terms for the multiplier form.
    pub constraints: Option<ConstraintSet>,
    /// The reduced (Maggi / Gibbs–Appell) form.
    pub reduced: Option<Reduction>,
    /// C(q, q̇) with C_ij = Σ_k Γ_ijk q̇_k, if asked for.
    pub coriolis: Option<Vec<Vec<Sym>>>,
    /// (J_q, J_v) of the right-hand side at the accelerations q̈ (acceleration
    /// symbols): J_q = ∂(Q − h)/∂q − [∂M/∂q_k q̈]_k, J_v = ∂(Q − h)/∂q̇; if asked for.
    pub jacobians: Option<[Vec<Vec<Sym>>; 2]>,
    /// The momentum ∂T/∂q̇ (emitted when asked for, and always for a rheonomic
    /// system, where the runtime's default M q̇ would be wrong).
    pub momentum: Option<Vec<Sym>>,
    /// ∂T/∂q at fixed q̇, if asked for.
    pub kinetic_gradient: Option<Vec<Sym>>,
    /// (mass, position ξ(q, t)) of every point mass and body centre, for tools and
    /// tests that form other functions of the motion (the Gibbs function, say).
    pub particles: Vec<(Sym, Vec<Sym>)>,
    /// Whether any body has rotational inertia (then `particles` alone does not
    /// give T).
    pub has_spin: bool,
    /// The articulated-body forward dynamics, if asked for.
    pub articulated: Option<Articulation>,
    /// Per coordinate, whether it is cyclic: read by none of the expressions
    /// above (only its rate enters the motion).
    pub cyclic: Vec<bool>,
    /// M (row-major, N²), Q − h and the articulated outputs with their
    /// parameter-only parts split off, computed once per parameter set by the
    /// generated code ([`lagrange_symbolic::Context::hoist`]).
    pub hoisted: lagrange_symbolic::Hoisted,
    /// The masses and inertias computed from parameters, which the generated
    /// `check_parameters` checks before a run.
    pub checks: Vec<crate::lowered::PhysicalCheck>,
    /// The bodies' poses, the points' positions and the shapes, for the scene.
    pub poses: crate::lowered::Poses,
}

impl Model {
    /// The number of velocities N: the coordinates and three per orientation.
    pub fn dof(&self) -> usize {
        self.coordinates.len() + 3 * self.orientations.len()
    }

    /// The number of entries of q: the coordinates and four per orientation.
    pub fn configuration_len(&self) -> usize {
        self.coordinates.len() + 4 * self.orientations.len()
    }

    /// M's upper triangle (row-major) and then Q − h, over the hoisted terms.
    /// The hoisting's layout is [M (N²), Q − h (N), articulated q̈ and pivots
    /// (2N, if emitted), G (K·N) and γ (K, if the multiplier form is emitted)].
    pub fn hoisted_upper_and_rhs(&self) -> Vec<Sym> {
        let n = self.dof();
        let out = &self.hoisted.outputs;
        (0..n)
            .flat_map(|i| (i..n).map(move |j| out[i * n + j]))
            .chain(out[n * n..n * n + n].iter().copied())
            .collect()
    }

    /// The articulated q̈ and then its pivots, over the hoisted terms.
    pub fn hoisted_articulated(&self) -> Option<&[Sym]> {
        let n = self.dof();
        let start = n * n + n;
        self.articulated
            .as_ref()
            .map(|_| &self.hoisted.outputs[start..start + 2 * n])
    }

    /// G (row-major) and then γ, over the hoisted terms.
    pub fn hoisted_constraints(&self) -> Option<&[Sym]> {
        let n = self.dof();
        let start = n * n + n + if self.articulated.is_some() { 2 * n } else { 0 };
        self.constraints.as_ref().map(|c| {
            let k = c.names.len();
            &self.hoisted.outputs[start..start + n * k + k]
        })
    }
}
