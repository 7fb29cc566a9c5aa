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
