//! Robots read from URDF (`urdf = "path"`): the description a file becomes
//! derives the same equations by both routes, takes the recursive route where
//! every joint is one it takes, says why where not, and a bad file is an error
//! that quotes the file and line.

mod common;
use common::{Lcg, close, eval, random_point};
use lagrange_codegen::mechanics::{BiasRoute, Model, Route};
use lagrange_codegen::urdf::Base;

fn robot(file: &str) -> String {
    format!(
        "#[lagrange(urdf(\"{}/../robots/{file}\", dynamics = ignore), gravity = [0, 0, -9.81])] struct Robot {{}}",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn model_by(src: &str, route: Route) -> Result<Model, String> {
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    lagrange_codegen::model_by(&input, route).map_err(|e| e.to_string())
}

/// M, h and Q of both routes at random states.
fn routes_agree(generic: &Model, recursive: &Model) {
    let n = generic.dof();
    let mut rng = Lcg(7);
    for _ in 0..10 {
        let p = random_point(generic, &mut rng);
        for i in 0..n {
            for j in 0..n {
                let (a, b) = (
                    eval(generic, generic.motion.mass[i][j], &p),
                    eval(recursive, recursive.motion.mass[i][j], &p),
                );
                assert!(close(a, b, 1e-12), "M[{i}][{j}]: {a} vs {b}");
            }
            let (a, b) = (
                eval(generic, generic.motion.rhs[i], &p),
                eval(recursive, recursive.motion.rhs[i], &p),
            );
            assert!(close(a, b, 1e-12), "(Q - h)[{i}]: {a} vs {b}");
        }
    }
}

#[test]
fn ur5_takes_the_recursive_route_and_agrees_with_the_generic_one() {
    let src = robot("ur5.urdf");
    let recursive = model_by(&src, Route::Recursive).unwrap();
    assert_eq!(recursive.variables.coordinates.len(), 6);
    assert_eq!(recursive.motion.derivation.route, BiasRoute::Recursive);
    routes_agree(&model_by(&src, Route::Generic).unwrap(), &recursive);
    // Six joints are derived both ways, and the cheaper program kept.
    let auto = model_by(&src, Route::Auto).unwrap();
    println!(
        "UR5 by Auto: {:?}, {:?}",
        auto.motion.derivation.route, auto.motion.derivation.reason
    );
}

#[test]
fn panda_with_its_sliding_fingers_takes_the_recursive_route() {
    let src = robot("panda.urdf");
    let model = model_by(&src, Route::Auto).unwrap();
    // Seven arm joints and one finger: the second finger mimics the first.
    assert_eq!(
        model.variables.coordinates.len(),
        8,
        "{:?}",
        model.variables.coordinates
    );
    assert_eq!(
        model.motion.derivation.route,
        BiasRoute::Recursive,
        "{:?}",
        model.motion.derivation.reason
    );
    routes_agree(&model_by(&src, Route::Generic).unwrap(), &model);
}

#[test]
fn bad_files_quote_the_file_and_line() {
    let dir = std::env::temp_dir().join("lagrange-urdf-tests");
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "<robot name='r'><link name='a'>",
            "bad.urdf:1: malformed XML",
        ),
        (
            "<robot name='r'>\n<link name='a'/>\n<joint name='j' type='revolute'>\n<parent link='a'/><child link='b'/></joint>\n</robot>",
            "bad.urdf:3: joint `j` names an unknown link `b`",
        ),
        (
            "<robot name='r'>\n<link name='a'/><link name='b'/><link name='c'/>\n<joint name='j' type='revolute'><parent link='a'/><child link='b'/><axis xyz='0 0 1'/></joint>\n<joint name='k' type='floating'><parent link='b'/><child link='c'/></joint>\n</robot>",
            "bad.urdf:4: joint `k` is floating but `b` is not a bare root",
        ),
        (
            "<robot name='r'>\n<link name='a'/><link name='b'/>\n<joint name='j' type='planar'><parent link='a'/><child link='b'/></joint>\n</robot>",
            "bad.urdf:3: joint `j` has type `planar`",
        ),
        (
            "<robot name='r'>\n<link name='a'/><link name='b'/>\n<joint name='j' type='revolute'><parent link='a'/><child link='b'/></joint>\n<joint name='k' type='revolute'><parent link='b'/><child link='a'/></joint>\n</robot>",
            "bad.urdf: every link is some joint's child",
        ),
        (
            "<robot name='r'>\n<link name='a'>\n<inertial><mass value='x'/><inertia ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>\n</robot>",
            "bad.urdf:3: `x` is not a number",
        ),
        (
            "<robot name='r'>\n<link name='a'>\n<inertial><mass value='1'/>\n<inertia ixx='-0.1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>\n</robot>",
            "bad.urdf:4: link `a`: <inertia ixx='-0.1'> is negative",
        ),
        (
            "<robot name='r'>\n<link name='a'>\n<inertial><mass value='1'/>\n<inertia ixx='1' iyy='1' izz='3' ixy='0' ixz='0' iyz='0'/></inertial></link>\n</robot>",
            "bad.urdf:4: link `a`: <inertia> is that of no rigid body",
        ),
        (
            "<robot name='r'>\n<link name='a'>\n<inertial><mass value='-2'/>\n<inertia ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/></inertial></link>\n</robot>",
            "bad.urdf:3: <mass value='-2'> is negative",
        ),
    ];
    for (text, expected) in cases {
        let path = dir.join("bad.urdf");
        std::fs::write(&path, text).unwrap();
        let e = lagrange_codegen::urdf::load("/", path.to_str().unwrap(), &[], Default::default())
            .err()
            .unwrap_or_default();
        let shown = e
            .replace(&format!("{}", dir.display()), "")
            .replace('/', "");
        assert!(
            shown.contains(&expected.replace('/', "")),
            "{e}\nexpected {expected}"
        );
    }
}

