//! The derivation's result, as `emit` and `doc` read it: a [`Model`] made of
//! parts, each a type of its own, so that an output touches its own part.

use lagrange_symbolic::{Context, Expr as Sym, Hoisted};

use super::expressions::{Expressions, entries};
use super::extra::{Coriolis, Hamilton};
use super::{Frames, InverseDynamics, Regressor, RhsJacobians};
use crate::constraint::{ConstraintDerivatives, ConstraintSet, Reduction};
use crate::lowered::{OrientationModel, PhysicalCheck, Poses};

pub use super::force::InputModel;
use super::forward::ForwardChoice;
pub use super::generic::BiasRoute;
pub use super::motion::{Derivation, EquationsOfMotion};
pub use super::recursive::Articulation;
use super::solved::SolvedDerivatives;

/// The equations of motion M q̈ + h = Q, the energies, the constrained forms
/// and the optional outputs, as expressions in one [`Context`].
///
/// With inputs, everything here but [`Model::inputs`] is the unforced system
/// (every input at zero); the inputs' share of Q is in [`InputModel`].
pub struct Model {
    /// The arena every expression of the parts lives in.
    pub ctx: Context,
    /// q, q̇ and the parameters: names, layout, which coordinates are cyclic.
    pub variables: Variables,
    /// M, h, Q and Q − h, and the route they were derived by.
    pub motion: EquationsOfMotion,
    /// T, V and the energy integral.
    pub energies: Energies,
    /// The point masses and bodies, and the checks of those computed from
    /// parameters.
    pub masses: Masses,
    /// The inputs' generalized forces and their Jacobians, if inputs were declared.
    pub inputs: Option<InputModel>,
    /// The multiplier form and the reduced form, those the description has.
    pub constraints: ConstraintForms,
    /// What `emit(...)` asked for (and the momentum of a rheonomic system).
    pub outputs: Outputs,
    /// M (row-major, N²), Q − h and the articulated outputs with their
    /// parameter-only parts split off, computed once per parameter set by the
    /// generated code ([`lagrange_symbolic::Context::hoist`]).
    pub hoisted: Hoisted,
    /// The bodies' poses, the points' positions and the shapes, for the scene.
    pub poses: Poses,
    /// The unilateral contacts' rows (derived last, so that a description
    /// without contacts has the same nodes as before).
    pub contacts: Vec<super::contact::ContactRowsModel>,
}

impl Model {
    /// The number of velocities N: the coordinates and three per orientation.
    pub fn dof(&self) -> usize {
        self.variables.dof()
    }

    /// The number of entries of q: the coordinates and four per orientation.
    pub fn configuration_len(&self) -> usize {
        self.variables.configuration_len()
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
        (self.outputs.articulated.as_ref()).map(|_| &self.hoisted.outputs[start..start + 2 * n])
    }

    /// G (row-major) and then γ, over the hoisted terms.
    pub fn hoisted_constraints(&self) -> Option<&[Sym]> {
        let n = self.dof();
        let articulated = self.outputs.articulated.is_some();
        let start = n * n + n + if articulated { 2 * n } else { 0 };
        self.constraints.multipliers.as_ref().map(|c| {
            let k = c.names.len();
            &self.hoisted.outputs[start..start + n * k + k]
        })
    }

    /// Every expression the generated code evaluates (the route not chosen,
    /// kept for tests, is left out), in no particular order.
    pub fn expressions(&self) -> Vec<Sym> {
        let mut out = Vec::new();
        self.motion.expressions(&mut out);
        self.energies.expressions(&mut out);
        self.inputs.expressions(&mut out);
        self.constraints.expressions(&mut out);
        self.outputs.expressions(&mut out);
        out
    }
}

/// What q, q̇ and the parameters are.
pub struct Variables {
    /// The coordinates' names, in the order of q.
    pub coordinates: Vec<String>,
    /// Free orientations: their θ coordinates follow `coordinates` (and are
    /// zero in every output), their quaternions follow the coordinates in q.
    pub orientations: Vec<OrientationModel>,
    /// The parameters' names.
    pub parameters: Vec<String>,
    /// Per coordinate, whether it is cyclic: read by no expression of the
    /// model (only its rate enters the motion).
    pub cyclic: Vec<bool>,
}

impl Variables {
    /// The number of velocities N: the coordinates and three per orientation.
    pub fn dof(&self) -> usize {
        self.coordinates.len() + 3 * self.orientations.len()
    }

    /// The number of entries of q: the coordinates and four per orientation.
    pub fn configuration_len(&self) -> usize {
        self.coordinates.len() + 4 * self.orientations.len()
    }
}

