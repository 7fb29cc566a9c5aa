//! Structural rules on the parsed description, one `check_*` per rule. Every rule
//! reports through the [`Ctxt`] and carries on, so all violations surface together.
//! Rules that need expressions resolved (unknown symbols, velocities in positions)
//! live in `lower`, where the names are known.

use std::collections::BTreeMap;

use syn::{Expr, Ident};

use crate::ast::{Extra, Formulation, System};
use crate::ctxt::Ctxt;

mod joints;
use joints::check_joints;

/// Names the expression language gives a meaning of its own.
pub(crate) const RESERVED: &[&str] = &["t", "pi", "PI", "dot", "self"];

/// Applies every structural rule; returns whether each name stands for one
/// thing. A name declared twice makes every use of it ambiguous, so the
/// caller must not resolve expressions (it would report, beside the
/// duplicate, whatever the wrong reading of each use implies: a cycle
/// through a body named like the parameter it reads).
pub fn check(cx: &Ctxt, system: &System) -> bool {
    check_has_coordinates(cx, system);
    check_has_points(cx, system);
    check_point_keys(cx, system);
    check_body_keys(cx, system);
    let unique = check_unique_names(cx, system);
    check_dimensions(cx, system);
    check_load_targets(cx, system);
    check_joints(cx, system);
    check_formulation(cx, system);
    check_batched(cx, system);
    unique
}

/// The formulations a system is emitted in: what `formulation(...)` asks for, or by
/// default multipliers when there are constraints and the reduced form when
/// `speeds(...)` are given.
pub fn formulations(system: &System) -> Vec<Formulation> {
    if !system.formulations.is_empty() {
        let mut out: Vec<Formulation> = system.formulations.iter().map(|(_, f)| *f).collect();
        out.dedup();
        return out;
    }
    let constrained = !(system.holonomic.is_empty() && system.nonholonomic.is_empty());
    let mut out = Vec::new();
    if constrained && system.speeds.is_empty() {
        out.push(Formulation::Multipliers);
    }
    if !system.speeds.is_empty() {
        out.push(Formulation::Reduced);
    }
    out
}

fn check_formulation(cx: &Ctxt, system: &System) {
    let constrained = !(system.holonomic.is_empty() && system.nonholonomic.is_empty());
    for (name, f) in &system.formulations {
        match f {
            Formulation::Multipliers if !constrained => cx.error_at(
                name.span(),
                "`multipliers` needs constraints: add `holonomic(...)` or `nonholonomic(...)`",
            ),
            Formulation::Reduced if !constrained && system.speeds.is_empty() => cx.error_at(
                name.span(),
                "`reduced` needs nonholonomic constraints or `speeds(...)` (quasi-velocities) to reduce to",
            ),
            _ => {}
        }
    }
    let chosen = formulations(system);
    for (name, e) in &system.extras {
        if *e == Extra::Reactions && !chosen.contains(&Formulation::Multipliers) {
            cx.error_at(
                name.span(),
                "`reactions` come from the multipliers: constraints are needed, in the `multipliers` formulation",
            );
        }
        if *e == Extra::Articulated && !chosen.is_empty() {
            cx.error_at(
                name.span(),
                "`articulated` replaces M and its factorisation in the unconstrained dynamics; a constrained system's runs need M: remove `articulated`",
            );
        }
    }
}

/// `batched` emits the unconstrained q̈ of `articulated` or `jacobians` over
/// four `f64` states per call.
fn check_batched(cx: &Ctxt, system: &System) {
    let Some((name, _)) = system.extras.iter().find(|(_, e)| *e == Extra::Batched) else {
        return;
    };
    let asked = |x: Extra| system.extras.iter().any(|(_, e)| *e == x);
    if !(asked(Extra::Articulated) || asked(Extra::Jacobians)) {
        cx.error_at(
            name.span(),
            "`batched` batches the q̈ program of `articulated` or `jacobians`: add one of them to `emit(...)`",
        );
    }
    if !formulations(system).is_empty() {
        cx.error_at(
            name.span(),
            "`batched` batches the unconstrained q̈; a constrained system's runs solve with its constraints: remove `batched`",
        );
    }
    if !matches!(system.scalar, crate::ast::Scalar::F64) {
        cx.error_at(
            name.span(),
            "`batched` runs four `f64` states per call: give the parameters the type `f64`",
        );
    }
}

