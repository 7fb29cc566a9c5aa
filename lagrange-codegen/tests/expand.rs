//! Expansion snapshot of a small system: the generated impl, pretty-printed, is
//! pinned so that any change to the emitted code is seen in review.

#[test]
fn pendulum_expansion() {
    let input: syn::DeriveInput = syn::parse_str(
        "#[lagrange(coordinates(theta), point(bob, mass = m, at = [l*sin(theta), -l*cos(theta)]), gravity = [0, -g])]
         pub struct Pendulum { pub m: f64, pub l: f64, pub g: f64 }",
    )
    .unwrap();
    let tokens = lagrange_codegen::expand(&input);
    let file: syn::File = syn::parse2(tokens).expect("expansion parses as a file");
    insta::assert_snapshot!(prettyplease::unparse(&file));
}

/// `emit(jacobians, batched)`: the batched q̈ and derivative programs beside
/// the scalar ones, parameters and constants splatted, states read as lanes.
#[test]
fn batched_pendulum_expansion() {
    let input: syn::DeriveInput = syn::parse_str(
        "#[lagrange(coordinates(theta), point(bob, mass = m, at = [l*sin(theta), -l*cos(theta)]), gravity = [0, -g], emit(jacobians, batched))]
         pub struct Pendulum { pub m: f64, pub l: f64, pub g: f64 }",
    )
    .unwrap();
    let tokens = lagrange_codegen::expand(&input);
    let file: syn::File = syn::parse2(tokens).expect("expansion parses as a file");
    insta::assert_snapshot!(prettyplease::unparse(&file));
}

/// Same input, same bytes: the emission must not depend on hash-map iteration order.
#[test]
fn expansion_is_deterministic() {
    let src = "#[lagrange(coordinates(a, b), define(x1 = l*sin(a), y1 = -l*cos(a)),
               point(p1, mass = m, at = [x1, y1]), point(p2, mass = m, at = [x1 + l*sin(b), y1 - l*cos(b)]),
               gravity = [0, -g])]
               struct D { m: f64, l: f64, g: f64 }";
    let input: syn::DeriveInput = syn::parse_str(src).unwrap();
    let a = lagrange_codegen::expand(&input).to_string();
    let b = lagrange_codegen::expand(&input).to_string();
    assert_eq!(a, b);
}

/// A constrained system with a body and every optional output: pins the shape of
/// the `Constrained` impl, the reactions and the Hamiltonian methods.
#[test]
fn constrained_body_expansion() {
    let input: syn::DeriveInput = syn::parse_str(
        "#[lagrange(coordinates(x, y, th),
           body(sled, mass = m, inertia = [0, 0, i], at = [x, y, 0], rotation = rot_z(th)),
           point(blade, on = sled, at = [-b, 0, 0]),
           nonholonomic(sideways = -sin(th) * dot(blade.x) + cos(th) * dot(blade.y)),
           emit(reactions, hamiltonian))]
         pub struct Sleigh { pub m: f64, pub i: f64, pub b: f64 }",
    )
    .unwrap();
    let tokens = lagrange_codegen::expand(&input);
    let file: syn::File = syn::parse2(tokens).expect("expansion parses as a file");
    insta::assert_snapshot!(prettyplease::unparse(&file));
}

/// A driven cart with a set-point spring: pins the shape of the `Driven` impl
/// (inputs emitted as `u[i]`) and of the unforced `Lagrangian` methods.
#[test]
fn driven_expansion() {
    let input: syn::DeriveInput = syn::parse_str(
        "#[lagrange(coordinates(x), inputs(push, xs),
           point(cart, mass = m, at = [x, 0]),
           potential = k / 2 * ((x - xs)^2),
           generalized_force(x = push * cos(x)))]
         pub struct Cart { pub m: f64, pub k: f64 }",
    )
    .unwrap();
    let tokens = lagrange_codegen::expand(&input);
    let file: syn::File = syn::parse2(tokens).expect("expansion parses as a file");
    insta::assert_snapshot!(prettyplease::unparse(&file));
}
