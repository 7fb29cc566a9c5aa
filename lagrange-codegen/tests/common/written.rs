//! Descriptions whose poses are written out (rotation matrices and
//! positions as `define`s of products multiplied out), for the recursive
//! route's reading of written-out trees.

/// Builds a description whose poses are written out: rotation matrices and
/// positions as `define`s of products multiplied out entry by entry.
#[derive(Default)]
pub struct Written {
    defines: Vec<String>,
}

impl Written {
    /// `name` = rot_axis(angle) as a matrix.
    fn turn(&mut self, name: &str, axis: usize, angle: &str) {
        let (c, s) = (format!("cos({angle})"), format!("sin({angle})"));
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        for r in 0..3 {
            for k in 0..3 {
                let e = match (r, k) {
                    _ if r == axis && k == axis => "1".to_string(),
                    _ if r == axis || k == axis => "0".to_string(),
                    _ if r == k => c.clone(),
                    _ if r == i && k == j => format!("-{s}"),
                    _ => s.clone(),
                };
                self.defines.push(format!("{name}_{r}{k} = {e}"));
            }
        }
    }

    /// `name` = the rotation by `angle` about the unit axis (x, y, z)
    /// (Rodrigues: c 1 + (1 − c) n nᵀ + s [n]×).
    fn about(&mut self, name: &str, n: [f64; 3], angle: &str) {
        let (c, s) = (format!("cos({angle})"), format!("sin({angle})"));
        let cross = [[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]];
        for r in 0..3 {
            for k in 0..3 {
                let diagonal = if r == k {
                    format!("{c} + ")
                } else {
                    String::new()
                };
                let e = format!(
                    "{diagonal}(1 - {c}) * {:.17} + {s} * {:.17}",
                    n[r] * n[k],
                    cross[r][k]
                );
                self.defines.push(format!("{name}_{r}{k} = {e}"));
            }
        }
    }

    /// `name` = a · b.
    fn mul(&mut self, name: &str, a: &str, b: &str) {
        for r in 0..3 {
            for k in 0..3 {
                let terms: Vec<String> =
                    (0..3).map(|l| format!("{a}_{r}{l} * {b}_{l}{k}")).collect();
                self.defines
                    .push(format!("{name}_{r}{k} = {}", terms.join(" + ")));
            }
        }
    }

    /// `name` = origin + rotation · v (`origin` empty: the world's).
    fn point(&mut self, name: &str, origin: &str, rotation: &str, v: [&str; 3]) {
        for (r, x) in ["x", "y", "z"].iter().enumerate() {
            let base = if origin.is_empty() {
                "0".to_string()
            } else {
                format!("{origin}_{x}")
            };
            let terms: Vec<String> = (0..3)
                .map(|l| format!("{rotation}_{r}{l} * ({})", v[l]))
                .collect();
            self.defines
                .push(format!("{name}_{x} = {base} + {}", terms.join(" + ")));
        }
    }

    fn matrix(name: &str) -> String {
        let rows: Vec<String> = (0..3)
            .map(|r| format!("[{name}_{r}0, {name}_{r}1, {name}_{r}2]"))
            .collect();
        format!("[{}]", rows.join(", "))
    }

    fn at(name: &str) -> String {
        format!("[{name}_x, {name}_y, {name}_z]")
    }
}

/// A robot written out: a base turned by a parameter angle, placements,
/// a joint about an axis that is no coordinate axis and whose body's
/// reference point is off the axis, a prismatic joint along a tilted line, a
/// fixed tool and a point mass given by its position alone.
pub fn robot() -> String {
    let mut w = Written::default();
    w.turn("zb", 2, "w");
    w.turn("za", 2, "a");
    w.turn("x4", 0, "0.4");
    w.turn("xq", 0, "1.5707963");
    w.turn("zb2", 2, "b");
    w.about("nc", [1.0 / 3f64.sqrt(); 3], "c");
    w.turn("tool", 0, "0.3");
    w.mul("ra", "zb", "za");
    w.mul("r1", "ra", "x4");
    w.mul("rb", "r1", "xq");
    w.mul("r2", "rb", "zb2");
    w.mul("r3", "r2", "nc");
    w.mul("rt", "r3", "tool");
    w.point("mount", "", "zb", ["0.1", "0", "h"]);
    w.point("t1", "mount", "r1", ["0", "0.1", "l"]);
    w.point("axis3", "t1", "r2", ["l", "0", "0.05"]);
    w.point("p3", "axis3", "r3", ["0.2", "-0.1", "0"]);
    w.point("p4", "axis3", "r2", ["0.1 + 0.3 * s", "0.05", "-2 * s"]);
    w.point("flange", "p3", "r3", ["0", "0.02", "l"]);
    w.point("tip", "flange", "rt", ["0", "0.05", "0.2"]);
    format!(
        "#[lagrange(coordinates(a, b, c, s), define({}),
            body(base, mass = m0, inertia = [i1, i2, i3], at = [0, 0, 0], rotation = {}),
            body(l1, mass = m1, inertia = [i1, i2, i3, p, 0, 0], com = [0.1, 0, 0.2],
                 at = {}, rotation = {}),
            body(l2, mass = m1, inertia = [i2, i3, i1], com = [l / 2, 0, 0], at = {}, rotation = {}),
            body(l3, mass = m0, inertia = [i1, i1, i3], com = [0, 0, l / 3], at = {}, rotation = {}),
            body(slider, mass = m1, inertia = [i2, i2, i3], com = [0, 0, -0.1], at = {}, rotation = {}),
            body(tool, mass = m1, inertia = [i3, i2, i1], com = [0, 0, 0.1], at = {}, rotation = {}),
            point(tip, at = {}, mass = m0),
            gravity = [0, 0, -g])]
         struct Robot {{ m0: f64, m1: f64, i1: f64, i2: f64, i3: f64, p: f64, h: f64, l: f64,
                        w: f64, g: f64 }}",
        w.defines.join(", "),
        Written::matrix("zb"),
        Written::at("mount"),
        Written::matrix("r1"),
        Written::at("t1"),
        Written::matrix("r2"),
        Written::at("p3"),
        Written::matrix("r3"),
        Written::at("p4"),
        Written::matrix("r2"),
        Written::at("flange"),
        Written::matrix("rt"),
        Written::at("tip"),
    )
}
