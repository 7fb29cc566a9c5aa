//! The derived equations checked numerically, independently of code emission:
//! the two derivations of h agree, M is the Hessian of T in the velocities, and the
//! generalized forces of a potential are −∂V/∂q — all at random states, against
//! central finite differences of the symbolic energies.

mod common;
use common::{Lcg, Point, close, eval, model, random_point};

fn check_model(src: &str) {
    let model = model(src);
    let mut rng = Lcg(12345);
    let n = model.dof();
    for _ in 0..20 {
        let p = random_point(&model, &mut rng);
        // 1. The projection and Christoffel routes give the same h (or the recursive
        // and the cheaper generic one; a large tree derives only the recursive one).
        for (i, &other) in model.motion.derivation.other_bias.iter().enumerate() {
            let a = eval(&model, model.motion.bias[i], &p);
            let b = eval(&model, other, &p);
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
                u: Vec::new(),
                quaternions: p.quaternions.clone(),
            };
            eval(&model, model.energies.kinetic, &pp)
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
                let m = eval(&model, model.motion.mass[i][j], &p);
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
                    u: Vec::new(),
                    quaternions: p.quaternions.clone(),
                };
                eval(&model, model.energies.potential, &pp)
            };
            let h = 1e-5;
            let fd = -(pot(h) - pot(-h)) / (2.0 * h);
            let qf = eval(&model, model.motion.forces[i], &p);
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
    let text = model.ctx.display(model.motion.mass[0][0]);
    assert!(!text.contains("sin") && !text.contains("cos"), "M = {text}");
    assert!(
        model.ctx.is_zero(model.motion.bias[0]),
        "h = {}",
        model.ctx.display(model.motion.bias[0])
    );
}

/// A heavy symmetric top in Suslov's Euler angles: body rotation terms in M and h.
#[test]
fn heavy_top_euler_zxz() {
    check_model(
        "#[lagrange(coordinates(psi, theta, phi),
           body(top, mass = m, inertia = [a, a, c], at = [l*sin(theta)*sin(psi), -l*sin(theta)*cos(psi), l*cos(theta)],
                rotation = euler_zxz(psi, theta, phi)),
           gravity = [0, 0, -g])]
         struct S { m: f64, a: f64, c: f64, l: f64, g: f64 }",
    );
}

/// The heavy top's precession and spin angles are cyclic: M, h and T must not
/// contain them (h from M's Christoffel symbols keeps M's simplified form; h by
/// projection carried sin ψ, cos ψ products that cancel only numerically), and h
/// is the textbook one: h_ψ = θ̇ sinθ (2(ml² + a − c) ψ̇ cosθ − c φ̇),
/// h_θ = ψ̇ sinθ (c φ̇ − (ml² + a − c) ψ̇ cosθ), h_φ = −c ψ̇ θ̇ sinθ.
#[test]
fn heavy_top_output_is_free_of_cyclic_coordinates() {
    let model = model(
        "#[lagrange(coordinates(psi, theta, phi),
           body(top, mass = m, inertia = [a, a, c], at = [l*sin(theta)*sin(psi), -l*sin(theta)*cos(psi), l*cos(theta)],
                rotation = euler_zxz(psi, theta, phi)),
           gravity = [0, 0, -g])]
         struct S { m: f64, a: f64, c: f64, l: f64, g: f64 }",
    );
    let q = model.ctx.coordinates();
    let (psi, phi) = (q[0], q[2]);
    let mut outputs = model.motion.bias.clone();
    outputs.extend(model.motion.mass.iter().flatten());
    outputs.extend(&model.motion.rhs);
    outputs.push(model.energies.kinetic);
    for &e in &outputs {
        for (name, c) in [("psi", psi), ("phi", phi)] {
            assert!(
                !model.ctx.depends_on(e, c),
                "{name} in {}",
                model.ctx.display(e)
            );
        }
    }
    let mut rng = Lcg(5);
    for _ in 0..10 {
        let p = random_point(&model, &mut rng);
        let [m, a, c, l, _g] = [0, 1, 2, 3, 4].map(|i| p.params[i]);
        let (th, [dpsi, dth, dphi]) = (p.q[1], [p.v[0], p.v[1], p.v[2]]);
        let big = m * l * l + a;
        let want = [
            dth * th.sin() * (2.0 * (big - c) * dpsi * th.cos() - c * dphi),
            dpsi * th.sin() * (c * dphi - (big - c) * dpsi * th.cos()),
            -c * dpsi * dth * th.sin(),
        ];
        for (i, w) in want.into_iter().enumerate() {
            let got = eval(&model, model.motion.bias[i], &p);
            assert!(close(got, w, 1e-12), "h[{i}]: {got} vs {w}");
        }
    }
}

