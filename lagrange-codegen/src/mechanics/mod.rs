//! Lagrange's equations of the second kind, derived symbolically.
//!
//! Input: the lowered description (positions ξ_ν(q,t), masses, gravity, potential,
//! forces, dissipation). Output: a [`Model`] holding M(q,t), h(q,q̇,t), Q(q,q̇,t) and
//! the energies as expressions in one [`Context`], ready for `emit`.
//!
//! h is derived twice — by the d'Alembert projection h = Σ m Jᵀκ and by
//! differentiating T (the Christoffel route) — and the cheaper program is kept.
//! The two must agree; a test checks that numerically.
//!
//! [`derive_with`] reads as the stages: per-point and per-body `kinematics` and
//! T; M and h by the `generic` route and/or the `recursive` one (the cheaper
//! kept, assembled in `motion`); Q by `force` with the inputs split off; the
//! `energy` functions; the optional outputs (`extra`, `derivatives`,
//! `inverse`, `frames`), the constrained forms (`forms`), all at the chart's
//! centre (`chart`), and one hoisting. The result is a [`Model`] of parts
//! (`model`), each its own type. Every step builds nodes in the order the
//! single function did, so the emitted code is unchanged byte for byte.

mod armature;
mod base_parameters;
mod chart;
mod contact;
mod cyclic;
mod derivatives;
mod energy;
mod expressions;
mod extra;
mod factor;
mod force;
mod forms;
mod forward;
mod frames;
mod generic;
mod inverse;
mod kinematics;
mod model;
mod motion;
mod recursive;
mod regressor;
mod solved;

pub use base_parameters::{BaseForm, Named};
pub use contact::ContactRowsModel;
pub use derivatives::RhsJacobians;
pub use expressions::Expressions;
pub use extra::{Coriolis, Hamilton};
pub use forward::{ForwardChoice, ForwardRoute};
pub use frames::Frames;
pub use inverse::InverseDynamics;
pub use model::{
    Articulation, BiasRoute, ConstraintForms, Derivation, Energies, EquationsOfMotion, InputModel,
    Masses, Model, Outputs, Variables,
};
pub use regressor::{Regressor, RegressorRoute};
pub use solved::SolvedDerivatives;

use std::mem::take;

use lagrange_symbolic::{Context, Expr as Sym};

use crate::ast::Extra;
use crate::constraint::{ConstraintSet, Reduction};
use crate::lowered::{ConstraintModel, Lowered, Poses, ReducedSpeeds};
use force::Applied;
use forms::{multiplier_form, reduced_if_asked};
use kinematics::at_zero;

/// Which derivation of M and h to use.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Route {
    /// The recursive route where the bodies form a kinematic tree; on small trees
    /// both routes are derived and the cheaper program kept.
    Auto,
    /// Differentiate ξ(q, t) (M = Σ Jᵀ m J, h by projection or Christoffel).
    Generic,
    /// Composite rigid bodies and recursive Newton–Euler; an error if the
    /// description is not a kinematic tree of revolute, sliding and spherical joints.
    Recursive,
}

/// Up to this many joints a detected tree is derived both ways (the generic
/// route grows as n³ but its constant is small: it wins on a heavy top).
const BOTH_ROUTES_UP_TO: usize = 6;

/// What a kinematic tree is, for the errors that need one.
const TREE: &str = "a kinematic tree of revolute, sliding and spherical joints: each body's rotation its parent's followed by rot_x/rot_y/rot_z of coordinates or of constant angles, or by a free orientation, its reference point fixed in the parent or sliding along fixed lines of it, every point mass fixed in a body (with poses written out as matrices and ξ(q): each body turning about a constant axis or sliding along a fixed line, by one coordinate, relative to the body whose coordinates its own extend)";

/// Why a description could not be derived (beyond what lowering reports).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DeriveError {
    /// A reduced form that cannot be built: speeds and constraints that do not
    /// determine the velocities.
    Reduction(String),
    /// `emit(articulated)` on a description that is not a kinematic tree, and
    /// why it is not.
    ArticulatedNeedsTree(String),
    /// [`Route::Recursive`] asked of a description that is not a kinematic
    /// tree, and why it is not.
    NotATree(String),
    /// `emit(jacobians)` with a free orientation on a description that is not
    /// a kinematic tree, and why it is not.
    JacobiansNeedTree(String),
}

