//! The whole description lowered: parameters and coordinates, then definitions,
//! bodies and points in dependency order (see `order`), then forces, constraints
//! and speeds. Produces [`Lowered`] for `mechanics`.

use lagrange_symbolic::Expr as Sym;
use syn::{BinOp, Expr, Ident};

use crate::ast::{Formulation, System};
use crate::check;
use crate::ctxt::Ctxt;
use crate::lower::rotation::Rotation;
use crate::lower::{CartesianRef, Frame, Lowerer, Mode, NoInputs};
use crate::lowered::{
    BodyFrame, ConstraintModel, Lowered, PhysicalCheck, PointModel, Skeleton, SpinModel,
};
use crate::mat3::{Mat3, mat_vec, parallel_axis};
use crate::order::Item;
use crate::physical;

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
    let applied = applied(&mut lw, system);
    let (holonomic, nonholonomic) = constraints(&mut lw, system);
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
        holonomic,
        nonholonomic,
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
    speeds: Option<&Option<Vec<(String, Sym)>>>,
) {
    let (q, qd) = (lw.ctx.coordinates(), lw.ctx.velocities());
    let reads = |e: Sym, on: &[Sym]| on.iter().any(|&x| lw.ctx.depends_on(e, x));
    let holonomic: Vec<bool> = holonomic.iter().map(|c| reads(c.value, &q)).collect();
    let nonholonomic: Vec<bool> = nonholonomic.iter().map(|c| reads(c.value, &qd)).collect();
    let user_speeds = speeds.into_iter().flatten().flatten();
    let speeds: Vec<bool> = user_speeds.map(|(_, u)| reads(*u, &qd)).collect();
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

/// The reduced form's speeds, each proved linear in the velocities; `None` to
/// have them chosen from the constraints.
fn speeds(lw: &mut Lowerer, system: &System) -> Option<Vec<(String, Sym)>> {
    if system.speeds.is_empty() {
        return None;
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
    Some(out)
}

/// Point masses, spins and body frames lowered so far.
#[derive(Default)]
struct Items {
    points: Vec<PointModel>,
    spins: Vec<SpinModel>,
    /// (body, rotation matrix, reference point) for the points fixed in bodies.
    rotations: Vec<(Ident, Mat3, Vec<Sym>)>,
    /// Where the masses sit relative to the bodies, for the recursive derivation.
    skeleton: Skeleton,
    /// Masses and inertias computed from parameters, checked at run time.
    checks: Vec<PhysicalCheck>,
}

/// A rigid body: its frame (for `B.x`, `B.omega_x` and points on it), its centre
/// of mass as a point mass, and its spin. The reference point is `at`; the centre
/// of mass is at + R·com when `com` is given.
fn lower_body(lw: &mut Lowerer, b: &crate::ast::Body, items: &mut Items) {
    let (Some(mass), Some(inertia), Some(at), Some(rotation)) =
        (&b.mass, &b.inertia, &b.at, &b.rotation)
    else {
        return;
    };
    let whose = |key: &str| format!("the {key} of body `{}`", b.name);
    let mass = lw.lowering_as(whose("mass"), |lw| {
        lw.without_inputs(NoInputs::MASS, |lw| lw.expr(mass, Mode::Constant))
    });
    let inertia = lw.lowering_as(whose("inertia"), |lw| {
        lw.without_inputs(NoInputs::INERTIA, |lw| inertia_matrix(lw, inertia))
    });
    let reference = lw.lowering_as(whose("position `at`"), |lw| {
        lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(at, Mode::Configuration))
    });
    let com = b.com.as_ref().map(|c| {
        lw.lowering_as(whose("centre of mass `com`"), |lw| {
            lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(c, Mode::Constant))
        })
    });
    let about = b.about.as_ref().map(|a| {
        lw.lowering_as(whose("inertia's reference point `about`"), |lw| {
            lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(a, Mode::Constant))
        })
    });
    let rotation = lw.lowering_as(whose("rotation"), |lw| {
        lw.without_inputs(NoInputs::ROTATION, |lw| lw.rotation(rotation))
    });
    let (Some(mass), Some(inertia), Some(reference), Some(rotation)) =
        (mass, inertia, reference, rotation)
    else {
        return;
    };
    let inertia = match about {
        None => inertia,
        Some(Some(point)) if point.len() == 3 => {
            let zero = lw.ctx.zero();
            let com = match &com {
                Some(Some(c)) if c.len() == 3 => c.clone(),
                _ => vec![zero; 3],
            };
            to_centre_of_mass(lw, inertia, mass, &point, &com)
        }
        Some(_) => return,
    };
    // `check` has reported a reference point or `com` that is not [x, y, z].
    if reference.len() != 3 {
        return;
    }
    let what = format!("body `{}`", b.name);
    let name = b.name.to_string();
    let syntax = b.mass.as_ref().unwrap_or(at);
    items
        .checks
        .extend(physical::mass(lw, &name, &what, syntax, mass));
    let spatial = rotation.omega_body.iter().all(|&w| !lw.ctx.is_zero(w));
    let shape = physical::Shape {
        moved: b.about.is_some(),
        spatial,
    };
    items
        .checks
        .extend(physical::inertia(lw, b, &inertia, shape));
    let centre = match &com {
        None => reference.clone(),
        Some(Some(offset)) if offset.len() == 3 => {
            offset_in_body(lw, &rotation.matrix, &reference, offset)
        }
        Some(_) => return,
    };
    record_body(
        lw,
        b,
        items,
        (mass, inertia),
        (reference, centre, com),
        rotation,
    );
}

