//! Catalog systems against closed forms and conserved quantities (issue 2):
//! the derive macro's equations, integrated by the runtime, reproduce what the
//! texts derive by hand.

use crate::catalog;

use catalog::*;
use lagrange::prelude::*;
use nalgebra::{Vector2, Vector3};

/// Large-amplitude pendulum: T = 4√(l/g) K(sin(θ0/2)), measured on the dense output
/// from the zero crossings of θ, to 1e-9 relative up to θ0 = 179°.
#[test]
fn simple_pendulum_period_matches_elliptic_integral() {
    let sys = Pendulum::<f64> {
        m: 1.3,
        l: 0.8,
        g: 9.81,
    };
    for deg in [10.0f64, 90.0, 150.0, 179.0] {
        let th0 = deg.to_radians();
        let exact = 4.0 * (sys.l / sys.g).sqrt() * elliptic_k((th0 / 2.0).sin());
        // Near 180° the bob lingers by the unstable top, where errors grow fastest.
        let tol = if deg > 170.0 { 1e-14 } else { 1e-12 };
        let traj = Simulation::new(&sys)
            .integrator(Dopri5::tol(tol))
            .run([th0], [0.0], 0.0..3.2 * exact)
            .unwrap();
        let zeros = traj.crossings(|_, q, _| q[0]).unwrap();
        assert!(zeros.len() >= 6, "{deg}°: only {} crossings", zeros.len());
        // Consecutive zeros are half a period apart.
        let k = zeros.len() - 1;
        let measured = 2.0 * (zeros[k] - zeros[0]) / k as f64;
        let rel = (measured - exact).abs() / exact;
        assert!(
            rel < 1e-9,
            "{deg}°: period {measured} vs {exact} (rel {rel:.2e})"
        );
    }
}

/// The generic description in f32: same equations, single precision.
#[test]
fn simple_pendulum_in_f32() {
    let sys = Pendulum::<f32> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let th0 = 1.0f32;
    let exact = 4.0 * (1.0f64 / 9.81).sqrt() * elliptic_k((0.5f64).sin());
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-6))
        .run([th0], [0.0f32], 0.0f32..3.0 * exact as f32)
        .unwrap();
    let zeros = traj.crossings(|_, q, _| q[0]).unwrap();
    let k = zeros.len() - 1;
    let measured = 2.0 * f64::from(zeros[k] - zeros[0]) / k as f64;
    assert!(
        (measured - exact).abs() / exact < 1e-4,
        "f32 period {measured} vs {exact}"
    );
}

