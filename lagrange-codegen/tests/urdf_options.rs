//! `urdf("..", ..)`'s options against the file shapes they meet, and the
//! names, angles, inertias and joints a real file writes that the importer
//! once read wrong or refused wrongly.

use lagrange_codegen::mechanics::{Model, Route};
use lagrange_codegen::urdf::{Base, InertiaRule, Options, from_text};

/// A base link and an arm on a revolute shoulder.
const ARM: &str = "<link name='base'><inertial><mass value='2'/><inertia ixx='0.1' iyy='0.2' izz='0.3' ixy='0' ixz='0' iyz='0'/></inertial></link>
<link name='arm'><inertial><origin xyz='0.1 0 0'/><mass value='1'/><inertia ixx='0.01' iyy='0.02' izz='0.02' ixy='0' ixz='0' iyz='0'/></inertial></link>
<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><origin xyz='0 0 0.2'/><axis xyz='0 1 0'/></joint>";

/// The arm hung from a world link by a floating joint placed at height 0.5.
fn floating_file() -> String {
    format!(
        "<robot name='r'><link name='world'/><joint name='free' type='floating'><parent link='world'/><child link='base'/><origin xyz='0 0 0.5'/></joint>{ARM}</robot>"
    )
}

fn read(text: &str, options: Options) -> Result<lagrange_codegen::urdf::Urdf, String> {
    from_text(text, "r.urdf", &[], options)
}

/// The items as token text (`point (p , on = b , ..)`), to compare and search.
fn texts(urdf: &lagrange_codegen::urdf::Urdf) -> Vec<String> {
    urdf.items.iter().map(ToString::to_string).collect()
}

fn with_base(base: Base) -> Options {
    Options {
        base,
        ..Default::default()
    }
}

/// The file written to a temporary path, read by the derive with `options`
/// (the attribute's text after the path): the model, or the one error.
fn derive(name: &str, text: &str, options: &str) -> Result<Model, String> {
    let path = std::env::temp_dir().join(format!("lagrange-urdf-options-{name}.urdf"));
    std::fs::write(&path, text).unwrap();
    let src = format!(
        "#[lagrange(urdf(\"{}\"{options}), gravity = [0, 0, -9.81])] struct R {{}}",
        path.display()
    );
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    lagrange_codegen::model_by(&input, Route::Auto).map_err(|e| e.to_string())
}

#[test]
fn base_fixed_fixes_a_files_floating_joint_where_it_places_the_base() {
    let fixed = read(&floating_file(), with_base(Base::Fixed)).unwrap();
    assert_eq!(fixed.coordinates, ["shoulder"]);
    let items = texts(&fixed);
    assert!(!items.iter().any(|i| i.starts_with("orientation")));
    let placed = quote::quote!(point(free_origin, on = world, at = [(0.0), (0.0), (0.5)]));
    assert!(items.contains(&placed.to_string()), "{items:?}");
    let model = derive("fixed", &floating_file(), ", base = fixed").unwrap();
    assert_eq!(model.variables.coordinates, ["shoulder"]);
}

#[test]
fn every_base_option_against_every_file_shape() {
    let plain = format!("<robot name='r'>{ARM}</robot>");
    let free = ["base_x", "base_y", "base_z", "shoulder"];
    let cases = [
        (&plain, Base::AsFile, &["shoulder"][..]),
        (&plain, Base::Fixed, &["shoulder"][..]),
        (&plain, Base::Floating, &free[..]),
        (&floating_file(), Base::AsFile, &free[..]),
        (&floating_file(), Base::Floating, &free[..]),
        (&floating_file(), Base::Fixed, &["shoulder"][..]),
    ];
    for (text, base, coordinates) in cases {
        let urdf = read(text, with_base(base)).unwrap();
        assert_eq!(urdf.coordinates, coordinates, "{base:?}");
    }
    // The file's own floating joint and `base = floating` read it alike.
    let a = read(&floating_file(), with_base(Base::AsFile)).unwrap();
    let b = read(&floating_file(), with_base(Base::Floating)).unwrap();
    assert_eq!(texts(&a), texts(&b));
}

