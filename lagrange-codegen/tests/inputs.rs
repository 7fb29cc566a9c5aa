//! `inputs(...)`: where they are accepted, where they are rejected (one spanned
//! error each, with the reason and the fix), and what the model keeps of them.

mod common;

use common::model;

fn errors(src: &str) -> Vec<String> {
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    match lagrange_codegen::model(&input) {
        Ok(_) => Vec::new(),
        Err(e) => e.into_iter().map(|e| e.to_string()).collect(),
    }
}

/// A planar or spatial scene with `inputs(u)` and the given items.
fn with(items: &str) -> String {
    format!("#[lagrange(coordinates(x, a), inputs(u), {items})] struct S {{ m: f64, l: f64 }}")
}

fn rejected(items: &str, place: &str) {
    let errs = errors(&with(items));
    assert_eq!(errs.len(), 1, "{items}: {errs:?}");
    let expected = format!("input `u` cannot appear in {place}:");
    assert!(errs[0].starts_with(&expected), "{items}: {}", errs[0]);
    assert!(
        errs[0].ends_with(
            "apply the input as a force (`force`, `generalized_force`, `potential` or `dissipation`)"
        ),
        "{}",
        errs[0]
    );
}

#[test]
fn rejected_wherever_the_derivation_differentiates_in_time() {
    let p = "point(p, mass = m, at = [x, 0, 0])";
    rejected("point(p, mass = m, at = [x + u, 0, 0])", "a position map");
    rejected(
        &format!(
            "{p}, body(b, mass = m, inertia = [l, l, l], at = [x, u, 0], rotation = rot_z(a))"
        ),
        "a position map",
    );
    rejected(
        &format!(
            "{p}, body(b, mass = m, inertia = [l, l, l], at = [x, 0, 0], rotation = rot_z(a + u))"
        ),
        "a rotation",
    );
    rejected(
        &format!(
            "{p}, body(b, mass = m, inertia = [l, u, l], at = [x, 0, 0], rotation = rot_z(a))"
        ),
        "an inertia",
    );
    rejected("point(p, mass = m * u, at = [x, a, 0])", "a mass");
    rejected(&format!("{p}, gravity = [0, 0, -u]"), "gravity");
    rejected(
        &format!("{p}, holonomic(c = x - u * a)"),
        "a holonomic constraint",
    );
    rejected(
        &format!("{p}, nonholonomic(c = dot(x) - u * dot(a))"),
        "a nonholonomic constraint",
    );
    rejected(
        &format!("{p}, nonholonomic(c = dot(x) - l * dot(a)), speeds(w = dot(a) + u)"),
        "a speed",
    );
}

#[test]
fn a_definition_carries_its_input_to_the_use_site() {
    let errs = errors(&with(
        "define(d = l * u), point(p, mass = m, at = [x, d, 0])",
    ));
    assert_eq!(errs.len(), 1, "{errs:?}");
    assert!(
        errs[0].starts_with("`d` uses the input `u`, which cannot appear in a position map"),
        "{}",
        errs[0]
    );
}

#[test]
fn accepted_in_forces() {
    let m = model(&with(
        "define(d = l * u * dot(x)), point(p, mass = m, at = [x, l * sin(a), 0]),
         force(p, [d, u, 0]), generalized_force(a = u), potential = m * ((x - u)^2),
         dissipation = u * (dot(a)^2)",
    ));
    let inputs = m.inputs.as_ref().expect("inputs declared");
    assert_eq!(inputs.names, ["u"]);
    assert_eq!(inputs.forces.len(), 2);
    assert_eq!(inputs.jacobian_u.len(), 2);
    assert_eq!(inputs.jacobian_u[0].len(), 1);
    // The unforced system has no input left in it.
    let u = inputs.symbols[0];
    let all = m
        .motion
        .forces
        .iter()
        .chain(&m.motion.rhs)
        .chain([&m.energies.potential, &m.energies.integral]);
    for &e in all {
        assert!(!m.ctx.depends_on(e, u));
    }
}

#[test]
fn no_inputs_no_input_model() {
    let m =
        model("#[lagrange(coordinates(x), point(p, mass = m, at = [x, 0]))] struct S { m: f64 }");
    assert!(m.inputs.is_none());
}

#[test]
fn names_clash_at_the_input() {
    for (items, what) in [
        ("inputs(x), point(p, mass = m, at = [x, 0])", "coordinate"),
        ("inputs(m), point(p, mass = m, at = [x, 0])", "parameter"),
        ("inputs(p), point(p, mass = m, at = [x, 0])", "point"),
        (
            "inputs(d), define(d = 2 * x), point(p, mass = m, at = [x, 0])",
            "definition",
        ),
    ] {
        let errs = errors(&format!(
            "#[lagrange(coordinates(x), {items})] struct S {{ m: f64 }}"
        ));
        assert_eq!(errs.len(), 1, "{items}: {errs:?}");
        assert!(
            errs[0].contains(&format!(
                "already used as a {what}; give the input another name"
            )),
            "{}",
            errs[0]
        );
    }
}
