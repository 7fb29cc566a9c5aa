//! The recursive route (composite rigid bodies for M, recursive Newton–Euler for
//! h and gravity) against the generic one (differentiating ξ(q)) on the same
//! descriptions: M, Q − h, h and Q agree at random states; a description that
//! is not a tree of revolute and sliding joints stays on the generic route.

mod common;
#[path = "common/written.rs"]
mod written;
use common::{Lcg, close, eval, random_point};
use lagrange_codegen::mechanics::{Articulation, BiasRoute, Model, Route};

fn model_by(src: &str, route: Route) -> Model {
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    match lagrange_codegen::model_by(&input, route) {
        Ok(m) => m,
        Err(e) => panic!("derivation failed: {e}"),
    }
}

/// Both routes evaluated at 20 random states (parameters, q, q̇).
fn routes_agree(src: &str) {
    let generic = model_by(src, Route::Generic);
    let recursive = model_by(src, Route::Recursive);
    assert_eq!(recursive.motion.derivation.route, BiasRoute::Recursive);
    assert_ne!(generic.motion.derivation.route, BiasRoute::Recursive);
    let n = generic.dof();
    let mut rng = Lcg(2024);
    for _ in 0..20 {
        let p = random_point(&generic, &mut rng);
        let pair = |a: lagrange_symbolic::Expr, b: lagrange_symbolic::Expr| {
            (eval(&generic, a, &p), eval(&recursive, b, &p))
        };
        for i in 0..n {
            for j in 0..n {
                let (a, b) = pair(generic.motion.mass[i][j], recursive.motion.mass[i][j]);
                assert!(close(a, b, 1e-12), "M[{i}][{j}]: {a} vs {b}\n{src}");
            }
            for (what, a, b) in [
                ("Q - h", generic.motion.rhs[i], recursive.motion.rhs[i]),
                ("h", generic.motion.bias[i], recursive.motion.bias[i]),
                ("Q", generic.motion.forces[i], recursive.motion.forces[i]),
            ] {
                let (a, b) = pair(a, b);
                assert!(close(a, b, 1e-12), "{what}[{i}]: {a} vs {b}\n{src}");
            }
        }
    }
}

#[test]
fn spatial_chains_agree() {
    for n in [1, 2, 3, 5] {
        routes_agree(&lagrange_codegen::chain::spatial_chain_source(n));
    }
}

#[test]
fn euler_top_on_massless_links_agrees() {
    // Three joints meet at the pivot: two massless links, then the top.
    routes_agree(
        "#[lagrange(coordinates(psi, theta, phi),
            body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
                 at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
            gravity = [0, 0, -g])]
         struct Top { m: f64, a: f64, c: f64, l: f64, g: f64 }",
    );
}

#[test]
fn branched_tree_with_point_masses_and_full_inertia() {
    // A base turning about z at a raised pivot, two arms on points of it (one
    // about x, one about y), a point mass on each arm, a full inertia tensor,
    // a user potential (a torsion spring) and a damper.
    routes_agree(
        "#[lagrange(coordinates(a, b, c, d),
            body(base, mass = m0, inertia = [i1, i2, i3, p, p2, p3], com = [0.1, 0.2, h],
                 at = [0, 0, h], rotation = rot_z(a)),
            point(left, on = base, at = [0, w, h]),
            point(right, on = base, at = [0.3, -w, 0.5 * h]),
            body(arm1, mass = m1, inertia = [i1, i2, i3], com = [0, 0, -l],
                 at = [left.x, left.y, left.z], rotation = rot_z(a) * rot_x(b)),
            body(arm2, mass = m2, inertia = [i2, i3, i1, p, 0, p3], com = [l, 0, -l],
                 at = [right.x, right.y, right.z], rotation = rot_z(a) * rot_y(c)),
            body(hand, mass = m1, inertia = [i3, i3, i1], com = [0, l, 0],
                 at = [tip.x, tip.y, tip.z], rotation = rot_z(a) * rot_y(c) * rot_x(d)),
            point(tip, on = arm2, at = [w, 0.2, -2 * l]),
            point(bob, on = arm1, at = [0, 0.1, -2 * l], mass = m2),
            point(nut, on = hand, at = [0, l, w], mass = m0),
            potential = k * (b^2) / 2 + k * (d^2) / 2,
            dissipation = k * (dot(a)^2) / 2,
            gravity = [0, g / 3, -g])]
         struct Arms { m0: f64, m1: f64, m2: f64, i1: f64, i2: f64, i3: f64, p: f64,
                       p2: f64, p3: f64, h: f64, w: f64, l: f64, k: f64, g: f64 }",
    );
}