impl std::fmt::Display for DeriveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DeriveError::Reduction(msg) => f.write_str(msg),
            DeriveError::ArticulatedNeedsTree(why) => write!(
                f,
                "`articulated` needs {TREE}; here {why}; without one, remove `articulated` (q̈ then comes from M and its Cholesky factorisation)"
            ),
            DeriveError::NotATree(why) => {
                write!(f, "the recursive route needs {TREE}; here {why}")
            }
            DeriveError::JacobiansNeedTree(why) => write!(
                f,
                "`jacobians` with a free orientation needs {TREE} (its derivatives are those of recursive Newton–Euler, in the tangent space); here {why}; without one, remove `jacobians` (`Linearizer::tangent` then takes central differences)"
            ),
        }
    }
}

/// Derives the model, by the recursive route where the bodies form a tree.
///
/// # Errors
/// See [`DeriveError`].
pub fn derive(lowered: Lowered) -> Result<Model, DeriveError> {
    derive_with(lowered, Route::Auto)
}

/// Derives the model by the given route.
///
/// # Errors
/// As [`derive()`], and [`DeriveError::NotATree`] for [`Route::Recursive`] on a
/// description that is not a tree.
pub fn derive_with(mut lowered: Lowered, route: Route) -> Result<Model, DeriveError> {
    let mut ctx = take(&mut lowered.ctx);
    let derived = unconstrained(&mut ctx, &mut lowered, route)?;
    let Lowered {
        holonomic,
        nonholonomic,
        contacts,
        speeds,
        multipliers,
        extras,
        ..
    } = lowered;
    let constrained = Constrained::new(&holonomic, &nonholonomic, multipliers, speeds);
    let mut model = finish(ctx, derived, constrained, &extras)?;
    let orientations = &model.variables.orientations;
    model.contacts = contact::rows(&mut model.ctx, &contacts, orientations);
    Ok(model)
}

/// The unconstrained system: M and h by the route chosen, Q with the inputs'
/// share split off, the energies and the outputs derived before the chart's
/// centre; the variables, checks and poses taken over from `lowered`.
fn unconstrained(
    ctx: &mut Context,
    lowered: &mut Lowered,
    route: Route,
) -> Result<Derived, DeriveError> {
    let qdd = ctx.accelerations();
    let zero_acc = at_zero(ctx, &qdd);
    let masses = (&lowered.points[..], &lowered.spins[..], &lowered.skeleton);
    let gravity = lowered.gravity.as_deref();
    let armature = lowered.armature();
    let tree = recursive::detect(ctx, route, masses, gravity).map(|t| t.with_armature(&armature));
    let generic = wants_generic(route, &tree)?;
    let (tree, not_a_tree) = tree.map_or_else(|why| (None, Some(why)), |t| (Some(t), None));
    let points = &lowered.points;
    let spins = &lowered.spins;
    let (kin, spin, rheonomic, kinetic) =
        kinematics::derive(ctx, points, spins, generic, &zero_acc);
    let kinetic = armature::kinetic(ctx, kinetic, &armature);
    let generic_terms = generic.then(|| {
        let mut g = generic::derive(ctx, &kin, &spin, kinetic, rheonomic, &zero_acc);
        armature::add_to_mass(ctx, &mut g.mass, &armature);
        g
    });
    let recursive_terms = recursive::cheaper(ctx, tree.as_ref(), generic_terms.as_ref());
    let route_reason = route_reason(recursive_terms.is_some(), tree.as_ref(), not_a_tree);
    let input_names = take(&mut lowered.inputs);
    let recursive = recursive_terms.is_some();
    let regressor = regressor_if_asked(ctx, lowered, route);
    let sources = sources(lowered, tree.as_ref(), recursive, route_reason.clone());
    let extras = &lowered.extras;
    let (forces, potential) = applied_forces(ctx, &kin, &sources, input_names)?;
    let q_at_zero = motion::Generalized {
        forces: &forces.generalized,
        gravity_potential: forces.gravity_potential,
    };
    let motion = motion::equations(
        ctx,
        recursive_terms,
        generic_terms,
        q_at_zero,
        rheonomic,
        route_reason,
    );
    let inverse = inverse_if_asked(ctx, extras, tree.as_ref(), &motion, &forces);
    let free = !lowered.orientations.is_empty();
    let jacobians = (extras.contains(&Extra::Jacobians))
        .then(|| derivatives::rhs_jacobians(ctx, tree.as_ref(), &motion, &sources, free));
    let (chart_mass, chart_gradient) = extra::in_chart(ctx, extras, free, kinetic);
    let kinetic = energy::cheaper_kinetic(ctx, rheonomic, kinetic, &motion.mass);
    let integral = energy::integral(ctx, rheonomic, kinetic, potential, &motion.mass);
    let particles = kin.iter().map(|k| (k.mass, k.position.clone())).collect();
    Ok(Derived {
        chart_mass,
        chart_gradient,
        variables: Variables {
            coordinates: take(&mut lowered.coordinates),
            orientations: take(&mut lowered.orientations),
            parameters: take(&mut lowered.parameters),
            cyclic: Vec::new(),
        },
        energies: Energies {
            kinetic,
            potential,
            integral,
        },
        masses: Masses {
            particles,
            has_spin: !spin.is_empty(),
            checks: take(&mut lowered.checks),
        },
        forces,
        motion,
        inverse,
        regressor,
        jacobians: jacobians.transpose()?,
        poses: take(&mut lowered.poses),
    })
}