fn check_body_keys(cx: &Ctxt, system: &System) {
    for b in &system.bodies {
        let missing = [
            (b.mass.is_none(), "mass = m"),
            (b.inertia.is_none(), "inertia = [A, B, C]"),
            (
                b.at.is_none(),
                "at = [x, y, z] (the centre of mass, or the reference point with `com`)",
            ),
            (
                b.rotation.is_none(),
                "rotation = rot_z(psi) * rot_x(theta) * ...",
            ),
        ];
        for (is_missing, key) in missing {
            if is_missing {
                cx.error_at(b.name.span(), format!("body `{}` needs `{key}`", b.name));
            }
        }
        if let Some(at) = &b.at
            && let Expr::Array(a) = at
            && a.elems.len() == 2
        {
            cx.error_spanned_by(
                at,
                format!("body `{}` is a spatial rigid body: give its centre as `[x, y, z]` (for a planar scene use z = 0 and `rot_z(angle)`)", b.name),
            );
        }
        if let Some(com) = &b.com
            && !matches!(com, Expr::Array(a) if a.elems.len() == 3)
        {
            cx.error_spanned_by(
                com,
                format!("`com` of body `{}` is the centre of mass in body coordinates relative to `at`: write `com = [bx, by, bz]`", b.name),
            );
        }
        if let Some(about) = &b.about
            && !matches!(about, Expr::Array(a) if a.elems.len() == 3)
        {
            cx.error_spanned_by(
                about,
                format!("`about` of body `{}` is the point its inertia is given about, in body coordinates relative to `at`: write `about = [ax, ay, az]`", b.name),
            );
        }
        if let Some(inertia) = &b.inertia {
            let n = match inertia {
                Expr::Array(a) => Some(a.elems.len()),
                _ => None,
            };
            if !matches!(n, Some(3 | 6)) {
                cx.error_spanned_by(
                    inertia,
                    format!(
                        "inertia of body `{}` has {}; expected the principal moments `[A, B, C]` or the six entries `[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]` of the inertia tensor about the centre of mass (products with the tensor's sign: I_xy = -∫xy dm)",
                        b.name,
                        match n {
                            Some(k) => format!("{k} entries"),
                            None => "no `[...]` list".to_string(),
                        }
                    ),
                );
            }
        }
    }
}

/// A coordinate that no mass or inertia moves with leaves a zero row in M: the
/// unconstrained and multiplier forms factor M, so that is an error at the
/// coordinate, not a singular matrix at run time. (The reduced form alone may
/// still be regular, M* = WᵀMW, when the constraints fix that coordinate's
/// velocity, so it is left to the run-time check there.) `zero_rows[i]` says
/// whether M's row i is zero; the check takes that rather than the derived model
/// so that it does not depend on the stage after it.
pub fn mass_rows(cx: &Ctxt, system: &System, zero_rows: &[bool]) {
    if formulations(system) == [Formulation::Reduced] {
        return;
    }
    for (i, name) in system.coordinates.iter().enumerate() {
        if zero_rows[i] {
            cx.error_at(
                name.span(),
                format!(
                    "no mass or inertia moves with `{name}`: its row of the mass matrix is zero, so \
                     its acceleration is undetermined; place a point or body whose position or \
                     rotation depends on `{name}`, or remove it from `coordinates(...)`"
                ),
            );
        }
    }
    // An orientation's three rows follow the coordinates' (its body-axis ω).
    let turns = zero_rows[system.coordinates.len()..].chunks(3);
    for (name, rows) in system.orientations.iter().zip(turns) {
        let axes: Vec<&str> = ["x", "y", "z"]
            .into_iter()
            .zip(rows)
            .filter_map(|(axis, &zero)| zero.then_some(axis))
            .collect();
        let msg = if axes.len() == 3 {
            format!(
                "orientation `{name}` turns no mass: no body's `rotation` is `{name}` (nor is a \
                 point placed on such a body), so nothing resists its angular velocity and the \
                 mass matrix is singular at every state; give a body `rotation = {name}`, or \
                 remove `{name}` from `orientation(...)`"
            )
        } else if axes.is_empty() {
            continue;
        } else {
            format!(
                "orientation `{name}`: no inertia resists turning about its body axis {}: the \
                 mass matrix is singular at every state; give the body it turns a positive \
                 moment about that axis",
                axes.join(", ")
            )
        };
        cx.error_at(name.span(), msg);
    }
}