/// What a robot description holds: placements between joints (a URDF joint's
/// fixed `rpy`, here a literal quarter turn and a parameter angle), a joint
/// about a tilted axis, a body with a constant turn after its joint (its
/// inertia and com in turned axes), a tool fixed in the last link (a fixed
/// joint) with a point mass on it, and a massive base fixed in space.
const ROBOT: &str = "#[lagrange(coordinates(a, b, c),
            body(base, mass = m0, inertia = [i1, i2, i3], at = [0, 0, 0], rotation = rot_z(w)),
            point(mount, on = base, at = [0.1, 0, h]),
            body(l1, mass = m1, inertia = [i1, i2, i3, p, 0, 0], com = [0.1, 0, 0.2],
                 at = [mount.x, mount.y, mount.z], rotation = rot_z(w) * rot_z(a) * rot_x(0.4)),
            point(t1, on = l1, at = [0, 0.1, l]),
            body(l2, mass = m1, inertia = [i2, i3, i1], com = [l / 2, 0, 0],
                 at = [t1.x, t1.y, t1.z],
                 rotation = rot_z(w) * rot_z(a) * rot_x(0.4) * rot_x(1.5707963) * rot_z(b)),
            point(t2, on = l2, at = [l, 0, 0.05]),
            body(l3, mass = m0, inertia = [i1, i1, i3], com = [0, 0, l / 3],
                 at = [t2.x, t2.y, t2.z],
                 rotation = rot_z(w) * rot_z(a) * rot_x(0.4) * rot_x(1.5707963) * rot_z(b)
                     * rot_y(w) * rot_z(c) * rot_y(-w)),
            point(flange, on = l3, at = [0, 0.02, l]),
            body(tool, mass = m1, inertia = [i3, i2, i1], com = [0, 0, 0.1],
                 at = [flange.x, flange.y, flange.z],
                 rotation = rot_z(w) * rot_z(a) * rot_x(0.4) * rot_x(1.5707963) * rot_z(b)
                     * rot_y(w) * rot_z(c) * rot_y(-w) * rot_x(0.3)),
            point(tip, on = tool, at = [0, 0.05, 0.2], mass = m0),
            gravity = [0, 0, -g])]
         struct Robot { m0: f64, m1: f64, i1: f64, i2: f64, i3: f64, p: f64, h: f64, l: f64,
                        w: f64, g: f64 }";

#[test]
fn placements_tilted_axes_and_fixed_bodies_agree() {
    routes_agree(ROBOT);
}

