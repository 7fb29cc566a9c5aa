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

/// `#[lagrange(...)] struct SpatialChain { m0.., l0.., r, g }`: n rigid rods,
/// rod k along its body x axis from its joint (centre of mass at l_k/2,
/// slender-cylinder moments of radius r), joint k+1 at the tip of rod k, the
/// rotation of rod k the product rot_z(q1)·rot_y(q2)·… up to its own joint
/// (axes alternating z, y), gravity along −z: the shape of a robot arm, the
/// scaling workload of issue 10's comparison with Pinocchio.
pub fn spatial_chain_source(n: usize) -> String {
    let coords: Vec<String> = (1..=n).map(|k| format!("q{k}")).collect();
    let mut s = format!("#[lagrange(coordinates({}), ", coords.join(", "));
    let mut rotation = String::new();
    for k in 0..n {
        let axis = if k % 2 == 0 { "z" } else { "y" };
        if k > 0 {
            rotation += " * ";
        }
        let _ = write!(rotation, "rot_{axis}(q{})", k + 1);
        let at = if k == 0 {
            "[0, 0, 0]".to_string()
        } else {
            format!("[j{k}.x, j{k}.y, j{k}.z]")
        };
        let _ = write!(
            s,
            "body(rod{k}, mass = m{k}, inertia = [m{k} * (r^2) / 2, m{k} * (3 * (r^2) + (l{k}^2)) / 12, \
             m{k} * (3 * (r^2) + (l{k}^2)) / 12], at = {at}, com = [l{k} / 2, 0, 0], rotation = {rotation}), "
        );
        if k + 1 < n {
            let _ = write!(s, "point(j{}, on = rod{k}, at = [l{k}, 0, 0]), ", k + 1);
        }
    }
    s += "gravity = [0, 0, -g])] pub struct SpatialChain { ";
    for k in 0..n {
        let _ = write!(s, "pub m{k}: f64, pub l{k}: f64, ");
    }
    s += "pub r: f64, pub g: f64 }";
    s
}

/// The same chain as [`spatial_chain_source`] with its poses written out as a
/// user without the `point(.., on = ..)` language would: each rod's rotation
/// as an explicit matrix whose entries are `define`s (R_k = R_{k−1}·rot(q_k),
/// multiplied out column by column), each rod's reference point as
/// ξ_k = ξ_{k−1} + l_{k−1} R_{k−1} e_x. The recursive route reads the tree
/// back from these expressions (`tree::written`).
pub fn spatial_chain_written_source(n: usize) -> String {
    let coords: Vec<String> = (1..=n).map(|k| format!("q{k}")).collect();
    let mut defs = Vec::new();
    for k in 0..n {
        let (c, s) = (format!("cos(q{})", k + 1), format!("sin(q{})", k + 1));
        let prev = |i: usize, j: usize| -> String {
            if k == 0 {
                (if i == j { "1" } else { "0" }).to_string()
            } else {
                format!("r{}_{i}{j}", k - 1)
            }
        };
        for i in 0..3 {
            let (col0, col1, col2) = if k % 2 == 0 {
                // · rot_z: e_x' = c e_x + s e_y, e_y' = −s e_x + c e_y.
                (
                    format!("{} * {c} + {} * {s}", prev(i, 0), prev(i, 1)),
                    format!("{} * {c} - {} * {s}", prev(i, 1), prev(i, 0)),
                    prev(i, 2),
                )
            } else {
                // · rot_y: e_x' = c e_x − s e_z, e_z' = s e_x + c e_z.
                (
                    format!("{} * {c} - {} * {s}", prev(i, 0), prev(i, 2)),
                    prev(i, 1),
                    format!("{} * {s} + {} * {c}", prev(i, 0), prev(i, 2)),
                )
            };
            for (j, e) in [col0, col1, col2].into_iter().enumerate() {
                defs.push(format!("r{k}_{i}{j} = {e}"));
            }
        }
        if k > 0 {
            for (i, x) in ["x", "y", "z"].iter().enumerate() {
                let before = if k == 1 {
                    "0".to_string()
                } else {
                    format!("{x}{}", k - 1)
                };
                defs.push(format!("{x}{k} = {before} + l{} * r{}_{i}0", k - 1, k - 1));
            }
        }
    }
    let mut s = format!(
        "#[lagrange(coordinates({}), define({}), ",
        coords.join(", "),
        defs.join(", ")
    );
    for k in 0..n {
        let at = if k == 0 {
            "[0, 0, 0]".to_string()
        } else {
            format!("[x{k}, y{k}, z{k}]")
        };
        let rows: Vec<String> = (0..3)
            .map(|i| format!("[r{k}_{i}0, r{k}_{i}1, r{k}_{i}2]"))
            .collect();
        let _ = write!(
            s,
            "body(rod{k}, mass = m{k}, inertia = [m{k} * (r^2) / 2, m{k} * (3 * (r^2) + (l{k}^2)) / 12, \
             m{k} * (3 * (r^2) + (l{k}^2)) / 12], at = {at}, com = [l{k} / 2, 0, 0], rotation = [{}]), ",
            rows.join(", ")
        );
    }
    s += "gravity = [0, 0, -g])] pub struct SpatialChain { ";
    for k in 0..n {
        let _ = write!(s, "pub m{k}: f64, pub l{k}: f64, ");
    }
    s += "pub r: f64, pub g: f64 }";
    s
}
