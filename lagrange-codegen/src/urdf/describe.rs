//! A robot read from URDF written as the description a user would write by
//! hand: one coordinate per moving joint, one body per link (its rotation its
//! parent's followed by the joint's `rpy` and its axis rotation), and one
//! point per joint on the parent link where the child hangs. Numbers are kept
//! as the file writes them, so the tree route recognises the description and
//! the equations read like the file.

use std::collections::{BTreeMap, BTreeSet};

use super::model::{Inertial, Joint, JointType, Number, ReadError, Robot};

/// The description's items as source text, with what the derive publishes
/// beside the equations.
pub struct Description {
    /// Items of `#[lagrange(...)]`, each one parseable on its own.
    pub items: Vec<String>,
    /// The coordinates' names (the moving, non-mimic joints), in tree order.
    pub coordinates: Vec<String>,
    /// Each coordinate's position limits (±∞ where the file gives none).
    pub limits: Vec<(f64, f64)>,
}

fn error(line: u32, message: String) -> ReadError {
    ReadError { line, message }
}

/// A name usable as a Rust identifier: other characters become `_`, a
/// leading digit gets a `_` before it, a keyword one after it.
fn identifier(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    if syn::parse_str::<syn::Ident>(&s).is_err() {
        s.push('_');
    }
    s
}

/// A number as a Rust expression: as written where that is one, else its value.
fn lit(n: &Number) -> String {
    let t = n.text.trim_start_matches('+');
    let ok = syn::parse_str::<syn::Expr>(t).is_ok()
        && t.chars().all(|c| c.is_ascii_digit() || "-.eE+".contains(c));
    if ok {
        format!("({t})")
    } else {
        format!("({:?})", n.value)
    }
}

