//! Compile-fail tests: each bad description must produce one clear error at the
//! offending token. The expected messages are pinned in `tests/ui/**/*.stderr`.
//! rustc's diagnostics format changes between releases, so the test only runs on
//! the toolchain the `.stderr` files were recorded with (as clap does).

#[rustversion::stable(1.95)]
#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*/*.rs");
}
