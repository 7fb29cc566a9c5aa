//! A robot read from URDF written as the description a user would write by
//! hand: one coordinate per moving joint, one body per link (its rotation its
//! parent's followed by the joint's `rpy` and its axis rotation), and one
//! point per joint on the parent link where the child hangs. The items are
//! built as tokens (`tokens`), never as text: numbers as f64 literals that
//! read back as the file's values bit for bit, the rotations as the products
//! of elementary turns the tree route recognises.

use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::model::{Inertial, Joint, JointType, Number, ReadError, Robot};
use super::options::{Base, DynamicsRule, LimitRule};
use super::tokens::{identifier, product};

/// The description's items, with what the derive publishes beside the
/// equations.
pub struct Description {
    /// Items of `#[lagrange(...)]`, each one item's tokens.
    pub items: Vec<TokenStream>,
    /// The coordinates' names (the moving, non-mimic joints), in tree order.
    pub coordinates: Vec<String>,
    /// Each coordinate's position limits (±∞ where the file gives none).
    pub limits: Vec<(f64, f64)>,
    /// Each coordinate's effort limit (∞ where the file gives none).
    pub efforts: Vec<f64>,
    /// Each coordinate's velocity limit (∞ where the file gives none).
    pub velocities: Vec<f64>,
}

fn error(line: u32, message: String) -> ReadError {
    ReadError { line, message }
}

/// `x` as an f64 literal (see `tokens::number`), or an error at `line` when
/// it is beyond f64's range: a file's numbers are finite, but one computed
/// from them (an inertia turned into the link's axes) may overflow.
fn number(x: f64, line: u32) -> Result<TokenStream, ReadError> {
    super::tokens::number(x).ok_or_else(|| {
        error(
            line,
            format!(
                "a number computed from the file here is {x}, beyond f64's range: write the \
                 file's quantities in other units"
            ),
        )
    })
}

/// The file's numbers `ns` as literals (see [`number`]).
fn numbers(ns: &[Number], line: u32) -> Result<Vec<TokenStream>, ReadError> {
    ns.iter().map(|n| number(n.value, line)).collect()
}

/// The links in tree order (parents first) with the joint each hangs on.
fn tree_order(robot: &Robot) -> Result<Vec<(&str, Option<&Joint>)>, ReadError> {
    let mut lines = BTreeMap::new();
    for l in &robot.links {
        if lines.insert(l.name.as_str(), l.line).is_some() {
            return Err(error(l.line, format!("link `{}` is defined twice", l.name)));
        }
    }
    let mut parent_of: BTreeMap<&str, &Joint> = BTreeMap::new();
    for j in &robot.joints {
        for end in [&j.parent, &j.child] {
            if !lines.contains_key(end.as_str()) {
                return Err(error(
                    j.line,
                    format!("joint `{}` names an unknown link `{end}`", j.name),
                ));
            }
        }
        if let Some(first) = parent_of.insert(j.child.as_str(), j) {
            return Err(error(
                j.line,
                format!(
                    "link `{}` is the child of two joints (`{}` and `{}`): a URDF describes a tree",
                    j.child, first.name, j.name
                ),
            ));
        }
    }
    let roots: Vec<&str> = robot
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !parent_of.contains_key(l))
        .collect();
    let root = match roots.as_slice() {
        [root] => *root,
        [] => {
            return Err(error(
                0,
                "every link is some joint's child: the joints form a cycle".into(),
            ));
        }
        many => {
            return Err(error(
                0,
                format!(
                    "the robot has {} root links ({}): a URDF has one",
                    many.len(),
                    many.join(", ")
                ),
            ));
        }
    };
    let mut order = vec![(root, None)];
    let mut k = 0;
    while k < order.len() {
        let link = order[k].0;
        for j in robot.joints.iter().filter(|j| j.parent == link) {
            order.push((j.child.as_str(), Some(j)));
        }
        k += 1;
    }
    if let Some(lost) = robot
        .links
        .iter()
        .find(|l| !order.iter().any(|(n, _)| *n == l.name))
    {
        return Err(error(
            lost.line,
            format!(
                "link `{}` is not reachable from the root `{root}`: its joints form a cycle",
                lost.name
            ),
        ));
    }
    Ok(order)
}

