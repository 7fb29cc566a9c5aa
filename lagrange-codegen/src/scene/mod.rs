//! The whole description lowered: parameters and coordinates, then definitions,
//! bodies and points in dependency order (see `order`), then forces, constraints
//! and speeds. Produces [`Lowered`] for `mechanics`.

mod contacts;
mod items;
mod joints;
use lagrange_symbolic::Expr as Sym;
use syn::{BinOp, Expr, Ident};

use crate::ast::{Formulation, System};
use crate::check;
use crate::ctxt::Ctxt;
use crate::lower::rotation::Rotation;
use crate::lower::{CartesianRef, Frame, Lowerer, Mode, NoInputs};
use crate::lowered::{
    BodyFrame, ConstraintModel, Lowered, PhysicalCheck, PointModel, ReducedSpeeds, Skeleton,
    SpinModel,
};
use crate::mat3::Mat3;
use crate::order::Item;
use crate::physical;
use items::{Items, lower_body, lower_point};

/// Lowers the description, in the order each part may refer to the ones before.
pub fn lower(cx: &Ctxt, system: &System) -> Option<Lowered> {
    let mut lw = Lowerer::new(cx);
    for p in &system.parameters {
        lw.declare_parameter(&p.name);
    }
    for q in &system.coordinates {
        lw.declare_coordinate(q);
    }
    for o in &system.orientations {
        lw.declare_orientation(o);
    }
    for u in &system.inputs {
        lw.declare_input(u);
    }
    let mut items = Items::default();
    for item in crate::order::lowering_order(cx, system) {
        match item {
            Item::Definition(i) => {
                let d = &system.definitions[i];
                lw.declare_definition(&d.name, &d.value);
            }
            Item::Body(i) => lower_body(&mut lw, &system.bodies[i], &mut items),
            Item::Point(i) => lower_point(&mut lw, &system.points[i], &mut items),
        }
    }
    crate::physical::free_bodies(&lw, &system.bodies, &items.skeleton, &items.spins);
    let mut applied = applied(&mut lw, system);
    let joints = joints::joints(&mut lw, system, &mut items.checks);
    applied.generalized_forces.extend(joints.forces);
    let (holonomic, nonholonomic) = constraints(&mut lw, system);
    let contacts = contacts::contacts(&mut lw, system);
    let formulations = check::formulations(system);
    let speeds = formulations
        .contains(&Formulation::Reduced)
        .then(|| speeds(&mut lw, system));
    // An input that a failed expression would have read is not reported unread.
    if !cx.has_errors() {
        check::inputs_read(cx, system, &inputs_read(&lw, &applied));
        constraints_read(&lw, system, [&holonomic, &nonholonomic], speeds.as_ref());
    }
    // Last, so that the shapes' nodes come after every node the equations use.
    let poses = crate::pose::collect(&mut lw, system, &items.points, &items.spins);
    if cx.has_errors() {
        return None;
    }
    let Items {
        points,
        spins,
        rotations: _,
        skeleton,
        checks,
    } = items;
    let names = |ids: &mut dyn Iterator<Item = &Ident>| ids.map(|c| c.to_string()).collect();
    let orientations = lw.orientation_models();
    Some(Lowered {
        ctx: lw.ctx,
        coordinates: names(&mut system.coordinates.iter()),
        orientations,
        inputs: names(&mut system.inputs.iter()),
        parameters: names(&mut system.parameters.iter().map(|p| &p.name)),
        points,
        spins,
        skeleton,
        gravity: applied.gravity,
        potential: applied.potential,
        dissipation: applied.dissipation,
        forces: applied.forces,
        generalized_forces: applied.generalized_forces,
        joint_coefficients: joints.coefficients,
        holonomic,
        nonholonomic,
        contacts,
        speeds,
        multipliers: formulations.contains(&Formulation::Multipliers),
        extras: system.extras.iter().map(|(_, e)| *e).collect(),
        checks,
        poses,
    })
}

/// Gravity, V, the dissipation function and the forces, lowered.
struct Applied {
    gravity: Option<Vec<Sym>>,
    potential: Option<Sym>,
    dissipation: Option<Sym>,
    forces: Vec<(Vec<Sym>, Vec<Sym>)>,
    generalized_forces: Vec<(usize, Sym)>,
}