/// C1 in (θ, φ): energy and the vertical angular momentum p_φ = m l² sin²θ φ̇ are
/// conserved to 1e-9 relative over 100 swings at rtol 1e-12.
#[test]
fn spherical_pendulum_conserves_energy_and_vertical_momentum() {
    let sys = SphericalPendulum {
        m: 0.7,
        l: 1.2,
        g: 9.81,
    };
    let (q0, v0) = (Vector2::new(1.1, 0.0), Vector2::new(0.0, 1.3));
    let swing = 2.0 * std::f64::consts::PI * (sys.l / sys.g).sqrt();
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run(q0, v0, 0.0..100.0 * swing)
        .unwrap();
    assert!(
        traj.integral_drift() < 1e-9,
        "energy drift {:.2e}",
        traj.integral_drift()
    );
    let p = |q: &Vector2<f64>, v: &Vector2<f64>| sys.m * sys.l * sys.l * q[0].sin().powi(2) * v[1];
    let p0 = p(&q0, &v0);
    let worst = traj
        .positions()
        .iter()
        .zip(traj.velocities())
        .map(|(q, v)| ((p(q, v) - p0) / p0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-9, "p_phi drift {worst:.2e}");
}

/// At the pole of the (θ, φ) chart the mass matrix is singular: a typed error that
/// names the time, never a NaN. Released from rest at θ0 the bob swings through the
/// pole θ = 0 after a quarter period; RK4 with a step that divides the quarter
/// period lands on it.
#[test]
fn spherical_pendulum_through_the_pole_is_a_typed_error() {
    let sys = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    match Simulation::new(&sys).run([0.0, 0.3], [0.5, 0.0], 0.0..1.0) {
        Err(Failure {
            error: Error::SingularMassMatrix { t, .. },
            ..
        }) => assert_eq!(t, 0.0),
        other => panic!("expected SingularMassMatrix at t = 0, got {other:?}"),
    }
    let th0 = 0.3f64;
    let quarter = (sys.l / sys.g).sqrt() * elliptic_k((th0 / 2.0).sin());
    let result = Simulation::new(&sys)
        .integrator(Rk4::step(quarter / 200.0))
        .run([th0, 0.0], [0.0, 0.0], 0.0..2.0 * quarter);
    match result {
        Err(Failure {
            error: Error::SingularMassMatrix { t, .. },
            ..
        }) => {
            assert!(
                (t - quarter).abs() < 2.0 * quarter / 200.0,
                "reported at t = {t}, pole at {quarter}"
            )
        }
        other => panic!("expected SingularMassMatrix near t = {quarter}, got {other:?}"),
    }
}

/// C2, Suslov ex. 95: the particle stays on the growing ellipsoid by construction;
/// what the equations must get right is that the only force beyond gravity is
/// normal to the surface (an ideal constraint). Check: the tangential part of
/// m ξ̈ − m g vanishes along the motion, with ξ̈ differentiated from the dense output.
#[test]
fn growing_ellipsoid_constraint_force_is_normal() {
    let sys = GrowingEllipsoid {
        m: 1.0,
        a: 1.0,
        b: 0.8,
        c: 0.6,
        g: 9.81,
    };
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run([1.0, 0.3], [0.2, 1.0], 1.0..3.0)
        .unwrap();
    let xi = |q: &Vector2<f64>, t: f64| {
        Vector3::new(
            sys.a * t * q[0].sin() * q[1].cos(),
            sys.b * t * q[0].sin() * q[1].sin(),
            sys.c * t * q[0].cos(),
        )
    };
    // ξ̇ = J q̇ + ∂ξ/∂t, by differentiating ξ(q(t), t) along the dense output.
    let velocity = |t: f64| {
        let d = 1e-6;
        let (qp, _) = traj.state_at(t + d).unwrap();
        let (qm, _) = traj.state_at(t - d).unwrap();
        (xi(&qp, t + d) - xi(&qm, t - d)) / (2.0 * d)
    };
    let gravity = Vector3::new(0.0, 0.0, -sys.g);
    let mut worst: f64 = 0.0;
    for k in 1..40 {
        let t = 1.05 + k as f64 * 0.045;
        let d = 1e-4;
        let acc = (velocity(t + d) - velocity(t - d)) / (2.0 * d);
        let residual = sys.m * (acc - gravity);
        let (q, _) = traj.state_at(t).unwrap();
        // Tangent vectors ∂ξ/∂q1, ∂ξ/∂q2 at (q, t).
        let e = 1e-6;
        for i in 0..2 {
            let mut qp = q;
            let mut qm = q;
            qp[i] += e;
            qm[i] -= e;
            let tangent = (xi(&qp, t) - xi(&qm, t)).normalize();
            worst = worst.max(residual.dot(&tangent).abs() / (sys.m * sys.g));
        }
    }
    assert!(worst < 1e-5, "tangential residual {worst:.2e} of m g");
}

/// C3, Suslov ex. 96/100: the centre of mass falls freely, J sin²φ ψ̇ is conserved,
/// and with ψ̇0 = 0 the rod turns uniformly, φ = φ0 + φ̇0 t.
#[test]
fn dumbbell_closed_forms() {
    let sys = Dumbbell {
        m1: 1.0,
        m2: 3.0,
        l: 1.5,
        gx: 0.5,
        gy: -0.3,
        gz: -9.81,
    };
    let (a, b) = (sys.m2 * sys.l / 4.0, sys.m1 * sys.l / 4.0);
    let inertia = sys.m1 * a * a + sys.m2 * b * b;
    let q0 = [0.1, -0.2, 0.3, 0.8, 0.4];
    let v0 = [1.0, 0.5, 2.0, 1.1, 0.9];
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run(q0, v0, 0.0..2.0)
        .unwrap();
    let g = [sys.gx, sys.gy, sys.gz];
    for (t, (q, v)) in traj
        .times()
        .iter()
        .zip(traj.positions().iter().zip(traj.velocities()))
    {
        for k in 0..3 {
            let exact = q0[k] + v0[k] * t + g[k] * t * t / 2.0;
            assert!(
                (q[k] - exact).abs() < 1e-9,
                "centre of mass component {k} at t = {t}"
            );
        }
        let momentum = inertia * q[3].sin().powi(2) * v[4];
        let momentum0 = inertia * q0[3].sin().powi(2) * v0[4];
        assert!(
            (momentum - momentum0).abs() < 1e-10 * momentum0.abs(),
            "J sin²φ ψ̇ at t = {t}"
        );
    }
    assert!(traj.integral_drift() < 1e-10);

    // ψ̇0 = 0, φ0 = 0.3: uniform rotation in a vertical plane until φ nears π, where
    // this chart is singular (sin φ = 0).
    let (phi0, omega) = (0.3, 1.7);
    let t_end = (std::f64::consts::PI - 0.2 - phi0) / omega;
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run(
            [0.0, 0.0, 0.0, phi0, 0.0],
            [0.0, 0.0, 0.0, omega, 0.0],
            0.0..t_end,
        )
        .unwrap();
    for (t, q) in traj.times().iter().zip(traj.positions()) {
        assert!(
            (q[3] - (phi0 + omega * t)).abs() < 1e-10,
            "φ at t = {t}: {}",
            q[3]
        );
    }
}

/// C7, Suslov ex. 101: the trajectory y + B = ±(2A/g)√(h − g z − A²), with h the
/// energy constant (T − U, U = −g z, unit mass) and A = ẏ/√2 from the first integral
/// of Jacobi's equation.
#[test]
fn heavy_particle_follows_jacobis_trajectory() {
    let sys = HeavyParticle { m: 1.0, g: 9.81 };
    let (q0, v0) = ([0.4, 1.0], [1.5, 4.0]);
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run(q0, v0, 0.0..1.5)
        .unwrap();
    let g = sys.g;
    let h = 0.5 * (v0[0] * v0[0] + v0[1] * v0[1]) + g * q0[1];
    let a = v0[0] / 2f64.sqrt();
    let root = |z: f64| (h - g * z - a * a).max(0.0).sqrt();
    // One constant B for both branches: y + B = −sgn(ż)(2A/g)√(h − g z − A²), the
    // text's ± being the sign of the descent.
    let b = -q0[0] - v0[1].signum() * (2.0 * a / g) * root(q0[1]);
    let mut worst: f64 = 0.0;
    for (q, v) in traj.positions().iter().zip(traj.velocities()) {
        let rhs = -v[1].signum() * (2.0 * a / g) * root(q[1]);
        worst = worst.max((q[0] + b - rhs).abs());
    }
    assert!(worst < 1e-7, "trajectory residual {worst:.2e}");
    // The motion passes the apex, so both branches were checked.
    assert!(
        traj.velocities().first().unwrap()[1] > 0.0 && traj.velocities().last().unwrap()[1] < 0.0
    );
}

/// The double pendulum is chaotic, but its energy is a sharp accuracy check.
#[test]
fn double_pendulum_conserves_energy() {
    let sys = DoublePendulum {
        m1: 1.0,
        m2: 1.5,
        l1: 1.0,
        l2: 0.7,
        g: 9.81,
    };
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run([2.0, 2.6], [0.0, 0.5], 0.0..20.0)
        .unwrap();
    assert!(
        traj.integral_drift() < 1e-9,
        "drift {:.2e}",
        traj.integral_drift()
    );
}

/// Generated equations equal the textbook double pendulum at random states.
#[test]
fn double_pendulum_matches_hand_derivation() {
    let (m1, m2, l1, l2, g) = (1.0, 1.5, 1.0, 0.7, 9.81);
    let sys = DoublePendulum { m1, m2, l1, l2, g };
    for k in 0..25 {
        let x = k as f64;
        let q = Vector2::new((1.3 * x).sin() * 3.0, (0.7 * x + 1.0).cos() * 3.0);
        let v = Vector2::new((2.1 * x).cos() * 2.0, (0.3 * x).sin() * 4.0);
        let c12 = (q[0] - q[1]).cos();
        let s12 = (q[0] - q[1]).sin();
        let m = sys.mass_matrix(&q, 0.0);
        let expected = nalgebra::Matrix2::new(
            (m1 + m2) * l1 * l1,
            m2 * l1 * l2 * c12,
            m2 * l1 * l2 * c12,
            m2 * l2 * l2,
        );
        assert!((m - expected).norm() < 1e-12);
        let h = sys.bias(&q, &v, 0.0);
        let expected = Vector2::new(
            m2 * l1 * l2 * s12 * v[1] * v[1],
            -m2 * l1 * l2 * s12 * v[0] * v[0],
        );
        assert!(
            (h - expected).norm() < 1e-12,
            "h = {h}, expected {expected}"
        );
        let f = sys.generalized_forces(&q, &v, 0.0);
        let expected = Vector2::new(-(m1 + m2) * g * l1 * q[0].sin(), -m2 * g * l2 * q[1].sin());
        assert!((f - expected).norm() < 1e-12);
    }
}

/// The 5-link chain in relative angles conserves energy.
#[test]
fn five_link_chain_conserves_energy() {
    let sys = Chain5 {
        m: 1.0,
        l: 0.5,
        g: 9.81,
    };
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-11))
        .run([1.0, 0.2, -0.2, 0.3, 0.1], [0.0; 5], 0.0..5.0)
        .unwrap();
    assert!(
        traj.integral_drift() < 1e-8,
        "drift {:.2e}",
        traj.integral_drift()
    );
}

