//! Lagrange's equations of the second kind, derived symbolically.
//!
//! Input: the lowered description (positions ξ_ν(q,t), masses, gravity, potential,
//! forces, dissipation). Output: a [`Model`] holding M(q,t), h(q,q̇,t), Q(q,q̇,t) and
//! the energies as expressions in one [`Context`], ready for `emit`.
//!
//! h is derived twice — by the d'Alembert projection h = Σ m Jᵀκ and by
//! differentiating T (the Christoffel route) — and the cheaper program is kept.
//! The two must agree; a test checks that numerically.

use lagrange_symbolic::{Context, Expr as Sym, Program};

use crate::ast::Extra;
use crate::constraint::{ConstraintSet, Reduction};
use crate::lowered::Lowered;
use crate::mat3::Mat3;

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
    /// M (row-major, N²), Q − h and the articulated outputs with their
    /// parameter-only parts split off, computed once per parameter set by the
    /// generated code ([`lagrange_symbolic::Context::hoist`]).
    pub hoisted: lagrange_symbolic::Hoisted,
}

impl Model {
    pub fn dof(&self) -> usize {
        self.coordinates.len()
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

/// Per-point kinematics: ξ, ξ̇, J = ∂ξ/∂q, ∂ξ/∂t and κ = ξ̈ − J q̈.
struct Kinematics {
    mass: Sym,
    velocity: Vec<Sym>,
    jacobian: Vec<Vec<Sym>>, // [component][coordinate]
    partial_t: Vec<Sym>,
    kappa: Vec<Sym>,
    position: Vec<Sym>,
}

/// Per-body rotational kinematics: ω = W q̇ + w_t, W = ∂ω/∂q̇, and κ_ω = ω̇ − W q̈.
struct Spin {
    inertia: Mat3,
    omega: [Sym; 3],
    jacobian: Vec<[Sym; 3]>, // [coordinate][component]
    kappa: [Sym; 3],
}

/// Which derivation of M and h to use.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Route {
    /// The recursive route where the bodies form a kinematic tree; on small trees
    /// both routes are derived and the cheaper program kept.
    Auto,
    /// Differentiate ξ(q, t) (M = Σ Jᵀ m J, h by projection or Christoffel).
    Generic,
    /// Composite rigid bodies and recursive Newton–Euler; an error if the
    /// description is not a kinematic tree of revolute joints.
    Recursive,
}

/// Up to this many joints a detected tree is derived both ways (the generic
/// route grows as n³ but its constant is small: it wins on a heavy top).
const BOTH_ROUTES_UP_TO: usize = 6;

/// What a kinematic tree is, for the errors that need one.
const TREE: &str = "a kinematic tree of revolute joints: each body's rotation its parent's followed by rot_x/rot_y/rot_z of coordinates, its reference point fixed in the parent, every point mass fixed in a body";

/// Why a description could not be derived (beyond what lowering reports).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DeriveError {
    /// A reduced form that cannot be built: speeds and constraints that do not
    /// determine the velocities.
    Reduction(String),
    /// `emit(articulated)` on a description that is not a kinematic tree.
    ArticulatedNeedsTree,
    /// [`Route::Recursive`] asked of a description that is not a kinematic tree.
    NotATree,
}