fn value(x: f64) -> String {
    format!("({x:?})")
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

/// `rot_z(yaw) * rot_y(pitch) * rot_x(roll)` of an origin's rpy, zeros left out.
fn rpy_factors(rpy: &[Number; 3]) -> Vec<String> {
    [(2, "z"), (1, "y"), (0, "x")]
        .iter()
        .filter(|&&(i, _)| !rpy[i].is_zero())
        .map(|&(i, axis)| format!("rot_{axis}({})", lit(&rpy[i])))
        .collect()
}

/// The rotation by `angle` about the unit axis `n`: an elementary factor when
/// n is a coordinate axis, else that factor conjugated by the constant
/// rotation taking z onto n.
fn axis_factors(n: [f64; 3], angle: &str) -> Vec<String> {
    let names = ["x", "y", "z"];
    for (i, name) in names.iter().enumerate() {
        let others_zero = (0..3).all(|k| k == i || n[k] == 0.0);
        if others_zero && n[i] == 1.0 {
            return vec![format!("rot_{name}({angle})")];
        }
        if others_zero && n[i] == -1.0 {
            let flip = names[(i + 1) % 3];
            return vec![
                format!("rot_{flip}(pi)"),
                format!("rot_{name}({angle})"),
                format!("rot_{flip}(-pi)"),
            ];
        }
    }
    let alpha = n[1].atan2(n[0]);
    let beta = n[2].clamp(-1.0, 1.0).acos();
    vec![
        format!("rot_z({})", value(alpha)),
        format!("rot_y({})", value(beta)),
        format!("rot_z({angle})"),
        format!("rot_y({})", value(-beta)),
        format!("rot_z({})", value(-alpha)),
    ]
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
fn mass_items(inertial: Option<&Inertial>, mass_field: Option<&str>) -> String {
    let Some(i) = inertial else {
        let mass = mass_field.unwrap_or("0");
        return format!("mass = {mass}, inertia = [0, 0, 0]");
    };
    let entries: Vec<String> = if i.origin.rpy.iter().all(Number::is_zero) {
        i.inertia.iter().map(lit).collect()
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
            .map(|(a, b)| value(rt(a, b)))
            .to_vec()
    };
    let com: Vec<String> = i.origin.xyz.iter().map(lit).collect();
    format!(
        "mass = {}, inertia = [{}], com = [{}]",
        mass_field.map_or_else(|| lit(&i.mass), str::to_string),
        entries.join(", "),
        com.join(", ")
    )
}

/// The robot as description items.
pub fn describe(robot: &Robot, fields: &[String]) -> Result<Description, ReadError> {
    let order = tree_order(robot)?;
    let inertials: BTreeMap<&str, Option<&Inertial>> = robot
        .links
        .iter()
        .map(|l| (l.name.as_str(), l.inertial.as_ref()))
        .collect();
    let mut names = BTreeSet::new();
    let mut unique = |name: &str, line: u32| -> Result<String, ReadError> {
        let id = identifier(name);
        if names.insert(id.clone()) {
            Ok(id)
        } else {
            Err(error(
                line,
                format!(
                    "`{name}` is named `{id}` in the description, which another link, joint or point already is"
                ),
            ))
        }
    };
    let mut coordinates = Vec::new();
    let mut limits = Vec::new();
    let mut angle_of: BTreeMap<&str, String> = BTreeMap::new();
    for (_, joint) in &order {
        let Some(j) = joint else { continue };
        if matches!(j.kind, JointType::Fixed) || j.mimic.is_some() {
            continue;
        }
        let q = unique(&j.name, j.line)?;
        angle_of.insert(j.name.as_str(), q.clone());
        coordinates.push(q);
        limits.push(j.limits.unwrap_or((f64::NEG_INFINITY, f64::INFINITY)));
    }
    let mut items = vec![format!("coordinates({})", coordinates.join(", "))];
    let mut factors: BTreeMap<&str, Vec<String>> = BTreeMap::new();
    for (link, joint) in &order {
        let body = unique(link, 0)?;
        let field = format!("{body}_mass");
        let masses = mass_items(
            inertials[link],
            fields.contains(&field).then_some(field.as_str()),
        );
        let Some(j) = joint else {
            factors.insert(link, Vec::new());
            items.push(format!(
                "body({body}, {masses}, at = [0, 0, 0], rotation = rot_z(0))"
            ));
            continue;
        };
        let (item, mine) = hang(
            j,
            &body,
            &masses,
            &factors[j.parent.as_str()],
            &angle_of,
            &mut unique,
        )?;
        items.extend(item);
        factors.insert(link, mine);
    }
    Ok(Description {
        items,
        coordinates,
        limits,
    })
}

/// The point where joint `j` sits on its parent and the child body hung
/// there, with the child's rotation factors.
fn hang(
    j: &Joint,
    body: &str,
    masses: &str,
    parent: &[String],
    angle_of: &BTreeMap<&str, String>,
    unique: &mut impl FnMut(&str, u32) -> Result<String, ReadError>,
) -> Result<(Vec<String>, Vec<String>), ReadError> {
    let parent_body = identifier(&j.parent);
    let point = unique(&format!("{}_origin", j.name), j.line)?;
    let angle = match &j.mimic {
        None => angle_of.get(j.name.as_str()).cloned(),
        Some(m) => {
            let Some(q) = angle_of.get(m.joint.as_str()) else {
                return Err(error(
                    j.line,
                    format!(
                        "joint `{}` mimics `{}`, which is not a moving joint",
                        j.name, m.joint
                    ),
                ));
            };
            Some(format!("{} * {q} + {}", lit(&m.multiplier), lit(&m.offset)))
        }
    };
    let mut mine: Vec<String> = parent.to_vec();
    mine.extend(rpy_factors(&j.origin.rpy));
    let xyz: Vec<String> = j.origin.xyz.iter().map(lit).collect();
    let at = match (j.kind, &angle) {
        (JointType::Prismatic, Some(s)) => {
            let a = rotate_rpy(&j.origin.rpy, unit_axis(j)?);
            let moved: Vec<String> = (0..3)
                .map(|k| format!("{} + {} * ({s})", xyz[k], value(a[k])))
                .collect();
            moved.join(", ")
        }
        _ => xyz.join(", "),
    };
    if let (JointType::Revolute | JointType::Continuous, Some(q)) = (j.kind, &angle) {
        mine.extend(axis_factors(unit_axis(j)?, q));
    }
    let rotation = if mine.is_empty() {
        "rot_z(0)".to_string()
    } else {
        mine.join(" * ")
    };
    let items = vec![
        format!("point({point}, on = {parent_body}, at = [{at}])"),
        format!(
            "body({body}, {masses}, at = [{point}.x, {point}.y, {point}.z], rotation = {rotation})"
        ),
    ];
    Ok((items, mine))
}
