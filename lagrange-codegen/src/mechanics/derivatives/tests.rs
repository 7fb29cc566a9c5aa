//! The closed-form derivatives of recursive Newton–Euler against the
//! link-axes recursion differentiated by the engine, both forced, on arms,
//! a mimic joint and floating bases, at pseudo-random states.

use std::cell::Cell;

use lagrange_symbolic::{Expr as Sym, Symbol, SymbolKind};

use crate::mechanics::{Model, Route};

thread_local! {
    /// `Some(true)`: take the closed form; `Some(false)`: the differentiated
    /// one; `None`: the cheaper.
    pub(super) static FORCED: Cell<Option<bool>> = const { Cell::new(None) };
}

fn model(src: &str, closed_form: bool) -> Model {
    FORCED.set(Some(closed_form));
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    let model = crate::model_by(&input, Route::Recursive);
    FORCED.set(None);
    model.unwrap_or_else(|e| panic!("derivation failed: {e}"))
}

/// A pseudo-random value per symbol and state, the same in both models
/// (symbols are matched by kind and index); quaternions unit.
fn value(m: &Model, s: Symbol, state: u64) -> f64 {
    let hash = |k: u64| {
        let x = (k + 1)
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(state.wrapping_mul(0xD1B5_4A32_D192_ED03));
        ((x >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    };
    match m.ctx.symbol_kind(s) {
        SymbolKind::Coordinate(i) => 1.5 * hash(i as u64),
        SymbolKind::Velocity(i) => 2.0 * hash(100 + i as u64),
        SymbolKind::Acceleration(i) => 2.0 * hash(200 + i as u64),
        SymbolKind::Parameter(i) => 1.0 + 0.5 * hash(300 + i as u64),
        SymbolKind::Time => 0.7,
        SymbolKind::Input(_) => 0.0,
        SymbolKind::Free => quaternion(m, s, state),
    }
}

fn quaternion(m: &Model, s: Symbol, state: u64) -> f64 {
    for o in &m.variables.orientations {
        if let Some(c) = o
            .quaternion
            .iter()
            .position(|&e| m.ctx.as_symbol(e) == Some(s))
        {
            let raw = [0.8, -0.3 + 0.1 * state as f64, 0.45, -0.2];
            let norm = raw.iter().map(|x| x * x).sum::<f64>().sqrt();
            return raw[c] / norm;
        }
    }
    f64::NAN
}

fn agree(src: &str) {
    let closed = model(src, true);
    let differentiated = model(src, false);
    let (a, b) = (
        closed
            .outputs
            .jacobians
            .as_ref()
            .expect("jacobians emitted"),
        differentiated
            .outputs
            .jacobians
            .as_ref()
            .expect("jacobians emitted"),
    );
    let eval = |m: &Model, e: Sym, k: u64| m.ctx.eval(e, &|s| value(m, s, k));
    let mut worst = 0.0f64;
    for k in 0..3 {
        for (x, y) in [(&a.position, &b.position), (&a.velocity, &b.velocity)] {
            for (rx, ry) in x.iter().zip(y) {
                for (&ex, &ey) in rx.iter().zip(ry) {
                    let (u, v) = (eval(&closed, ex, k), eval(&differentiated, ey, k));
                    assert!(u.is_finite() && v.is_finite(), "{u} vs {v}");
                    worst = worst.max((u - v).abs() / (1.0 + u.abs().max(v.abs())));
                }
            }
        }
    }
    assert!(worst < 1e-11, "closed form off by {worst:e}\n{src}");
}

fn urdf(file: &str, options: &str) -> String {
    format!(
        "#[lagrange(urdf(\"{}/../robots/{file}\"{options}), gravity = [0, 0, -9.81], emit(jacobians))] struct Robot {{}}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn arms_agree() {
    agree(&urdf("xarm7.urdf", ", dynamics = ignore"));
    agree(&urdf("ur5.urdf", ""));
}

#[test]
fn a_mimic_joint_sums_its_joints() {
    agree(&urdf("panda.urdf", ", dynamics = ignore"));
}

#[test]
fn a_floating_base_differentiates_along_its_tangent() {
    agree(&urdf("solo12.urdf", ", base = floating"));
}

#[test]
fn a_free_top() {
    agree(
        "#[lagrange(
            orientation(att),
            body(top, rotation = att, at = [0, 0, 0], mass = m, com = [0, 0, l], inertia = [a, a, c]),
            gravity = [0, 0, -g],
        emit(jacobians))]
        struct Top { m: f64, l: f64, a: f64, c: f64, g: f64 }",
    );
}

/// M and Q − h read off the closed form's composites equal the motion's
/// (CRBA and recursive Newton–Euler in link axes), with a mimic joint, a
/// rotor's inertia and joint damping.
fn same_dynamics(src: &str) {
    let m = model(src, true);
    let j = m.outputs.jacobians.as_ref().expect("jacobians emitted");
    let (mass, rhs) = j.dynamics.as_ref().expect("the closed form's M and Q − h");
    let eval = |e: Sym, k: u64| m.ctx.eval(e, &|s| value(&m, s, k));
    let mut worst = 0.0f64;
    for k in 0..3 {
        let ours = mass.iter().flatten().chain(rhs);
        let motion = m.motion.mass.iter().flatten().chain(&m.motion.rhs);
        for (&a, &b) in ours.zip(motion) {
            let (u, v) = (eval(a, k), eval(b, k));
            assert!(u.is_finite() && v.is_finite(), "{u} vs {v}");
            worst = worst.max((u - v).abs() / (1.0 + u.abs().max(v.abs())));
        }
    }
    assert!(worst < 1e-12, "M, Q − h off by {worst:e}\n{src}");
}

#[test]
fn the_composites_give_the_motions_mass_matrix_and_forces() {
    same_dynamics(&urdf("xarm7.urdf", ", dynamics = ignore"));
    same_dynamics(&urdf("ur5.urdf", ""));
    same_dynamics(&urdf("panda.urdf", ", dynamics = ignore"));
    same_dynamics(&urdf("z1.urdf", ", dynamics = read"));
    same_dynamics(
        "#[lagrange(
            coordinates(a, b, c),
            body(upper, rotation = rot_z(a) * rot_y(b), at = [0, 0, 0], mass = m1, com = [0.1, 0, l1], inertia = [0.1, 0.2, 0.3]),
            point(elbow, on = upper, at = [0, 0.1, l1]),
            body(lower, rotation = rot_z(a) * rot_y(b) * rot_x(c), at = [elbow.x, elbow.y, elbow.z], mass = m2, com = [0, 0, l2], inertia = [0.2, 0.2, 0.1]),
            joint(a, damping = d, armature = ia),
            joint(c, armature = ic),
            gravity = [0, 0, -g],
            emit(jacobians))]
        struct Arm { m1: f64, m2: f64, l1: f64, l2: f64, d: f64, ia: f64, ic: f64, g: f64 }",
    );
}
