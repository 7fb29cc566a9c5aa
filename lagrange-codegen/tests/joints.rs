//! `joint(q, damping = b, armature = Ia)` on both routes: against the same
//! chain without the items, M gains Ia on its diagonal and Q gains −b q̇,
//! nothing else changes; and every output agrees with M and Q − h (the
//! generic and recursive routes, the inverse dynamics, the articulated q̈ by
//! both its programs, the right-hand side's Jacobians).

mod common;
use common::{Lcg, Point, close, random_point};
use lagrange_codegen::mechanics::{Model, Route};
use lagrange_symbolic::{Expr, SymbolKind};

/// A spatial chain of three rods; with `joints` the first joint is damped
/// and geared (b1, a1 parameters), the second damped, the third geared
/// (literals).
fn chain(joints: bool, emit: &str) -> String {
    let src = lagrange_codegen::chain::spatial_chain_source(3);
    let src = src.replace("#[lagrange(", &format!("#[lagrange(emit({emit}), "));
    if !joints {
        return src;
    }
    src.replace(
        "gravity = [0, 0, -g])] pub struct SpatialChain { ",
        "joint(q1, damping = b1, armature = a1), joint(q2, damping = 0.4), \
         joint(q3, armature = 0.02, friction = 0), gravity = [0, 0, -g])] \
         pub struct SpatialChain { pub b1: f64, pub a1: f64, ",
    )
}

fn model_by(src: &str, route: Route) -> Model {
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    lagrange_codegen::model_by(&input, route).unwrap_or_else(|e| panic!("{e}"))
}

/// `e` of `model` at `p` (its parameters named as in `from`), q̈ = `qdd`,
/// the free symbols `extra` = `tau`.
fn at(
    model: &Model,
    e: Expr,
    from: (&Model, &Point),
    qdd: &[f64],
    extra: (&[Expr], &[f64]),
) -> f64 {
    let (named, p) = from;
    model.ctx.eval(e, &|s| match model.ctx.symbol_kind(s) {
        SymbolKind::Coordinate(i) => p.q[i],
        SymbolKind::Velocity(i) => p.v[i],
        SymbolKind::Acceleration(i) => qdd[i],
        SymbolKind::Time => p.t,
        SymbolKind::Parameter(i) => {
            let name = &model.variables.parameters[i];
            let k = named.variables.parameters.iter().position(|n| n == name);
            p.params[k.expect("the parameter is the joints' model's")]
        }
        _ => {
            let k = extra
                .0
                .iter()
                .position(|&x| model.ctx.as_symbol(x) == Some(s));
            extra.1[k.expect("a free symbol is an extra force")]
        }
    })
}

/// The value of parameter `name` at `p`.
fn param(model: &Model, p: &Point, name: &str) -> f64 {
    p.params[model
        .variables
        .parameters
        .iter()
        .position(|n| n == name)
        .unwrap()]
}

#[test]
fn armature_adds_to_m_and_damping_to_q_on_both_routes() {
    let bare_src = chain(false, "inverse_dynamics");
    let src = chain(true, "inverse_dynamics");
    let generic = model_by(&src, Route::Generic);
    let mut rng = Lcg(11);
    for route in [Route::Generic, Route::Recursive] {
        let bare = model_by(&bare_src, route);
        let with = model_by(&src, route);
        for _ in 0..10 {
            let p = random_point(&with, &mut rng);
            let qdd: Vec<f64> = (0..3).map(|_| 2.0 * rng.next()).collect();
            let ev = |m: &Model, e: Expr| at(m, e, (&with, &p), &qdd, (&[], &[]));
            let (b1, a1) = (param(&with, &p, "b1"), param(&with, &p, "a1"));
            let armature = [a1, 0.0, 0.02];
            let damping = [-b1 * p.v[0], -0.4 * p.v[1], 0.0];
            for i in 0..3 {
                for j in 0..3 {
                    let added =
                        ev(&with, with.motion.mass[i][j]) - ev(&bare, bare.motion.mass[i][j]);
                    let want = if i == j { armature[i] } else { 0.0 };
                    assert!(
                        close(added, want, 1e-12),
                        "{route:?} M[{i}][{j}] gained {added}"
                    );
                    let other = ev(&generic, generic.motion.mass[i][j]);
                    assert!(close(ev(&with, with.motion.mass[i][j]), other, 1e-12));
                }
                let gained = ev(&with, with.motion.forces[i]) - ev(&bare, bare.motion.forces[i]);
                assert!(
                    close(gained, damping[i], 1e-12),
                    "{route:?} Q[{i}] gained {gained}"
                );
                let h = (
                    ev(&with, with.motion.bias[i]),
                    ev(&bare, bare.motion.bias[i]),
                );
                assert!(close(h.0, h.1, 1e-12), "{route:?} h[{i}] changed");
                let rhs = ev(&with, with.motion.rhs[i]);
                assert!(close(rhs, ev(&generic, generic.motion.rhs[i]), 1e-12));
                // τ = M q̈ + h − Q: the losses and the rotors' inertia are in it.
                let tau = ev(&with, with.outputs.inverse.as_ref().unwrap().torques[i]);
                let m_qdd: f64 = (0..3)
                    .map(|j| ev(&with, with.motion.mass[i][j]) * qdd[j])
                    .sum();
                assert!(
                    close(tau, m_qdd - rhs, 1e-11),
                    "{route:?} τ[{i}]: {tau} vs {}",
                    m_qdd - rhs
                );
                let bare_tau = ev(&bare, bare.outputs.inverse.as_ref().unwrap().torques[i]);
                let extra = armature[i] * qdd[i] - damping[i];
                assert!(
                    close(tau - bare_tau, extra, 1e-11),
                    "{route:?} τ[{i}] gained {}",
                    tau - bare_tau
                );
            }
            let t = ev(&with, with.energies.kinetic) - ev(&bare, bare.energies.kinetic);
            let rotors: f64 = (0..3).map(|i| armature[i] * p.v[i] * p.v[i] / 2.0).sum();
            assert!(
                close(t, rotors, 1e-12),
                "{route:?} T gained {t}, not {rotors}"
            );
        }
    }
}

