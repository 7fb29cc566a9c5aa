//! The derive never panics: random descriptions — random expressions over the
//! names in scope, points, bodies, constraints, speeds, in valid and invalid
//! combinations — either expand to code that parses or to spanned errors.

use proptest::prelude::*;

/// A random expression of the description language (and some things outside it).
fn expr() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        Just("x".to_string()),
        Just("y".to_string()),
        Just("a".to_string()),
        Just("m".to_string()),
        Just("l".to_string()),
        Just("t".to_string()),
        Just("pi".to_string()),
        Just("2".to_string()),
        Just("0.5".to_string()),
        Just("0".to_string()),
        Just("dot(x)".to_string()),
        Just("dot(a)".to_string()),
        Just("p.x".to_string()),
        Just("p.z".to_string()),
        Just("dot(p.y)".to_string()),
        Just("b.omega_z".to_string()),
        Just("b.omega_1".to_string()),
        Just("b.x".to_string()),
        Just("nope".to_string()),
        Just("self.m".to_string()),
        Just("f".to_string()),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} + {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} - {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} * {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} / {b})")),
            (inner.clone(), 0..4i32).prop_map(|(a, n)| format!("(({a})^{n})")),
            inner.clone().prop_map(|a| format!("sin({a})")),
            inner.clone().prop_map(|a| format!("cos({a})")),
            inner.clone().prop_map(|a| format!("sqrt({a})")),
            inner.clone().prop_map(|a| format!("-{a}")),
            inner.clone().prop_map(|a| format!("{a}.exp()")),
            (inner.clone(), inner).prop_map(|(a, b)| format!("atan2({a}, {b})")),
        ]
    })
}

/// Items built from random expressions, some valid and some not.
fn items() -> impl Strategy<Value = Vec<String>> {
    let item = prop_oneof![
        (expr(), expr()).prop_map(|(a, b)| format!("point(q, mass = m, at = [{a}, {b}, 0])")),
        expr().prop_map(|a| format!("potential = {a}")),
        expr().prop_map(|a| format!("holonomic(h1 = {a})")),
        expr().prop_map(|a| format!("nonholonomic(n1 = {a})")),
        expr().prop_map(|a| format!("speeds(u1 = {a})")),
        expr().prop_map(|a| format!("force(p, [{a}, 0, 0])")),
        expr().prop_map(|a| format!("generalized_force(x = {a})")),
        expr().prop_map(|a| format!("dissipation = {a}")),
        expr().prop_map(|a| format!(
            "body(c, mass = m, inertia = [l, l, {a}], at = [0, 0, 0], rotation = rot_x({a}))"
        )),
        Just("formulation(reduced)".to_string()),
        Just("formulation(multipliers)".to_string()),
        Just("emit(reactions, coriolis, jacobians, hamiltonian)".to_string()),
        Just(
            "body(c, mass = m, inertia = [l, l], at = [0, 0], rotation = [[1, 0], [0, 1]])"
                .to_string()
        ),
    ];
    prop::collection::vec(item, 0..4)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn expand_never_panics(position in (expr(), expr()), extra in items()) {
        let src = format!(
            "#[lagrange(coordinates(x, y, a), inputs(f),
               body(b, mass = m, inertia = [l, l, m], at = [x, y, 0], rotation = rot_z(a)),
               point(p, mass = m, at = [{}, {}, 0]),
               gravity = [0, 0, -9.81], {})]
             struct S {{ m: f64, l: f64 }}",
            position.0,
            position.1,
            extra.join(", ")
        );
        let input: syn::DeriveInput = syn::parse_str(&src).expect("the harness writes valid Rust");
        let result = std::panic::catch_unwind(|| lagrange_codegen::expand(&input));
        let tokens = match result {
            Ok(t) => t,
            Err(_) => panic!("expand panicked on\n{src}"),
        };
        // Either way the output is Rust items (code, or compile_error! plus stubs).
        prop_assert!(syn::parse2::<syn::File>(tokens).is_ok(), "unparsable output for\n{src}");
    }
}