/// An input that no force, potential or dissipation reads would be ignored by
/// every controller driving it. `read[j]` says whether the lowered applied
/// forces (forces, generalized forces, V, D) depend on input j.
pub fn inputs_read(cx: &Ctxt, system: &System, read: &[bool]) {
    let q = system
        .coordinates
        .first()
        .map_or("q".to_string(), ToString::to_string);
    for (name, _) in system.inputs.iter().zip(read).filter(|(_, r)| !**r) {
        cx.error_at(
            name.span(),
            format!(
                "input `{name}` is read by no force, potential or dissipation: a controller \
                 driving it would move nothing; remove it from `inputs(...)` or use it in a \
                 force, e.g. `generalized_force({q} = {name})`"
            ),
        );
    }
}

/// An input that the applied forces read but that drops out of the generalized
/// forces (a potential term without the coordinates, `u - u`): `moves[j]` says
/// whether ΔQ depends on input j.
pub fn inputs_move(cx: &Ctxt, system: &System, moves: &[bool]) {
    for (name, _) in system.inputs.iter().zip(moves).filter(|(_, m)| !**m) {
        cx.error_at(
            name.span(),
            format!(
                "input `{name}` drops out of every generalized force (it appears only in terms \
                 the equations do not feel, such as a potential term without the coordinates), \
                 so a controller driving it would move nothing; use it in a force, or in a \
                 potential or dissipation term together with the coordinates or velocities"
            ),
        );
    }
}

/// A holonomic constraint that depends on no coordinate constrains nothing
/// (its row of G is zero, and a run would stop at once with redundant
/// constraints); a nonholonomic one without velocities is a condition on the
/// configuration; a speed without velocities is no speed (its row of the
/// reduced form is zero). `reads` says, per holonomic constraint,
/// nonholonomic constraint and user speed, whether it reads the coordinates
/// (resp. the velocities).
pub fn constraints_read(cx: &Ctxt, system: &System, reads: [&[bool]; 3]) {
    let what = [
        (
            system.holonomic.iter().map(|c| &c.name).collect::<Vec<_>>(),
            "holonomic constraint",
            "the coordinates: it constrains nothing (its row of G would be zero); write it with the coordinates or points' coordinates (`P.x`)",
        ),
        (
            system.nonholonomic.iter().map(|c| &c.name).collect(),
            "nonholonomic constraint",
            "the velocities: it is a condition on the configuration; write it as `holonomic(...)`, or with the velocities (`dot(q)`, `dot(P.x)`)",
        ),
        (
            system.speeds.iter().map(|u| &u.name).collect(),
            "speed",
            "the velocities: it is no speed (its row of the reduced form would be zero); write it with `dot(q)`",
        ),
    ];
    for ((items, kind, fix), reads) in what.into_iter().zip(reads) {
        for (name, _) in items.iter().zip(reads).filter(|(_, r)| !**r) {
            cx.error_at(
                name.span(),
                format!("{kind} `{name}` does not depend on {fix}"),
            );
        }
    }
}

