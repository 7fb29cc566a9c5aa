//! `urdf = "path"`: a robot's URDF file read at compile time and written as
//! the description items a user would write by hand (`describe`), so that the
//! rest of the derive, and every check, sees an ordinary description.
//!
//! The path is relative to the crate's manifest directory; the generated code
//! includes the file's bytes, so the crate rebuilds when the file changes.
//! URDF is parsed with `roxmltree`: a small, maintained, read-only XML tree
//! that keeps each element's position, which is what the errors need (file and
//! line).

mod describe;
mod dynamics;
mod inertia;
mod model;
mod options;
mod tokens;

pub use options::{
    Base, DEFAULT_SNAP, DynamicsRule, InertiaRule, Options, SNAP_BOUND, parse_attribute,
};

use proc_macro2::{Group, Span, TokenStream, TokenTree};

/// A URDF file read into description items.
pub struct Urdf {
    /// The file's absolute path (for `include_bytes!`).
    pub path: String,
    /// The description's items, each one item of `#[lagrange(...)]` as
    /// tokens (spanned at the call site; see [`Urdf::items_at`]).
    pub items: Vec<TokenStream>,
    /// The robot's name.
    pub name: String,
    /// The coordinates (moving, non-mimic joints, in tree order).
    pub coordinates: Vec<String>,
    /// Their position limits (±∞ where the file gives none).
    pub limits: Vec<(f64, f64)>,
    /// Their effort limits (∞ where the file gives none).
    pub efforts: Vec<f64>,
    /// Their velocity limits (∞ where the file gives none).
    pub velocities: Vec<f64>,
    /// The angles snapped to multiples of π/2: where, as written, as snapped.
    pub snapped: Vec<(String, f64, f64)>,
    /// The inertias `inertia = repair` changed: the link, the entries (ixx,
    /// iyy, izz, ixy, ixz, iyz) as written and as used.
    pub repaired: Vec<inertia::Repaired>,
}

/// Rewrites every `rpy` angle within `tol` of a multiple of π/2 (but not
/// already one) as that multiple, and says which: the file's `1.5707963` is
/// not π/2, and only the exact quarter turn makes the placements' zeros exact.
fn snap(robot: &mut model::Robot, tol: f64) -> Vec<(String, f64, f64)> {
    let mut changed = Vec::new();
    let mut one = |at: String, n: &mut model::Number| {
        let k = (n.value / std::f64::consts::FRAC_PI_2).round();
        let exact = k * std::f64::consts::FRAC_PI_2;
        if n.value != exact && (n.value - exact).abs() <= tol {
            changed.push((at, n.value, exact));
            *n = model::Number {
                text: format!("{exact:?}"),
                value: exact,
            };
        }
    };
    for j in &mut robot.joints {
        for (k, n) in j.origin.rpy.iter_mut().enumerate() {
            one(format!("joint `{}` rpy[{k}]", j.name), n);
        }
    }
    for l in &mut robot.links {
        if let Some(i) = &mut l.inertial {
            for (k, n) in i.origin.rpy.iter_mut().enumerate() {
                one(format!("link `{}` inertial rpy[{k}]", l.name), n);
            }
        }
    }
    changed
}

impl Urdf {
    /// The items with every token spanned at `span` (the path in the
    /// attribute), so that an error an item raises points there.
    pub fn items_at(&self, span: Span) -> impl Iterator<Item = TokenStream> + '_ {
        self.items
            .iter()
            .map(move |item| respan(item.clone(), span))
    }
}

/// `tokens` with every span set to `span`.
fn respan(tokens: TokenStream, span: Span) -> TokenStream {
    tokens
        .into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) => {
                let mut out = Group::new(g.delimiter(), respan(g.stream(), span));
                out.set_span(span);
                TokenTree::Group(out)
            }
            mut other => {
                other.set_span(span);
                other
            }
        })
        .collect()
}

/// Reads `path` (relative to `manifest_dir`) into description items; the
/// error quotes the file and line.
pub fn load(
    manifest_dir: &str,
    path: &str,
    fields: &[String],
    options: Options,
) -> Result<Urdf, String> {
    let full = std::path::Path::new(manifest_dir).join(path);
    let text = std::fs::read_to_string(&full)
        .map_err(|e| format!("cannot read the URDF file `{}`: {e}", full.display()))?;
    from_text(&text, path, fields, options).map(|mut urdf| {
        urdf.path = full.display().to_string();
        urdf
    })
}

/// [`load`] for the text of a file named `path`; angles within `options.snap`
/// of a multiple of π/2 become it (see `snap`). A struct field named
/// `<link>_mass` (among `fields`) replaces that link's mass.
pub fn from_text(
    text: &str,
    path: &str,
    fields: &[String],
    options: Options,
) -> Result<Urdf, String> {
    let at = |e: model::ReadError| match e.line {
        0 => format!("{path}: {}", e.message),
        line => format!("{path}:{line}: {}", e.message),
    };
    let mut robot = model::parse(text).map_err(at)?;
    let repaired = inertia::apply(&mut robot, options.inertia).map_err(at)?;
    let snapped = snap(&mut robot, options.snap);
    let rules = (options.base, options.dynamics, options.limits);
    let d = describe::describe(&robot, fields, rules).map_err(at)?;
    Ok(Urdf {
        path: path.to_string(),
        items: d.items,
        name: robot.name,
        coordinates: d.coordinates,
        limits: d.limits,
        efforts: d.efforts,
        velocities: d.velocities,
        snapped,
        repaired,
    })
}
