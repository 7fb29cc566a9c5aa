//! The dynamics regressor (`emit(regressor)`): Y π equals the inverse
//! dynamics τ at random states (parameters, q, q̇, q̈) on trees of every kind
//! the recursive route reads (chains, placements and tilted axes, fixed
//! bodies, point masses, sliding joints, poses written out, free
//! orientations), and the energy regressor Y_E π equals T + V; π's names in
//! Pinocchio's order. On descriptions that are not trees (point masses at
//! ξ(q, t), a body placed by ξ(q) with a rotation, a closed chain in its own
//! coordinate, a constraint in extra coordinates) Y comes by the generic
//! route and Y π = M q̈ + h − Q_gravity; a tree's Y by both routes agrees
//! column by column; and the momentum regressor's Y_p π = ∂T/∂q̇.

mod common;
#[path = "common/written.rs"]
mod written;
use common::{Lcg, eval, model, random_point};
use lagrange_codegen::mechanics::{Model, RegressorRoute, Route};
use lagrange_symbolic::SymbolKind;

/// The description with `emit(regressor, inverse_dynamics)` added.
fn with_regressor(src: &str) -> String {
    src.replacen(
        "#[lagrange(",
        "#[lagrange(emit(regressor, inverse_dynamics), ",
        1,
    )
}

/// Max |Y π − τ| over 10 random states, each relative to 1 + |τ|.
fn y_pi_minus_tau(m: &Model) -> f64 {
    let r = m
        .outputs
        .regressor
        .as_ref()
        .expect("the regressor is derived");
    let tau = &m.outputs.inverse.as_ref().expect("τ is derived").torques;
    let mut rng = Lcg(34);
    let mut worst = 0.0f64;
    for _ in 0..10 {
        let p = random_point(m, &mut rng);
        let a: Vec<f64> = (0..m.dof()).map(|_| 3.0 * rng.next()).collect();
        let env = common::env(m, &p);
        let env = |s| match m.ctx.symbol_kind(s) {
            SymbolKind::Acceleration(i) => a[i],
            _ => env(s),
        };
        let pi: Vec<f64> = r.parameters.iter().map(|&e| m.ctx.eval(e, &env)).collect();
        for (i, row) in r.rows.iter().enumerate() {
            let y_pi: f64 = row
                .iter()
                .zip(&pi)
                .map(|(&y, p)| m.ctx.eval(y, &env) * p)
                .sum();
            let want = m.ctx.eval(tau[i], &env);
            assert!(
                y_pi.is_finite() && want.is_finite(),
                "row {i}: {y_pi} vs {want}"
            );
            worst = worst.max((y_pi - want).abs() / (1.0 + want.abs()));
        }
    }
    worst
}

/// Max |Y_E π − (T + V)| over 10 random states, relative to 1 + |T + V|
/// (the descriptions have no potential but gravity's).
fn energy_misfit(m: &Model) -> f64 {
    let r = m
        .outputs
        .regressor
        .as_ref()
        .expect("the regressor is derived");
    let mut rng = Lcg(43);
    let mut worst = 0.0f64;
    for _ in 0..10 {
        let p = random_point(m, &mut rng);
        let pi: Vec<f64> = r.parameters.iter().map(|&e| eval(m, e, &p)).collect();
        let y_pi: f64 = r
            .energy
            .iter()
            .zip(&pi)
            .map(|(&y, p_k)| eval(m, y, &p) * p_k)
            .sum();
        let want = eval(m, m.energies.kinetic, &p) + eval(m, m.energies.potential, &p);
        assert!(y_pi.is_finite() && want.is_finite(), "{y_pi} vs {want}");
        worst = worst.max((y_pi - want).abs() / (1.0 + want.abs()));
    }
    worst
}

fn agrees(src: &str) {
    let m = model(&with_regressor(src));
    let worst = y_pi_minus_tau(&m);
    assert!(worst < 1e-12, "|Y π − τ| = {worst:e}\n{src}");
    let energy = energy_misfit(&m);
    assert!(energy < 1e-12, "|Y_E π − (T + V)| = {energy:e}\n{src}");
}

