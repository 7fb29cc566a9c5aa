//! The derived equations checked numerically, independently of code emission:
//! the two derivations of h agree, M is the Hessian of T in the velocities, and the
//! generalized forces of a potential are −∂V/∂q — all at random states, against
//! central finite differences of the symbolic energies.

use lagrange_codegen::mechanics::Model;
use lagrange_symbolic::{Symbol, SymbolKind};

/// A deterministic pseudo-random sequence (no dependency needed for a handful of points).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
}

struct Point {
    q: Vec<f64>,
    v: Vec<f64>,
    t: f64,
    params: Vec<f64>,
}

fn env<'a>(model: &'a Model, p: &'a Point) -> impl Fn(Symbol) -> f64 + 'a {
    move |s| match model.ctx.symbol_kind(s) {
        SymbolKind::Coordinate(i) => p.q[i],
        SymbolKind::Velocity(i) => p.v[i],
        SymbolKind::Time => p.t,
        SymbolKind::Parameter(i) => p.params[i],
        SymbolKind::Acceleration(_) | SymbolKind::Free => f64::NAN,
    }
}

fn model(src: &str) -> Model {
    let input: syn::DeriveInput = syn::parse_str(src).expect("test input parses");
    match lagrange_codegen::model(&input) {
        Ok(m) => m,
        Err(e) => panic!("derivation failed: {e}"),
    }
}

fn random_point(model: &Model, rng: &mut Lcg) -> Point {
    let n = model.dof();
    Point {
        q: (0..n).map(|_| 1.5 * rng.next()).collect(),
        v: (0..n).map(|_| 2.0 * rng.next()).collect(),
        t: 1.5 + rng.next(),
        params: model
            .parameters
            .iter()
            .map(|_| 1.0 + 0.5 * rng.next())
            .collect(),
    }
}

fn eval(model: &Model, e: lagrange_symbolic::Expr, p: &Point) -> f64 {
    model.ctx.eval(e, &env(model, p))
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

fn check_model(src: &str) {
    let model = model(src);
    let mut rng = Lcg(12345);
    let n = model.dof();
    for _ in 0..20 {
        let p = random_point(&model, &mut rng);
        // 1. The projection and Christoffel routes give the same h.
        for i in 0..n {
            let a = eval(&model, model.bias[i], &p);
            let b = eval(&model, model.bias_other[i], &p);
            assert!(close(a, b, 1e-12), "h[{i}]: {a} vs {b} in\n{src}");
        }
        // 2. M is the Hessian of T in the velocities (T is quadratic in q̇, so central
        // differences are exact up to rounding).
        let kin = |v: &[f64]| {
            let pp = Point {
                q: p.q.clone(),
                v: v.to_vec(),
                t: p.t,
                params: p.params.clone(),
            };
            eval(&model, model.kinetic, &pp)
        };
        let d = 1e-3;
        for i in 0..n {
            for j in 0..n {
                let shifted = |si: f64, sj: f64| {
                    let mut v = p.v.clone();
                    v[i] += si;
                    v[j] += sj;
                    kin(&v)
                };
                let fd = (shifted(d, d) - shifted(d, -d) - shifted(-d, d) + shifted(-d, -d))
                    / (4.0 * d * d);
                let m = eval(&model, model.mass[i][j], &p);
                assert!(close(m, fd, 1e-6), "M[{i}][{j}]: {m} vs {fd}");
            }
        }
        // 3. With no forces but a potential, Q = −∂V/∂q.
        for i in 0..n {
            let pot = |dq: f64| {
                let mut q = p.q.clone();
                q[i] += dq;
                let pp = Point {
                    q,
                    v: p.v.clone(),
                    t: p.t,
                    params: p.params.clone(),
                };
                eval(&model, model.potential, &pp)
            };
            let h = 1e-5;
            let fd = -(pot(h) - pot(-h)) / (2.0 * h);
            let qf = eval(&model, model.forces[i], &p);
            assert!(close(qf, fd, 1e-7), "Q[{i}]: {qf} vs {fd}");
        }
    }
}

#[test]
fn spherical_pendulum() {
    check_model(
        "#[lagrange(coordinates(theta, phi),
           point(bob, mass = m, at = [l*sin(theta)*cos(phi), l*sin(theta)*sin(phi), -l*cos(theta)]),
           gravity = [0, 0, -g])]
         struct S { m: f64, l: f64, g: f64 }",
    );
}

#[test]
fn rheonomic_ellipsoid() {
    check_model(
        "#[lagrange(coordinates(q1, q2),
           point(p, mass = m, at = [a*t*sin(q1)*cos(q2), b*t*sin(q1)*sin(q2), c*t*cos(q1)]),
           gravity = [0, 0, -g])]
         struct S { m: f64, a: f64, b: f64, c: f64, g: f64 }",
    );
}

#[test]
fn dumbbell() {
    check_model(
        "#[lagrange(coordinates(xc, yc, zc, phi, psi),
           define(a = m2 * l / (m1 + m2), b = m1 * l / (m1 + m2)),
           point(p1, mass = m1, at = [xc + a*sin(phi)*cos(psi), yc + a*sin(phi)*sin(psi), zc + a*cos(phi)]),
           point(p2, mass = m2, at = [xc - b*sin(phi)*cos(psi), yc - b*sin(phi)*sin(psi), zc - b*cos(phi)]),
           gravity = [gx, gy, gz])]
         struct S { m1: f64, m2: f64, l: f64, gx: f64, gy: f64, gz: f64 }",
    );
}

#[test]
fn chain_in_relative_angles_with_spring() {
    check_model(
        "#[lagrange(coordinates(a1, a2, a3),
           define(x1 = l*sin(a1), y1 = -l*cos(a1),
                  x2 = x1 + l*sin(a1 + a2), y2 = y1 - l*cos(a1 + a2),
                  x3 = x2 + l*sin(a1 + a2 + a3), y3 = y2 - l*cos(a1 + a2 + a3)),
           point(b1, mass = m, at = [x1, y1]),
           point(b2, mass = 2 * m, at = [x2, y2]),
           point(b3, mass = m, at = [x3, y3]),
           gravity = [0, -g],
           potential = k * (pow(a2, 2) + a3.powi(2)) / 2)]
         struct S { m: f64, l: f64, g: f64, k: f64 }",
    );
}

/// The symbolic engine must find cos²+sin² = 1: the pendulum's M is m·l², not a sum.
#[test]
fn pendulum_mass_matrix_is_simplified() {
    let model = model(
        "#[lagrange(coordinates(theta), point(bob, mass = m, at = [l*sin(theta), -l*cos(theta)]), gravity = [0, -g])]
         struct S { m: f64, l: f64, g: f64 }",
    );
    let text = model.ctx.display(model.mass[0][0]);
    assert!(!text.contains("sin") && !text.contains("cos"), "M = {text}");
    assert!(
        model.ctx.is_zero(model.bias[0]),
        "h = {}",
        model.ctx.display(model.bias[0])
    );
}