/// Sliding joints: a cart on a rail at the root carrying a pendulum, and a
/// telescoping link sliding along a tilted line of a turning arm, with a
/// wrist after it.
#[test]
fn sliding_joints_agree() {
    let src = "#[lagrange(coordinates(x, a, s, c),
        body(cart, mass = m0, inertia = [i1, i2, i3], at = [x, 0, 0], rotation = rot_z(0)),
        point(pivot, on = cart, at = [0, 0.1, 0.2]),
        body(arm, mass = m1, inertia = [i1, i2, i3], com = [0, 0, -l / 2],
             at = [pivot.x, pivot.y, pivot.z], rotation = rot_z(0) * rot_x(a) * rot_y(w)),
        point(slide, on = arm, at = [0.1 + 0.3 * s, 0.05, -l - 2 * s]),
        body(rod, mass = m1, inertia = [i2, i2, i3], com = [0, 0, -0.1],
             at = [slide.x, slide.y, slide.z], rotation = rot_z(0) * rot_x(a) * rot_y(w) * rot_x(0.2)),
        point(wrist, on = rod, at = [0, 0, -0.3]),
        body(hand, mass = m0, inertia = [i3, i1, i2], com = [0.02, 0, -0.05],
             at = [wrist.x, wrist.y, wrist.z],
             rotation = rot_z(0) * rot_x(a) * rot_y(w) * rot_x(0.2) * rot_z(c)),
        gravity = [0, 0.5, -g])]
     struct Crane { m0: f64, m1: f64, i1: f64, i2: f64, i3: f64, l: f64, w: f64, g: f64 }";
    routes_agree(src);
    articulated_agrees(&src.replace(
        "#[lagrange(coordinates",
        "#[lagrange(emit(articulated), coordinates",
    ));
    // A finger on the hand slides back as the rod slides out: `s` drives two
    // joints (a mimic joint, one an ancestor of the other), whose shares the
    // recursions sum; the articulated-body algorithm does not apply, and
    // `emit(articulated)` factorises M.
    let mimic = src.replace(
        "gravity = [0, 0.5, -g]",
        "point(grip, on = hand, at = [-0.5 * s, 0.01, -0.1]),
         body(finger, mass = m1, inertia = [i1, i1, i3], at = [grip.x, grip.y, grip.z],
              rotation = rot_z(0) * rot_x(a) * rot_y(w) * rot_x(0.2) * rot_z(c)),
         gravity = [0, 0.5, -g]",
    );
    routes_agree(&mimic);
    let articulated = mimic.replace(
        "#[lagrange(coordinates",
        "#[lagrange(emit(articulated), coordinates",
    );
    articulated_agrees(&articulated);
    let model = model_by(&articulated, Route::Auto);
    let choice = model.outputs.forward_route.expect("a route");
    assert_eq!(choice.articulated_body, None);
    assert!(choice.other.is_none());
}

#[test]
fn non_trees_stay_generic_and_say_why() {
    let cases = [
        (
            "#[lagrange(coordinates(x, th),
                body(b, mass = m, inertia = [m, m, m], at = [cos(x), sin(x), 0], rotation = rot_z(th)))]
             struct Ring { m: f64 }",
            "body `b`: its reference point moves, but it has no parent body",
        ),
        (
            "#[lagrange(coordinates(a, b),
                body(b1, mass = m, inertia = [m, m, m], at = [0, 0, 0], rotation = rot_z(a + b)),
                point(p, mass = m, at = [a, b, 0]))]
             struct Sum { m: f64 }",
            "body `b1`: its factor rot_z turns by an angle that is neither one coordinate nor constant",
        ),
        (
            "#[lagrange(coordinates(th, s),
                body(b, mass = m, inertia = [m, m, m], at = [0, 0, 0], rotation = rot_z(th)),
                point(p, mass = m, at = [s, 0, 0]))]
             struct Free { m: f64 }",
            "coordinate `s` moves no joint",
        ),
        (
            "#[lagrange(coordinates(th),
                body(b, mass = m, inertia = [m, m, m], at = [0, 0, 0], rotation = rot_z(th)),
                point(p, mass = m, at = [th, 0, 0]))]
             struct Loose { m: f64 }",
            "point `p`: it has mass and moves, but is not fixed in a body",
        ),
        (
            "#[lagrange(coordinates(a, b),
                body(b1, mass = m, inertia = [m, m, m], at = [0, 0, 0],
                     rotation = [[cos(a + b), -sin(a + b), 0], [sin(a + b), cos(a + b), 0], [0, 0, 1]]))]
             struct Written { m: f64 }",
            "body `b1`: it moves by 2 coordinates (a, b) relative to its parent",
        ),
        (
            "#[lagrange(coordinates(th),
                body(wheel, mass = m, inertia = [m, m, m], at = [th, 0, 0],
                     rotation = [[cos(th), -sin(th), 0], [sin(th), cos(th), 0], [0, 0, 1]]))]
             struct Rolling { m: f64 }",
            "body `wheel`: relative to its parent (the body whose coordinates its own extend), it neither turns about a fixed axis nor slides along a fixed line as `th` changes",
        ),
        (
            "#[lagrange(coordinates(th),
                body(spun, mass = m, inertia = [m, m, m], at = [0, 0, 0],
                     rotation = [[cos(th + w * t), -sin(th + w * t), 0],
                                 [sin(th + w * t), cos(th + w * t), 0], [0, 0, 1]]))]
             struct Driven { m: f64, w: f64 }",
            "body `spun`: its written-out pose depends on time",
        ),
    ];
    for (src, why) in cases {
        let input: syn::DeriveInput = syn::parse_str(src).unwrap();
        let refused = lagrange_codegen::model_by(&input, Route::Recursive).err();
        let message = refused.map(|e| e.to_string()).unwrap_or_default();
        assert!(
            message.contains("kinematic tree") && message.contains(why),
            "not a tree, yet not refused with the reason {why:?} (message {message:?}):\n{src}"
        );
        let model = model_by(src, Route::Auto);
        assert_ne!(model.motion.derivation.route, BiasRoute::Recursive);
        let text = lagrange_codegen::doc::equations(&model);
        let reason = model.motion.derivation.reason.unwrap_or_default();
        assert!(reason.starts_with(why), "{reason:?} is not {why:?}:\n{src}");
        assert!(
            text.contains(&format!("not recursive because {why}")),
            "{text}"
        );
    }
}