/// `rot_z(yaw) * rot_y(pitch) * rot_x(roll)` of an origin's rpy, zeros left
/// out; `line` is the origin's element's.
fn rpy_factors(rpy: &[Number; 3], line: u32) -> Result<Vec<TokenStream>, ReadError> {
    let mut out = Vec::new();
    for (i, axis) in [(2, "z"), (1, "y"), (0, "x")] {
        if !rpy[i].is_zero() {
            let rot = elementary(axis);
            let angle = number(rpy[i].value, line)?;
            out.push(quote!(#rot(#angle)));
        }
    }
    Ok(out)
}

/// `rot_x`, `rot_y` or `rot_z`: the elementary turn about `axis`.
fn elementary(axis: &str) -> Ident {
    format_ident!("rot_{axis}")
}

/// The rotation by `angle` about the unit axis `n`: an elementary factor when
/// n is a coordinate axis, else that factor conjugated by the constant
/// rotation taking z onto n; `line` is the joint's.
fn axis_factors(
    n: [f64; 3],
    angle: &TokenStream,
    line: u32,
) -> Result<Vec<TokenStream>, ReadError> {
    let names = ["x", "y", "z"];
    for (i, name) in names.iter().enumerate() {
        let others_zero = (0..3).all(|k| k == i || n[k] == 0.0);
        let rot = elementary(name);
        if others_zero && n[i] == 1.0 {
            return Ok(vec![quote!(#rot(#angle))]);
        }
        if others_zero && n[i] == -1.0 {
            let flip = elementary(names[(i + 1) % 3]);
            return Ok(vec![
                quote!(#flip(pi)),
                quote!(#rot(#angle)),
                quote!(#flip(-pi)),
            ]);
        }
    }
    let alpha = n[1].atan2(n[0]);
    let beta = n[2].clamp(-1.0, 1.0).acos();
    let [a, b, minus_b, minus_a] = [alpha, beta, -beta, -alpha].map(|x| number(x, line));
    let a = a?;
    let b = b?;
    let minus_b = minus_b?;
    let minus_a = minus_a?;
    Ok(vec![
        quote!(rot_z(#a)),
        quote!(rot_y(#b)),
        quote!(rot_z(#angle)),
        quote!(rot_y(#minus_b)),
        quote!(rot_z(#minus_a)),
    ])
}

/// The joint's axis as a unit vector.
fn unit_axis(j: &Joint) -> Result<[f64; 3], ReadError> {
    let a = [j.axis[0].value, j.axis[1].value, j.axis[2].value];
    let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if norm == 0.0 || !norm.is_finite() {
        return Err(error(j.line, format!("joint `{}` has a zero axis", j.name)));
    }
    Ok(if (norm - 1.0).abs() < 1e-12 {
        a
    } else {
        a.map(|x| x / norm)
    })
}

/// R(rpy) v, R = Rz(yaw) Ry(pitch) Rx(roll).
fn rotate_rpy(rpy: &[Number; 3], v: [f64; 3]) -> [f64; 3] {
    let m = rpy_matrix(rpy);
    [0, 1, 2].map(|i| (0..3).map(|k| m[i][k] * v[k]).sum())
}

fn rpy_matrix(rpy: &[Number; 3]) -> [[f64; 3]; 3] {
    let (sr, cr) = rpy[0].value.sin_cos();
    let (sp, cp) = rpy[1].value.sin_cos();
    let (sy, cy) = rpy[2].value.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// `mass = .., inertia = [..], com = [..]` in link axes; `mass_field`, a
/// struct field named `<link>_mass`, replaces the file's mass (a payload).
fn mass_items(
    inertial: Option<&Inertial>,
    mass_field: Option<&Ident>,
) -> Result<TokenStream, ReadError> {
    let Some(i) = inertial else {
        let mass = mass_field.map_or_else(|| quote!(0), |f| quote!(#f));
        return Ok(quote!(mass = #mass, inertia = [0, 0, 0]));
    };
    let entries = if i.origin.rpy.iter().all(Number::is_zero) {
        numbers(&i.inertia, i.line)?
    } else {
        let [xx, yy, zz, xy, xz, yz] = i.inertia.clone().map(|n| n.value);
        let t = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
        let r = rpy_matrix(&i.origin.rpy);
        let rt = |a: usize, b: usize| -> f64 {
            (0..3)
                .map(|k| (0..3).map(|l| r[a][k] * t[k][l] * r[b][l]).sum::<f64>())
                .sum()
        };
        [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
            .into_iter()
            .map(|(a, b)| number(rt(a, b), i.line))
            .collect::<Result<_, _>>()?
    };
    let com = numbers(&i.origin.xyz, i.line)?;
    let mass = match mass_field {
        Some(field) => quote!(#field),
        None => number(i.mass.value, i.line)?,
    };
    Ok(quote!(mass = #mass, inertia = [#(#entries),*], com = [#(#com),*]))
}

/// The names given so far, so that no two items share one. URDF keeps links
/// and joints in separate name spaces, the description has one: the joints'
/// names (coordinates, points) are given first, and a link whose name is
/// taken is the body `<link>_link`.
#[derive(Default)]
struct Names(BTreeSet<String>);

impl Names {
    /// `name` as an identifier, or an error at `line` if another item has it.
    fn unique(&mut self, name: &str, line: u32) -> Result<Ident, ReadError> {
        let id = identifier(name);
        if self.0.insert(id.to_string()) {
            return Ok(id);
        }
        Err(error(
            line,
            format!(
                "`{name}` is named `{id}` in the description, which another link, joint or \
                 point, or a field of the struct, already is; rename one of them"
            ),
        ))
    }

    /// The body of link `name`: its name, or `<name>_link` where a joint's
    /// coordinate or point (or another link) already has it.
    fn body(&mut self, name: &str, line: u32) -> Result<Ident, ReadError> {
        let id = identifier(name);
        match self.0.contains(&id.to_string()) {
            false => self.unique(name, line),
            true => self.unique(&format!("{id}_link"), line),
        }
    }
}

/// The coordinates: a free root's position first (when the root is free,
/// `free_root` the line of its link), then one per moving, non-mimic joint
/// in tree order; their limits; and each joint's coordinate.
struct Coordinates<'r> {
    names: Vec<Ident>,
    /// The file's line each comes from (its joint's, or the free root's).
    lines: Vec<u32>,
    limits: Vec<(f64, f64)>,
    efforts: Vec<f64>,
    velocities: Vec<f64>,
    angle_of: BTreeMap<&'r str, Ident>,
}

fn coordinates<'r>(
    order: &[(&'r str, Option<&'r Joint>)],
    names: &mut Names,
    free_root: Option<u32>,
) -> Result<Coordinates<'r>, ReadError> {
    let mut out = Coordinates {
        names: Vec::new(),
        lines: Vec::new(),
        limits: Vec::new(),
        efforts: Vec::new(),
        velocities: Vec::new(),
        angle_of: BTreeMap::new(),
    };
    if let (Some(line), Some((root, _))) = (free_root, order.first()) {
        let root = identifier(root);
        for axis in ["x", "y", "z"] {
            out.names
                .push(names.unique(&format!("{root}_{axis}"), line)?);
            out.lines.push(line);
            out.limits.push((f64::NEG_INFINITY, f64::INFINITY));
            out.efforts.push(f64::INFINITY);
            out.velocities.push(f64::INFINITY);
        }
    }
    for (_, joint) in order {
        let Some(j) = joint else { continue };
        if matches!(j.kind, JointType::Fixed) || j.mimic.is_some() {
            continue;
        }
        let q = names.unique(&j.name, j.line)?;
        out.angle_of.insert(j.name.as_str(), q.clone());
        out.names.push(q);
        out.lines.push(j.line);
        out.limits
            .push(j.limits.unwrap_or((f64::NEG_INFINITY, f64::INFINITY)));
        out.efforts.push(j.effort.unwrap_or(f64::INFINITY));
        out.velocities.push(j.velocity.unwrap_or(f64::INFINITY));
    }
    Ok(out)
}

/// The robot as description items, its base as `base` says: on a free root
/// (coordinates `<root>_x`, `_y`, `_z` for its origin in world axes, first as
/// in Pinocchio's free flyer, and an orientation `<root>_turn` for its
/// rotation, which every other link's rotation begins with) or fixed.
pub fn describe(
    robot: &Robot,
    fields: &[String],
    (base, dynamics, limits): (Base, DynamicsRule, LimitRule),
) -> Result<Description, ReadError> {
    let (robot, floating) = based(robot, base)?;
    let order = tree_order(&robot)?;
    // The struct's fields are parameters, in the description's one name space.
    let mut names = Names(fields.iter().cloned().collect());
    let root_line = robot
        .links
        .iter()
        .find(|l| l.name == order[0].0)
        .map_or(0, |l| l.line);
    let turn = match floating {
        true => Some(names.unique(&format!("{}_turn", identifier(order[0].0)), root_line)?),
        false => None,
    };
    let c = coordinates(&order, &mut names, turn.as_ref().map(|_| root_line))?;
    if c.names.is_empty() {
        return Err(motionless(&robot.name));
    }
    let (points, bodies) = points_and_bodies(&robot, &order, &mut names)?;
    let coordinate_names = &c.names;
    let mut items = vec![quote!(coordinates(#(#coordinate_names),*))];
    items.extend(turn.iter().map(|t| quote!(orientation(#t))));
    let inertials: BTreeMap<&str, Option<&Inertial>> = robot
        .links
        .iter()
        .map(|l| (l.name.as_str(), l.inertial.as_ref()))
        .collect();
    let mut factors: BTreeMap<&str, Vec<TokenStream>> = BTreeMap::new();
    for (link, joint) in &order {
        let body = &bodies[link];
        let field = format_ident!("{body}_mass");
        let masses = mass_items(
            inertials[link],
            fields.contains(&field.to_string()).then_some(&field),
        )?;
        let Some(j) = joint else {
            let (item, mine) = root_body(body, &masses, turn.as_ref(), &c.names);
            items.push(item);
            factors.insert(link, mine);
            continue;
        };
        let parent = (&bodies[j.parent.as_str()], &factors[j.parent.as_str()][..]);
        let (item, mine) = hang(
            j,
            (body, &masses),
            parent,
            &c.angle_of,
            &points[j.name.as_str()],
        )?;
        items.extend(item);
        factors.insert(link, mine);
    }
    items.extend(super::dynamics::joint_items(
        &robot,
        dynamics,
        &c.names,
        &c.angle_of,
    )?);
    if limits == LimitRule::Stops {
        items.extend(stop_items(&c, &mut names)?);
    }
    Ok(Description {
        items,
        coordinates: c.names.iter().map(Ident::to_string).collect(),
        limits: c.limits,
        efforts: c.efforts,
        velocities: c.velocities,
    })
}

/// The error for a robot whose joints are all fixed.
fn motionless(robot: &str) -> ReadError {
    error(
        0,
        format!(
            "the robot `{robot}` has no moving joint (every joint is fixed): nothing in it can \
             move; give a joint a moving type in the file, or put the base on a free root with \
             `urdf(\"..\", base = floating)`"
        ),
    )
}

/// `limits = stops`: a plastic `stop(..)` per finite bound of each
/// coordinate, named `<q>_lower` and `<q>_upper`.
fn stop_items(c: &Coordinates, names: &mut Names) -> Result<Vec<TokenStream>, ReadError> {
    let mut items = Vec::new();
    for ((q, &line), &(lower, upper)) in c.names.iter().zip(&c.lines).zip(&c.limits) {
        if let Some(bound) = super::tokens::number(lower) {
            let name = names.unique(&format!("{q}_lower"), line)?;
            items.push(quote!(stop(#name, #q >= #bound, restitution = 0)));
        }
        if let Some(bound) = super::tokens::number(upper) {
            let name = names.unique(&format!("{q}_upper"), line)?;
            items.push(quote!(stop(#name, #q <= #bound, restitution = 0)));
        }
    }
    Ok(items)
}

/// Each joint's point `<joint>_origin`, then each link's body (named after
/// the joints, so that a link whose name a joint took is `<link>_link`).
#[allow(clippy::type_complexity)]
fn points_and_bodies<'r>(
    robot: &'r Robot,
    order: &[(&'r str, Option<&'r Joint>)],
    names: &mut Names,
) -> Result<(BTreeMap<&'r str, Ident>, BTreeMap<&'r str, Ident>), ReadError> {
    let mut points = BTreeMap::new();
    for j in order.iter().filter_map(|(_, j)| *j) {
        let point = names.unique(&format!("{}_origin", j.name), j.line)?;
        points.insert(j.name.as_str(), point);
    }
    let mut bodies = BTreeMap::new();
    for &(link, _) in order {
        let line = robot
            .links
            .iter()
            .find(|l| l.name == link)
            .map_or(0, |l| l.line);
        bodies.insert(link, names.body(link, line)?);
    }
    Ok((points, bodies))
}

/// The root link's body and its rotation factors: fixed in space, or on a
/// free root turned by the orientation `turn` at the first three coordinates.
fn root_body(
    body: &Ident,
    masses: &TokenStream,
    turn: Option<&Ident>,
    coordinates: &[Ident],
) -> (TokenStream, Vec<TokenStream>) {
    let Some(turn) = turn else {
        let item = quote!(body(#body, #masses, at = [0, 0, 0], rotation = rot_z(0)));
        return (item, Vec::new());
    };
    let at = coordinates.iter().take(3);
    let item = quote!(body(#body, #masses, at = [#(#at),*], rotation = #turn));
    (item, vec![quote!(#turn)])
}

/// The robot with its base as `base` says, and whether that base is on a
/// free root. A file's floating joint (which must hang a bare root link, the
/// world, and be the only one) puts its child on a free root: the robot
/// without that joint and the world link, as `base = floating` reads a file
/// without one. With `base = fixed` that joint becomes a fixed joint, so the
/// base stays where the joint's origin puts it.
fn based(robot: &Robot, base: Base) -> Result<(Cow<'_, Robot>, bool), ReadError> {
    let floating: Vec<&Joint> = robot
        .joints
        .iter()
        .filter(|j| matches!(j.kind, JointType::Floating))
        .collect();
    let Some(&free) = floating.first() else {
        return Ok((Cow::Borrowed(robot), base == Base::Floating));
    };
    if let Some(second) = floating.get(1) {
        return Err(error(
            second.line,
            format!(
                "joint `{}` is floating, and so is `{}`: one free root is read, the robot's base",
                second.name, free.name
            ),
        ));
    }
    let parent = free.parent.as_str();
    let siblings = robot.joints.iter().filter(|j| j.parent == parent).count();
    if robot.joints.iter().any(|j| j.child == parent) || siblings > 1 {
        return Err(error(
            free.line,
            format!(
                "joint `{}` is floating but `{parent}` is not a bare root holding only it: a \
                 free joint is read only where it puts the robot's base on a free root",
                free.name
            ),
        ));
    }
    let mut out = robot.clone();
    if base == Base::Fixed {
        for j in out.joints.iter_mut().filter(|j| j.name == free.name) {
            j.kind = JointType::Fixed;
        }
        return Ok((Cow::Owned(out), false));
    }
    out.joints.retain(|j| j.name != free.name);
    out.links.retain(|l| l.name != parent);
    Ok((Cow::Owned(out), true))
}

/// The point where joint `j` sits on its parent and the child body hung
/// there, with the child's rotation factors.
fn hang(
    j: &Joint,
    (body, masses): (&Ident, &TokenStream),
    (parent_body, parent): (&Ident, &[TokenStream]),
    angle_of: &BTreeMap<&str, Ident>,
    point: &Ident,
) -> Result<(Vec<TokenStream>, Vec<TokenStream>), ReadError> {
    let angle = match &j.mimic {
        None => angle_of.get(j.name.as_str()).map(|q| quote!(#q)),
        Some(m) => {
            let Some(q) = angle_of.get(m.joint.as_str()) else {
                return Err(error(
                    j.line,
                    format!(
                        "joint `{}` mimics `{}`, which is not a moving joint; a joint that \
                         follows a fixed one is fixed too: make it `type=\"fixed\"`",
                        j.name, m.joint
                    ),
                ));
            };
            let factor = number(m.multiplier.value, j.line)?;
            let offset = number(m.offset.value, j.line)?;
            Some(quote!(#factor * #q + #offset))
        }
    };
    let mut mine: Vec<TokenStream> = parent.to_vec();
    mine.extend(rpy_factors(&j.origin.rpy, j.line)?);
    let xyz = numbers(&j.origin.xyz, j.line)?;
    let at = match (j.kind, &angle) {
        (JointType::Prismatic, Some(s)) => {
            let a = rotate_rpy(&j.origin.rpy, unit_axis(j)?);
            xyz.iter()
                .zip(a)
                .map(|(x, a)| {
                    let a = number(a, j.line)?;
                    Ok(quote!(#x + #a * (#s)))
                })
                .collect::<Result<_, _>>()?
        }
        _ => xyz,
    };
    if let (JointType::Revolute | JointType::Continuous, Some(q)) = (j.kind, &angle) {
        mine.extend(axis_factors(unit_axis(j)?, q, j.line)?);
    }
    let rotation = product(&mine);
    let items = vec![
        quote!(point(#point, on = #parent_body, at = [#(#at),*])),
        quote!(body(#body, #masses, at = [#point.x, #point.y, #point.z], rotation = #rotation)),
    ];
    Ok((items, mine))
}