impl std::fmt::Display for DeriveError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DeriveError::Reduction(msg) => f.write_str(msg),
            DeriveError::ArticulatedNeedsTree => write!(
                f,
                "`articulated` needs {TREE}; without one, remove `articulated` (q̈ then comes from M and its Cholesky factorisation)"
            ),
            DeriveError::NotATree => write!(f, "the recursive route needs {TREE}"),
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
pub fn derive_with(lowered: Lowered, route: Route) -> Result<Model, DeriveError> {
    let Lowered {
        mut ctx,
        coordinates,
        inputs: input_names,
        parameters,
        points,
        spins,
        skeleton,
        gravity,
        potential,
        dissipation,
        forces,
        generalized_forces,
        holonomic,
        nonholonomic,
        speeds,
        multipliers,
        extras,
    } = lowered;
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let t = ctx.time();
    let n = q.len();
    let zero_acc: Vec<(Sym, Sym)> = {
        let z = ctx.zero();
        qdd.iter().map(|&a| (a, z)).collect()
    };
    let tree = match route {
        Route::Generic => None,
        Route::Auto | Route::Recursive => {
            let point_masses: Vec<Sym> = points.iter().map(|p| p.mass).collect();
            let point_positions: Vec<Vec<Sym>> =
                points.iter().map(|p| p.position.clone()).collect();
            let inertias: Vec<Mat3> = spins.iter().map(|s| s.inertia).collect();
            let masses = crate::tree::Masses {
                point_masses: &point_masses,
                point_positions: &point_positions,
                inertias: &inertias,
                gravity: gravity.as_deref(),
            };
            crate::tree::detect(&mut ctx, &skeleton, &masses)
        }
    };
    if route == Route::Recursive && tree.is_none() {
        return Err(DeriveError::NotATree);
    }
    let generic = tree
        .as_ref()
        .is_none_or(|t| route == Route::Auto && t.len() <= BOTH_ROUTES_UP_TO);

    // sin/cos of sums of coordinates are expanded into products of sin/cos of the
    // coordinates themselves, so an n-link chain costs ~2n transcendental calls.
    // The Jacobians and κ are only needed by the generic route.
    let kin: Vec<Kinematics> = points
        .iter()
        .map(|p| {
            let position: Vec<Sym> = p.position.iter().map(|&x| ctx.expand_trig(x)).collect();
            let velocity: Vec<Sym> = position.iter().map(|&x| ctx.time_derivative(x)).collect();
            let jacobian = if generic {
                position
                    .iter()
                    .map(|&x| q.iter().map(|&qi| ctx.diff(x, qi)).collect())
                    .collect()
            } else {
                Vec::new()
            };
            let partial_t = position.iter().map(|&x| ctx.diff(x, t)).collect();
            let kappa = if generic {
                velocity
                    .iter()
                    .map(|&v| {
                        let a = ctx.time_derivative(v);
                        ctx.substitute(a, &zero_acc)
                    })
                    .collect()
            } else {
                Vec::new()
            };
            Kinematics {
                mass: p.mass,
                velocity,
                jacobian,
                partial_t,
                kappa,
                position,
            }
        })
        .collect();
    let zero_vel: Vec<(Sym, Sym)> = {
        let z = ctx.zero();
        qd.iter().map(|&v| (v, z)).collect()
    };
    let spin: Vec<Spin> = spins
        .iter()
        .map(|b| {
            let omega = b.omega.map(|w| ctx.expand_trig(w));
            let jacobian = qd.iter().map(|&v| omega.map(|w| ctx.diff(w, v))).collect();
            let kappa = omega.map(|w| {
                let a = ctx.time_derivative(w);
                ctx.substitute(a, &zero_acc)
            });
            Spin {
                inertia: b.inertia,
                omega,
                jacobian,
                kappa,
            }
        })
        .collect();
    let rheonomic = kin
        .iter()
        .any(|k| k.partial_t.iter().any(|&x| !ctx.is_zero(x)))
        || spin.iter().any(|s| {
            s.omega.iter().any(|&w| {
                let w0 = ctx.substitute(w, &zero_vel);
                !ctx.is_zero(w0)
            })
        });

    let kinetic = {
        let mut terms: Vec<Sym> = kin
            .iter()
            .map(|k| {
                let sq = dot(&mut ctx, &k.velocity, &k.velocity);
                ctx.mul(k.mass, sq)
            })
            .collect();
        for s in &spin {
            let iw = mat_vec(&mut ctx, &s.inertia, &s.omega);
            terms.push(dot(&mut ctx, &s.omega, &iw));
        }
        let s = ctx.sum(&terms);
        let half = ctx.rational(1, 2);
        let e = ctx.mul(half, s);
        ctx.collect(e)
    };
    let cost = |ctx: &Context, h: &[Sym]| Program::new(ctx, h).op_count().weighted();
    let generic_terms = generic.then(|| {
        let mass = mass_matrix(&mut ctx, &kin, &spin, n);
        let projection = bias_projection(&mut ctx, &kin, &spin, n);
        let christoffel = christoffel_bias(&mut ctx, kinetic, &q, &qd, &zero_acc);
        let (route, bias, other) = if cost(&ctx, &projection) <= cost(&ctx, &christoffel) {
            (BiasRoute::Projection, projection, christoffel)
        } else {
            (BiasRoute::Christoffel, christoffel, projection)
        };
        // M's entries come out simplified (sin² + cos² folded, cyclic
        // coordinates gone) where T's velocity products do not: for a
        // scleronomic system h from M's Christoffel symbols keeps that form.
        if !rheonomic {
            let from_mass = bias_from_mass(&mut ctx, &mass, &q, &qd);
            if cost(&ctx, &from_mass) < cost(&ctx, &bias) {
                return (mass, BiasRoute::MassMatrix, from_mass, bias);
            }
        }
        (mass, route, bias, other)
    });
    // The recursive route: M by CRBA, and h − Q_gravity in one RNEA pass for the
    // right-hand side (h alone for the `bias` output).
    let recursive_terms = tree.as_ref().map(|tree| {
        let mass = crate::tree::mass_matrix(&mut ctx, tree);
        let with_gravity = crate::tree::inverse_dynamics(&mut ctx, tree, true);
        let bias = crate::tree::inverse_dynamics(&mut ctx, tree, false);
        (mass, with_gravity, bias)
    });
    let flat =
        |m: &[Vec<Sym>], v: &[Sym]| -> Vec<Sym> { m.iter().flatten().chain(v).copied().collect() };
    let recursive_terms = match (generic_terms.as_ref(), recursive_terms) {
        (Some((gm, _, gh, _)), Some((rm, rg, rh))) => {
            let generic_cost = cost(&ctx, &flat(gm, gh));
            (cost(&ctx, &flat(&rm, &rg)) < generic_cost).then_some((rm, rg, rh))
        }
        (_, r) => r,
    };
    // Potential energy: the user's V plus the potential of uniform gravity, −Σ m g·ξ.
    let gravity_potential = {
        let mut terms = Vec::new();
        if let Some(g) = &gravity {
            for k in &kin {
                let gx = dot(&mut ctx, g, &k.position);
                let mg = ctx.mul(k.mass, gx);
                terms.push(ctx.neg(mg));
            }
        }
        ctx.sum(&terms)
    };
    let potential_total = {
        let v = match potential {
            Some(v) => ctx.add(v, gravity_potential),
            None => gravity_potential,
        };
        ctx.collect(v)
    };
    // Q without gravity's share, for the recursive algorithms (which take
    // gravity as a base acceleration); the generic route's Q has it all.
    let wants_articulated = extras.contains(&Extra::Articulated);
    let zero = ctx.zero();
    let forces_of = |ctx: &mut Context, v: Sym| {
        generalized_forces_of(ctx, &q, &qd, v, dissipation, &forces, &generalized_forces)
    };
    let without_gravity = (recursive_terms.is_some() || wants_articulated)
        .then(|| forces_of(&mut ctx, potential.unwrap_or(zero)));
    let generalized = match (&recursive_terms, &without_gravity) {
        (Some(_), Some(rest)) => rest.clone(),
        _ => forces_of(&mut ctx, potential_total),
    };
    let articulated = match (wants_articulated, &tree, &without_gravity) {
        (false, _, _) => None,
        (true, Some(tree), Some(rest)) => Some(articulation(&mut ctx, tree, rest)),
        (true, _, _) => return Err(DeriveError::ArticulatedNeedsTree),
    };
    // The `Lagrangian` methods are the unforced system: every input at zero.
    let (generalized, potential_total, inputs) =
        split_inputs(&mut ctx, input_names, generalized, potential_total);
    let (mass, bias, bias_other, bias_route, rhs, generalized) = match recursive_terms {
        Some((mass, with_gravity, bias)) => {
            let rhs: Vec<Sym> = (0..n)
                .map(|i| ctx.sub(generalized[i], with_gravity[i]))
                .collect();
            let total = (0..n)
                .map(|i| {
                    let dv = ctx.diff(gravity_potential, q[i]);
                    let e = ctx.sub(generalized[i], dv);
                    ctx.collect(e)
                })
                .collect();
            let other = generic_terms.map(|g| g.2).unwrap_or_default();
            (mass, bias, other, BiasRoute::Recursive, rhs, total)
        }
        None => {
            let (mass, route, bias, other) = generic_terms.expect("the generic route was derived");
            let rhs: Vec<Sym> = (0..n)
                .map(|i| {
                    let r = ctx.sub(generalized[i], bias[i]);
                    ctx.collect(r)
                })
                .collect();
            (mass, bias, other, route, rhs, generalized)
        }
    };

    // T = ½ q̇ᵀ M q̇ for a scleronomic system, printed and emitted in M's
    // simplified form where that is the cheaper program.
    let kinetic = if rheonomic {
        kinetic
    } else {
        let from_mass = quadratic_form(&mut ctx, &mass, &qd);
        let cost = |ctx: &Context, e: Sym| Program::new(ctx, &[e]).op_count().weighted();
        if cost(&ctx, from_mass) < cost(&ctx, kinetic) {
            from_mass
        } else {
            kinetic
        }
    };
    let integral = if rheonomic {
        // Jacobi integral T2 − T0 + V (Suslov 32.56), with T2 = ½ q̇ᵀ M q̇ and
        // T0 = T at q̇ = 0.
        let t2 = {
            let mut terms = Vec::new();
            for i in 0..n {
                for j in 0..n {
                    let mv = ctx.mul(mass[i][j], qd[j]);
                    terms.push(ctx.mul(qd[i], mv));
                }
            }
            let s = ctx.sum(&terms);
            let half = ctx.rational(1, 2);
            ctx.mul(half, s)
        };
        let t0 = ctx.substitute(kinetic, &zero_vel);
        let e = ctx.sub(t2, t0);
        let e = ctx.add(e, potential_total);
        ctx.collect(e)
    } else {
        let e = ctx.add(kinetic, potential_total);
        ctx.collect(e)
    };

    let wants = |e: Extra| extras.contains(&e);
    let coriolis = wants(Extra::Coriolis).then(|| coriolis_matrix(&mut ctx, &mass, &q, &qd));
    let jacobians = wants(Extra::Jacobians).then(|| rhs_jacobians(&mut ctx, &mass, &rhs));
    let hamiltonian = wants(Extra::Hamiltonian);
    let momentum = (hamiltonian || rheonomic).then(|| {
        qd.iter()
            .map(|&v| {
                let p = ctx.diff(kinetic, v);
                ctx.collect(p)
            })
            .collect()
    });
    let kinetic_gradient = hamiltonian.then(|| {
        q.iter()
            .map(|&x| {
                let g = ctx.diff(kinetic, x);
                ctx.collect(g)
            })
            .collect()
    });
    let constraints = multipliers.then(|| {
        let mut c = crate::constraint::multiplier_form(&mut ctx, &holonomic, &nonholonomic);
        if wants(Extra::Jacobians) {
            c.derivatives = Some(crate::constraint::constraint_derivatives(&mut ctx, &c));
        }
        c
    });
    let reduced = match speeds {
        None => None,
        Some(speeds) => {
            let free_speeds = speeds.is_none();
            let speeds = match speeds {
                Some(s) => s,
                None => crate::constraint::default_speeds(
                    &mut ctx,
                    &holonomic,
                    &nonholonomic,
                    &coordinates,
                )
                .map_err(DeriveError::Reduction)?,
            };
            let mut r = crate::constraint::reduce(
                &mut ctx,
                &holonomic,
                &nonholonomic,
                &speeds,
                &coordinates,
            )
            .map_err(DeriveError::Reduction)?;
            r.free_speeds = free_speeds;
            if wants(Extra::Jacobians) {
                r.derivatives = Some(crate::constraint::reduced_derivatives(&mut ctx, &r));
            }
            Some(r)
        }
    };

    // One hoisting over every program that takes the terms, in the layout
    // `Model::hoisted_*` reads.
    let hoisted = {
        let mut outputs: Vec<Sym> = mass.iter().flatten().chain(&rhs).copied().collect();
        if let Some(a) = &articulated {
            outputs.extend(&a.accelerations);
            outputs.extend(&a.pivots);
        }
        if let Some(c) = &constraints {
            outputs.extend(c.jacobian.iter().flatten());
            outputs.extend(&c.gamma);
        }
        ctx.hoist(&outputs, "__hoisted")
    };
    Ok(Model {
        ctx,
        coordinates,
        parameters,
        rheonomic,
        mass,
        bias,
        forces: generalized,
        rhs,
        kinetic,
        potential: potential_total,
        integral,
        bias_route,
        bias_other,
        inputs,
        constraints,
        reduced,
        coriolis,
        jacobians,
        momentum,
        kinetic_gradient,
        particles: kin.iter().map(|k| (k.mass, k.position.clone())).collect(),
        has_spin: !spin.is_empty(),
        articulated,
        hoisted,
    })
}