#[test]
fn spatial_chains() {
    for n in [1, 2, 3, 5] {
        agrees(&lagrange_codegen::chain::spatial_chain_source(n));
    }
}

#[test]
fn euler_top_on_massless_links() {
    agrees(
        "#[lagrange(coordinates(psi, theta, phi),
            body(top, mass = m, inertia = [a, a, c], about = [0, 0, 0], com = [0, 0, l],
                 at = [0, 0, 0], rotation = euler_zxz(psi, theta, phi)),
            gravity = [0, 0, -g])]
         struct Top { m: f64, a: f64, c: f64, l: f64, g: f64 }",
    );
}

/// Placements, a tilted axis, a body turned after its joint, a fixed tool
/// with a point mass on it, a massive base fixed in space, full tensors.
const ROBOT: &str = "#[lagrange(coordinates(a, b, c),
    body(base, mass = m0, inertia = [i1, i2, i3], at = [0, 0, 0], rotation = rot_z(w)),
    point(mount, on = base, at = [0.1, 0, h]),
    body(l1, mass = m1, inertia = [i1, i2, i3, p, 0, 0], com = [0.1, 0, 0.2],
         at = [mount.x, mount.y, mount.z], rotation = rot_z(w) * rot_z(a) * rot_x(0.4)),
    point(t1, on = l1, at = [0, 0.1, l]),
    body(l2, mass = m1, inertia = [i2, i3, i1, p, p / 2, p / 3], com = [l / 2, 0.1, 0],
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
fn placements_tilted_axes_fixed_bodies_and_point_masses() {
    agrees(ROBOT);
}

#[test]
fn sliding_joints() {
    agrees(
        "#[lagrange(coordinates(x, a, s),
            body(cart, mass = m0, inertia = [i1, i2, i3], at = [x, 0, 0], rotation = rot_z(0)),
            point(pivot, on = cart, at = [0, 0.1, 0.2]),
            body(arm, mass = m1, inertia = [i1, i2, i3], com = [0, 0.1, -l / 2],
                 at = [pivot.x, pivot.y, pivot.z], rotation = rot_z(0) * rot_x(a) * rot_y(w)),
            point(rail, on = arm, at = [s * 0.6, 0, -s * 0.8]),
            body(slider, mass = m0, inertia = [i2, i2, i3], com = [0.1, 0, 0],
                 at = [rail.x, rail.y, rail.z], rotation = rot_z(0) * rot_x(a) * rot_y(w)),
            gravity = [0, 0, -g])]
         struct Slides { m0: f64, m1: f64, i1: f64, i2: f64, i3: f64, l: f64, w: f64, g: f64 }",
    );
}

#[test]
fn poses_written_out() {
    agrees(&written::robot());
}

/// A floating base carrying a two-joint arm.
const FLOATING_ARM: &str = "#[lagrange(coordinates(x, y, z, j1, j2), orientation(base),
            body(hub, mass = 5.0, inertia = [0.4, 0.5, 0.6], com = [0.01, 0.02, 0.03],
                 at = [x, y, z], rotation = base),
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
fn free_orientations() {
    agrees(FLOATING_ARM);
}

#[test]
fn parameters_are_named_in_pinocchios_order() {
    let m = model(&with_regressor(ROBOT));
    let names = &m.outputs.regressor.as_ref().expect("derived").names;
    let l1: Vec<&str> = names.iter().filter_map(|n| n.strip_prefix("l1.")).collect();
    assert_eq!(
        l1,
        [
            "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz"
        ]
    );
    // Five bodies of ten and one point mass of one, in declaration order.
    assert_eq!(names.len(), 51);
    assert_eq!(names[0], "base.m");
    assert_eq!(names[50], "tip.m");
}