fn applied(lw: &mut Lowerer, system: &System) -> Applied {
    let gravity = system
        .gravity
        .as_ref()
        .and_then(|g| lw.without_inputs(NoInputs::GRAVITY, |lw| lw.vector(g, Mode::Configuration)));
    let potential = system
        .potential
        .as_ref()
        .and_then(|v| lw.expr(v, Mode::Configuration));
    let dissipation = system.dissipation.as_ref().and_then(|d| {
        let value = lw.expr(d, Mode::State)?;
        physical::dissipation(lw, d, value, &system.coordinates);
        Some(value)
    });
    let mut forces = Vec::new();
    for f in &system.forces {
        let at = lw.frame_of(&f.point).map(|i| lw.frames[i].position.clone());
        if let (Some(at), Some(v)) = (at, lw.vector(&f.value, Mode::State)) {
            forces.push((at, v));
        }
    }
    for t in &system.torques {
        forces.extend(lw.torque(t).into_iter().flatten());
    }
    let mut generalized_forces = Vec::new();
    for g in &system.generalized_forces {
        let target = system.coordinates.iter().position(|c| *c == g.coordinate);
        if let (Some(i), Some(v)) = (target, lw.expr(&g.value, Mode::State)) {
            generalized_forces.push((i, v));
        }
    }
    Applied {
        gravity,
        potential,
        dissipation,
        forces,
        generalized_forces,
    }
}

/// Per input, whether the applied forces read it.
fn inputs_read(lw: &Lowerer, a: &Applied) -> Vec<bool> {
    let mut all: Vec<Sym> = a.potential.into_iter().chain(a.dissipation).collect();
    all.extend(a.forces.iter().flat_map(|(_, f)| f.iter().copied()));
    all.extend(a.generalized_forces.iter().map(|(_, g)| *g));
    let inputs = lw.ctx.inputs();
    inputs
        .iter()
        .map(|&u| all.iter().any(|&e| lw.ctx.depends_on(e, u)))
        .collect()
}

/// Whether each constraint reads the coordinates (holonomic) or the velocities
/// (nonholonomic, and each user speed), for `check::constraints_read`.
fn constraints_read(
    lw: &Lowerer,
    system: &System,
    [holonomic, nonholonomic]: [&[ConstraintModel]; 2],
    speeds: Option<&ReducedSpeeds>,
) {
    let q = lw.ctx.coordinates();
    let qd = lw.ctx.velocities();
    let reads = |e: Sym, on: &[Sym]| on.iter().any(|&x| lw.ctx.depends_on(e, x));
    let holonomic: Vec<bool> = holonomic.iter().map(|c| reads(c.value, &q)).collect();
    let nonholonomic: Vec<bool> = nonholonomic.iter().map(|c| reads(c.value, &qd)).collect();
    let user_speeds = speeds.and_then(ReducedSpeeds::named).unwrap_or_default();
    let speeds: Vec<bool> = user_speeds.iter().map(|(_, u)| reads(*u, &qd)).collect();
    check::constraints_read(lw.cx, system, [&holonomic, &nonholonomic, &speeds]);
}

/// The holonomic and the nonholonomic constraints, the latter proved linear in
/// the velocities.
fn constraints(lw: &mut Lowerer, system: &System) -> (Vec<ConstraintModel>, Vec<ConstraintModel>) {
    let holonomic: Vec<ConstraintModel> = system
        .holonomic
        .iter()
        .filter_map(|c| {
            lw.lowering_as(format!("holonomic constraint `{}`", c.name), |lw| {
                lw.without_inputs(NoInputs::HOLONOMIC, |lw| {
                    constraint(lw, &c.name, &c.value, Mode::Configuration)
                })
            })
        })
        .collect();
    let nonholonomic: Vec<ConstraintModel> = system
        .nonholonomic
        .iter()
        .filter_map(|c| {
            let m = lw.without_inputs(NoInputs::NONHOLONOMIC, |lw| {
                constraint(lw, &c.name, &c.value, Mode::State)
            })?;
            linear_in_velocities(
                lw,
                &c.value,
                m.value,
                &format!("nonholonomic constraint `{}`", c.name),
            )
            .then_some(m)
        })
        .collect();
    (holonomic, nonholonomic)
}

/// The reduced form's speeds: the user's, each proved linear in the
/// velocities, or none named, to have them chosen from the constraints.
fn speeds(lw: &mut Lowerer, system: &System) -> ReducedSpeeds {
    if system.speeds.is_empty() {
        return ReducedSpeeds::Chosen;
    }
    let mut out = Vec::new();
    for u in &system.speeds {
        let lowered = lw.without_inputs(NoInputs::SPEED, |lw| lw.expr(&u.value, Mode::State));
        let Some(e) = lowered else {
            continue;
        };
        if linear_in_velocities(lw, &u.value, e, &format!("speed `{}`", u.name)) {
            out.push((u.name.to_string(), e));
        }
    }
    ReducedSpeeds::Named(out)
}