/// Brings a lowered body into scope and records its centre as a point mass, its
/// spin, and its frame for the points fixed in it and the recursive route.
fn record_body(
    lw: &mut Lowerer,
    b: &crate::ast::Body,
    items: &mut Items,
    (mass, inertia): (Sym, Mat3),
    (reference, centre, com): (Vec<Sym>, Vec<Sym>, Option<Option<Vec<Sym>>>),
    rotation: Rotation,
) {
    lw.declare_frame(
        &b.name,
        Frame {
            name: b.name.to_string(),
            position: reference.clone(),
            omega: Some([rotation.omega_world, rotation.omega_body]),
            axes: Some(rotation.matrix),
        },
    );
    let index = items.spins.len();
    let zero = lw.ctx.zero();
    let local = match &com {
        Some(Some(offset)) => offset.clone(),
        _ => vec![zero; 3],
    };
    items.skeleton.bodies.push(BodyFrame {
        factors: rotation.factors,
        matrix: rotation.matrix,
        reference: reference.clone(),
    });
    items.skeleton.masses.push(Some((index, local)));
    items
        .skeleton
        .anchors
        .push((reference.clone(), index, vec![zero; 3]));
    items
        .rotations
        .push((b.name.clone(), rotation.matrix, reference));
    items.points.push(PointModel {
        name: b.name.to_string(),
        mass,
        position: centre,
    });
    items.spins.push(SpinModel {
        name: b.name.to_string(),
        inertia,
        omega: rotation.omega_body,
    });
}

/// The parallel-axis theorem: an inertia tensor about the body point `about`
/// moved to the centre of mass `com` (both in body coordinates),
/// I_com = I_about − m (|d|² E − d dᵀ) with d = com − about.
fn to_centre_of_mass(
    lw: &mut Lowerer,
    about_point: [[Sym; 3]; 3],
    mass: Sym,
    about: &[Sym],
    com: &[Sym],
) -> [[Sym; 3]; 3] {
    let d = [0, 1, 2].map(|i| lw.ctx.sub(com[i], about[i]));
    let shift = parallel_axis(&mut lw.ctx, mass, d);
    let mut out = about_point;
    for i in 0..3 {
        for j in 0..3 {
            let entry = lw.ctx.sub(out[i][j], shift[i][j]);
            out[i][j] = lw.ctx.collect(entry);
        }
    }
    out
}

/// origin + R·local: a point given in body coordinates.
fn offset_in_body(lw: &mut Lowerer, r: &Mat3, origin: &[Sym], local: &[Sym]) -> Vec<Sym> {
    let rb = mat_vec(&mut lw.ctx, r, [local[0], local[1], local[2]]);
    (0..3).map(|i| lw.ctx.add(origin[i], rb[i])).collect()
}

/// A point: in world coordinates, or fixed in a body (`on = B`, coordinates
/// relative to the body's reference point in its axes); a point mass if it has
/// a mass.
fn lower_point(lw: &mut Lowerer, p: &crate::ast::Point, items: &mut Items) {
    let Some(at) = &p.at else { return };
    let local = lw.lowering_as(format!("the position of point `{}`", p.name), |lw| {
        lw.without_inputs(NoInputs::POSITION, |lw| lw.vector(at, Mode::Configuration))
    });
    let mass = p.mass.as_ref().map(|m| {
        lw.lowering_as(format!("the mass of point `{}`", p.name), |lw| {
            lw.without_inputs(NoInputs::MASS, |lw| lw.expr(m, Mode::Constant))
        })
    });
    let (position, fixed_in) = match (&p.on, local) {
        (_, None) => return,
        (None, Some(x)) => (x, None),
        (Some(body), Some(local)) => {
            let Some(index) = items.rotations.iter().position(|(n, _, _)| n == body) else {
                return;
            };
            // `check` has reported body coordinates that are not [x, y, z].
            if local.len() != 3 {
                return;
            }
            let (r, c) = (items.rotations[index].1, items.rotations[index].2.clone());
            let position = offset_in_body(lw, &r, &c, &local);
            items
                .skeleton
                .anchors
                .push((position.clone(), index, local.clone()));
            (position, Some((index, local)))
        }
    };
    lw.declare_frame(
        &p.name,
        Frame {
            name: p.name.to_string(),
            position: position.clone(),
            omega: None,
            axes: None,
        },
    );
    if let (Some(Some(mass)), Some(syntax)) = (mass, &p.mass) {
        let what = format!("point `{}`", p.name);
        let name = p.name.to_string();
        items
            .checks
            .extend(physical::mass(lw, &name, &what, syntax, mass));
        items.skeleton.masses.push(fixed_in);
        items.points.push(PointModel {
            name: p.name.to_string(),
            mass,
            position,
        });
    }
}

/// `[A, B, C]` → diag(A, B, C); `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` → the symmetric tensor.
fn inertia_matrix(lw: &mut Lowerer, e: &Expr) -> Option<[[Sym; 3]; 3]> {
    let entries = lw.vector(e, Mode::Constant)?;
    // `check` has reported any other length.
    if !(entries.len() == 3 || entries.len() == 6) {
        return None;
    }
    let zero = lw.ctx.zero();
    let mut m = [[zero; 3]; 3];
    for i in 0..3 {
        m[i][i] = entries[i];
    }
    if entries.len() == 6 {
        for (k, (i, j)) in [(0, 1), (0, 2), (1, 2)].into_iter().enumerate() {
            m[i][j] = entries[3 + k];
            m[j][i] = entries[3 + k];
        }
    }
    Some(m)
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
        let (fname, dim) = (frame.name.clone(), frame.position.len());
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