#[test]
fn an_angle_in_degrees_is_refused_at_its_line() {
    let text = format!(
        "<robot name='r'>{ARM}\n<link name='tool'/>\n<joint name='mount' type='fixed'><parent link='arm'/><child link='tool'/>\n<origin rpy='90 0 0'/></joint></robot>"
    );
    let e = read(&text, Options::default()).err().unwrap();
    assert!(
        e.starts_with("r.urdf:6: rpy angle `90` exceeds a full turn")
            && e.contains("radians")
            && e.contains("90° = 1.5708"),
        "{e}"
    );
    // A full turn as files write it (6.28318530718 > 2π by 4e-12) is an angle.
    let turn = text.replace("rpy='90 0 0'", "rpy='6.28318530718 0 -6.28318530718'");
    assert!(read(&turn, Options::default()).is_ok());
}

/// URDF keeps links and joints in separate name spaces: a joint named as the
/// link it moves keeps its name as the coordinate, and the link's body is
/// `<link>_link`.
#[test]
fn a_joint_and_a_link_of_one_name_both_keep_a_name() {
    let text = "<robot name='r'><link name='base'/>
<link name='fr_tele'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial></link>
<joint name='fr_tele' type='prismatic'><parent link='base'/><child link='fr_tele'/><axis xyz='0 0 1'/></joint></robot>";
    let urdf = read(text, Options::default()).unwrap();
    assert_eq!(urdf.coordinates, ["fr_tele"]);
    let items = texts(&urdf);
    let body = items
        .iter()
        .find(|i| i.starts_with("body (fr_tele_link ,"))
        .unwrap_or_else(|| panic!("{items:?}"));
    assert!(body.contains("at = [fr_tele_origin . x"), "{body}");
    let model = derive("clash", text, "").unwrap();
    assert_eq!(model.variables.coordinates, ["fr_tele"]);
}

#[test]
fn a_name_the_description_reserves_gets_an_underscore() {
    let text = format!("<robot name='r'>{ARM}</robot>").replace("'shoulder'", "'pi'");
    let model = derive("pi", &text, "").unwrap();
    assert_eq!(model.variables.coordinates, ["pi_"]);
}

/// Two names that are one identifier are refused at the second one's line.
#[test]
fn a_name_clash_quotes_the_file_and_line() {
    let text = format!(
        "<robot name='r'>{ARM}\n<link name='hand'/>\n<joint name='shoulder-origin' type='revolute'><parent link='arm'/><child link='hand'/></joint></robot>"
    );
    let e = read(&text, Options::default()).err().unwrap();
    assert!(
        e.starts_with("r.urdf:3: `shoulder_origin` is named `shoulder_origin`"),
        "{e}"
    );
}

#[test]
fn a_robot_without_a_moving_joint_says_so() {
    let text = "<robot name='statue'><link name='a'/><link name='b'/>
<joint name='j' type='fixed'><parent link='a'/><child link='b'/></joint></robot>";
    let e = derive("statue", text, "").err().unwrap();
    assert!(
        e.contains("lagrange-urdf-options-statue.urdf: the robot `statue` has no moving joint"),
        "{e}"
    );
    assert!(!e.contains("coordinates()"), "{e}");
}

/// A gripper locked by hand: its leader made fixed, the fixed followers still
/// name it in their `<mimic>`, which a fixed joint ignores.
#[test]
fn a_fixed_joints_mimic_is_ignored() {
    let text = format!(
        "<robot name='r'>{ARM}<link name='left'/><link name='right'/>
<joint name='finger' type='fixed'><parent link='arm'/><child link='left'/><origin xyz='0.2 0 0'/></joint>
<joint name='finger2' type='fixed'><parent link='arm'/><child link='right'/><mimic joint='finger' multiplier='-1'/></joint></robot>"
    );
    let model = derive("mimic", &text, "").unwrap();
    assert_eq!(model.variables.coordinates, ["shoulder"]);
}

/// The arm's link with moments (1, 1, 3) · 10⁻², a tenth beyond a rigid
/// body's (izz ≤ ixx + iyy).
fn unphysical() -> String {
    format!("<robot name='r'>{ARM}</robot>").replace(
        "ixx='0.01' iyy='0.02' izz='0.02'",
        "ixx='0.01' iyy='0.01' izz='0.03'",
    )
}