/// Max over 10 random states of |Y π − (M q̈ + h − Q)| relative to
/// 1 + |M q̈ + h − Q| (the descriptions' only force is gravity, so Q is
/// Q_gravity), and of |Y_p π − ∂T/∂q̇| relative to 1 + |∂T/∂q̇|.
fn generic_misfits(m: &mut Model) -> (f64, f64) {
    let qd = m.ctx.velocities();
    let momenta: Vec<_> = qd
        .iter()
        .map(|&v| m.ctx.diff(m.energies.kinetic, v))
        .collect();
    let r = m
        .outputs
        .regressor
        .as_ref()
        .expect("the regressor is derived");
    let mut rng = Lcg(35);
    let (mut forces, mut momentum) = (0.0f64, 0.0f64);
    for _ in 0..10 {
        let p = random_point(m, &mut rng);
        let a: Vec<f64> = (0..m.dof()).map(|_| 3.0 * rng.next()).collect();
        let env = common::env(m, &p);
        let env = |s| match m.ctx.symbol_kind(s) {
            SymbolKind::Acceleration(i) => a[i],
            _ => env(s),
        };
        let pi: Vec<f64> = r.parameters.iter().map(|&e| m.ctx.eval(e, &env)).collect();
        let times_pi = |row: &[lagrange_symbolic::Expr]| -> f64 {
            row.iter()
                .zip(&pi)
                .map(|(&y, p)| m.ctx.eval(y, &env) * p)
                .sum()
        };
        for (i, &p_i) in momenta.iter().enumerate() {
            let mass_times_a: f64 = (m.motion.mass[i].iter().zip(&a))
                .map(|(&m_ij, a_j)| m.ctx.eval(m_ij, &env) * a_j)
                .sum();
            let want = mass_times_a - m.ctx.eval(m.motion.rhs[i], &env);
            let y_pi = times_pi(&r.rows[i]);
            assert!(
                y_pi.is_finite() && want.is_finite(),
                "row {i}: {y_pi} vs {want}"
            );
            forces = forces.max((y_pi - want).abs() / (1.0 + want.abs()));
            let want = m.ctx.eval(p_i, &env);
            let y_pi = times_pi(&r.momentum[i]);
            assert!(
                y_pi.is_finite() && want.is_finite(),
                "row {i}: {y_pi} vs {want}"
            );
            momentum = momentum.max((y_pi - want).abs() / (1.0 + want.abs()));
        }
    }
    (forces, momentum)
}

/// Y's program's operation count.
fn y_ops(m: &Model) -> lagrange_symbolic::OpCount {
    let r = m.outputs.regressor.as_ref().expect("derived");
    let entries: Vec<_> = r.rows.iter().flatten().copied().collect();
    lagrange_symbolic::Program::new(&m.ctx, &entries).op_count()
}

