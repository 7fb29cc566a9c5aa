//! Constraint terms, reduced forms and the Coriolis matrix checked numerically on
//! the symbolic model: Jacobians and γ against finite differences, the reduced
//! (Maggi / Gibbs–Appell) equations against the multiplier form solved as a
//! saddle-point system, C8's closed form, and Ṁ − 2C skew-symmetric.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

mod common;
use common::{Lcg, Point, close, eval, model, random_point};
use lagrange_codegen::mechanics::Model;
use nalgebra::{DMatrix, DVector};

fn shifted(p: &Point, dq: &[f64], dv: &[f64], dt: f64) -> Point {
    Point {
        q: p.q.iter().zip(dq).map(|(a, b)| a + b).collect(),
        v: p.v.iter().zip(dv).map(|(a, b)| a + b).collect(),
        t: p.t + dt,
        params: p.params.clone(),
        u: p.u.clone(),
        quaternions: p.quaternions.clone(),
    }
}

/// G = ∂Φ/∂q, g = ∂Φ/∂t for holonomic rows, and γ = −d/dt(G q̇ + g) at q̈ = 0, by
/// central differences along the motion.
fn check_constraint_terms(src: &str) {
    let model = model(src);
    let c = model
        .constraints
        .multipliers
        .as_ref()
        .expect("multiplier form");
    let n = model.dof();
    let mut rng = Lcg(7);
    for _ in 0..10 {
        let p = random_point(&model, &mut rng);
        let zeros = vec![0.0; n];
        for row in 0..c.holonomic {
            for j in 0..n {
                let h = 1e-6;
                let mut dq = zeros.clone();
                dq[j] = h;
                let plus = eval(&model, c.phi[row], &shifted(&p, &dq, &zeros, 0.0));
                dq[j] = -h;
                let minus = eval(&model, c.phi[row], &shifted(&p, &dq, &zeros, 0.0));
                let fd = (plus - minus) / (2.0 * h);
                let g = eval(&model, c.jacobian[row][j], &p);
                assert!(close(g, fd, 1e-7), "G[{row}][{j}]: {g} vs {fd}");
            }
        }
        // d/dt (G q̇ + g) with q̈ = 0: move q along q̇ and t along 1, keep q̇.
        let velocity_residual = |p: &Point, row: usize| {
            let mut s = eval(&model, c.velocity_term[row], p);
            for j in 0..n {
                s += eval(&model, c.jacobian[row][j], p) * p.v[j];
            }
            s
        };
        for row in 0..c.names.len() {
            let h = 1e-5;
            let dq: Vec<f64> = p.v.iter().map(|v| v * h).collect();
            let mdq: Vec<f64> = dq.iter().map(|x| -x).collect();
            let plus = velocity_residual(&shifted(&p, &dq, &zeros, h), row);
            let minus = velocity_residual(&shifted(&p, &mdq, &zeros, -h), row);
            let fd = -(plus - minus) / (2.0 * h);
            let gamma = eval(&model, c.gamma[row], &p);
            assert!(close(gamma, fd, 1e-6), "γ[{row}]: {gamma} vs {fd}");
        }
    }
}

#[test]
fn cartesian_pendulum_terms() {
    check_constraint_terms(
        "#[lagrange(coordinates(x, y, z), point(bob, mass = m, at = [x, y, z]),
           gravity = [0, 0, -g], holonomic(thread = (bob.x^2) + (bob.y^2) + (bob.z^2) - (l^2)))]
         struct S { m: f64, l: f64, g: f64 }",
    );
}

#[test]
fn rheonomic_and_nonholonomic_terms() {
    // A bead on a wire turning at rate w, and a knife edge: both kinds of rows, with t.
    // (The second point gives th inertia: a coordinate nothing moves with is an error.)
    check_constraint_terms(
        "#[lagrange(coordinates(x, y, th),
           point(p, mass = m, at = [x, y]),
           point(tip, mass = m, at = [x + cos(th), y + sin(th)]),
           holonomic(wire = y*cos(w*t) - x*sin(w*t) - d),
           nonholonomic(blade = -sin(th)*dot(x) + cos(th)*dot(y) + c*t*dot(th)))]
         struct S { m: f64, w: f64, d: f64, c: f64 }",
    );
}