#[test]
fn a_bad_file_is_one_compile_error_at_the_attribute() {
    let path = std::env::temp_dir().join("lagrange-urdf-expand.urdf");
    std::fs::write(
        &path,
        "<robot name='r'>\n<link name='a'/>\n<joint name='j' type='revolute'>\n<parent link='a'/><child link='b'/></joint>\n</robot>",
    )
    .unwrap();
    let src = format!("#[lagrange(urdf = \"{}\")] struct R {{}}", path.display());
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    let out = lagrange_codegen::expand(&input).to_string();
    assert_eq!(out.matches("compile_error").count(), 1, "{out}");
    assert!(
        out.contains(":3: joint `j` names an unknown link `b`"),
        "{out}"
    );
}

/// A file's floating joint from a bare world link reads as `base = floating`
/// on the same robot without it: the same description, item for item.
#[test]
fn a_floating_joint_at_the_root_is_a_free_base() {
    let arm = "<link name='base'><inertial><mass value='2'/><inertia ixx='0.1' iyy='0.2' izz='0.3' ixy='0' ixz='0' iyz='0'/></inertial></link>
<link name='arm'><inertial><origin xyz='0.1 0 0'/><mass value='1'/><inertia ixx='0.01' iyy='0.02' izz='0.02' ixy='0' ixz='0' iyz='0'/></inertial></link>
<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><origin xyz='0 0 0.2'/><axis xyz='0 1 0'/></joint>";
    let free = format!(
        "<robot name='r'><link name='world'/><joint name='free' type='floating'><parent link='world'/><child link='base'/></joint>{arm}</robot>"
    );
    let based = format!("<robot name='r'>{arm}</robot>");
    let read = |text: &str, base: Base| {
        let options = lagrange_codegen::urdf::Options {
            base,
            ..Default::default()
        };
        lagrange_codegen::urdf::from_text(text, "r.urdf", &[], options)
            .unwrap_or_else(|e| panic!("{e}"))
    };
    let (a, b) = (read(&free, Base::AsFile), read(&based, Base::Floating));
    let texts = |urdf: &lagrange_codegen::urdf::Urdf| -> Vec<String> {
        urdf.items.iter().map(ToString::to_string).collect()
    };
    assert_eq!(texts(&a), texts(&b));
    assert_eq!(a.coordinates, ["base_x", "base_y", "base_z", "shoulder"]);
    let turn = quote::quote!(orientation(base_turn)).to_string();
    assert!(texts(&a).contains(&turn), "{:?}", texts(&a));
}