/// A point pendulum; a double pendulum of point masses; a body on a curve
/// turning with its coordinates (ten parameters with first moments and
/// products of inertia); a slider-crank in its crank angle alone (a closed
/// chain in minimal coordinates, its rod a body); a pendulum on a support
/// moving with time; a spherical pendulum in Cartesian coordinates with its
/// thread as a holonomic constraint (Y is the unconstrained equations'); a
/// free body on a curve (a free orientation, Y taken at its chart's
/// centre).
const NOT_TREES: [&str; 7] = [
    "#[lagrange(coordinates(theta),
        point(bob, mass = m, at = [l * sin(theta), -l * cos(theta), 0]),
        gravity = [0, -g, 0])]
     struct Pendulum { m: f64, l: f64, g: f64 }",
    "#[lagrange(coordinates(a, b),
        point(p1, mass = m1, at = [l1 * sin(a), -l1 * cos(a), 0]),
        point(p2, mass = m2, at = [p1.x + l2 * sin(b), p1.y - l2 * cos(b), 0]),
        gravity = [0, -g, 0])]
     struct Double { m1: f64, m2: f64, l1: f64, l2: f64, g: f64 }",
    "#[lagrange(coordinates(x, y),
        body(disk, mass = m, inertia = [a, b, c, d, e, f], com = [u, w, h],
             at = [x, x * x, y], rotation = rot_z(x) * rot_x(y)),
        gravity = [0, 0, -g])]
     struct Curve { m: f64, a: f64, b: f64, c: f64, d: f64, e: f64, f: f64,
                    u: f64, w: f64, h: f64, g: f64 }",
    "#[lagrange(coordinates(th),
        point(pin, mass = mp, at = [0.4 * cos(th), 0.4 * sin(th), 0]),
        point(slider, mass = ms,
              at = [0.4 * cos(th) + sqrt(1.44 - 0.16 * sin(th) * sin(th)), 0, 0]),
        body(rod, mass = mr, inertia = [0.01, 0.02, j], com = [c, 0.01, 0],
             at = [pin.x, pin.y, 0], rotation = rot_z(-asin(0.4 * sin(th) / 1.2))),
        gravity = [0, -g, 0])]
     struct SliderCrank { mp: f64, ms: f64, mr: f64, j: f64, c: f64, g: f64 }",
    "#[lagrange(coordinates(theta),
        point(bob, mass = m, at = [s * cos(w * t) + l * sin(theta), -l * cos(theta), 0]),
        gravity = [0, -g, 0])]
     struct Shaken { m: f64, s: f64, w: f64, l: f64, g: f64 }",
    "#[lagrange(coordinates(x, y, z),
        point(bob, mass = m, at = [x, y, z]),
        gravity = [0, 0, -g],
        holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - (l^2)))]
     struct CartesianSpherical { m: f64, l: f64, g: f64 }",
    "#[lagrange(coordinates(x, y), orientation(turn),
        body(puck, mass = m, inertia = [a, b, c], com = [u, w, h],
             at = [x, x * x, y], rotation = turn),
        gravity = [0, 0, -g])]
     struct FreeOnCurve { m: f64, a: f64, b: f64, c: f64, u: f64, w: f64, h: f64, g: f64 }",
];

#[test]
fn descriptions_that_are_no_trees_take_the_generic_route() {
    for src in NOT_TREES {
        let mut m = model(&with_regressor(src));
        let r = m.outputs.regressor.as_ref().expect("derived");
        assert!(
            matches!(&r.route, RegressorRoute::Lagrange(why) if !why.is_empty()),
            "{:?}\n{src}",
            r.route
        );
        let (forces, momentum) = generic_misfits(&mut m);
        let energy = energy_misfit(&m);
        eprintln!(
            "{}: |Y π − (M q̈ + h − Q_g)| {forces:.1e}, |Y_p π − p| {momentum:.1e}, |Y_E π − E| {energy:.1e}; Y {:?}",
            src.split("struct ")
                .nth(1)
                .unwrap_or(src)
                .split(' ')
                .next()
                .unwrap_or(""),
            y_ops(&m)
        );
        assert!(
            forces < 1e-12,
            "|Y π − (M q̈ + h − Q_g)| = {forces:e}\n{src}"
        );
        assert!(momentum < 1e-12, "|Y_p π − ∂T/∂q̇| = {momentum:e}\n{src}");
        assert!(energy < 1e-12, "|Y_E π − (T + V)| = {energy:e}\n{src}");
    }
}

/// The parameters' names on the generic route are the tree route's: a
/// body's ten in Pinocchio's order, a point mass's m.
#[test]
fn the_generic_route_names_pi_as_the_tree_route_does() {
    let m = model(&with_regressor(NOT_TREES[3]));
    let names = &m.outputs.regressor.as_ref().expect("derived").names;
    // In the description's order once its items are put in dependency order
    // (the rod is placed at the pin), as on the tree route.
    let want = [
        "pin.m", "rod.m", "rod.mx", "rod.my", "rod.mz", "rod.Ixx", "rod.Ixy", "rod.Iyy", "rod.Ixz",
        "rod.Iyz", "rod.Izz", "slider.m",
    ];
    assert_eq!(names, &want);
}