/// q̈ by the articulated-body algorithm with `rest`, every generalized force
/// but gravity's (which the algorithm takes as a base acceleration), at zero
/// input, plus the runtime's extra forces `tau[i]`.
fn articulation(ctx: &mut Context, tree: &crate::tree::Tree, rest: &[Sym]) -> Articulation {
    let zero = ctx.zero();
    let at_zero: Vec<(Sym, Sym)> = ctx.inputs().iter().map(|&u| (u, zero)).collect();
    let extra: Vec<Sym> = (0..rest.len())
        .map(|i| ctx.free_symbol(&format!("tau{i}")))
        .collect();
    let tau: Vec<Sym> = rest
        .iter()
        .zip(&extra)
        .map(|(&r, &x)| {
            let r = ctx.substitute(r, &at_zero);
            ctx.add(r, x)
        })
        .collect();
    let fd = crate::tree::forward_dynamics(ctx, tree, &tau);
    Articulation {
        accelerations: fd.accelerations,
        pivots: fd.pivots,
        extra,
    }
}

/// ½ q̇ᵀ M q̇, off-diagonal pairs once.
fn quadratic_form(ctx: &mut Context, mass: &[Vec<Sym>], qd: &[Sym]) -> Sym {
    let n = qd.len();
    let mut terms = Vec::new();
    for i in 0..n {
        for j in i..n {
            if ctx.is_zero(mass[i][j]) {
                continue;
            }
            let vv = ctx.mul(qd[i], qd[j]);
            let e = ctx.mul(mass[i][j], vv);
            terms.push(if i == j { e } else { ctx.add(e, e) });
        }
    }
    let s = ctx.sum(&terms);
    let half = ctx.rational(1, 2);
    let e = ctx.mul(half, s);
    ctx.collect(e)
}

