//! Source text of the generic planar n-link pendulum (distinct masses and lengths,
//! absolute angles from the downward vertical): the scaling workload of the
//! derivation benchmarks and the `opcount` report.

use std::fmt::Write;

/// `#[lagrange(...)] struct ChainN { m1.., l1.., g }` for `n` links.
pub fn n_link_source(n: usize) -> String {
    let mut s = String::from("#[lagrange(coordinates(");
    let coords: Vec<String> = (1..=n).map(|k| format!("th{k}")).collect();
    s += &coords.join(", ");
    s += "), define(";
    let mut defs = Vec::new();
    for k in 1..=n {
        if k == 1 {
            defs.push("x1 = l1 * sin(th1), y1 = -l1 * cos(th1)".to_string());
        } else {
            let j = k - 1;
            defs.push(format!(
                "x{k} = x{j} + l{k} * sin(th{k}), y{k} = y{j} - l{k} * cos(th{k})"
            ));
        }
    }
    s += &defs.join(", ");
    s += "), ";
    for k in 1..=n {
        let _ = write!(s, "point(b{k}, mass = m{k}, at = [x{k}, y{k}]), ");
    }
    s += "gravity = [0, -g])] pub struct Chain { ";
    for k in 1..=n {
        let _ = write!(s, "pub m{k}: f64, pub l{k}: f64, ");
    }
    s += "pub g: f64 }";
    s
}