/// Trees whose Y is built both ways, by recursive Newton–Euler and (the
/// generic route forced) by the Euler–Lagrange operator: the same columns,
/// entry by entry, at random states; and both routes' operation counts.
#[test]
fn a_tree_by_both_routes_agrees_column_by_column() {
    let top_of_points = "#[lagrange(coordinates(psi, theta, phi),
        body(frame, mass = 0, inertia = [0, 0, 0], at = [0, 0, 0],
             rotation = euler_zxz(psi, theta, phi)),
        point(p1, on = frame, mass = m1, at = [a1, 0, c1]),
        point(p2, on = frame, mass = m2, at = [0, b2, c2]),
        point(p3, on = frame, mass = m3, at = [a3, b3, 0]),
        gravity = [0, 0, -g])]
     struct TopOfPoints { m1: f64, m2: f64, m3: f64, a1: f64, c1: f64, b2: f64,
                          c2: f64, a3: f64, b3: f64, g: f64 }";
    let sources = [
        ("heavy top of point masses", top_of_points.to_string()),
        (
            "spatial chain, 2 links",
            lagrange_codegen::chain::spatial_chain_source(2),
        ),
        (
            "spatial chain, 4 links",
            lagrange_codegen::chain::spatial_chain_source(4),
        ),
        ("placements and point masses", ROBOT.to_string()),
        ("floating arm", FLOATING_ARM.to_string()),
        (
            "UR5",
            format!(
                "#[lagrange(urdf = \"{}/../robots/ur5.urdf\", gravity = [0, 0, -9.81])] struct Ur5 {{}}",
                env!("CARGO_MANIFEST_DIR")
            ),
        ),
    ];
    for (name, src) in sources {
        let src = with_regressor(&src);
        let input: syn::DeriveInput = syn::parse_str(&src).expect("parses");
        let tree = model(&src);
        let generic = lagrange_codegen::model_by(&input, Route::Generic).expect("derives");
        let (r_tree, r_generic) = (
            tree.outputs.regressor.as_ref().expect("derived"),
            generic.outputs.regressor.as_ref().expect("derived"),
        );
        assert_eq!(r_tree.route, RegressorRoute::Recursive, "{name}");
        assert!(
            matches!(r_generic.route, RegressorRoute::Lagrange(_)),
            "{name}"
        );
        assert_eq!(r_tree.names, r_generic.names, "{name}");
        let mut rng = Lcg(36);
        let mut worst = 0.0f64;
        for _ in 0..5 {
            let p = random_point(&tree, &mut rng);
            let a: Vec<f64> = (0..tree.dof()).map(|_| 3.0 * rng.next()).collect();
            let at = |m: &Model, e| {
                let env = common::env(m, &p);
                m.ctx.eval(e, &|s| match m.ctx.symbol_kind(s) {
                    SymbolKind::Acceleration(i) => a[i],
                    _ => env(s),
                })
            };
            for (row_t, row_g) in r_tree.rows.iter().zip(&r_generic.rows) {
                for (&y_t, &y_g) in row_t.iter().zip(row_g) {
                    let (t, g) = (at(&tree, y_t), at(&generic, y_g));
                    assert!(t.is_finite() && g.is_finite(), "{name}: {t} vs {g}");
                    worst = worst.max((t - g).abs() / (1.0 + t.abs()));
                }
            }
        }
        eprintln!(
            "{name}: max |Y_tree − Y_generic| / (1 + |Y_tree|) = {worst:.1e}; Y by the tree {:?}, by the generic route {:?}",
            y_ops(&tree),
            y_ops(&generic)
        );
        assert!(worst < 1e-11, "{name}: {worst:e}");
    }
}