/// h_i = Σ_{j≤k} c_ijk q̇_j q̇_k with c_ijk = ∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i
/// (halved on the diagonal j = k): the Christoffel symbols of M, for T = ½ q̇ᵀ M q̇.
fn bias_from_mass(ctx: &mut Context, mass: &[Vec<Sym>], q: &[Sym], qd: &[Sym]) -> Vec<Sym> {
    let n = q.len();
    // d[k][i][j] = ∂M_ij/∂q_k, the same node at (i, j) and (j, i).
    let mut d = vec![vec![vec![ctx.zero(); n]; n]; n];
    for (k, dk) in d.iter_mut().enumerate() {
        for i in 0..n {
            for j in i..n {
                let e = ctx.diff(mass[i][j], q[k]);
                dk[i][j] = e;
                dk[j][i] = e;
            }
        }
    }
    let half = ctx.rational(1, 2);
    (0..n)
        .map(|i| {
            let mut terms = Vec::new();
            for j in 0..n {
                for k in j..n {
                    let c = ctx.sum(&[d[k][i][j], d[j][i][k]]);
                    let c = ctx.sub(c, d[i][j][k]);
                    let c = if j == k { ctx.mul(half, c) } else { c };
                    let c = ctx.collect(c);
                    if ctx.is_zero(c) {
                        continue;
                    }
                    let vv = ctx.mul(qd[j], qd[k]);
                    terms.push(ctx.mul(c, vv));
                }
            }
            let h = ctx.sum(&terms);
            ctx.collect(h)
        })
        .collect()
}

