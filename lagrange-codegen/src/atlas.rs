//! `emit(atlas)`: the free twin of a description written in Euler angles.
//!
//! Each rotation written as three Euler angles of coordinates about one
//! point (`euler_zxz(ψ, θ, φ)`, `euler_zyx(..)`, or three successive `rot_*`
//! whose middle axis differs from both ends) becomes a free orientation in a
//! copy of the description, the twin: its M and h depend on no chart, and
//! the runtime's atlas reads any chart's equations from it. Its inputs and
//! constraints (holonomic and nonholonomic) are the user's, which may read
//! the bodies but not the angles; it is emitted in the multiplier form
//! alone, the one the atlas runs. This stage works
//! on the parsed description (`ast::System` → `ast::System`); the twin
//! then goes through the same stages as the user's description.
//!
//! Every Euler sequence has a second chart: the same sequence after the
//! constant turn R_b(π/2) about its middle axis b. That turn takes e_a to an
//! axis perpendicular to e_a, and a chart's singular set is where the body's
//! c axis lies along e_a (through the offset): the two sets are disjoint,
//! which [`second_chart_is_disjoint`] checks for each rotation at build time.

use proc_macro2::{Span, TokenStream, TokenTree};
use quote::ToTokens;
use syn::{BinOp, Expr, Ident};

use crate::ast::{Formulation, System};
use crate::ctxt::Ctxt;

/// One rotation in Euler angles, as the atlas publishes it.
pub struct EulerTriple {
    /// The first body whose rotation holds it.
    pub body: String,
    /// The three angles' places in the user's coordinates.
    pub coordinates: [usize; 3],
    /// The sequence (0 = x, 1 = y, 2 = z).
    pub axes: [usize; 3],
    /// The twin's orientation that stands for it.
    pub orientation: Ident,
}