/// Dissipation, a generalized torque and a Cartesian force all enter Q with the
/// right sign: the power balance dE/dt = −c θ̇² + (a cos ωt) θ̇ + f l cos θ θ̇.
#[test]
fn driven_pendulum_power_balance() {
    let sys = DrivenPendulum {
        m: 1.0,
        l: 0.9,
        g: 9.81,
        c: 0.3,
        a: 1.2,
        w: 2.0,
        f: 0.5,
    };
    let traj = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-12))
        .run([0.5], [0.0], 0.0..5.0)
        .unwrap();
    let energy = |t: f64| {
        let (q, v) = traj.state_at(t).unwrap();
        sys.integral(&q, &v, t)
    };
    for k in 1..20 {
        let t = k as f64 * 0.25;
        let d = 1e-4;
        let de = (energy(t + d) - energy(t - d)) / (2.0 * d);
        let (q, v) = traj.state_at(t).unwrap();
        let power = -sys.c * v[0] * v[0]
            + sys.a * (sys.w * t).cos() * v[0]
            + sys.f * sys.l * q[0].cos() * v[0];
        assert!(
            (de - power).abs() < 1e-6,
            "t = {t}: dE/dt = {de}, power = {power}"
        );
    }
}

/// The derived equations are documented: the text the rustdoc shows is available.
#[test]
fn equations_are_documented() {
    let text = SphericalPendulum::EQUATIONS;
    assert!(text.contains("M[1][1] = m*l^2*sin(theta)^2"), "{text}");
    assert!(text.contains("T + V"));
    assert!(GrowingEllipsoid::EQUATIONS.contains("Jacobi integral"));
}

/// The LaTeX export: one `aligned` block with the same entries.
#[test]
fn equations_in_latex() {
    let text = SphericalPendulum::EQUATIONS_LATEX;
    assert!(text.starts_with("\\begin{aligned}\n") && text.ends_with("\\end{aligned}\n"));
    assert!(text.contains("M_{1, 1} &= "), "{text}");
    assert!(text.contains("\\sin"), "{text}");
    assert_eq!(
        text.lines().count() - 2,
        SphericalPendulum::EQUATIONS
            .lines()
            .skip_while(|l| !l.starts_with("Entries not listed"))
            .filter(|l| l.contains(" = "))
            .count(),
        "{text}"
    );
}