fn check_has_coordinates(cx: &Ctxt, system: &System) {
    if system.coordinates.is_empty() && system.orientations.is_empty() {
        cx.error_at(
            system.span,
            "no generalized coordinates: add `coordinates(q1, q2, ...)` (or a free rotation, `orientation(name)`) to #[lagrange(...)]",
        );
    }
}

fn check_has_points(cx: &Ctxt, system: &System) {
    let has_mass = !(system.points.is_empty() && system.bodies.is_empty());
    if !has_mass {
        cx.error_at(
            system.span,
            "no point masses: the kinetic energy would be zero; add `point(name, mass = m, at = [x, y, z])`",
        );
    }
}

fn check_point_keys(cx: &Ctxt, system: &System) {
    for p in &system.points {
        if let Some(body) = &p.on
            && !system.bodies.iter().any(|b| b.name == *body)
        {
            cx.error_at(
                body.span(),
                format!(
                    "point `{}` is on {}; bodies are declared with `body(name, ...)`",
                    p.name,
                    what_is(system, body, "body")
                ),
            );
        }
        if p.at.is_none() {
            cx.error_at(
                p.name.span(),
                format!(
                    "point `{}` has no position: add `at = [x, y]` or `at = [x, y, z]`",
                    p.name
                ),
            );
        }
        if p.mass.is_none() && p.on.is_none() {
            cx.error_at(
                p.name.span(),
                format!("point `{}` has no mass: add `mass = ...`", p.name),
            );
        }
    }
}

/// Coordinates, parameters, inputs, definitions and points share one namespace.
/// Inputs are declared last, so a clash involving an input is reported at the
/// input's name.
fn check_unique_names(cx: &Ctxt, system: &System) -> bool {
    let mut seen: BTreeMap<String, &'static str> = BTreeMap::new();
    let mut unique = true;
    let mut declare = |name: &Ident, what: &'static str| {
        let key = name.to_string();
        if RESERVED.contains(&key.as_str()) {
            cx.error_at(
                name.span(),
                format!("`{key}` is reserved in #[lagrange] expressions; rename this {what}"),
            );
            unique = false;
        } else if let Some(prev) = seen.get(&key) {
            let msg = if what == "input" {
                format!(
                    "duplicate name `{key}`: already used as a {prev}; give the input another name (names of inputs, coordinates, orientations, parameters, definitions, points, bodies and speeds must all differ)"
                )
            } else {
                format!("duplicate name `{key}`: already used as a {prev}")
            };
            cx.error_at(name.span(), msg);
            unique = false;
        } else {
            seen.insert(key, what);
        }
    };
    for p in &system.parameters {
        declare(&p.name, "parameter");
    }
    for q in &system.coordinates {
        declare(q, "coordinate");
    }
    for o in &system.orientations {
        declare(o, "orientation");
    }
    for d in &system.definitions {
        declare(&d.name, "definition");
    }
    for p in &system.points {
        declare(&p.name, "point");
    }
    for b in &system.bodies {
        declare(&b.name, "body");
    }
    for c in &system.holonomic {
        declare(&c.name, "constraint");
    }
    for c in &system.nonholonomic {
        declare(&c.name, "constraint");
    }
    for u in &system.speeds {
        declare(&u.name, "speed");
    }
    for u in &system.inputs {
        declare(u, "input");
    }
    unique
}

/// "unknown `wanted` `name`", or "`name`, which is a parameter, not a
/// `wanted`" when the name is declared as something else.
fn what_is(system: &System, name: &Ident, wanted: &str) -> String {
    let declared: [(&str, bool); 7] = [
        ("coordinate", system.coordinates.contains(name)),
        (
            "parameter",
            system.parameters.iter().any(|p| p.name == *name),
        ),
        ("input", system.inputs.contains(name)),
        (
            "definition",
            system.definitions.iter().any(|d| d.name == *name),
        ),
        ("point", system.points.iter().any(|p| p.name == *name)),
        ("body", system.bodies.iter().any(|b| b.name == *name)),
        ("speed", system.speeds.iter().any(|u| u.name == *name)),
    ];
    match declared.iter().find(|(_, is)| *is) {
        Some((kind, _)) => {
            let a = |w: &str| {
                if w.starts_with(['a', 'e', 'i', 'o', 'u']) {
                    "an"
                } else {
                    "a"
                }
            };
            format!(
                "`{name}`, which is {} {kind}, not {} {wanted}",
                a(kind),
                a(wanted)
            )
        }
        None => format!("unknown {wanted} `{name}`"),
    }
}