/// The rolling sphere in the multiplier form (z kept, with z = a) and in the reduced
/// form (z eliminated): solving the saddle-point system of the first must give the
/// accelerations W u̇ + κ of the second, at random states that satisfy the
/// constraints.
#[test]
fn reduced_form_equals_multiplier_form() {
    let full = model(
        "#[lagrange(coordinates(x, y, z, psi, theta, phi),
           body(ball, mass = m, inertia = [j, j, j], at = [x, y, z], rotation = euler_zxz(psi, theta, phi)),
           gravity = [0, 0, -g],
           holonomic(height = ball.z - a),
           nonholonomic(roll_x = dot(ball.x) - a * ball.omega_y, roll_y = dot(ball.y) + a * ball.omega_x))]
         struct S { m: f64, j: f64, a: f64, g: f64 }",
    );
    let reduced = model(
        "#[lagrange(coordinates(x, y, psi, theta, phi),
           body(ball, mass = m, inertia = [j, j, j], at = [x, y, a], rotation = euler_zxz(psi, theta, phi)),
           gravity = [0, 0, -g],
           nonholonomic(roll_x = dot(ball.x) - a * ball.omega_y, roll_y = dot(ball.y) + a * ball.omega_x),
           formulation(reduced))]
         struct S { m: f64, j: f64, a: f64, g: f64 }",
    );
    let r = reduced.constraints.reduced.as_ref().expect("reduced form");
    assert_eq!(r.names, ["dot_psi", "dot_theta", "dot_phi"]);
    let mut rng = Lcg(99);
    for _ in 0..10 {
        let mut p = random_point(&reduced, &mut rng);
        let f = reduced_at(&reduced, &mut p);
        let v = p.v.clone();
        let ud = f.mass.clone().lu().solve(&f.force).expect("M* regular");
        let qdd = &f.w * ud + &f.kappa;
        // The same state in the full model: z = a, ż = 0. Parameters are in the
        // same order (m, j, a, g).
        let a = p.params[2];
        let fp = Point {
            q: vec![p.q[0], p.q[1], a, p.q[2], p.q[3], p.q[4]],
            v: vec![v[0], v[1], 0.0, v[2], v[3], v[4]],
            t: p.t,
            params: p.params.clone(),
            u: Vec::new(),
            quaternions: p.quaternions.clone(),
        };
        let sol = saddle_point(&full, &fp);
        let expected = [sol[0], sol[1], sol[3], sol[4], sol[5]];
        for i in 0..5 {
            assert!(
                close(qdd[i], expected[i], 1e-9),
                "q̈[{i}]: {} vs {}",
                qdd[i],
                expected[i]
            );
        }
        assert!(sol[2].abs() < 1e-12, "z̈ = {}", sol[2]);
    }
}

/// Solves [M −Gᵀ; G 0] [q̈; ν] = [Q − h; γ] densely.
fn saddle_point(model: &Model, p: &Point) -> Vec<f64> {
    let c = model
        .constraints
        .multipliers
        .as_ref()
        .expect("multiplier form");
    let n = model.dof();
    let k = c.names.len();
    let mut a = DMatrix::zeros(n + k, n + k);
    let mut b = DVector::zeros(n + k);
    for i in 0..n {
        for j in 0..n {
            a[(i, j)] = eval(model, model.motion.mass[i][j], p);
        }
        b[i] = eval(model, model.motion.rhs[i], p);
    }
    for r in 0..k {
        for j in 0..n {
            let g = eval(model, c.jacobian[r][j], p);
            a[(n + r, j)] = g;
            a[(j, n + r)] = -g;
        }
        b[n + r] = eval(model, c.gamma[r], p);
    }
    let x = a.lu().solve(&b).expect("regular saddle point");
    x.iter().take(n).copied().collect()
}

