//! The `EQUATIONS` text's note on what is listed: M is symmetric and only its
//! upper triangle is written, so "entries not listed are zero" excepts the
//! mirror entries, in the formula form and in the shared listing alike.

mod common;
use common::model;

const SYMMETRIC: &str =
    "M is symmetric: only its entries M[i][j] with i <= j are listed (M[j][i] is the same).";

#[test]
fn small_systems_state_the_symmetry() {
    let m = model(
        "#[lagrange(coordinates(a, b), define(x1 = l*sin(a), y1 = -l*cos(a)),
           point(p1, mass = m, at = [x1, y1]), point(p2, mass = m, at = [x1 + l*sin(b), y1 - l*cos(b)]),
           gravity = [0, -g])]
         struct D { m: f64, l: f64, g: f64 }",
    );
    let text = lagrange_codegen::doc::equations(&m);
    let note =
        format!("\n{SYMMETRIC}\nEntries not listed (other than those mirror entries) are zero.\n");
    assert!(text.contains(&note), "{text}");
    assert!(
        text.contains("M[0][1] = ") && !text.contains("M[1][0]"),
        "{text}"
    );
}

#[test]
fn listings_state_the_symmetry() {
    let src = lagrange_codegen::chain::spatial_chain_source(8);
    let m = model(&src);
    let text = lagrange_codegen::doc::equations(&m);
    let note = format!(
        "\n{SYMMETRIC}\nShared intermediates are named x<k>; entries not listed (other than those mirror entries) are zero.\n"
    );
    assert!(text.contains(&note), "{}", &text[..text.len().min(2000)]);
}

/// A free orientation's angular velocity is written as `VELOCITIES` and the
/// CSV tables name it, `turn.wx`, and its rate `dot(turn.wx)`: never
/// `dot(turn.wx)` for ω itself, as if `turn.wx` were a coordinate.
#[test]
fn an_angular_velocity_is_named_as_the_runtime_names_it() {
    let m = model(
        "#[lagrange(orientation(turn),
           body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
                at = [0, 0, 0], rotation = turn),
           gravity = [0, 0, -g])]
         struct Top { m: f64, a: f64, c: f64, l: f64, g: f64 }",
    );
    let text = lagrange_codegen::doc::equations(&m);
    assert!(
        text.contains("angular velocity in body axes q' = (turn.wx, turn.wy, turn.wz), its rate q'' = (dot(turn.wx), dot(turn.wy), dot(turn.wz))"),
        "{text}"
    );
    // h = ω × Iω reads the angular velocities by those names.
    let h = text
        .lines()
        .find(|l| l.starts_with("h[0]"))
        .unwrap_or_default();
    assert!(
        h.contains("turn.wy") && h.contains("turn.wz") && !h.contains("dot("),
        "{text}"
    );
}