/// Positions written with angle sums (a crank and a coupler, b + th): M's
/// entries come out as the closed forms — M₁₁ = m₂d² + m₃r², M₀₀ with
/// 2 m₂ r_a d cos th — and neither M nor h depends on the cyclic angle b, where
/// the squares of the Jacobian's sums of products used to keep it.
#[test]
fn angle_sums_in_positions_give_closed_forms() {
    let src = "#[lagrange(coordinates(b, th),
        point(p1, mass = m1, at = [ra * cos(b), ra * sin(b)]),
        point(p2, mass = m2, at = [ra * cos(b) + d * cos(b + th), ra * sin(b) + d * sin(b + th)]),
        point(p3, mass = m3, at = [rr * cos(b) * cos(th) - rr * sin(b) * sin(th), rr * sin(b + th)]))]
     struct S { m1: f64, m2: f64, m3: f64, ra: f64, d: f64, rr: f64 }";
    check_model(src);
    let model = model(src);
    let b = model.ctx.coordinates()[0];
    let mut outputs = model.motion.bias.clone();
    outputs.extend(model.motion.mass.iter().flatten());
    for &e in &outputs {
        assert!(!model.ctx.depends_on(e, b), "b in {}", model.ctx.display(e));
    }
    let mut rng = Lcg(9);
    let p = random_point(&model, &mut rng);
    let [m1, m2, m3, ra, d, rr] = [0, 1, 2, 3, 4, 5].map(|i| p.params[i]);
    let th = p.q[1];
    let want = [
        [
            m1 * ra * ra + m2 * (ra * ra + d * d + 2.0 * ra * d * th.cos()) + m3 * rr * rr,
            0.0,
        ],
        [0.0, m2 * d * d + m3 * rr * rr],
    ];
    for (i, j) in [(0, 0), (1, 1)] {
        let got = eval(&model, model.motion.mass[i][j], &p);
        assert!(
            close(got, want[i][j], 1e-13),
            "M[{i}][{j}]: {got} vs {}",
            want[i][j]
        );
    }
    assert_eq!(
        model.ctx.display(model.motion.mass[1][1]),
        "m2*d^2 + m3*rr^2",
        "M₁₁ as the closed form"
    );
}

/// A full inertia tensor, a yaw–pitch–roll rotation and an explicit matrix factor.
#[test]
fn body_with_full_tensor_and_explicit_matrix() {
    check_model(
        "#[lagrange(coordinates(x, a, b, c),
           body(blk, mass = m, inertia = [i1, i2, i3, p, 0.1, -0.2], at = [x, 0, 0],
                rotation = euler_zyx(a, b, 0) * [[1, 0, 0], [0, cos(c), -sin(c)], [0, sin(c), cos(c)]]),
           potential = k * (x^2) / 2)]
         struct S { m: f64, i1: f64, i2: f64, i3: f64, p: f64, k: f64 }",
    );
}

/// A rotation driven in time (rheonomic): T1 and T0 terms from the spin.
#[test]
fn body_on_a_turntable() {
    check_model(
        "#[lagrange(coordinates(r, theta),
           body(disk, mass = m, inertia = [a, a, c], at = [r*cos(w*t), r*sin(w*t), 0],
                rotation = rot_z(w*t) * rot_x(theta)),
           potential = k * (r^2) / 2)]
         struct S { m: f64, a: f64, c: f64, w: f64, k: f64 }",
    );
}
