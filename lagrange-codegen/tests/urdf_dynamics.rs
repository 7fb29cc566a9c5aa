//! `urdf(.., dynamics = read | ignore)`: the joints' `<dynamics damping
//! friction>` read as `joint(q, damping = b)` items, left out, or, without
//! the option, refused at the first moving joint that states a loss.

use lagrange_codegen::urdf::{DynamicsRule, Options, from_text};

/// A base, an arm on a shoulder that states `shoulder`'s `<dynamics>`, and a
/// finger that mimics the shoulder at `multiplier` and states `finger`'s.
fn arm(shoulder: &str, finger: &str, multiplier: &str) -> String {
    format!(
        "<robot name='r'>
<link name='base'><inertial><mass value='2'/><inertia ixx='0.1' iyy='0.2' izz='0.3' ixy='0' ixz='0' iyz='0'/></inertial></link>
<link name='arm'><inertial><origin xyz='0.1 0 0'/><mass value='1'/><inertia ixx='0.01' iyy='0.02' izz='0.02' ixy='0' ixz='0' iyz='0'/></inertial></link>
<link name='tip'><inertial><mass value='0.1'/><inertia ixx='0.001' iyy='0.001' izz='0.001' ixy='0' ixz='0' iyz='0'/></inertial></link>
<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><axis xyz='0 1 0'/>
{shoulder}</joint>
<joint name='finger' type='prismatic'><parent link='arm'/><child link='tip'/><axis xyz='1 0 0'/>
<mimic joint='shoulder' multiplier='{multiplier}'/>
{finger}</joint>
</robot>"
    )
}

fn read(text: &str, dynamics: DynamicsRule) -> Result<Vec<String>, String> {
    let options = Options {
        dynamics,
        ..Default::default()
    };
    let urdf = from_text(text, "r.urdf", &[], options)?;
    Ok(urdf.items.iter().map(ToString::to_string).collect())
}

fn joints(items: &[String]) -> Vec<&String> {
    items.iter().filter(|i| i.starts_with("joint")).collect()
}

#[test]
fn a_file_without_losses_reads_as_the_rigid_body_dynamics() {
    let zero = arm("<dynamics damping='0' friction='0.0'/>", "", "1");
    let unset = read(&zero, DynamicsRule::Unset).unwrap();
    assert_eq!(unset, read(&zero, DynamicsRule::Ignore).unwrap());
    assert_eq!(unset, read(&zero, DynamicsRule::Read).unwrap());
    assert!(joints(&unset).is_empty(), "{unset:?}");
}

#[test]
fn a_stated_loss_without_the_option_is_refused_at_its_line() {
    let lossy = arm("<dynamics damping='0.5'/>", "", "1");
    let e = read(&lossy, DynamicsRule::Unset).unwrap_err();
    assert!(
        e.starts_with(
            "r.urdf:6: joint `shoulder` states <dynamics damping=\"0.5\" friction=\"0\">, which \
             the rigid-body equations leave out; write `dynamics = read`"
        ),
        "{e}"
    );
    assert!(e.contains("or `dynamics = ignore`"), "{e}");
    let ignored = read(&lossy, DynamicsRule::Ignore).unwrap();
    assert!(joints(&ignored).is_empty());
}

#[test]
fn read_gives_each_coordinate_its_damping_and_its_followers() {
    // The finger slides at 2 q̇: its loss −0.25 · 2 q̇ does virtual work
    // 2 δq, so the shoulder's coordinate takes 0.5 + 0.25 · 2² = 1.5.
    let lossy = arm(
        "<dynamics damping='0.5'/>",
        "<dynamics damping='0.25'/>",
        "2",
    );
    let items = read(&lossy, DynamicsRule::Read).unwrap();
    let want = quote::quote!(joint(shoulder, damping = (1.5))).to_string();
    assert_eq!(joints(&items), [&want]);
    let base: Vec<String> = read(&lossy, DynamicsRule::Ignore).unwrap();
    assert_eq!(items.len(), base.len() + 1);
}