/// h_i = d/dt ∂T/∂q̇_i − ∂T/∂q_i at q̈ = 0.
fn christoffel_bias(
    ctx: &mut Context,
    kinetic: Sym,
    q: &[Sym],
    qd: &[Sym],
    zero_acc: &[(Sym, Sym)],
) -> Vec<Sym> {
    (0..q.len())
        .map(|i| {
            let p = ctx.diff(kinetic, qd[i]);
            let dp = ctx.time_derivative(p);
            let dp = ctx.substitute(dp, zero_acc);
            let dq = ctx.diff(kinetic, q[i]);
            let h = ctx.sub(dp, dq);
            ctx.collect(h)
        })
        .collect()
}

/// Splits Q(u) and V(u) into the unforced Q(0), V(0) and the inputs' part ΔQ
/// with its Jacobians. Without inputs, Q and V are returned untouched.
fn split_inputs(
    ctx: &mut Context,
    names: Vec<String>,
    total: Vec<Sym>,
    potential: Sym,
) -> (Vec<Sym>, Sym, Option<InputModel>) {
    let u = ctx.inputs();
    if u.is_empty() {
        return (total, potential, None);
    }
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let zero = ctx.zero();
    let at_zero: Vec<(Sym, Sym)> = u.iter().map(|&x| (x, zero)).collect();
    let unforced = |ctx: &mut Context, e: Sym| {
        let e = ctx.substitute(e, &at_zero);
        ctx.collect(e)
    };
    let q0: Vec<Sym> = total.iter().map(|&e| unforced(ctx, e)).collect();
    let v0 = unforced(ctx, potential);
    let jacobian = |ctx: &mut Context, rows: &[Sym], wrt: &[Sym]| -> Vec<Vec<Sym>> {
        rows.iter()
            .map(|&r| {
                wrt.iter()
                    .map(|&x| {
                        let d = ctx.diff(r, x);
                        ctx.collect(d)
                    })
                    .collect()
            })
            .collect()
    };
    let jacobian_u = jacobian(ctx, &total, &u);
    // Where Q is affine in u (forces proportional to the inputs, set-points in
    // a quadratic potential), ΔQ = Σ u_j ∂Q/∂u_j: the derivatives have already
    // dropped every term without an input, whereas Q(u) − Q(0) would keep them
    // nested in factored sums that only cancel numerically.
    let forces: Vec<Sym> = (0..total.len())
        .map(|i| {
            let affine = jacobian_u[i]
                .iter()
                .all(|&d| u.iter().all(|&x| !ctx.depends_on(d, x)));
            let d = if affine {
                let terms: Vec<Sym> = jacobian_u[i]
                    .iter()
                    .zip(&u)
                    .map(|(&d, &x)| ctx.mul(x, d))
                    .collect();
                ctx.sum(&terms)
            } else {
                ctx.sub(total[i], q0[i])
            };
            ctx.collect(d)
        })
        .collect();
    let model = InputModel {
        names,
        jacobian_q: jacobian(ctx, &forces, &q),
        jacobian_v: jacobian(ctx, &forces, &qd),
        jacobian_u,
        symbols: u,
        forces,
    };
    (q0, v0, Some(model))
}