/// A file's numbers read as their values whichever way XML spells them,
/// `.5`, `1.e0` and `+2` among them, which are no Rust literals: the robot
/// expands as the one written `0.5`, `1` and `2`.
#[test]
fn numbers_read_as_their_values_in_any_spelling() {
    let file = |mass: &str, x: &str, z: &str| {
        format!(
            "<robot name='r'><link name='base'/><link name='a'><inertial><mass value='{mass}'/>\
             <inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial></link>\
             <joint name='j' type='revolute'><parent link='base'/><child link='a'/>\
             <origin xyz='{x} 0 {z}'/><axis xyz='0 1 0'/></joint></robot>"
        )
    };
    let path = std::env::temp_dir().join("lagrange-urdf-spellings.urdf");
    let expand = |text: String| {
        std::fs::write(&path, text).unwrap();
        let src = format!(
            "#[lagrange(urdf = \"{}\", gravity = [0, 0, -9.81])] struct R {{}}",
            path.display()
        );
        lagrange_codegen::expand(&syn::parse_str(&src).unwrap()).to_string()
    };
    let spelled = expand(file("1.e0", ".5", "+2"));
    assert!(!spelled.contains("compile_error"), "{spelled}");
    assert_eq!(spelled, expand(file("1", "0.5", "2")));
}

/// A lone base link without an `<inertial>` put on a free root has nothing
/// that resists its motion: one compile error at the `urdf` path, naming the
/// body, not a singular mass matrix at run time.
#[test]
fn a_massless_floating_base_is_refused_at_the_attribute() {
    let path = std::env::temp_dir().join("lagrange-urdf-massless-base.urdf");
    std::fs::write(&path, "<robot name='r'>\n<link name='base'/>\n</robot>").unwrap();
    let src = format!(
        "#[lagrange(urdf(\"{}\", base = floating))] struct R {{}}",
        path.display()
    );
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    let out = lagrange_codegen::expand(&input).to_string();
    assert_eq!(out.matches("compile_error").count(), 1, "{out}");
    assert!(
        out.contains("body `base`: a free orientation turns it and nothing else"),
        "{out}"
    );
}

/// M and Q − h of a model, counted as the emitted program's operations.
fn operations(model: &Model) -> usize {
    let mut outputs: Vec<lagrange_symbolic::Expr> =
        model.motion.mass.iter().flatten().copied().collect();
    outputs.extend(&model.motion.rhs);
    lagrange_symbolic::Program::new(&model.ctx, &outputs)
        .op_count()
        .total()
}

/// Each arm transcribed by hand from its URDF: every rotation an explicit
/// matrix of `define`s (a product of its parent's and the joint's), every
/// position ξ(q) = origin + R · offset, the Panda's mimic finger's too. The
/// derive reads the tree back onto the recursive route; the equations equal
/// the URDF's and cost within 10 % of them.
#[test]
fn arms_written_out_read_back_onto_the_recursive_route() {
    for file in [
        "panda.urdf",
        "ur5.urdf",
        "kinova.urdf",
        "z1.urdf",
        "xarm7.urdf",
    ] {
        let path = format!("{}/../robots/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(path).expect("the arms' URDFs are in robots/");
        let ignored = lagrange_codegen::urdf::Options {
            dynamics: lagrange_codegen::urdf::DynamicsRule::Ignore,
            ..Default::default()
        };
        let urdf =
            lagrange_codegen::urdf::from_text(&text, file, &[], ignored).expect("the arm reads");
        let items = lagrange_codegen::chain::written_out(&urdf.items);
        let src = format!(
            "#[lagrange({}, gravity = [0, 0, -9.81])] struct Robot {{}}",
            items.join(", ")
        );
        assert!(!src.contains(" on = "), "every point is written out: {src}");
        let written = model_by(&src, Route::Recursive).unwrap();
        let from_urdf = model_by(&robot(file), Route::Recursive).unwrap();
        routes_agree(&from_urdf, &written);
        let (w, u) = (operations(&written), operations(&from_urdf));
        println!("{file} M + (Q − h): written out {w} operations, from the URDF {u}");
        assert!(
            w * 10 <= u * 11,
            "{file}: written out {w} operations, URDF {u}"
        );
    }
}