#[test]
fn long_chains_take_the_recursive_route_alone() {
    let src = lagrange_codegen::chain::spatial_chain_source(8);
    let model = model_by(&src, Route::Auto);
    assert_eq!(model.motion.derivation.route, BiasRoute::Recursive);
    assert!(model.motion.derivation.other_bias.is_empty());
}

/// Solves M x = b by Gaussian elimination with partial pivoting (small n).
#[allow(clippy::needless_range_loop)] // the textbook index form
fn solve(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| m[i][k].abs().total_cmp(&m[j][k].abs()))
            .unwrap();
        m.swap(k, p);
        b.swap(k, p);
        for i in k + 1..n {
            let f = m[i][k] / m[k][k];
            for j in k..n {
                m[i][j] -= f * m[k][j];
            }
            b[i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| m[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / m[k][k];
    }
    x
}

/// The articulated-body q̈ (with extra generalized forces τ) equals
/// M⁻¹(Q − h + τ) from the same description at random states.
/// Both routes of `emit(articulated)`, the one emitted and the other, give
/// M⁻¹(Q − h + τ) and positive pivots.
fn articulated_agrees(src: &str) {
    let model = model_by(src, Route::Auto);
    let chosen = (model.outputs.articulated.as_ref()).expect("emit(articulated) was asked for");
    let choice = (model.outputs.forward_route.as_ref()).expect("a route was chosen");
    for fd in std::iter::once(chosen).chain(&choice.other) {
        route_agrees(&model, fd, src);
    }
}

fn route_agrees(model: &Model, fd: &Articulation, src: &str) {
    let n = model.dof();
    let mut rng = Lcg(77);
    for _ in 0..20 {
        let p = random_point(model, &mut rng);
        let tau: Vec<f64> = (0..n).map(|_| 3.0 * rng.next()).collect();
        let base = common::env(model, &p);
        let env = |s: lagrange_symbolic::Symbol| match fd
            .extra
            .iter()
            .position(|&e| model.ctx.as_symbol(e) == Some(s))
        {
            Some(i) => tau[i],
            None => base(s),
        };
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| eval(model, model.motion.mass[i][j], &p))
                    .collect()
            })
            .collect();
        let rhs: Vec<f64> = (0..n)
            .map(|i| eval(model, model.motion.rhs[i], &p) + tau[i])
            .collect();
        let expected = solve(m, rhs);
        for (i, &want) in expected.iter().enumerate() {
            let got = model.ctx.eval(fd.accelerations[i], &env);
            assert!(
                close(got, want, 1e-10),
                "q̈[{i}] of {n}: {got} vs {want}\n{src}"
            );
        }
        for &d in &fd.pivots {
            let d = model.ctx.eval(d, &env);
            assert!(d > 0.0, "a pivot of a positive definite M: {d}\n{src}");
        }
    }
}