/// The twin of `system` and its Euler rotations, or `None` (with errors at
/// `at`, the `atlas` keyword, or at the offending token) when the
/// description has no rotation the atlas can cover or uses an angle
/// elsewhere.
pub fn twin(cx: &Ctxt, system: &System, at: &Ident) -> Option<(System, Vec<EulerTriple>)> {
    if !supported(cx, system, at) {
        return None;
    }
    let mut triples = Vec::new();
    let mut twin = system.clone();
    for body in &mut twin.bodies {
        if let Some(rotation) = &mut body.rotation {
            *rotation = rewrite(rotation, system, &body.name, &mut triples);
        }
    }
    if triples.is_empty() {
        cx.error_at(
            at.span(),
            "`emit(atlas)`: no rotation here has a second chart; the atlas covers three Euler angles of coordinates about one point: `euler_zxz(psi, theta, phi)`, `euler_zyx(..)` or three successive `rot_x/y/z` of coordinates whose middle axis differs from both ends",
        );
        return None;
    }
    for t in &triples {
        if !second_chart_is_disjoint(t.axes) {
            cx.error_at(
                at.span(),
                format!("`emit(atlas)`: `{}`'s rotation has no second chart", t.body),
            );
            return None;
        }
    }
    let angles: Vec<String> = (triples.iter())
        .flat_map(|t| t.coordinates.map(|i| system.coordinates[i].to_string()))
        .collect();
    if let Some((ident, owner)) = used_elsewhere(&twin, &angles) {
        let instead = if owner == NONHOLONOMIC {
            let b = &triples[0].body;
            format!(
                "write the row on the bodies' velocities and angular velocities (`dot({b}.x)`, `{b}.omega_y`)"
            )
        } else {
            "write what depends on the orientation from positions (gravity, points of the body)"
                .into()
        };
        cx.error_at(
            ident.span(),
            format!("`{ident}` is an Euler angle of a rotation that `emit(atlas)` moves between charts, so it (or its rate) may appear only as that rotation's angle, not in {owner}; {instead}, or drop `emit(atlas)`"),
        );
        return None;
    }
    twin.coordinates
        .retain(|c| !angles.contains(&c.to_string()));
    twin.orientations = triples.iter().map(|t| t.orientation.clone()).collect();
    twin.extras.clear();
    twin.shapes.clear();
    // The atlas runs the multiplier form in every chart: the twin is
    // emitted in that form alone (the user's speeds, which may read the
    // angles, stay the user's).
    twin.speeds.clear();
    twin.formulations
        .retain(|(_, f)| *f == Formulation::Multipliers);
    twin.ident = Ident::new("__AtlasFree", Span::call_site());
    twin.generics.params.insert(0, syn::parse_quote!('__twin));
    Some((twin, triples))
}

/// The line `EQUATIONS` gives an `emit(atlas)` description: each rotation,
/// its chart and its second one.
pub fn describe(system: &System) -> Option<String> {
    system
        .extras
        .iter()
        .find(|(_, e)| *e == crate::ast::Extra::Atlas)?;
    let mut triples = Vec::new();
    for body in &system.bodies {
        if let Some(rotation) = &body.rotation {
            rewrite(rotation, system, &body.name, &mut triples);
        }
    }
    let axis = |a: usize| ["x", "y", "z"][a];
    let rotations: Vec<String> = triples
        .iter()
        .map(|t| {
            let names = t.coordinates.map(|i| system.coordinates[i].to_string());
            let sequence = t.axes.map(axis).join("-");
            format!(
                "`{}`'s ({}) in {sequence}, and {sequence} after rot_{}(π/2)",
                t.body,
                names.join(", "),
                axis(t.axes[1])
            )
        })
        .collect();
    Some(format!(
        "atlas: {}; a run leaves the user's chart where its conditioning (|sin| or |cos| of the middle angle) falls below 0.6 and comes back above 0.8 (`Simulation::run_atlas`).",
        rotations.join("; ")
    ))
}

/// What the atlas does not cover yet, refused at `at`. Constraints,
/// holonomic and nonholonomic, are run with multipliers: a description
/// emitted only in the reduced form is refused, one that asks for both
/// (`formulation(multipliers, reduced)`) runs its multiplier form.
fn supported(cx: &Ctxt, system: &System, at: &Ident) -> bool {
    let formulations = crate::check::formulations(system);
    if formulations.contains(&Formulation::Reduced)
        && !formulations.contains(&Formulation::Multipliers)
    {
        cx.error_at(
            at.span(),
            "`emit(atlas)` runs constraints with multipliers, and this description is emitted only in the reduced form (`speeds(..)` or `formulation(reduced)`): ask for both with `formulation(multipliers, reduced)` (the atlas runs the multiplier form, `run_reduced` the reduced one), or drop `emit(atlas)`",
        );
        return false;
    }
    let refused = [
        (
            !system.orientations.is_empty(),
            "a free orientation in the same description: the atlas runs a configuration of coordinates alone; give the Euler-angle rotation an `orientation(..)` of its own instead (a quaternion needs no chart)",
        ),
        (
            system.urdf.is_some(),
            "a URDF robot: its joints turn about one axis each, so it has no Euler triple to switch; a robot's free root is a quaternion already (`base = floating`)",
        ),
    ];
    match refused.iter().find(|(yes, _)| *yes) {
        Some((_, why)) => {
            cx.error_at(
                at.span(),
                format!("`emit(atlas)` is not available with {why}"),
            );
            false
        }
        None => true,
    }
}

/// Whether R_b(π/2) takes e_a off the line of e_a (so that the second
/// chart's singular set misses the first's): the rotated e_a, by the
/// right-hand rule, has no e_a component.
pub fn second_chart_is_disjoint([a, b, _]: [usize; 3]) -> bool {
    // R_b(π/2) e_a = e_b × e_a: the cross product of two different axes.
    let mut turned = [0i8; 3];
    if a != b {
        let third = 3 - a - b;
        turned[third] = if (b + 1) % 3 == a { 1 } else { -1 };
    }
    turned[a] == 0 && turned.iter().any(|&x| x != 0)
}

/// `rotation` with each Euler triple replaced by its orientation's name;
/// new triples are appended to `triples`, ones seen before reuse theirs.
fn rewrite(rotation: &Expr, system: &System, body: &Ident, triples: &mut Vec<EulerTriple>) -> Expr {
    let mut factors = Vec::new();
    flatten(rotation, &mut factors);
    let mut out: Vec<Expr> = Vec::new();
    let mut i = 0;
    while i < factors.len() {
        let (found, used) = triple_at(&factors[i..], system);
        let Some((coordinates, axes)) = found else {
            out.push(factors[i].clone());
            i += 1;
            continue;
        };
        let k = match triples.iter().position(|t| t.coordinates == coordinates) {
            Some(k) => k,
            None => {
                triples.push(EulerTriple {
                    body: body.to_string(),
                    coordinates,
                    axes,
                    orientation: Ident::new(
                        &format!("__euler_{}", triples.len()),
                        Span::call_site(),
                    ),
                });
                triples.len() - 1
            }
        };
        let name = &triples[k].orientation;
        out.push(syn::parse_quote!(#name));
        i += used;
    }
    (out.into_iter())
        .reduce(|acc, f| syn::parse_quote!(#acc * #f))
        .unwrap_or_else(|| rotation.clone())
}

/// The triple that starts the factors, and how many factors it spans.
/// A triple found: its coordinates and its axes.
type Found = Option<([usize; 3], [usize; 3])>;

fn triple_at(factors: &[Expr], system: &System) -> (Found, usize) {
    let Some((name, args)) = call(&factors[0]) else {
        return (None, 1);
    };
    let sequence = match name.as_str() {
        "euler_zxz" => Some([2, 0, 2]),
        "euler_zyx" => Some([2, 1, 0]),
        _ => None,
    };
    if let Some(axes) = sequence {
        let coordinates = args
            .iter()
            .map(|a| coordinate(a, system))
            .collect::<Option<Vec<_>>>();
        return match coordinates.and_then(|c| <[usize; 3]>::try_from(c).ok()) {
            Some(c) => (Some((c, axes)), 1),
            None => (None, 1),
        };
    }
    if factors.len() < 3 {
        return (None, 1);
    }
    let turns: Option<Vec<(usize, usize)>> = factors[..3]
        .iter()
        .map(|f| {
            let (name, args) = call(f)?;
            let axis = ["rot_x", "rot_y", "rot_z"]
                .iter()
                .position(|r| *r == name)?;
            Some((axis, coordinate(args.first()?, system)?))
        })
        .collect();
    match turns {
        Some(t) if t[1].0 != t[0].0 && t[1].0 != t[2].0 && distinct([t[0].1, t[1].1, t[2].1]) => (
            Some(([t[0].1, t[1].1, t[2].1], [t[0].0, t[1].0, t[2].0])),
            3,
        ),
        _ => (None, 1),
    }
}

fn distinct([a, b, c]: [usize; 3]) -> bool {
    a != b && b != c && a != c
}

/// The function name and arguments of a call `f(a, ..)`.
fn call(e: &Expr) -> Option<(String, Vec<&Expr>)> {
    match e {
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) => Some((p.path.get_ident()?.to_string(), c.args.iter().collect())),
            _ => None,
        },
        Expr::Paren(p) => call(&p.expr),
        Expr::Group(g) => call(&g.expr),
        _ => None,
    }
}

/// The index of the coordinate a bare path names.
fn coordinate(e: &Expr, system: &System) -> Option<usize> {
    let Expr::Path(p) = e else { return None };
    let id = p.path.get_ident()?;
    system.coordinates.iter().position(|c| c == id)
}

/// The factors of a product, left to right.
fn flatten(e: &Expr, out: &mut Vec<Expr>) {
    match e {
        Expr::Binary(b) if matches!(b.op, BinOp::Mul(_)) => {
            flatten(&b.left, out);
            flatten(&b.right, out);
        }
        Expr::Paren(p) if matches!(&*p.expr, Expr::Binary(b) if matches!(b.op, BinOp::Mul(_))) => {
            flatten(&p.expr, out)
        }
        _ => out.push(e.clone()),
    }
}

/// Where [`used_elsewhere`] found an angle in a nonholonomic row.
const NONHOLONOMIC: &str = "a nonholonomic constraint";

/// The first token of the (rewritten) description that names one of
/// `angles`, with where it is.
fn used_elsewhere(system: &System, angles: &[String]) -> Option<(Ident, &'static str)> {
    let mut places: Vec<(TokenStream, &'static str)> = Vec::new();
    let mut add = |e: &Option<Expr>, what: &'static str| {
        if let Some(e) = e {
            places.push((e.to_token_stream(), what));
        }
    };
    for b in &system.bodies {
        add(&b.rotation, "a rotation outside its Euler triple");
        for e in [&b.at, &b.mass, &b.inertia, &b.com, &b.about] {
            add(e, "a body's mass, inertia or placement");
        }
    }
    for p in &system.points {
        add(&p.at, "a point's position");
        add(&p.mass, "a point's mass");
    }
    add(&system.gravity, "gravity");
    add(&system.potential, "the potential");
    add(&system.dissipation, "the dissipation");
    let mut rest: Vec<(TokenStream, &'static str)> = Vec::new();
    for d in &system.definitions {
        rest.push((d.value.to_token_stream(), "a `define`"));
    }
    for f in &system.forces {
        rest.push((f.value.to_token_stream(), "a force"));
    }
    for t in &system.torques {
        rest.push((t.value.to_token_stream(), "a torque"));
    }
    for c in &system.holonomic {
        rest.push((c.value.to_token_stream(), "a holonomic constraint"));
    }
    for c in &system.nonholonomic {
        rest.push((c.value.to_token_stream(), NONHOLONOMIC));
    }
    for g in &system.generalized_forces {
        rest.push((
            g.coordinate.to_token_stream(),
            "a generalized force's coordinate",
        ));
        rest.push((g.value.to_token_stream(), "a generalized force"));
    }
    for j in &system.joints {
        rest.push((j.coordinate.to_token_stream(), "a joint's coordinate"));
    }
    places.extend(rest);
    places
        .into_iter()
        .find_map(|(tokens, what)| first_named(tokens, angles).map(|i| (i, what)))
}

fn first_named(tokens: TokenStream, names: &[String]) -> Option<Ident> {
    tokens.into_iter().find_map(|t| match t {
        TokenTree::Ident(i) if names.contains(&i.to_string()) => Some(i),
        TokenTree::Group(g) => first_named(g.stream(), names),
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ball rolling on the plane in both constrained forms, its speeds
    /// the angles' rates: the twin keeps the rolling rows, in the
    /// multiplier form alone and without the speeds (which read the
    /// angles), and the whole description expands without an error.
    #[test]
    fn the_twin_of_both_forms_keeps_the_rows_with_multipliers_only() {
        let input: syn::DeriveInput = syn::parse_str(
            "#[lagrange(coordinates(x, y, psi, theta, phi),
               body(ball, mass = m, inertia = [j, j, j], at = [x, y, a],
                    rotation = euler_zxz(psi, theta, phi)),
               nonholonomic(slip_x = dot(ball.x) - a * ball.omega_y,
                            slip_y = dot(ball.y) + a * ball.omega_x),
               speeds(u1 = dot(psi), u2 = dot(theta), u3 = dot(phi)),
               formulation(multipliers, reduced),
               emit(atlas))]
             struct Ball { m: f64, j: f64, a: f64 }",
        )
        .unwrap();
        let cx = Ctxt::new();
        let system = crate::attr::parse(&cx, &input).unwrap();
        let at = &system.extras[0].0;
        let (twin, triples) = twin(&cx, &system, at).unwrap();
        cx.check().unwrap();
        assert_eq!(triples.len(), 1);
        assert_eq!(twin.nonholonomic.len(), 2);
        assert!(twin.speeds.is_empty());
        let forms: Vec<_> = twin.formulations.iter().map(|(_, f)| *f).collect();
        assert_eq!(forms, [Formulation::Multipliers]);
        let tokens = crate::expand(&input).to_string();
        assert!(!tokens.contains("compile_error"), "{tokens}");
    }

    #[test]
    fn every_euler_sequence_has_a_disjoint_second_chart() {
        for a in 0..3 {
            for b in (0..3).filter(|&b| b != a) {
                for c in (0..3).filter(|&c| c != b) {
                    assert!(second_chart_is_disjoint([a, b, c]));
                }
            }
        }
        assert!(!second_chart_is_disjoint([2, 2, 0]));
    }
}
