//! A URDF file read into links and joints, numbers kept as written, each
//! element with its line for the errors. Only what the dynamics need is read:
//! inertials, joint origins, axes, types, limits, mimics and `<dynamics>`
//! (visuals and collisions are skipped).

use roxmltree::{Document, Node};

/// A number as the file writes it, and its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Number {
    pub text: String,
    pub value: f64,
}

impl Number {
    pub fn zero() -> Self {
        Number {
            text: "0".into(),
            value: 0.0,
        }
    }

    pub fn is_zero(&self) -> bool {
        self.value == 0.0
    }
}

/// `xyz` and `rpy` of an `<origin>` (zeros when absent).
#[derive(Clone, Debug)]
pub struct Origin {
    pub xyz: [Number; 3],
    pub rpy: [Number; 3],
}

/// A link's `<inertial>`: mass, the inertial frame, and the tensor entries in it.
#[derive(Clone, Debug)]
pub struct Inertial {
    pub mass: Number,
    pub origin: Origin,
    /// ixx, iyy, izz, ixy, ixz, iyz.
    pub inertia: [Number; 6],
    /// The `<inertia>` element's line.
    pub line: u32,
}

#[derive(Clone, Debug)]
pub struct Link {
    pub name: String,
    pub line: u32,
    pub inertial: Option<Inertial>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointType {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    /// Six degrees of freedom: read only as the joint that puts the robot's
    /// base on a free root (see `describe::free_root`).
    Floating,
}

/// `<mimic joint=".." multiplier=".." offset="..">`.
#[derive(Clone, Debug)]
pub struct Mimic {
    pub joint: String,
    pub multiplier: Number,
    pub offset: Number,
}

#[derive(Clone, Debug)]
pub struct Joint {
    pub name: String,
    pub line: u32,
    pub kind: JointType,
    pub parent: String,
    pub child: String,
    pub origin: Origin,
    /// The axis as written (URDF's default x when absent).
    pub axis: [Number; 3],
    /// Lower and upper position limits, if the file gives them.
    pub limits: Option<(f64, f64)>,
    /// The `<limit effort>`: the most force or torque the joint's actuator
    /// gives, if the file states it.
    pub effort: Option<f64>,
    /// The `<limit velocity>`: the joint's top speed, if the file states it.
    pub velocity: Option<f64>,
    pub mimic: Option<Mimic>,
    /// `<dynamics damping=".." friction="..">`, if the file gives it.
    pub dynamics: Option<Dynamics>,
}

/// `<dynamics damping=".." friction="..">` (each 0 when absent), with the
/// element's line.
#[derive(Clone, Debug)]
pub struct Dynamics {
    pub damping: Number,
    pub friction: Number,
    pub line: u32,
}

#[derive(Clone)]
pub struct Robot {
    pub name: String,
    pub links: Vec<Link>,
    pub joints: Vec<Joint>,
}

/// A failure to read the file: the line (0 when it has none) and what.
pub struct ReadError {
    pub line: u32,
    pub message: String,
}

fn error(line: u32, message: impl Into<String>) -> ReadError {
    ReadError {
        line,
        message: message.into(),
    }
}

fn line_of(doc: &Document, node: Node) -> u32 {
    doc.text_pos_at(node.range().start).row
}

/// Parses the text of a URDF file.
pub fn parse(text: &str) -> Result<Robot, ReadError> {
    let doc =
        Document::parse(text).map_err(|e| error(e.pos().row, format!("malformed XML: {e}")))?;
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        return Err(error(
            line_of(&doc, root),
            "the root element is not <robot>",
        ));
    }
    let mut links = Vec::new();
    let mut joints = Vec::new();
    for node in root.children().filter(Node::is_element) {
        match node.tag_name().name() {
            "link" => links.push(link(&doc, node)?),
            "joint" => joints.push(joint(&doc, node)?),
            _ => {}
        }
    }
    let name = root.attribute("name").unwrap_or("robot").to_string();
    Ok(Robot {
        name,
        links,
        joints,
    })
}

fn required<'a>(doc: &Document, node: Node<'a, '_>, attribute: &str) -> Result<&'a str, ReadError> {
    node.attribute(attribute).ok_or_else(|| {
        error(
            line_of(doc, node),
            format!("<{}> has no `{attribute}`", node.tag_name().name()),
        )
    })
}

fn number(doc: &Document, node: Node, text: &str) -> Result<Number, ReadError> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| error(line_of(doc, node), format!("`{text}` is not a number")))?;
    if !value.is_finite() {
        return Err(error(line_of(doc, node), format!("`{text}` is not finite")));
    }
    Ok(Number {
        text: text.trim().to_string(),
        value,
    })
}

/// Three numbers separated by blanks (`xyz="0 0 1"`).
fn triple(doc: &Document, node: Node, text: Option<&str>) -> Result<[Number; 3], ReadError> {
    let Some(text) = text else {
        return Ok([Number::zero(), Number::zero(), Number::zero()]);
    };
    let parts: Vec<&str> = text.split_whitespace().collect();
    if parts.len() != 3 {
        return Err(error(
            line_of(doc, node),
            format!("`{text}` should be three numbers"),
        ));
    }
    Ok([
        number(doc, node, parts[0])?,
        number(doc, node, parts[1])?,
        number(doc, node, parts[2])?,
    ])
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.has_tag_name(tag))
}

fn origin(doc: &Document, node: Node) -> Result<Origin, ReadError> {
    match child(node, "origin") {
        None => triple(doc, node, None).map(|zero| Origin {
            xyz: zero.clone(),
            rpy: zero,
        }),
        Some(o) => Ok(Origin {
            xyz: triple(doc, o, o.attribute("xyz"))?,
            rpy: angles(doc, o, triple(doc, o, o.attribute("rpy"))?)?,
        }),
    }
}

