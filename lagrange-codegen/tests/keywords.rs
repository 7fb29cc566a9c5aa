//! The attribute's words in the errors: a typo of an output or a formulation
//! is answered with the word it meant, and a list written as an assignment
//! with the list's form, every output in it.

fn error(attribute: &str) -> String {
    let src = format!(
        "#[lagrange(coordinates(x), point(p, mass = m, at = [x, 0]), {attribute})] struct S {{ m: f64 }}"
    );
    let input: syn::DeriveInput = syn::parse_str(&src).expect("a struct");
    match lagrange_codegen::model(&input) {
        Ok(_) => panic!("`{attribute}` was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_misspelt_output_is_answered_with_the_output_it_meant() {
    let e = error("emit(corolis)");
    assert!(e.contains("did you mean `coriolis`?"), "{e}");
}

#[test]
fn an_unknown_output_is_answered_with_every_output_and_what_it_gives() {
    let e = error("emit(identification)");
    for output in ["reactions", "inverse_dynamics", "kinematics", "atlas"] {
        assert!(e.contains(&format!("`{output}`: ")), "{e}");
    }
}

#[test]
fn a_misspelt_formulation_is_answered_with_the_one_it_meant() {
    let e = error("formulation(reduce)");
    assert!(e.contains("did you mean `reduced`?"), "{e}");
}

#[test]
fn emit_written_as_an_assignment_shows_every_output() {
    let e = error("emit = [coriolis]");
    assert!(
        e.contains("emit(reactions, coriolis, jacobians, hamiltonian, articulated, inverse_dynamics, kinematics, atlas, batched, regressor)"),
        "{e}"
    );
}

#[test]
fn a_misspelt_batched_is_answered_with_batched() {
    let e = error("emit(jacobians, batch)");
    assert!(e.contains("did you mean `batched`?"), "{e}");
}

#[test]
fn batched_alone_says_which_program_it_batches() {
    let e = error("emit(batched)");
    assert!(
        e.contains("`batched` batches the q̈ program of `articulated` or `jacobians`"),
        "{e}"
    );
}

#[test]
fn batched_refuses_constraints_and_other_scalars() {
    let src = "#[lagrange(coordinates(x, y), point(p, mass = m, at = [x, y]), holonomic(c = x - y), emit(jacobians, batched))] struct S { m: f64 }";
    let input: syn::DeriveInput = syn::parse_str(src).expect("a struct");
    let e = lagrange_codegen::model(&input)
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("`batched` batches the unconstrained q̈"), "{e}");
    let src = "#[lagrange(coordinates(x), point(p, mass = m, at = [x, 0]), emit(jacobians, batched))] struct S { m: f32 }";
    let input: syn::DeriveInput = syn::parse_str(src).expect("a struct");
    let e = lagrange_codegen::model(&input)
        .err()
        .expect("refused")
        .to_string();
    assert!(
        e.contains("`batched` runs four `f64` states per call"),
        "{e}"
    );
}
