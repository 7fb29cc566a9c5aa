//! Writes the spatial chains of issue 10 (n = 6, 10, 12, 14, 30) as derived
//! models, one module each (`nN`, `aN` with the articulated-body algorithm,
//! and `wN` written out), for `benches/spatial.rs` and `tests/spatial.rs`.

use std::fmt::Write;

fn main() {
    let mut out = String::new();
    // `nN` derives M and Q − h (q̈ by Cholesky), `aN` adds the articulated-body
    // algorithm (q̈ in O(n)).
    let sizes = [6, 10, 12, 14, 30];
    let variants = sizes
        .iter()
        .map(|&n| (n, "n", ""))
        .chain(sizes.iter().map(|&n| (n, "a", "emit(articulated), ")))
        .chain([6, 12].map(|n| (n, "w", "")));
    for (n, prefix, extra) in variants {
        // `wN`: the same chain with its poses written out (explicit matrices
        // of `define`s, ξ(q) as sums), whose tree the derive reads back.
        let source = if prefix == "w" {
            lagrange_codegen::chain::spatial_chain_written_source(n)
        } else {
            lagrange_codegen::chain::spatial_chain_source(n)
        }
        .replace("#[lagrange(", &format!("#[lagrange({extra}"));
        let fields: Vec<String> = (0..n)
            .map(|k| format!("m{k}: 1.0 + 0.1 * {k}.0, l{k}: 1.0 - 0.02 * {k}.0"))
            .collect();
        let _ = write!(
            out,
            "pub mod {prefix}{n} {{\n#[derive(lagrange::Lagrangian)]\n{source}\n\
             impl SpatialChain {{\n    /// The benchmark's parameters (those of `SerialChain::benchmark`).\n    pub fn benchmark() -> Self {{\n        \
             SpatialChain {{ {}, r: 0.05, g: 9.81 }}\n    }}\n}}\n}}\n",
            fields.join(", ")
        );
    }
    let dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let dir = std::path::Path::new(&dir);
    std::fs::write(dir.join("spatial_chains.rs"), out).expect("OUT_DIR is writable");
    // The planar chains (point masses, absolute angles) beside the closed form.
    let mut out = String::new();
    for n in [10, 20, 30] {
        let source = lagrange_codegen::chain::n_link_source(n);
        let fields: Vec<String> = (1..=n)
            .map(|k| {
                format!(
                    "m{k}: 1.0 + 0.1 * {}.0, l{k}: 1.0 - 0.02 * {}.0",
                    k - 1,
                    k - 1
                )
            })
            .collect();
        let _ = write!(
            out,
            "pub mod planar{n} {{\n#[derive(lagrange::Lagrangian)]\n{source}\n\
             impl Chain {{\n    /// The closed form's parameters.\n    pub fn sample() -> Self {{\n        \
             Chain {{ {}, g: 9.81 }}\n    }}\n}}\n}}\n",
            fields.join(", ")
        );
    }
    std::fs::write(dir.join("planar_chains.rs"), out).expect("OUT_DIR is writable");
    // Two arms transcribed by hand from their URDF files (every rotation a
    // matrix of `define`s, every position ξ(q)), for `benches/urdf.rs`.
    let mut out = String::new();
    for (module, file) in [("panda", "panda.urdf"), ("kinova", "kinova.urdf")] {
        let path = format!("../robots/{file}");
        println!("cargo::rerun-if-changed={path}");
        let text = std::fs::read_to_string(&path).expect("the arms' URDFs are in robots/");
        // The rigid-body dynamics, as Pinocchio's `rnea` and `aba` compute.
        let ignored = lagrange_codegen::urdf::Options {
            dynamics: lagrange_codegen::urdf::DynamicsRule::Ignore,
            ..Default::default()
        };
        let urdf =
            lagrange_codegen::urdf::from_text(&text, file, &[], ignored).expect("the arm reads");
        let items = lagrange_codegen::chain::written_out(&urdf.items);
        let _ = write!(
            out,
            "pub mod {module} {{\n#[derive(lagrange::Lagrangian, Default)]\n\
             #[lagrange({}, gravity = [0, 0, -9.81])]\npub struct Robot {{}}\n}}\n",
            items.join(", ")
        );
    }
    std::fs::write(dir.join("written_arms.rs"), out).expect("OUT_DIR is writable");
    println!("cargo::rerun-if-changed=build.rs");
}