/// C8 (seed 003, Pars 13.1): a particle in the plane in polar coordinates with the
/// quasi-velocity w = x ẏ − y ẋ = r² θ̇. The reduced equations must be
/// m (r̈ − w²/r³) = R and m ẇ = r S for forces R (radial) and S (transverse) (Pars
/// writes them per unit mass).
#[test]
fn quasi_velocity_gibbs_appell() {
    let m = model(
        "#[lagrange(coordinates(r, theta),
           point(p, mass = mass, at = [r*cos(theta), r*sin(theta)]),
           force(p, [fr*cos(theta) - fs*sin(theta), fr*sin(theta) + fs*cos(theta)]),
           speeds(rdot = dot(r), w = p.x*dot(p.y) - p.y*dot(p.x)))]
         struct S { mass: f64, fr: f64, fs: f64 }",
    );
    let mut rng = Lcg(3);
    for _ in 0..10 {
        let mut p = random_point(&m, &mut rng);
        p.q[0] = 0.5 + p.q[0].abs();
        let (mass, fr, fs) = (p.params[0], p.params[1], p.params[2]);
        let (radius, rdot, w) = (p.q[0], p.u[0], p.u[1]);
        let red = reduced_at(&m, &mut p);
        let (ms, f) = (&red.mass, &red.force);
        assert!(ms[(0, 1)].abs() < 1e-14 && ms[(1, 0)].abs() < 1e-14);
        let rdd = f[0] / ms[(0, 0)];
        let wd = f[1] / ms[(1, 1)];
        assert!(close(mass * (rdd - w * w / radius.powi(3)), fr, 1e-12));
        assert!(
            close(mass * wd, radius * fs, 1e-12),
            "{wd} vs {}",
            radius * fs
        );
        // The kinematics: θ̇ = w / r².
        assert!(close(p.v[1], w / (radius * radius), 1e-14));
        assert!(close(p.v[0], rdot, 1e-14));
    }
}

/// The reduced form at p with the speeds p.u, as the runtime computes it from
/// the emitted rows: q̇ = A⁻¹((u, 0) − b) (stored in p.v), W = A⁻¹[I; 0],
/// κ = A⁻¹ c, M* = Wᵀ M W, F* = Wᵀ (Q − h − M κ).
struct NumericReduced {
    w: DMatrix<f64>,
    kappa: DVector<f64>,
    mass: DMatrix<f64>,
    force: DVector<f64>,
}

fn reduced_at(m: &Model, p: &mut Point) -> NumericReduced {
    let r = m.constraints.reduced.as_ref().expect("reduced form");
    let (n, k) = (m.dof(), r.names.len());
    let a = DMatrix::from_fn(n, n, |i, j| eval(m, r.matrix[i][j], p));
    let b = DVector::from_fn(n, |i, _| eval(m, r.free[i], p));
    let inv = a.try_inverse().expect("regular rows");
    let target = DVector::from_fn(n, |i, _| if i < k { p.u[i] } else { 0.0 }) - b;
    p.v = (&inv * target).iter().copied().collect();
    let c = DVector::from_fn(n, |i, _| eval(m, r.rates[i], p));
    let mm = DMatrix::from_fn(n, n, |i, j| eval(m, m.motion.mass[i][j], p));
    let rhs = DVector::from_fn(n, |i, _| eval(m, m.motion.rhs[i], p));
    let w = inv.columns(0, k).into_owned();
    let kappa = &inv * c;
    NumericReduced {
        mass: w.transpose() * &mm * &w,
        force: w.transpose() * (rhs - &mm * &kappa),
        w,
        kappa,
    }
}

/// Ṁ − 2C is skew-symmetric and C q̇ is h (scleronomic).
#[test]
fn coriolis_matrix_properties() {
    let m = model(
        "#[lagrange(coordinates(a, b),
           point(p1, mass = m1, at = [l1*sin(a), -l1*cos(a)]),
           point(p2, mass = m2, at = [l1*sin(a) + l2*sin(b), -l1*cos(a) - l2*cos(b)]),
           gravity = [0, -g], emit(coriolis))]
         struct S { m1: f64, m2: f64, l1: f64, l2: f64, g: f64 }",
    );
    let c = &m
        .outputs
        .coriolis
        .as_ref()
        .expect("coriolis asked for")
        .matrix;
    let mut rng = Lcg(5);
    for _ in 0..10 {
        let p = random_point(&m, &mut rng);
        let n = 2;
        let h = 1e-6;
        let mdot = |i: usize, j: usize| {
            let dq: Vec<f64> = p.v.iter().map(|v| v * h).collect();
            let mdq: Vec<f64> = dq.iter().map(|x| -x).collect();
            let z = vec![0.0; n];
            (eval(&m, m.motion.mass[i][j], &shifted(&p, &dq, &z, 0.0))
                - eval(&m, m.motion.mass[i][j], &shifted(&p, &mdq, &z, 0.0)))
                / (2.0 * h)
        };
        for i in 0..n {
            for j in 0..n {
                let s_ij = mdot(i, j) - 2.0 * eval(&m, c[i][j], &p);
                let s_ji = mdot(j, i) - 2.0 * eval(&m, c[j][i], &p);
                assert!((s_ij + s_ji).abs() < 1e-7, "({i},{j}): {s_ij} vs {s_ji}");
            }
            let cq: f64 = (0..n).map(|j| eval(&m, c[i][j], &p) * p.v[j]).sum();
            assert!(close(cq, eval(&m, m.motion.bias[i], &p), 1e-12));
        }
    }
}