/// J_q = ∂(Q − h)/∂q − [∂M/∂q_k q̈]_k and J_v = ∂(Q − h)/∂q̇, with q̈ left as the
/// acceleration symbols (the runtime passes the current q̈).
fn rhs_jacobians(ctx: &mut Context, mass: &[Vec<Sym>], rhs: &[Sym]) -> [Vec<Vec<Sym>>; 2] {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let n = q.len();
    let jq = (0..n)
        .map(|i| {
            (0..n)
                .map(|k| {
                    let mut terms = vec![ctx.diff(rhs[i], q[k])];
                    for j in 0..n {
                        let dm = ctx.diff(mass[i][j], q[k]);
                        let t = ctx.mul(dm, qdd[j]);
                        terms.push(ctx.neg(t));
                    }
                    let s = ctx.sum(&terms);
                    ctx.collect(s)
                })
                .collect()
        })
        .collect();
    let jv = (0..n)
        .map(|i| {
            (0..n)
                .map(|k| {
                    let d = ctx.diff(rhs[i], qd[k]);
                    ctx.collect(d)
                })
                .collect()
        })
        .collect();
    [jq, jv]
}

/// C_ij = Σ_k Γ_ijk q̇_k with Γ_ijk = ½(∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i): the
/// factorisation of the Christoffel terms for which Ṁ − 2C is skew-symmetric.
fn coriolis_matrix(ctx: &mut Context, mass: &[Vec<Sym>], q: &[Sym], qd: &[Sym]) -> Vec<Vec<Sym>> {
    let n = q.len();
    let half = ctx.rational(1, 2);
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let terms: Vec<Sym> = (0..n)
                        .map(|k| {
                            let a = ctx.diff(mass[i][j], q[k]);
                            let b = ctx.diff(mass[i][k], q[j]);
                            let c = ctx.diff(mass[j][k], q[i]);
                            let g = ctx.add(a, b);
                            let g = ctx.sub(g, c);
                            let g = ctx.mul(half, g);
                            ctx.mul(g, qd[k])
                        })
                        .collect();
                    let s = ctx.sum(&terms);
                    ctx.collect(s)
                })
                .collect()
        })
        .collect()
}