/// T, V (gravity's and the user's, at zero input) and the energy integral.
pub struct Energies {
    /// The kinetic energy T(q, q̇, t).
    pub kinetic: Sym,
    /// The potential energy V(q, t): gravity's and the user's.
    pub potential: Sym,
    /// The energy integral (Jacobi's integral T₂ − T₀ + V, which is T + V for a
    /// scleronomic system).
    pub integral: Sym,
}

impl Expressions for Energies {
    fn expressions(&self, out: &mut Vec<Sym>) {
        out.extend([self.kinetic, self.potential, self.integral]);
    }
}

/// The masses of the description, for tools and tests that form other
/// functions of the motion (the Gibbs function, say), and for the emitted
/// `check_parameters`.
pub struct Masses {
    /// (mass, position ξ(q, t)) of every point mass and body centre.
    pub particles: Vec<(Sym, Vec<Sym>)>,
    /// Whether any body has rotational inertia (then `particles` alone does not
    /// give T).
    pub has_spin: bool,
    /// The masses and inertias computed from parameters, which the generated
    /// `check_parameters` checks before a run.
    pub checks: Vec<PhysicalCheck>,
}

/// The constrained forms the description has: the multiplier form (Φ, G, g,
/// γ) and the reduced (Maggi / Gibbs–Appell) form.
#[derive(Default)]
pub struct ConstraintForms {
    /// The multiplier form, if the description has constraints and asks for it.
    pub multipliers: Option<ConstraintSet>,
    /// The reduced form, if asked for.
    pub reduced: Option<Reduction>,
}

impl Expressions for ConstraintForms {
    fn expressions(&self, out: &mut Vec<Sym>) {
        if let Some(c) = &self.multipliers {
            out.extend(&c.phi);
            out.extend(c.jacobian.iter().flatten());
            out.extend(&c.velocity_term);
            out.extend(&c.gamma);
            entries(out, c.reactions.iter().map(|(_, r)| r));
            c.derivatives.expressions(out);
        }
        if let Some(r) = &self.reduced {
            out.extend(&r.speeds);
            out.extend(r.matrix.iter().flatten());
            out.extend(&r.free);
            out.extend(&r.rates);
            r.derivatives.expressions(out);
        }
    }
}

impl Expressions for ConstraintDerivatives {
    fn expressions(&self, out: &mut Vec<Sym>) {
        let d = self;
        entries(
            out,
            [&d.force_q, &d.acceleration_q, &d.gamma_v, &d.velocity_q],
        );
    }
}

/// The optional outputs, each its own part: what `emit(...)` asked for, and
/// the momentum a rheonomic system always has.
#[derive(Default)]
pub struct Outputs {
    /// Hamilton's form: the momentum ∂T/∂q̇ (also alone, for a rheonomic
    /// system, where the runtime's default M q̇ would be wrong) and ∂T/∂q
    /// (`emit(hamiltonian)`).
    pub hamilton: Option<Hamilton>,
    /// C(q, q̇) with C_ij = Σ_k Γ_ijk q̇_k (`emit(coriolis)`).
    pub coriolis: Option<Coriolis>,
    /// The right-hand side's Jacobians at the accelerations q̈
    /// (`emit(jacobians)`).
    pub jacobians: Option<RhsJacobians>,
    /// q̈ and its derivatives in (q, q̇, τ) as one program, M factorised in
    /// it (`emit(jacobians)` on a system without constraints).
    pub solved: Option<SolvedDerivatives>,
    /// The emitted q̈ (`emit(articulated)`): the articulated-body algorithm
    /// or M factorised, whichever [`forward_route`](Self::forward_route) chose.
    pub articulated: Option<Articulation>,
    /// Which route `articulated` takes and both routes' operation counts.
    pub forward_route: Option<ForwardChoice>,
    /// τ = M q̈ + h − Q and the gravity torques (`emit(inverse_dynamics)`).
    pub inverse: Option<InverseDynamics>,
    /// The frames' Jacobians and the centre of mass (`emit(kinematics)`).
    pub frames: Option<Frames>,
    /// The dynamics regressor Y and the inertial parameters π
    /// (`emit(regressor)`).
    pub regressor: Option<Regressor>,
}

impl Expressions for Outputs {
    /// The outputs the cyclic coordinates are read off, as before they were
    /// parts: not the frames (a body's pose may read a coordinate the motion
    /// does not, a wheel's spin angle) nor the inverse dynamics (which read
    /// what M, h and Q read).
    fn expressions(&self, out: &mut Vec<Sym>) {
        self.coriolis.expressions(out);
        self.jacobians.expressions(out);
        self.hamilton.expressions(out);
        self.articulated.expressions(out);
    }
}
