//! Source texts of the benchmark workloads: the generic planar n-link pendulum
//! (distinct masses and lengths, absolute angles from the downward vertical),
//! the spatial chain written with factors and written out, and robots'
//! URDF items transcribed with their poses written out — for the derivation
//! benchmarks, the `opcount` report, `lagrange-bench` and the tests of the
//! recursive route.

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
        let c = format!("cos(q{})", k + 1);
        let s = format!("sin(q{})", k + 1);
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

/// Description items (as [`crate::urdf`] writes them: `body(.., at = [p.x,
/// p.y, p.z], rotation = rot_*(..) * ..)` and `point(p, on = body, at = [..])`)
/// with every pose written out as a user transcribing a robot by hand would:
/// each body's rotation an explicit matrix of `define`s, the product of its
/// nearest written ancestor's matrix and its remaining factors; each point's
/// and body's position as ξ(q) = origin + R · offset. The workload for the
/// recursive route's reading of written-out trees (`tree::written`).
///
/// # Panics
/// On items that are not of that shape (this is a benchmark fixture).
pub fn written_out(items: &[proc_macro2::TokenStream]) -> Vec<String> {
    let mut w = Transcriber::default();
    let mut out = Vec::new();
    for item in items {
        let call: syn::ExprCall = syn::parse2(item.clone()).expect("an item is a call");
        let kind = quote::ToTokens::to_token_stream(&call.func).to_string();
        let args: Vec<&syn::Expr> = call.args.iter().collect();
        match kind.as_str() {
            "body" => out.push(w.body(&args)),
            "point" => out.extend(w.point(&args)),
            _ => out.push(item.to_string()),
        }
    }
    out.insert(1, format!("define({})", w.defines.join(", ")));
    out
}

/// The state of [`written_out`]: the defines so far, each body's rotation
/// factors and matrix name, each point's and body's position name.
#[derive(Default)]
struct Transcriber {
    defines: Vec<String>,
    bodies: Vec<(String, Vec<String>, String)>,
    count: usize,
}

fn text(e: &syn::Expr) -> String {
    quote::ToTokens::to_token_stream(e).to_string()
}

/// `name = value` arguments by name; the first argument is the item's name.
fn named<'e>(args: &[&'e syn::Expr], key: &str) -> Option<&'e syn::Expr> {
    args.iter().find_map(|a| match a {
        syn::Expr::Assign(a) if text(&a.left) == key => Some(&*a.right),
        _ => None,
    })
}

fn factors(e: &syn::Expr, out: &mut Vec<String>) {
    match e {
        syn::Expr::Binary(b) if matches!(b.op, syn::BinOp::Mul(_)) => {
            factors(&b.left, out);
            factors(&b.right, out);
        }
        other => out.push(text(other)),
    }
}

impl Transcriber {
    fn fresh(&mut self, stem: &str) -> String {
        self.count += 1;
        format!("{stem}{}", self.count)
    }

    /// A matrix define `name` from its nine entries.
    fn matrix(&mut self, name: &str, entry: impl Fn(usize, usize) -> String) {
        for r in 0..3 {
            for c in 0..3 {
                self.defines
                    .push(format!("{name}_{r}{c} = {}", entry(r, c)));
            }
        }
    }

    /// The matrix of one factor `rot_a(angle)`.
    fn factor(&mut self, f: &str) -> String {
        let name = self.fresh("f");
        let axis = ["rot_x", "rot_y", "rot_z"]
            .iter()
            .position(|r| f.starts_with(r))
            .expect("a factor is rot_x/rot_y/rot_z");
        let angle = f[5..].trim().to_string();
        let i = (axis + 1) % 3;
        let j = (axis + 2) % 3;
        self.matrix(&name, |r, c| match (r, c) {
            _ if r == axis && c == axis => "1".into(),
            _ if r == axis || c == axis => "0".into(),
            _ if r == c => format!("cos{angle}"),
            _ if r == i && c == j => format!("-sin{angle}"),
            _ => format!("sin{angle}"),
        });
        name
    }

    fn product(&mut self, a: &str, b: &str) -> String {
        let name = self.fresh("r");
        self.matrix(&name, |r, c| {
            let terms: Vec<String> = (0..3).map(|k| format!("{a}_{r}{k} * {b}_{k}{c}")).collect();
            terms.join(" + ")
        });
        name
    }

    fn body(&mut self, args: &[&syn::Expr]) -> String {
        let name = text(args[0]);
        let mut fs = Vec::new();
        factors(
            named(args, "rotation").expect("a body has a rotation"),
            &mut fs,
        );
        let start = self
            .bodies
            .iter()
            .filter(|(_, pf, _)| fs.starts_with(pf))
            .max_by_key(|(_, pf, _)| pf.len())
            .map(|(_, pf, m)| (pf.len(), m.clone()));
        let (done, mut matrix) = start.unwrap_or((0, String::new()));
        for f in &fs[done..] {
            let m = self.factor(f);
            matrix = if matrix.is_empty() {
                m
            } else {
                self.product(&matrix, &m)
            };
        }
        let at = text(named(args, "at").expect("a body has `at`"))
            .replace(" . ", ".")
            .replace(".x", "_x")
            .replace(".y", "_y")
            .replace(".z", "_z");
        self.defines.extend(
            ["x", "y", "z"]
                .iter()
                .zip(split3(&at))
                .map(|(c, e)| format!("{name}_{c} = {e}")),
        );
        self.bodies.push((name.clone(), fs, matrix.clone()));
        let kept: Vec<String> = args
            .iter()
            .filter(|a| !matches!(a, syn::Expr::Assign(x) if ["at", "rotation"].contains(&text(&x.left).as_str())))
            .map(|a| text(a))
            .collect();
        let rows: Vec<String> = (0..3)
            .map(|r| format!("[{matrix}_{r}0, {matrix}_{r}1, {matrix}_{r}2]"))
            .collect();
        format!(
            "body({}, at = [{name}_x, {name}_y, {name}_z], rotation = [{}])",
            kept.join(", "),
            rows.join(", ")
        )
    }

    /// Defines the point's position; a point with mass stays an item.
    fn point(&mut self, args: &[&syn::Expr]) -> Option<String> {
        let name = text(args[0]);
        let on = text(named(args, "on").expect("a point is on a body"));
        let (_, _, matrix) = self
            .bodies
            .iter()
            .find(|(b, _, _)| *b == on)
            .expect("its body comes first")
            .clone();
        let offset = split3(&text(named(args, "at").expect("a point has `at`")));
        for (r, c) in ["x", "y", "z"].iter().enumerate() {
            let terms: Vec<String> = (0..3)
                .map(|k| format!("{matrix}_{r}{k} * ({})", offset[k]))
                .collect();
            self.defines
                .push(format!("{name}_{c} = {on}_{c} + {}", terms.join(" + ")));
        }
        named(args, "mass").map(|m| {
            format!(
                "point({name}, mass = {}, at = [{name}_x, {name}_y, {name}_z])",
                text(m)
            )
        })
    }
}

/// `[a, b, c]` → its three entries.
fn split3(list: &str) -> Vec<String> {
    let e: syn::ExprArray = syn::parse_str(list).expect("a 3-vector");
    e.elems.iter().map(text).collect()
}