#[test]
fn an_unphysical_inertia_is_refused_naming_the_link_and_the_way_through() {
    let e = read(&unphysical(), Options::default()).err().unwrap();
    assert!(
        e.starts_with("r.urdf:2: link `arm`: <inertia> is that of no rigid body")
            && e.contains("inertia = repair")
            && e.contains("inertia = as_written"),
        "{e}"
    );
}

/// (1, 1, 3) · 10⁻² is 10⁻² beyond izz = ixx + iyy; its projection onto
/// that plane moves each moment by a third of it: (4/3, 4/3, 8/3) · 10⁻².
#[test]
fn repair_uses_the_nearest_physical_inertia_and_lists_it() {
    let options = Options {
        inertia: InertiaRule::Repair,
        ..Default::default()
    };
    let urdf = read(&unphysical(), options).unwrap();
    let [(link, written, used)] = urdf.repaired.as_slice() else {
        panic!("{:?}", urdf.repaired)
    };
    assert_eq!(link, "arm");
    assert_eq!(written, &[0.01, 0.01, 0.03, 0.0, 0.0, 0.0]);
    let want = [4.0 / 300.0, 4.0 / 300.0, 8.0 / 300.0, 0.0, 0.0, 0.0];
    assert!(
        (0..6).all(|k| (used[k] - want[k]).abs() < 1e-16),
        "{used:?}"
    );
    let model = derive("repair", &unphysical(), ", inertia = repair").unwrap();
    assert_eq!(model.variables.coordinates, ["shoulder"]);
    assert!(derive("written", &unphysical(), ", inertia = as_written").is_ok());
    assert!(derive("refused", &unphysical(), "").is_err());
}

/// A joint named as a field of the struct is refused at the joint's line,
/// not at the path alone.
#[test]
fn a_joint_named_as_a_field_quotes_the_file_and_line() {
    let path = std::env::temp_dir().join("lagrange-urdf-options-field.urdf");
    std::fs::write(&path, format!("<robot name='r'>{ARM}</robot>")).unwrap();
    let src = format!(
        "#[lagrange(urdf = \"{}\")] struct R {{ shoulder: f64 }}",
        path.display()
    );
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    let e = lagrange_codegen::model_by(&input, Route::Auto)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("lagrange-urdf-options-field.urdf:3: `shoulder` is named `shoulder`"),
        "{e}"
    );
}

/// An inertia used as written that no f64 holds once turned into its link's
/// axes (the `<inertial>`'s rpy) is refused at the file's line, not written
/// as a literal no compiler reads.
#[test]
fn an_inertia_that_overflows_in_the_links_axes_is_refused_at_its_line() {
    let text = "<robot name='r'><link name='base'/>\n<link name='arm'><inertial><origin rpy='0.7 0.3 0'/>\n\
        <mass value='1'/><inertia ixx='1.7e308' iyy='1.7e308' izz='1.7e308' ixy='1.7e308' ixz='0' iyz='0'/>\
        </inertial></link><joint name='j' type='revolute'><parent link='base'/><child link='arm'/>\
        <axis xyz='0 0 1'/></joint></robot>";
    let as_written = Options {
        inertia: InertiaRule::AsWritten,
        ..Default::default()
    };
    let e = read(text, as_written).err().unwrap_or_default();
    assert!(
        e.starts_with("r.urdf:3: a number computed from the file here is inf"),
        "{e}"
    );
}

/// A stop that `limits = stops` makes, named as a field of the struct, is
/// refused at its joint's line.
#[test]
fn a_stop_named_as_a_field_quotes_its_joints_line() {
    let path = std::env::temp_dir().join("lagrange-urdf-options-stop.urdf");
    let limited = ARM.replace(
        "<axis xyz='0 1 0'/>",
        "<axis xyz='0 1 0'/><limit lower='-1' upper='1'/>",
    );
    std::fs::write(&path, format!("<robot name='r'>{limited}</robot>")).unwrap();
    let src = format!(
        "#[lagrange(urdf(\"{}\", limits = stops))] struct R {{ shoulder_lower: f64 }}",
        path.display()
    );
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    let e = lagrange_codegen::model_by(&input, Route::Auto)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("lagrange-urdf-options-stop.urdf:3: `shoulder_lower` is named"),
        "{e}"
    );
}