fn mat_vec(ctx: &mut Context, a: &Mat3, v: &[Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| dot(ctx, &a[i], v))
}

fn cross(ctx: &mut Context, a: &[Sym; 3], b: &[Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let p = ctx.mul(a[j], b[k]);
        let m = ctx.mul(a[k], b[j]);
        ctx.sub(p, m)
    })
}

fn dot(ctx: &mut Context, a: &[Sym], b: &[Sym]) -> Sym {
    let terms: Vec<Sym> = a.iter().zip(b).map(|(&x, &y)| ctx.mul(x, y)).collect();
    ctx.sum(&terms)
}

/// M_ij = Σ_ν m_ν (J_ν)_·iᵀ (J_ν)_·j + Σ_bodies W_iᵀ I W_j, then factored so common
/// factors are computed once.
fn mass_matrix(ctx: &mut Context, kin: &[Kinematics], spin: &[Spin], n: usize) -> Vec<Vec<Sym>> {
    let mut m = vec![vec![ctx.zero(); n]; n];
    for i in 0..n {
        for j in i..n {
            let mut terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let ci: Vec<Sym> = k.jacobian.iter().map(|row| row[i]).collect();
                    let cj: Vec<Sym> = k.jacobian.iter().map(|row| row[j]).collect();
                    let d = dot(ctx, &ci, &cj);
                    ctx.mul(k.mass, d)
                })
                .collect();
            for s in spin {
                let iw = mat_vec(ctx, &s.inertia, &s.jacobian[j]);
                terms.push(dot(ctx, &s.jacobian[i], &iw));
            }
            let s = ctx.sum(&terms);
            let s = ctx.collect(s);
            let s = simplest_entry(ctx, s);
            m[i][j] = s;
            m[j][i] = s;
        }
    }
    m
}