/// Lowers a constraint with point coordinates kept symbolic, takes ∂f/∂ξ (or ∂f/∂ξ̇)
/// for the reactions, then composes with ξ(q,t).
fn constraint(lw: &mut Lowerer, name: &Ident, value: &Expr, mode: Mode) -> Option<ConstraintModel> {
    lw.cartesian = Some(Vec::new());
    let raw = lw.expr(value, mode);
    let refs = lw.cartesian.take().unwrap_or_default();
    let raw = raw?;
    // Reactions: a holonomic constraint pushes along ∂f/∂ξ, a nonholonomic one
    // along ∂f/∂ξ̇; references of the other kind do not contribute.
    let wanted_velocity = mode == Mode::State;
    let mut cartesian: Vec<(String, Vec<Sym>)> = Vec::new();
    for r in refs.iter().filter(|r| r.velocity == wanted_velocity) {
        let frame = &lw.frames[r.frame];
        let fname = frame.name.clone();
        let dim = frame.position.len();
        let partial = lw.ctx.diff(raw, r.symbol);
        let partial = compose(lw, partial, &refs);
        let entry = match cartesian.iter().position(|(n, _)| *n == fname) {
            Some(i) => i,
            None => {
                let zero = lw.ctx.zero();
                cartesian.push((fname, vec![zero; dim]));
                cartesian.len() - 1
            }
        };
        cartesian[entry].1[r.component] = partial;
    }
    let value = compose(lw, raw, &refs);
    Some(ConstraintModel {
        name: name.to_string(),
        value,
        cartesian,
    })
}

/// Replaces recorded point coordinates (and velocities) by their expressions in q.
fn compose(lw: &mut Lowerer, e: Sym, refs: &[CartesianRef]) -> Sym {
    let map: Vec<(Sym, Sym)> = refs
        .iter()
        .map(|r| {
            let x = lw.frames[r.frame].position[r.component];
            let x = if r.velocity {
                lw.ctx.time_derivative(x)
            } else {
                x
            };
            (r.symbol, x)
        })
        .collect();
    if map.is_empty() {
        e
    } else {
        lw.ctx.substitute(e, &map)
    }
}

/// Whether `value` (lowered from `syntax`) is at most linear in the velocities;
/// if not, reports the smallest offending term of `syntax`.
fn linear_in_velocities(lw: &mut Lowerer, syntax: &Expr, value: Sym, what: &str) -> bool {
    if is_linear(lw, value) {
        return true;
    }
    let culprit = nonlinear_term(lw, syntax);
    lw.cx.error_spanned_by(
        culprit,
        format!(
            "{what} must be linear in the velocities, but `{}` is not",
            quote::ToTokens::to_token_stream(culprit)
        ),
    );
    false
}

fn is_linear(lw: &mut Lowerer, e: Sym) -> bool {
    let qd = lw.ctx.velocities();
    qd.iter().all(|&v| {
        let d = lw.ctx.diff(e, v);
        let d = lw.ctx.simplify(d);
        qd.iter().all(|&w| !lw.ctx.depends_on(d, w))
    })
}

/// The smallest subexpression of `e` that is nonlinear in the velocities (e itself
/// if no operand is). Re-lowering a subexpression that lowered once cannot fail.
fn nonlinear_term<'e>(lw: &mut Lowerer, e: &'e Expr) -> &'e Expr {
    let children: Vec<&Expr> = match e {
        Expr::Paren(p) => vec![&p.expr],
        Expr::Group(g) => vec![&g.expr],
        Expr::Unary(u) => vec![&u.expr],
        Expr::Binary(b) if matches!(b.op, BinOp::Add(_) | BinOp::Sub(_)) => {
            vec![&b.left, &b.right]
        }
        Expr::Binary(b) => vec![&b.left, &b.right],
        Expr::Call(c) => c.args.iter().collect(),
        Expr::MethodCall(m) => std::iter::once(&*m.receiver).chain(m.args.iter()).collect(),
        _ => Vec::new(),
    };
    for c in children {
        lw.cartesian = Some(Vec::new());
        let v = lw.expr(c, Mode::State);
        let refs = lw.cartesian.take().unwrap_or_default();
        if let Some(v) = v {
            let v = compose(lw, v, &refs);
            if !is_linear(lw, v) {
                return nonlinear_term(lw, c);
            }
        }
    }
    e
}