/// Where Q comes from, as the description gives it and the route chosen
/// needs it.
fn sources<'a>(
    lowered: &'a Lowered,
    tree: Option<&'a crate::tree::Tree>,
    recursive: bool,
    route_reason: Option<String>,
) -> Sources<'a> {
    Sources {
        gravity: lowered.gravity.as_deref(),
        potential: lowered.potential,
        applied: Applied {
            dissipation: lowered.dissipation,
            forces: &lowered.forces,
            generalized: &lowered.generalized_forces,
        },
        tree,
        recursive,
        articulated: lowered.extras.contains(&Extra::Articulated),
        route_reason,
    }
}

/// Whether to derive the generic route (besides the recursive one, if there is a
/// tree), or the error when the recursive route was required of a non-tree.
fn wants_generic(
    route: Route,
    tree: &Result<crate::tree::Tree, crate::tree::NotATree>,
) -> Result<bool, DeriveError> {
    match (route, tree) {
        (Route::Recursive, Err(why)) => Err(DeriveError::NotATree(why.to_string())),
        (_, Err(_)) => Ok(true),
        (_, Ok(t)) => Ok(route == Route::Auto && t.len() <= BOTH_ROUTES_UP_TO),
    }
}

/// `emit(inverse_dynamics)`: τ and the gravity torques.
fn inverse_if_asked(
    ctx: &mut Context,
    extras: &[Extra],
    tree: Option<&crate::tree::Tree>,
    motion: &EquationsOfMotion,
    forces: &Forces,
) -> Option<InverseDynamics> {
    let asked = extras.contains(&Extra::InverseDynamics);
    // On the recursive route Q leaves gravity out.
    let rest = (motion.derivation.route == BiasRoute::Recursive).then_some(&forces.generalized[..]);
    let potential = forces.gravity_potential;
    asked.then(|| inverse::inverse_dynamics(ctx, tree, motion, potential, rest))
}

/// `emit(regressor)`: Y on the tree, or by the generic route where there is
/// none (or where `route` asks for it).
fn regressor_if_asked(ctx: &mut Context, lowered: &mut Lowered, route: Route) -> Option<Regressor> {
    if !lowered.extras.contains(&Extra::Regressor) {
        return None;
    }
    let masses = regressor::MassModel {
        points: &lowered.points,
        spins: &lowered.spins,
        skeleton: &mut lowered.skeleton,
        gravity: lowered.gravity.as_deref(),
    };
    let joints = &lowered.joint_coefficients;
    Some(regressor::regressor(ctx, masses, joints, route))
}

/// Why M and h are not by the recursive route (`None` when they are): the
/// reason the description is not a tree, or that the generic program won.
fn route_reason(
    recursive: bool,
    tree: Option<&crate::tree::Tree>,
    not_a_tree: Option<crate::tree::NotATree>,
) -> Option<String> {
    if recursive {
        return None;
    }
    not_a_tree.map(|why| why.to_string()).or_else(|| {
        tree.map(|t| {
            format!(
                "the generic program is the cheaper one on this small tree ({} joints)",
                t.len()
            )
        })
    })
}

/// Where Q comes from: gravity, V and the applied forces, and what the recursive
/// algorithms need of it.
struct Sources<'a> {
    gravity: Option<&'a [Sym]>,
    potential: Option<Sym>,
    applied: Applied<'a>,
    tree: Option<&'a crate::tree::Tree>,
    /// Whether M and h come from the recursions (which take gravity as a base
    /// acceleration, so Q leaves it out).
    recursive: bool,
    /// Whether `emit(articulated)` asked for the articulated-body q̈.
    articulated: bool,
    /// Why M and h are not by the recursive route, for the error when the
    /// articulated q̈ needs a tree.
    route_reason: Option<String>,
}

