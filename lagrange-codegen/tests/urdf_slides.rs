//! A prismatic joint's link has no rotation factor of its own; what hangs on
//! it by a rotated fixed frame must still be found on it (not on the ground
//! with the slide's coordinate driving a second joint), so `emit(articulated)`
//! holds, and its q̈ equals the generic route's M⁻¹(Q − h).

mod common;
use common::{Lcg, close, eval, random_point};
use lagrange_codegen::mechanics::{Model, Route};

fn inertial(mass: f64, i: [f64; 6], com: &str) -> String {
    let [xx, yy, zz, xy, xz, yz] = i;
    format!(
        "<inertial><origin xyz='{com}'/><mass value='{mass}'/><inertia ixx='{xx}' iyy='{yy}' izz='{zz}' ixy='{xy}' ixz='{xz}' iyz='{yz}'/></inertial>"
    )
}

/// A sliding link with a fixed child placed by `rpy="0 0 0.5"`.
fn slide_and_turned_tool() -> String {
    format!(
        "<robot name='slide'>
<link name='base'/>
<link name='slider'>{}</link>
<link name='tool'>{}</link>
<joint name='lift' type='prismatic'><parent link='base'/><child link='slider'/><origin xyz='0 0 0.3'/><axis xyz='0 0 1'/><limit lower='0' upper='0.35'/></joint>
<joint name='mount' type='fixed'><parent link='slider'/><child link='tool'/><origin xyz='0.1 0 0.2' rpy='0 0 0.5'/></joint>
</robot>",
        inertial(2.0, [0.02, 0.03, 0.04, 0.0, 0.0, 0.0], "0 0 0.1"),
        inertial(0.5, [0.004, 0.005, 0.006, 0.001, 0.0, 0.0], "0.05 0.02 0"),
    )
}

/// A TIAGo-like torso: a prismatic lift, then a fixed arm mount turned by a
/// quarter turn, and three revolute joints with rotated fixed frames between.
fn torso_and_arm() -> String {
    format!(
        "<robot name='torso'>
<link name='base_footprint'/>
<link name='torso_lift_link'>{}</link>
<link name='arm_mount'/>
<link name='arm_1_link'>{}</link>
<link name='arm_2_link'>{}</link>
<link name='elbow_frame'/>
<link name='arm_3_link'>{}</link>
<joint name='torso_lift_joint' type='prismatic'><parent link='base_footprint'/><child link='torso_lift_link'/><origin xyz='-0.062 0 0.8885'/><axis xyz='0 0 1'/><limit lower='0' upper='0.35'/></joint>
<joint name='arm_mount_joint' type='fixed'><parent link='torso_lift_link'/><child link='arm_mount'/><origin xyz='0.155 0.014 -0.151' rpy='0 0 -1.5708'/></joint>
<joint name='arm_1_joint' type='revolute'><parent link='arm_mount'/><child link='arm_1_link'/><origin xyz='0.0 0.0 0.0' rpy='0 0 0'/><axis xyz='0 0 1'/><limit lower='0.07' upper='2.68'/></joint>
<joint name='arm_2_joint' type='revolute'><parent link='arm_1_link'/><child link='arm_2_link'/><origin xyz='0.125 0.018 -0.031' rpy='1.5708 0 0'/><axis xyz='0 0 1'/><limit lower='-1.5' upper='1.02'/></joint>
<joint name='elbow_frame_joint' type='fixed'><parent link='arm_2_link'/><child link='elbow_frame'/><origin xyz='0.089 0 -0.0015' rpy='-1.5708 0.3 1.5708'/></joint>
<joint name='arm_3_joint' type='revolute'><parent link='elbow_frame'/><child link='arm_3_link'/><origin xyz='0 0 -0.22' rpy='0 0 0'/><axis xyz='0 0 1'/><limit lower='-3.5' upper='1.5'/></joint>
</robot>",
        inertial(
            11.0,
            [0.27, 0.20, 0.14, 0.002, -0.004, 0.001],
            "-0.03 0.0 -0.13"
        ),
        inertial(
            1.6,
            [0.002, 0.004, 0.004, 0.0001, 0.0, 0.0],
            "0.061 0.0 -0.036"
        ),
        inertial(
            1.8,
            [0.002, 0.005, 0.005, 0.0, 0.0003, 0.0],
            "0.030 0.0 0.001"
        ),
        inertial(
            2.0,
            [0.012, 0.012, 0.002, 0.0, 0.0, 0.0002],
            "0.007 -0.026 -0.105"
        ),
    )
}

fn model_by(text: &str, name: &str, emit: &str, route: Route) -> Model {
    let path = std::env::temp_dir().join(format!("lagrange-urdf-slides-{name}.urdf"));
    std::fs::write(&path, text).unwrap();
    let src = format!(
        "#[lagrange(urdf = \"{}\", gravity = [0, 0, -9.81]{emit})] struct R {{}}",
        path.display()
    );
    let input: syn::DeriveInput = syn::parse_str(&src).unwrap();
    lagrange_codegen::model_by(&input, route).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// x of M x = b by Gaussian elimination (M positive definite).
fn solve(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        for i in k + 1..n {
            let f = m[i][k] / m[k][k];
            let pivot = m[k].clone();
            for (x, p) in m[i][k..].iter_mut().zip(&pivot[k..]) {
                *x -= f * p;
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

/// The articulated route's q̈ against the generic route's M⁻¹(Q − h) at
/// random states; the largest relative difference.
fn articulated_against_generic(text: &str, name: &str) -> f64 {
    let aba = model_by(text, name, ", emit(articulated)", Route::Auto);
    let generic = model_by(text, name, "", Route::Generic);
    let fd = aba.outputs.articulated.as_ref().expect("emit(articulated)");
    let n = generic.dof();
    let mut worst: f64 = 0.0;
    let mut rng = Lcg(11);
    for _ in 0..20 {
        let p = random_point(&generic, &mut rng);
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| eval(&generic, generic.motion.mass[i][j], &p))
                    .collect()
            })
            .collect();
        let rhs: Vec<f64> = (0..n)
            .map(|i| eval(&generic, generic.motion.rhs[i], &p))
            .collect();
        let want = solve(m, rhs);
        let env = common::env(&aba, &p);
        let tau = |s| match fd.extra.iter().any(|&e| aba.ctx.as_symbol(e) == Some(s)) {
            true => 0.0,
            false => env(s),
        };
        for (i, &w) in want.iter().enumerate() {
            let got = aba.ctx.eval(fd.accelerations[i], &tau);
            assert!(close(got, w, 1e-11), "{name} q̈[{i}]: {got} vs {w}");
            worst = worst.max((got - w).abs() / (1.0 + w.abs()));
        }
    }
    worst
}

#[test]
fn a_slide_then_a_turned_fixed_frame_takes_the_articulated_route() {
    let worst = articulated_against_generic(&slide_and_turned_tool(), "tool");
    println!("slide and turned tool: q̈ agrees to {worst:.1e}");
}

#[test]
fn a_torso_lift_then_an_arm_takes_the_articulated_route() {
    let worst = articulated_against_generic(&torso_and_arm(), "torso");
    println!("torso and arm: q̈ agrees to {worst:.1e}");
}