/// Entries up to this DAG size are also tried expanded (see [`simplest_entry`]).
const EXPAND_ENTRIES_UP_TO: usize = 400;

/// The cheapest of an entry as derived, expanded and collected (where
/// sin² + cos² = 1 meets the squares of the Jacobian's sums of products:
/// m₂((l₁ cos a + l₂ cos(a+b))² + (…)²) becomes m₂(l₁² + l₂² + 2 l₁ l₂ cos b)),
/// and that with angle sums folded.
fn simplest_entry(ctx: &mut Context, e: Sym) -> Sym {
    if ctx.node_count(e) > EXPAND_ENTRIES_UP_TO {
        return e;
    }
    let expanded = ctx.expand(e);
    let collected = ctx.collect(expanded);
    let folded = ctx.fold_angle_sums(collected);
    [collected, folded].into_iter().fold(e, |best, c| {
        if entry_cost(ctx, c) < entry_cost(ctx, best) {
            c
        } else {
            best
        }
    })
}

/// Operations of an entry's program, with sines and cosines of bare
/// coordinates free (every program computes those once anyway) and any other
/// call at the weight of a call.
fn entry_cost(ctx: &Context, e: Sym) -> usize {
    let ops = Program::new(ctx, &[e]).op_count();
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![e];
    let mut compound_calls = 0;
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        let node = ctx.node(x);
        if let lagrange_symbolic::Node::Call(_, a) = node
            && ctx.as_symbol(*a).is_none()
        {
            compound_calls += 1;
        }
        stack.extend(node.children());
    }
    ops.add + ops.mul + 4 * ops.div + 20 * compound_calls
}

/// h_i = Σ_ν m_ν (J_ν)_·iᵀ κ_ν + Σ_bodies W_iᵀ (I κ_ω + ω × I ω) (Euler's equations
/// projected onto the coordinates).
fn bias_projection(ctx: &mut Context, kin: &[Kinematics], spin: &[Spin], n: usize) -> Vec<Sym> {
    let euler: Vec<[Sym; 3]> = spin
        .iter()
        .map(|s| {
            let ik = mat_vec(ctx, &s.inertia, &s.kappa);
            let iw = mat_vec(ctx, &s.inertia, &s.omega);
            let gyro = cross(ctx, &s.omega, &iw);
            [0, 1, 2].map(|c| ctx.add(ik[c], gyro[c]))
        })
        .collect();
    (0..n)
        .map(|i| {
            let mut terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let ci: Vec<Sym> = k.jacobian.iter().map(|row| row[i]).collect();
                    let d = dot(ctx, &ci, &k.kappa);
                    ctx.mul(k.mass, d)
                })
                .collect();
            for (s, e) in spin.iter().zip(&euler) {
                terms.push(dot(ctx, &s.jacobian[i], e));
            }
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect()
}

/// Q = −∂V/∂q + Σ_ν J_νᵀ F_ν − ∂D/∂q̇ + explicit generalized forces (Suslov 32.28–32.31).
fn generalized_forces_of(
    ctx: &mut Context,
    q: &[Sym],
    qd: &[Sym],
    potential: Sym,
    dissipation: Option<Sym>,
    forces: &[(Vec<Sym>, Vec<Sym>)],
    generalized: &[(usize, Sym)],
) -> Vec<Sym> {
    (0..q.len())
        .map(|i| {
            let mut terms = Vec::new();
            let dv = ctx.diff(potential, q[i]);
            terms.push(ctx.neg(dv));
            for (at, f) in forces {
                let ci: Vec<Sym> = at.iter().map(|&x| ctx.diff(x, q[i])).collect();
                terms.push(dot(ctx, &ci, f));
            }
            if let Some(d) = dissipation {
                let dd = ctx.diff(d, qd[i]);
                terms.push(ctx.neg(dd));
            }
            for (c, g) in generalized {
                if *c == i {
                    terms.push(*g);
                }
            }
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect()
}