/// Friction is read as the joint's dry friction bound; a follower turning
/// at 2 q̇ adds twice its own (they slip and stick together).
#[test]
fn read_gives_each_coordinate_its_friction_and_its_followers() {
    let rough = arm(
        "<dynamics damping='0.5' friction='0.2'/>",
        "<dynamics friction='0.1'/>",
        "2",
    );
    let items = read(&rough, DynamicsRule::Read).unwrap();
    let want = quote::quote!(joint(shoulder, damping = (0.5), friction = (0.4))).to_string();
    assert_eq!(joints(&items), [&want]);
}

#[test]
fn read_refuses_negative_losses_at_their_lines() {
    let rough = arm("<dynamics friction='-0.2'/>", "", "1");
    let e = read(&rough, DynamicsRule::Read).unwrap_err();
    assert!(
        e.starts_with("r.urdf:6: joint `shoulder`: friction = -0.2 is negative"),
        "{e}"
    );
    let negative = arm("", "<dynamics damping='-0.1'/>", "1");
    let e = read(&negative, DynamicsRule::Read).unwrap_err();
    assert!(
        e.starts_with("r.urdf:9: joint `finger`: damping = -0.1 is negative"),
        "{e}"
    );
}

/// The shipped arms that state losses: the xArm7 and the Z1 state
/// damping and friction at every joint, the Panda damping alone.
#[test]
fn the_shipped_arms_under_each_rule() {
    let file = |name: &str| {
        let path = format!("{}/../robots/{name}", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(path).unwrap()
    };
    for name in ["xarm7.urdf", "z1.urdf", "panda.urdf"] {
        let e = read(&file(name), DynamicsRule::Unset).unwrap_err();
        assert!(
            e.contains("which the rigid-body equations leave out"),
            "{name}: {e}"
        );
        read(&file(name), DynamicsRule::Ignore).unwrap();
    }
    for (name, count) in [("xarm7.urdf", 7), ("z1.urdf", 7)] {
        let items = read(&file(name), DynamicsRule::Read).unwrap();
        let joints = joints(&items);
        assert_eq!(joints.len(), count, "{name}: {joints:?}");
        assert!(
            joints.iter().all(|j| j.contains("friction")),
            "{name}: {joints:?}"
        );
    }
    let panda = read(&file("panda.urdf"), DynamicsRule::Read).unwrap();
    assert_eq!(
        joints(&panda).len(),
        8,
        "seven arm joints and the finger: {panda:?}"
    );
    for name in ["ur5.urdf", "ur10.urdf", "kinova.urdf"] {
        let unset = read(&file(name), DynamicsRule::Unset).unwrap();
        assert_eq!(
            unset,
            read(&file(name), DynamicsRule::Ignore).unwrap(),
            "{name}"
        );
    }
}

/// The derive's error for the xArm7 read without the option, whole: the
/// path, the first joint that states a loss and its line, and the fix. (A
/// trybuild test cannot pin it: its crate is built under the target
/// directory, where a relative path to `robots/` does not lead.)
#[test]
fn the_xarm7_without_the_option_is_refused_naming_joint1_and_its_line() {
    let path = format!("{}/../robots/xarm7.urdf", env!("CARGO_MANIFEST_DIR"));
    let src = format!("#[lagrange(urdf = \"{path}\", gravity = [0, 0, -9.81])] struct X {{}}");
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    let e = lagrange_codegen::model(&input).err().map(|e| e.to_string());
    let want = format!(
        "{path}:179: joint `joint1` states <dynamics damping=\"10\" friction=\"1\">, which the \
         rigid-body equations leave out; write `dynamics = read` in `urdf(\"..\", ..)` to add \
         its damping and friction as `joint(q, damping = b, friction = fc)` items (run by \
         `run_contacts` where there is friction), or `dynamics = ignore` for the rigid-body \
         dynamics (what Pinocchio's rnea and aba compute)"
    );
    assert_eq!(e.as_deref(), Some(want.as_str()));
}