#[test]
fn articulated_accelerations_take_the_armature() {
    let model = model_by(&chain(true, "articulated"), Route::Auto);
    let chosen = model.outputs.articulated.as_ref().expect("asked for");
    let choice = model
        .outputs
        .forward_route
        .as_ref()
        .expect("a route was chosen");
    let programs: Vec<_> = std::iter::once(chosen).chain(&choice.other).collect();
    assert_eq!(
        programs.len(),
        2,
        "both the articulated-body and the factored programs"
    );
    let mut rng = Lcg(5);
    for _ in 0..10 {
        let p = random_point(&model, &mut rng);
        let tau: Vec<f64> = (0..3).map(|_| 3.0 * rng.next()).collect();
        let ev = |e: Expr| at(&model, e, (&model, &p), &[], (&[], &[]));
        let m = nalgebra::Matrix3::from_fn(|i, j| ev(model.motion.mass[i][j]));
        let rhs = nalgebra::Vector3::from_fn(|i, _| ev(model.motion.rhs[i]) + tau[i]);
        let want = m.lu().solve(&rhs).expect("M is positive definite");
        for fd in &programs {
            for (i, &w) in want.iter().enumerate() {
                let got = at(
                    &model,
                    fd.accelerations[i],
                    (&model, &p),
                    &[],
                    (&fd.extra, &tau),
                );
                assert!(close(got, w, 1e-10), "q̈[{i}]: {got} vs {w}");
            }
        }
    }
}

#[test]
fn jacobians_take_the_damping_on_both_routes() {
    let src = chain(true, "jacobians");
    let generic = model_by(&src, Route::Generic);
    let recursive = model_by(&src, Route::Recursive);
    let bare = model_by(&chain(false, "jacobians"), Route::Recursive);
    let mut rng = Lcg(3);
    for _ in 0..5 {
        let p = random_point(&generic, &mut rng);
        let qdd: Vec<f64> = (0..3).map(|_| 2.0 * rng.next()).collect();
        let ev = |m: &Model, e: Expr| at(m, e, (&generic, &p), &qdd, (&[], &[]));
        let b1 = param(&generic, &p, "b1");
        let [g, r, o] =
            [&generic, &recursive, &bare].map(|m| m.outputs.jacobians.as_ref().unwrap());
        for i in 0..3 {
            for k in 0..3 {
                for (gj, rj) in [(&g.position, &r.position), (&g.velocity, &r.velocity)] {
                    let (a, b) = (ev(&generic, gj[i][k]), ev(&recursive, rj[i][k]));
                    assert!(close(a, b, 1e-11), "[{i}][{k}]: {a} vs {b}");
                }
                let gained = ev(&recursive, r.velocity[i][k]) - ev(&bare, o.velocity[i][k]);
                let want = match (i, k) {
                    (0, 0) => -b1,
                    (1, 1) => -0.4,
                    _ => 0.0,
                };
                assert!(
                    close(gained, want, 1e-11),
                    "∂(Q − h)/∂q̇[{i}][{k}] gained {gained}"
                );
            }
        }
    }
}
