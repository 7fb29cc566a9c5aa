//! Which form `emit(jacobians)` gives `Differentiable`: the one program of q̈
//! and its derivatives, or the emitted M, Q − h and Jacobians around M's
//! factorisation at run time (`factored_derivatives`), for a system whose one
//! program passes `FACTORED_ABOVE_OPS`.

fn expanded(urdf: &str, emit: &str) -> String {
    let src = format!(
        "#[lagrange(urdf(\"{}/../robots/{urdf}), gravity = [0, 0, -9.81], emit({emit}))] struct Robot {{}}",
        env!("CARGO_MANIFEST_DIR")
    );
    let input: syn::DeriveInput = syn::parse_str(&src).expect("source parses");
    lagrange_codegen::expand(&input).to_string()
}

fn factored(urdf: &str, emit: &str) -> bool {
    let code = expanded(urdf, emit);
    assert!(
        code.contains("acceleration_derivatives_unchecked"),
        "{urdf}: no Differentiable"
    );
    code.contains("factored_derivatives")
}

#[test]
fn long_programs_factor_at_run_time_and_the_rest_stay_one_program() {
    // Seven-joint chains with general axes: 8,591 and 9,389 operations.
    assert!(factored("z1.urdf\", dynamics = ignore", "jacobians"));
    assert!(factored("xarm7.urdf\", dynamics = ignore", "jacobians"));
    // Eight coordinates (the mimic finger), M with four zero entries.
    assert!(factored("panda.urdf\", dynamics = ignore", "jacobians"));
    // A branched tree (36,807 operations; M with 114 zeros of 324): the
    // dense factorisation at run time still ran 1.2× as fast.
    assert!(factored("solo12.urdf\", base = floating", "jacobians"));
    // Shorter programs: the UR5's 3,671, the Kinova's 6,311.
    assert!(!factored("ur5.urdf\"", "jacobians"));
    assert!(!factored("kinova.urdf\"", "jacobians"));
    // Beside `batched`, whose lanes run the one program bit for bit.
    assert!(!factored(
        "z1.urdf\", dynamics = ignore",
        "jacobians, batched"
    ));
}