/// Q at zero input and what depends on it.
struct Forces {
    generalized: Vec<Sym>,
    /// −Σ m g·ξ alone (the recursive route adds its gradient back into Q).
    gravity_potential: Sym,
    inputs: Option<InputModel>,
    articulated: Option<Articulation>,
    /// `emit(articulated)` on a tree with a coordinate driving two joints
    /// (a mimic joint): only the factored route applies.
    factored_only: bool,
}

/// Q (with or without gravity's share, by the route), the inputs' share of
/// Q and V, and the articulated q̈; and V (the user's plus gravity's) at zero
/// input.
fn applied_forces(
    ctx: &mut Context,
    kin: &[kinematics::Kinematics],
    s: &Sources,
    input_names: Vec<String>,
) -> Result<(Forces, Sym), DeriveError> {
    let gravity_potential = energy::gravity_potential(ctx, s.gravity, kin);
    let potential_total = energy::total_potential(ctx, s.potential, gravity_potential);
    // Q without gravity's share, for the recursive algorithms (which take
    // gravity as a base acceleration); the generic route's Q has it all.
    let zero = ctx.zero();
    let without_gravity = (s.recursive || s.articulated).then(|| {
        s.applied
            .generalized_forces(ctx, s.potential.unwrap_or(zero))
    });
    let generalized = match (s.recursive, &without_gravity) {
        (true, Some(rest)) => rest.clone(),
        _ => s.applied.generalized_forces(ctx, potential_total),
    };
    // A coordinate driving two joints (a mimic joint) is beyond the
    // articulated-body algorithm, not beyond M's factorisation.
    let factored_only = s.articulated && s.tree.is_some_and(|t| t.shared_coordinate().is_some());
    let articulated = match (s.articulated, s.tree, &without_gravity) {
        (false, _, _) => None,
        (true, Some(_), _) if factored_only => None,
        (true, Some(tree), Some(rest)) => Some(recursive::articulation(ctx, tree, rest)),
        (true, _, _) => {
            let why = s.route_reason.clone().unwrap_or_default();
            return Err(DeriveError::ArticulatedNeedsTree(why));
        }
    };
    // The `Lagrangian` methods are the unforced system: every input at zero.
    let (generalized, potential, inputs) =
        force::split_inputs(ctx, input_names, generalized, potential_total);
    let forces = Forces {
        generalized,
        gravity_potential,
        inputs,
        articulated,
        factored_only,
    };
    Ok((forces, potential))
}

/// Everything derived before the optional outputs and the constrained forms.
pub(super) struct Derived {
    /// M written in the orientations' θ (for `emit(coriolis)` with them).
    chart_mass: Option<Vec<Vec<Sym>>>,
    /// ∂T/∂q at fixed q̇ written in the orientations' θ (for
    /// `emit(hamiltonian)` with them), taken at the centre with the rest.
    chart_gradient: Option<Vec<Sym>>,
    variables: Variables,
    motion: EquationsOfMotion,
    energies: Energies,
    masses: Masses,
    forces: Forces,
    /// `emit(inverse_dynamics)`.
    inverse: Option<InverseDynamics>,
    /// `emit(regressor)`.
    regressor: Option<Regressor>,
    /// `emit(jacobians)`, before the chart's centre.
    jacobians: Option<RhsJacobians>,
    poses: Poses,
}

/// The constraints and which constrained forms to build.
pub(super) struct Constrained<'a> {
    pub holonomic: &'a [ConstraintModel],
    pub nonholonomic: &'a [ConstraintModel],
    pub multipliers: bool,
    pub speeds: Option<ReducedSpeeds>,
}

impl<'a> Constrained<'a> {
    fn new(
        holonomic: &'a [ConstraintModel],
        nonholonomic: &'a [ConstraintModel],
        multipliers: bool,
        speeds: Option<ReducedSpeeds>,
    ) -> Self {
        Constrained {
            holonomic,
            nonholonomic,
            multipliers,
            speeds,
        }
    }
}

/// What is derived in the orientations' θ before their centre is taken.
struct InTheta {
    constraints: Option<ConstraintSet>,
    reduced: Option<Reduction>,
    frames: Option<Frames>,
    coriolis: Option<Vec<Vec<Sym>>>,
}