/// Number of components of a `[..]` vector expression, or an error at it.
pub fn vector_len(cx: &Ctxt, expr: &Expr, what: &str) -> Option<usize> {
    match expr {
        Expr::Array(a) => {
            let n = a.elems.len();
            if n == 2 || n == 3 {
                Some(n)
            } else {
                cx.error_spanned_by(
                    expr,
                    format!("{what} has {n} components; expected 2 (planar) or 3 (spatial)"),
                );
                None
            }
        }
        _ => {
            cx.error_spanned_by(
                expr,
                format!("{what} must be a vector `[x, y]` or `[x, y, z]`"),
            );
            None
        }
    }
}

/// All points, gravity and forces live in one space: 2-D or 3-D, fixed by the first point.
fn check_dimensions(cx: &Ctxt, system: &System) {
    let mut dim: Option<(usize, String)> = None;
    let mut agree = |expr: &Expr, what: String| {
        if let Some(n) = vector_len(cx, expr, &what) {
            match &dim {
                None => dim = Some((n, what)),
                Some((d, first)) if *d != n => cx.error_spanned_by(
                    expr,
                    format!("{what} has {n} components but {first} has {d}; a system is either planar or spatial"),
                ),
                Some(_) => {}
            }
        }
    };
    for b in &system.bodies {
        if let Some(at) = &b.at {
            agree(at, format!("the centre of body `{}`", b.name));
        }
    }
    for p in &system.points {
        if let Some(at) = &p.at {
            agree(at, format!("the position of point `{}`", p.name));
        }
    }
    if let Some(g) = &system.gravity {
        agree(g, "gravity".to_string());
    }
    for f in &system.forces {
        agree(&f.value, format!("the force on `{}`", f.point));
    }
    // A torque turns a body, which is spatial: always three components.
    for t in &system.torques {
        let what = format!("the torque on `{}`", t.body);
        if let Some(n) = vector_len(cx, &t.value, &what).filter(|&n| n != 3) {
            cx.error_spanned_by(
                &t.value,
                format!("{what} has {n} components; it needs three"),
            );
        }
    }
}

/// Each load names a target of the right kind: a force a point or a body, a
/// torque a body, a generalized force a coordinate.
fn check_load_targets(cx: &Ctxt, system: &System) {
    for f in &system.forces {
        let known = system.points.iter().any(|p| p.name == f.point)
            || system.bodies.iter().any(|b| b.name == f.point);
        if !known {
            let hint = if system.coordinates.contains(&f.point) {
                format!(
                    "a force on a coordinate is `generalized_force({} = ...)`",
                    f.point
                )
            } else {
                "points are declared with `point(name, ...)` and bodies with `body(name, ...)`"
                    .to_string()
            };
            let what = what_is(system, &f.point, "point");
            cx.error_at(f.point.span(), format!("force on {what}; {hint}"));
        }
    }
    for t in &system.torques {
        if !system.bodies.iter().any(|b| b.name == t.body) {
            let what = what_is(system, &t.body, "body");
            cx.error_at(
                t.body.span(),
                format!(
                    "torque on {what}; a torque turns a body declared with `body(name, ...)` \
                     (on a coordinate, it is `generalized_force(q = ...)`)"
                ),
            );
        }
    }
    for g in &system.generalized_forces {
        if !system.coordinates.contains(&g.coordinate) {
            cx.error_at(
                g.coordinate.span(),
                format!(
                    "generalized force for {}; it names one of `coordinates(...)`",
                    what_is(system, &g.coordinate, "coordinate")
                ),
            );
        }
    }
}