#[test]
fn articulated_body_accelerations_agree_with_the_mass_matrix() {
    for n in [1, 2, 4, 7] {
        let src = lagrange_codegen::chain::spatial_chain_source(n).replace(
            "#[lagrange(coordinates",
            "#[lagrange(emit(articulated), coordinates",
        );
        articulated_agrees(&src);
    }
    articulated_agrees(
        "#[lagrange(emit(articulated), coordinates(psi, theta, phi),
            body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
                 at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
            potential = k * (psi^2) / 2,
            gravity = [0, 0, -g])]
         struct Top { m: f64, a: f64, c: f64, l: f64, g: f64, k: f64 }",
    );
    articulated_agrees(&ROBOT.replace(
        "#[lagrange(coordinates",
        "#[lagrange(emit(articulated), coordinates",
    ));
}

/// Free orientations on the recursive route: a spherical joint (three axes
/// at the chart's centre, velocity products from the entering velocity
/// alone) and a free body (three sliding joints and a spherical one).
const FREE_BODY: &str = "#[lagrange(coordinates(x, y, z), orientation(turn),
    body(brick, mass = m, inertia = [a, b, c], at = [x, y, z], rotation = turn),
    gravity = [0, 0, -g])]
 struct Brick { m: f64, a: f64, b: f64, c: f64, g: f64 }";

const SPHERICAL_CHAIN: &str = "#[lagrange(orientation(upper, lower),
    body(arm, mass = m, inertia = [a, b, c], com = [0.1, 0, -l],
         at = [0, 0, 0], rotation = upper),
    point(tip, on = arm, at = [0, 0.2, -2 * l]),
    body(hand, mass = m, inertia = [a, a, c], com = [0, 0, -l],
         at = [tip.x, tip.y, tip.z], rotation = upper * rot_x(0.3) * lower),
    gravity = [0, 0, -g])]
 struct Chain { m: f64, a: f64, b: f64, c: f64, l: f64, g: f64 }";

const FLOATING_ARM: &str = "#[lagrange(coordinates(x, y, z, j1, j2), orientation(base),
    body(hub, mass = 5.0, inertia = [0.4, 0.5, 0.6], at = [x, y, z], rotation = base),
    point(shoulder, on = hub, at = [0.3, 0.1, 0.2]),
    body(upper, mass = 1.5, inertia = [0.01, 0.05, 0.05], com = [0.2, 0, 0],
         at = [shoulder.x, shoulder.y, shoulder.z], rotation = base * rot_z(j1)),
    point(elbow, on = upper, at = [0.4, 0, 0]),
    body(fore, mass = 1.0, inertia = [0.005, 0.02, 0.02], com = [0.15, 0, 0],
         at = [elbow.x, elbow.y, elbow.z], rotation = base * rot_z(j1) * rot_y(j2)),
    point(load, mass = 0.3, on = fore, at = [0.3, 0.05, 0]),
    gravity = [0, 0, -g])]
 struct FloatingArm { g: f64 }";

#[test]
fn spherical_joints_and_free_bodies_agree() {
    for src in [FREE_BODY, SPHERICAL_CHAIN, FLOATING_ARM] {
        routes_agree(src);
    }
}