/// With orientations both forms' constraint rows (their rates need the
/// θ-derivatives; their derivatives for `emit(jacobians)` would be in θ: not
/// built), the frames and the Christoffel symbols (of M in θ) are derived in
/// θ, then everything is taken at the centre.
fn in_theta(
    ctx: &mut Context,
    d: &mut Derived,
    c: &Constrained,
    extras: &[Extra],
) -> Result<InTheta, DeriveError> {
    let v = &d.variables;
    let free = !v.orientations.is_empty();
    let mut constraints = (free && c.multipliers).then(|| multiplier_form(ctx, c, false));
    let in_theta = free.then_some((&v.coordinates[..], &v.orientations[..]));
    let mut reduced = in_theta.map_or(Ok(None), |(q, o)| reduced_if_asked(ctx, c, q, o, false))?;
    let particles = &d.masses.particles;
    let mut frames =
        (extras.contains(&Extra::Kinematics)).then(|| frames::frames(ctx, &d.poses, particles));
    let mut coriolis = d.chart_mass.take().map(|mass| {
        let q = ctx.coordinates();
        let qd = ctx.velocities();
        extra::coriolis_matrix(ctx, &mass, &q, &qd)
    });
    let forms = chart::Forms {
        constraints: constraints.as_mut(),
        reduced: reduced.as_mut(),
    };
    chart::at_centre(ctx, d, forms, frames.as_mut(), coriolis.as_mut());
    Ok(InTheta {
        constraints,
        reduced,
        frames,
        coriolis,
    })
}

/// Adds the optional outputs, the constrained forms and the hoisting.
fn finish(
    mut ctx: Context,
    mut d: Derived,
    c: Constrained,
    extras: &[Extra],
) -> Result<Model, DeriveError> {
    let wants = |e: Extra| extras.contains(&e);
    let early = in_theta(&mut ctx, &mut d, &c, extras)?;
    let hamilton = extra::hamilton_form(&mut ctx, &mut d, wants(Extra::Hamiltonian));
    let slots = (
        d.variables.coordinates.len(),
        d.variables.orientations.len(),
    );
    let mass = &d.motion.mass;
    let coriolis = extra::coriolis(
        &mut ctx,
        early.coriolis,
        mass,
        wants(Extra::Coriolis),
        slots,
    );
    let jacobians = wants(Extra::Jacobians);
    let multipliers = (early.constraints).or_else(|| {
        c.multipliers
            .then(|| multiplier_form(&mut ctx, &c, jacobians))
    });
    let reduced = match early.reduced {
        None => reduced_if_asked(&mut ctx, &c, &d.variables.coordinates, &[], jacobians)?,
        r => r,
    };
    let unconstrained = c.holonomic.is_empty() && c.nonholonomic.is_empty();
    let solved = (d.jacobians.as_ref())
        .filter(|_| unconstrained)
        .map(|j| solved::solved(&mut ctx, &d.motion.mass, &d.motion.rhs, j));
    let (articulated, forward_route) = match d.forces.articulated.take() {
        Some(a) => {
            let (a, choice) = forward::fastest(&mut ctx, a, &d.motion);
            (Some(a), Some(choice))
        }
        None if d.forces.factored_only => {
            let (a, choice) = forward::factored_only(&mut ctx, &d.motion);
            (Some(a), Some(choice))
        }
        None => (None, None),
    };
    let hoisted = hoist(
        &mut ctx,
        &d.motion,
        articulated.as_ref(),
        multipliers.as_ref(),
    );
    let mut model = Model {
        ctx,
        variables: d.variables,
        motion: d.motion,
        energies: d.energies,
        masses: d.masses,
        inputs: d.forces.inputs,
        constraints: ConstraintForms {
            multipliers,
            reduced,
        },
        outputs: Outputs {
            hamilton,
            coriolis,
            jacobians: d.jacobians,
            solved,
            articulated,
            forward_route,
            inverse: d.inverse,
            regressor: d.regressor,
            frames: early.frames,
        },
        hoisted,
        poses: d.poses,
        contacts: Vec::new(),
    };
    model.variables.cyclic = cyclic::cyclic(&model);
    Ok(model)
}

/// One hoisting over every program that takes the terms, in the layout
/// `Model::hoisted_*` reads.
fn hoist(
    ctx: &mut Context,
    motion: &EquationsOfMotion,
    articulated: Option<&Articulation>,
    constraints: Option<&ConstraintSet>,
) -> lagrange_symbolic::Hoisted {
    let mass = motion.mass.iter().flatten();
    let mut outputs: Vec<Sym> = mass.chain(&motion.rhs).copied().collect();
    if let Some(a) = articulated {
        outputs.extend(&a.accelerations);
        outputs.extend(&a.pivots);
    }
    if let Some(c) = constraints {
        outputs.extend(c.jacobian.iter().flatten());
        outputs.extend(&c.gamma);
    }
    ctx.hoist(&outputs, "__hoisted")
}
