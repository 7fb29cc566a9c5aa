//! The summary the gallery prints: a markdown table that fits 100 columns;
//! the checks each row passes are in index.html.

use crate::row::Row;

pub(crate) fn print(rows: &[Row]) {
    println!("lagrange gallery: DOPRI5 at rtol = atol = 1e-10, f64\n");
    println!(
        "| {:<42} | {:>3} | {:>6} | {:>7} | {:>7} | {:>7} | {:>6} |",
        "system", "dof", "steps", "evals", "drift", "resid.", "ms"
    );
    println!(
        "|{}|{}|{}|{}|{}|{}|{}|",
        "-".repeat(44),
        "-".repeat(4) + ":",
        "-".repeat(7) + ":",
        "-".repeat(8) + ":",
        "-".repeat(8) + ":",
        "-".repeat(8) + ":",
        "-".repeat(7) + ":"
    );
    for r in rows {
        let drift = r.drift.map_or("—".to_string(), |d| format!("{d:.1e}"));
        let res = r
            .residuals
            .map_or("—".to_string(), |[p, v]| format!("{:.0e}", p.max(v)));
        let name: String = r.system.chars().take(42).collect();
        println!(
            "| {:<42} | {:>3} | {:>6} | {:>7} | {:>7} | {:>7} | {:>6.1} |",
            name, r.dof, r.accepted, r.evaluations, drift, res, r.wall_ms
        );
    }
    println!(
        "\ndrift: max |I(t) − I(0)| / |I(0)| of T + V (or the Jacobi integral); resid.: largest"
    );
    println!("|Φ| or |G q̇ + g| along the run; — where it does not apply.");
}