/// The robots shipped in `robots/`, read from their URDF: Y π = τ, and the
/// operation counts of Y's program and of τ's (printed, for the record: a
/// test asserts no speed).
#[test]
fn robots_from_urdf() {
    for file in [
        "ur5.urdf",
        "panda.urdf",
        "kinova.urdf",
        "z1.urdf",
        "xarm7.urdf",
        "solo12.urdf",
    ] {
        let src = format!(
            "#[lagrange(urdf(\"{}/../robots/{file}\", dynamics = ignore), gravity = [0, 0, -9.81])] struct Robot {{}}",
            env!("CARGO_MANIFEST_DIR")
        );
        let m = model(&with_regressor(&src));
        let worst = y_pi_minus_tau(&m);
        let energy = energy_misfit(&m);
        assert!(energy < 1e-12, "{file}: |Y_E π − (T + V)| = {energy:e}");
        let r = m.outputs.regressor.as_ref().expect("derived");
        let entries: Vec<_> = r.rows.iter().flatten().copied().collect();
        let y = lagrange_symbolic::Program::new(&m.ctx, &entries).op_count();
        let tau = &m.outputs.inverse.as_ref().expect("derived").torques;
        let t = lagrange_symbolic::Program::new(&m.ctx, tau).op_count();
        let momentum: Vec<_> = r.momentum.iter().flatten().copied().collect();
        let p = lagrange_symbolic::Program::new(&m.ctx, &momentum).op_count();
        eprintln!(
            "{file}: {} parameters, max |Y π − τ| / (1 + |τ|) = {worst:.1e}; Y: {} mul {} add, τ: {} mul {} add, Y_p: {} mul {} add",
            r.names.len(),
            y.mul,
            y.add,
            t.mul,
            t.add,
            p.mul,
            p.add
        );
        assert!(worst < 1e-12, "{file}: |Y π − τ| = {worst:e}");
    }
}

/// Q's forces other than gravity (a potential, a damper, a generalized
/// force) are outside π: Y is the same with them, and Y π is still
/// M q̈ + h − Q_gravity, the same system's without them.
#[test]
fn forces_other_than_gravity_stay_outside_y() {
    let bare = NOT_TREES[1];
    let loaded = bare.replacen(
        "gravity = [0, -g, 0])]",
        "gravity = [0, -g, 0], potential = k * (a^2) / 2, dissipation = c * (dot(b)^2) / 2,
          generalized_force(b = k * cos(t)))]",
        1,
    );
    let loaded = loaded.replacen("g: f64 }", "g: f64, k: f64, c: f64 }", 1);
    assert_ne!(loaded, bare);
    let mut bare = model(&with_regressor(bare));
    let loaded = model(&with_regressor(&loaded));
    let (forces, _) = generic_misfits(&mut bare);
    assert!(forces < 1e-12, "{forces:e}");
    // The parameters the two share come first, in the same order, so the
    // same random points evaluate both alike.
    let (r_bare, r_loaded) = (
        bare.outputs.regressor.as_ref().expect("derived"),
        loaded.outputs.regressor.as_ref().expect("derived"),
    );
    let mut rng = Lcg(37);
    for _ in 0..5 {
        let p = random_point(&loaded, &mut rng);
        let a: Vec<f64> = (0..loaded.dof()).map(|_| 3.0 * rng.next()).collect();
        let at = |m: &Model, e| {
            let env = common::env(m, &p);
            m.ctx.eval(e, &|s| match m.ctx.symbol_kind(s) {
                SymbolKind::Acceleration(i) => a[i],
                _ => env(s),
            })
        };
        for (row_b, row_l) in r_bare.rows.iter().zip(&r_loaded.rows) {
            for (&y_b, &y_l) in row_b.iter().zip(row_l) {
                let (b, l) = (at(&bare, y_b), at(&loaded, y_l));
                assert!((b - l).abs() <= 1e-14 * (1.0 + b.abs()), "{b} vs {l}");
            }
        }
        // And the loaded system's Q is not gravity's alone: its rhs differs.
        let differs = (bare.motion.rhs.iter().zip(&loaded.motion.rhs))
            .any(|(&b, &l)| (at(&bare, b) - at(&loaded, l)).abs() > 1e-6);
        assert!(differs);
    }
}