/// Gibbs–Appell against the projection: the Gibbs function S = ½ Σ m |ξ̈|², with
/// q̈ = W u̇ + κ, must give M* = ∂²S/∂u̇² = Σ m (J W)ᵀ (J W) and
/// F* = Wᵀ Q − ∂S/∂u̇ at u̇ = 0, where ξ̈ = J q̈ + ξ̈₀ is taken from the particles'
/// positions differentiated twice in time. Two derivations share nothing but W
/// and κ.
fn check_gibbs_appell(src: &str) {
    let mut m = model(src);
    assert!(
        !m.masses.has_spin,
        "the Gibbs function here covers particles only"
    );
    let n = m.dof();
    let qdd = m.ctx.accelerations();
    let zero = m.ctx.zero();
    let at_rest: Vec<_> = qdd.iter().map(|&a| (a, zero)).collect();
    // Per particle component: (mass, J row, ξ̈ at q̈ = 0).
    let mut components = Vec::new();
    for (mass, position) in m.masses.particles.clone() {
        for x in position {
            let v = m.ctx.time_derivative(x);
            let a = m.ctx.time_derivative(v);
            let row: Vec<_> = qdd.iter().map(|&d| m.ctx.diff(a, d)).collect();
            let a0 = m.ctx.substitute(a, &at_rest);
            components.push((mass, row, a0));
        }
    }
    let mut rng = Lcg(11);
    for _ in 0..10 {
        let mut p = random_point(&m, &mut rng);
        p.q[0] = 0.5 + p.q[0].abs();
        let red = reduced_at(&m, &mut p);
        let k = red.w.ncols();
        let mut hess = DMatrix::zeros(k, k);
        let mut grad = DVector::zeros(k);
        for (mass, row, a0) in &components {
            let mass = eval(&m, *mass, &p);
            let j = DMatrix::from_fn(1, n, |_, i| eval(&m, row[i], &p));
            let jw = &j * &red.w;
            let a = (&j * &red.kappa)[0] + eval(&m, *a0, &p);
            hess += mass * jw.transpose() * &jw;
            grad += mass * a * jw.transpose().column(0);
        }
        let q = DVector::from_fn(n, |i, _| eval(&m, m.motion.forces[i], &p));
        let wq = red.w.transpose() * q;
        for a in 0..k {
            for b in 0..k {
                let (x, y) = (hess[(a, b)], red.mass[(a, b)]);
                assert!(close(x, y, 1e-10), "M*[{a}][{b}]: {x} vs {y}");
            }
            let (x, y) = (wq[a] - grad[a], red.force[a]);
            assert!(close(x, y, 1e-10), "F*[{a}]: {x} vs {y}");
        }
    }
}

#[test]
fn gibbs_appell_quasi_velocity() {
    check_gibbs_appell(
        "#[lagrange(coordinates(r, theta),
           point(p, mass = mass, at = [r*cos(theta), r*sin(theta)]),
           force(p, [fr*cos(theta) - fs*sin(theta), fr*sin(theta) + fs*cos(theta)]),
           potential = k * (r^2) / 2,
           speeds(rdot = dot(r), w = p.x*dot(p.y) - p.y*dot(p.x)))]
         struct S { mass: f64, fr: f64, fs: f64, k: f64 }",
    );
}

#[test]
fn gibbs_appell_knife_edge_dumbbell() {
    // Two particles on a rod, a knife edge at the first: the velocity of p1 has no
    // component across the rod. Speeds chosen by the macro.
    check_gibbs_appell(
        "#[lagrange(coordinates(x, y, th),
           point(p1, mass = m1, at = [x, y]),
           point(p2, mass = m2, at = [x + l*cos(th), y + l*sin(th)]),
           force(p2, [c*sin(t), 0]),
           gravity = [0, -g],
           nonholonomic(edge = -sin(th)*dot(p1.x) + cos(th)*dot(p1.y)),
           formulation(reduced))]
         struct S { m1: f64, m2: f64, l: f64, c: f64, g: f64 }",
    );
}
