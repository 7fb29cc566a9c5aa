//! The base parameters in closed form (`tree::regrouped`, printed in the
//! `EQUATIONS` texts): a planar 2R arm's against the textbook's, and on the
//! robots shipped in `robots/` the count against the numerical rank that
//! Pinocchio's regressor gives (`tests/data/urdf_regressor.txt`).

mod common;
use common::model;

fn base(src: &str) -> lagrange_codegen::mechanics::BaseForm {
    let mut m = model(src);
    let r = m
        .outputs
        .regressor
        .take()
        .expect("the regressor is derived");
    r.base
        .expect("a tree without free orientations has a closed form")
}

/// A planar 2R arm in the vertical plane (the runtime test's): six base
/// parameters, ZZ1 + m2 l1² and MX1 + m2 l1 among them (Khalil and
/// Dombre, *Modeling, Identification and Control of Robots*, §12.5).
#[test]
fn a_planar_2r_arm_regroups_as_the_textbook_does() {
    let form = base(
        "#[lagrange(
            coordinates(q1, q2),
            body(link1, mass = m1, inertia = [0.01, 0.02, i1], com = [c1, d1, 0],
                 at = [0, 0, 0], rotation = rot_z(q1)),
            point(elbow, on = link1, at = [l1, 0, 0]),
            body(link2, mass = m2, inertia = [0.01, 0.02, i2], com = [c2, d2, 0],
                 at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
            gravity = [0, -9.81, 0],
            emit(regressor),
        )]
        struct Arm2R { m1: f64, m2: f64, i1: f64, i2: f64, c1: f64, d1: f64, c2: f64, d2: f64, l1: f64 }",
    );
    let texts: Vec<&str> = form.parameters.iter().map(|p| p.text.as_str()).collect();
    eprintln!(
        "{texts:#?}\nno effect: {:?}\ndependent: {:?}",
        form.without_effect, form.dependent
    );
    assert_eq!(
        texts,
        [
            "link1.mxR = link1.mx + l1 link2.m",
            "link1.my",
            "link1.IzzR = link1.Izz + l1^2 link2.m",
            "link2.mx",
            "link2.my",
            "link2.Izz",
        ]
    );
    assert!(form.dependent.is_empty(), "{:?}", form.dependent);
}

/// The same arm with drives: each joint's damping, friction and armature is
/// a base parameter of its own, but the first joint's armature, which turns
/// about an axis fixed in space as link 1's axial inertia does and shows
/// only as q̈1 on row 1: it regroups into ZZ1R (Khalil and Dombre, §12.5.3).
#[test]
fn a_root_joints_armature_regroups_into_its_links_axial_inertia() {
    let form = base(
        "#[lagrange(
            coordinates(q1, q2),
            inputs(u),
            body(link1, mass = m1, inertia = [0.01, 0.02, i1], com = [c1, d1, 0],
                 at = [0, 0, 0], rotation = rot_z(q1)),
            point(elbow, on = link1, at = [l1, 0, 0]),
            body(link2, mass = m2, inertia = [0.01, 0.02, i2], com = [c2, d2, 0],
                 at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
            gravity = [0, -9.81, 0],
            joint(q1, damping = b1, friction = 0.4, armature = ia),
            joint(q2, damping = b2, motor = u, gear = n, rotor = ir),
            emit(regressor),
        )]
        struct Arm2R { m1: f64, m2: f64, i1: f64, i2: f64, c1: f64, d1: f64, c2: f64, d2: f64,
                       l1: f64, b1: f64, b2: f64, ia: f64, n: f64, ir: f64 }",
    );
    let texts: Vec<&str> = form.parameters.iter().map(|p| p.text.as_str()).collect();
    eprintln!(
        "{texts:#?}
dependent: {:?}",
        form.dependent
    );
    assert_eq!(
        texts,
        [
            "link1.mxR = link1.mx + l1 link2.m",
            "link1.my",
            "link1.IzzR = link1.Izz + l1^2 link2.m + q1.armature",
            "link2.mx",
            "link2.my",
            "link2.Izz",
            "q1.damping",
            "q1.friction",
            "q2.damping",
            "q2.armature",
        ]
    );
    assert!(form.dependent.is_empty(), "{:?}", form.dependent);
}

/// The arms shipped in `robots/`: as many base parameters as the numerical
/// rank of Pinocchio's stacked regressor (`tests/data/urdf_regressor.txt`,
/// written by `lagrange-bench/peer/pinocchio/urdf_regressor.py`), none left
/// dependent beyond the rules.
#[test]
fn the_shipped_arms_have_as_many_as_pinocchios_rank() {
    for (file, rank) in [
        ("ur5.urdf", 36),
        ("kinova.urdf", 36),
        ("z1.urdf", 43),
        ("xarm7.urdf", 43),
    ] {
        let form = base(&format!(
            "#[lagrange(urdf(\"{}/../robots/{file}\", dynamics = ignore), gravity = [0, 0, -9.81], emit(regressor))] struct Robot {{}}",
            env!("CARGO_MANIFEST_DIR")
        ));
        eprintln!(
            "{file}: {} base parameters, {} without effect, dependent {:?}",
            form.parameters.len(),
            form.without_effect.len(),
            form.dependent
        );
        for p in form.parameters.iter().take(4) {
            eprintln!("  {}", p.text);
        }
        assert!(form.dependent.is_empty(), "{file}: {:?}", form.dependent);
        assert_eq!(form.parameters.len(), rank, "{file}");
    }
    // The xArm7 with its file's damping and friction: one more base
    // parameter for each (its joints have no armature).
    let form = base(&format!(
        "#[lagrange(urdf(\"{}/../robots/xarm7.urdf\", dynamics = read), gravity = [0, 0, -9.81], emit(regressor))] struct Robot {{}}",
        env!("CARGO_MANIFEST_DIR")
    ));
    assert!(form.dependent.is_empty(), "{:?}", form.dependent);
    assert_eq!(form.parameters.len(), 43 + 2 * 7);
}

/// The `EQUATIONS` texts list them after the entries, in text and LaTeX.
#[test]
fn the_texts_print_them() {
    let m = model(
        "#[lagrange(
            coordinates(q1, q2),
            body(link1, mass = m1, inertia = [0.01, 0.02, i1], com = [c1, 0, 0],
                 at = [0, 0, 0], rotation = rot_z(q1)),
            point(elbow, on = link1, at = [l1, 0, 0]),
            body(link2, mass = m2, inertia = [0.01, 0.02, i2], com = [c2, 0, 0],
                 at = [elbow.x, elbow.y, elbow.z], rotation = rot_z(q1) * rot_z(q2)),
            gravity = [0, -9.81, 0],
            emit(regressor),
        )]
        struct Arm2R { m1: f64, m2: f64, i1: f64, i2: f64, c1: f64, c2: f64, l1: f64 }",
    );
    let texts = lagrange_codegen::doc::texts(&m);
    assert!(
        texts.equations.contains("Base parameters (6 of them;"),
        "{}",
        texts.equations
    );
    assert!(
        texts
            .equations
            .contains("\nlink1.IzzR = link1.Izz + l1^2 link2.m\n"),
        "{}",
        texts.equations
    );
    assert!(
        texts.latex.contains(
            "\\mathrm{link1.IzzR} &= \\mathrm{link1.Izz} + l_{1}^{2} \\mathrm{link2.m} \\\\"
        ),
        "{}",
        texts.latex
    );
}