#[test]
fn articulated_bodies_with_free_orientations_agree_with_the_mass_matrix() {
    for src in [FREE_BODY, SPHERICAL_CHAIN, FLOATING_ARM] {
        articulated_agrees(&src.replace("#[lagrange(", "#[lagrange(emit(articulated), "));
    }
}

/// `emit(jacobians)` by the recursive route (−∂τ/∂q, −∂τ/∂q̇ of recursive
/// Newton–Euler) against the generic one (∂(Q − h)/∂q − ∂M/∂q q̈) at random
/// states and accelerations.
fn jacobians_agree(src: &str) {
    let src = src.replace("#[lagrange(", "#[lagrange(emit(jacobians), ");
    let generic = model_by(&src, Route::Generic);
    let recursive = model_by(&src, Route::Recursive);
    let n = generic.dof();
    let mut rng = Lcg(99);
    for _ in 0..10 {
        let p = random_point(&generic, &mut rng);
        let qdd: Vec<f64> = (0..n).map(|_| 2.0 * rng.next()).collect();
        let at = |model: &Model, e: lagrange_symbolic::Expr| {
            let base = common::env(model, &p);
            model.ctx.eval(e, &|s| match model.ctx.symbol_kind(s) {
                lagrange_symbolic::SymbolKind::Acceleration(i) => qdd[i],
                _ => base(s),
            })
        };
        let g = generic.outputs.jacobians.as_ref().expect("asked for");
        let r = recursive.outputs.jacobians.as_ref().expect("asked for");
        let (gq, gv, rq, rv) = (&g.position, &g.velocity, &r.position, &r.velocity);
        for i in 0..n {
            for k in 0..n {
                for (what, g, r) in [("J_q", gq, rq), ("J_v", gv, rv)] {
                    let (a, b) = (at(&generic, g[i][k]), at(&recursive, r[i][k]));
                    assert!(close(a, b, 1e-11), "{what}[{i}][{k}]: {a} vs {b}\n{src}");
                }
            }
        }
    }
}

#[test]
fn recursive_jacobians_agree_with_the_generic_ones() {
    for n in [1, 3, 5] {
        jacobians_agree(&lagrange_codegen::chain::spatial_chain_source(n));
    }
    jacobians_agree(ROBOT);
}

#[test]
fn written_out_chains_agree() {
    for n in [1, 2, 3, 5] {
        routes_agree(&lagrange_codegen::chain::spatial_chain_written_source(n));
    }
}

#[test]
fn written_out_robot_agrees() {
    let src = written::robot();
    routes_agree(&src);
    articulated_agrees(&src.replace("#[lagrange(", "#[lagrange(emit(articulated), "));
    jacobians_agree(&src);
}

/// Rotations as factors, positions written out: the factor reading refuses
/// (no point of the parent at the reference point), the written-out one
/// reads the tree.
#[test]
fn factored_rotations_with_written_out_positions_agree() {
    routes_agree(
        "#[lagrange(coordinates(q1, q2, q3),
            body(rod0, mass = m0, inertia = [i1, i2, i2], com = [l0 / 2, 0, 0],
                 at = [0, 0, h], rotation = rot_z(q1)),
            body(rod1, mass = m1, inertia = [i1, i2, i2], com = [l1 / 2, 0, 0],
                 at = [l0 * cos(q1), l0 * sin(q1), h], rotation = rot_z(q1) * rot_y(q2)),
            body(rod2, mass = m1, inertia = [i1, i2, i2], com = [l1 / 2, 0, 0],
                 at = [l0 * cos(q1) + l1 * cos(q1) * cos(q2), l0 * sin(q1) + l1 * sin(q1) * cos(q2),
                       h - l1 * sin(q2)],
                 rotation = rot_z(q1) * rot_y(q2) * rot_x(0.3) * rot_z(q3)),
            gravity = [0, 0, -g])]
         struct Arm { m0: f64, m1: f64, i1: f64, i2: f64, l0: f64, l1: f64, h: f64, g: f64 }",
    );
}