fn link(doc: &Document, node: Node) -> Result<Link, ReadError> {
    let name = required(doc, node, "name")?.to_string();
    let inertial = match child(node, "inertial") {
        None => None,
        Some(i) => Some(inertial(doc, i)?),
    };
    Ok(Link {
        name,
        line: line_of(doc, node),
        inertial,
    })
}

fn inertial(doc: &Document, node: Node) -> Result<Inertial, ReadError> {
    let line = line_of(doc, node);
    let element = child(node, "mass").ok_or_else(|| error(line, "<inertial> has no <mass>"))?;
    let mass = number(doc, element, required(doc, element, "value")?)?;
    let tensor =
        child(node, "inertia").ok_or_else(|| error(line, "<inertial> has no <inertia>"))?;
    let entry = |key: &str| number(doc, tensor, required(doc, tensor, key)?);
    let inertia = [
        entry("ixx")?,
        entry("iyy")?,
        entry("izz")?,
        entry("ixy")?,
        entry("ixz")?,
        entry("iyz")?,
    ];
    if mass.value < 0.0 {
        return Err(error(
            line_of(doc, element),
            format!("<mass value='{}'> is negative: a mass never is", mass.text),
        ));
    }
    Ok(Inertial {
        mass,
        origin: origin(doc, node)?,
        inertia,
        line: line_of(doc, tensor),
    })
}

/// The largest angle a file may write, in magnitude: a full turn (and the
/// round-off of a file's 6.28318530718). Beyond it an angle is almost surely
/// in degrees.
const TURN: f64 = std::f64::consts::TAU * (1.0 + 1e-9);

/// An `rpy` in radians, refused at its line when an angle exceeds a turn.
fn angles(doc: &Document, node: Node, rpy: [Number; 3]) -> Result<[Number; 3], ReadError> {
    if let Some(a) = rpy.iter().find(|a| a.value.abs() > TURN) {
        return Err(error(
            line_of(doc, node),
            format!(
                "rpy angle `{}` exceeds a full turn (2π = 6.2832): URDF angles are in radians, \
                 so this looks like degrees; write it in radians (90° = 1.5708, {}° = {:.4})",
                a.text,
                a.text,
                a.value.to_radians()
            ),
        ));
    }
    Ok(rpy)
}

fn joint_type(doc: &Document, node: Node, name: &str) -> Result<JointType, ReadError> {
    Ok(match required(doc, node, "type")? {
        "revolute" => JointType::Revolute,
        "continuous" => JointType::Continuous,
        "prismatic" => JointType::Prismatic,
        "fixed" => JointType::Fixed,
        "floating" => JointType::Floating,
        other => {
            return Err(error(
                line_of(doc, node),
                format!(
                    "joint `{name}` has type `{other}`, which is not supported (revolute, \
                     continuous, prismatic and fixed are)"
                ),
            ));
        }
    })
}

fn joint(doc: &Document, node: Node) -> Result<Joint, ReadError> {
    let name = required(doc, node, "name")?.to_string();
    let kind = joint_type(doc, node, &name)?;
    let end = |tag: &str| -> Result<String, ReadError> {
        let element = child(node, tag)
            .ok_or_else(|| error(line_of(doc, node), format!("joint `{name}` has no <{tag}>")))?;
        Ok(required(doc, element, "link")?.to_string())
    };
    let axis = match child(node, "axis") {
        None => [
            Number {
                text: "1".into(),
                value: 1.0,
            },
            Number::zero(),
            Number::zero(),
        ],
        Some(a) => triple(doc, a, a.attribute("xyz"))?,
    };
    let limits = match child(node, "limit") {
        Some(l) if kind != JointType::Continuous => Some((
            number(doc, l, l.attribute("lower").unwrap_or("0"))?.value,
            number(doc, l, l.attribute("upper").unwrap_or("0"))?.value,
        )),
        _ => None,
    };
    let limit = |key: &str| -> Result<Option<f64>, ReadError> {
        match child(node, "limit").and_then(|l| l.attribute(key).map(|e| (l, e))) {
            Some((l, e)) => Ok(Some(number(doc, l, e)?.value)),
            None => Ok(None),
        }
    };
    let (effort, velocity) = (limit("effort")?, limit("velocity")?);
    // A fixed (or floating) joint's <mimic> has no coordinate to follow: a
    // gripper locked by hand keeps its followers' tags, and they stay fixed.
    let mimic = match child(node, "mimic") {
        None => None,
        Some(_) if matches!(kind, JointType::Fixed | JointType::Floating) => None,
        Some(m) => Some(Mimic {
            joint: required(doc, m, "joint")?.to_string(),
            multiplier: number(doc, m, m.attribute("multiplier").unwrap_or("1"))?,
            offset: number(doc, m, m.attribute("offset").unwrap_or("0"))?,
        }),
    };
    let dynamics = match child(node, "dynamics") {
        None => None,
        Some(d) => Some(Dynamics {
            damping: number(doc, d, d.attribute("damping").unwrap_or("0"))?,
            friction: number(doc, d, d.attribute("friction").unwrap_or("0"))?,
            line: line_of(doc, d),
        }),
    };
    Ok(Joint {
        parent: end("parent")?,
        child: end("child")?,
        name,
        line: line_of(doc, node),
        kind,
        origin: origin(doc, node)?,
        axis,
        limits,
        effort,
        velocity,
        mimic,
        dynamics,
    })
}
