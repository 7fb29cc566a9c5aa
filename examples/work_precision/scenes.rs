//! The non-stiff scenes: the simple pendulum, Kepler, the spherical pendulum,
//! the double pendulum on two horizons, the rolling sphere and a tumbling
//! body (a quaternion: nq = 4, nv = 3).

use super::*;

/// The simple pendulum released from rest at 170°, measured at 10¼ exact periods.
///
/// Why not at 10 periods, where the exact state is simply the initial one: that
/// is a turning point (θ̇ = 0), where θ(t) is flat, so a phase error δt shows only
/// as ½ |θ̈| δt² — the error measure then squares every method's phase error
/// and flatters them (symplectic ones most, whose error is almost all phase).
/// A quarter period later the bob passes the bottom at full speed and the phase
/// error shows at first order. The closed form θ(t) = 2 asin(k sn(K − ω0 t | k²))
/// covers any t; at 10 periods it returns θ0 (checked below).
pub(crate) fn pendulum() -> Result<Scene, Error> {
    let title = "Simple pendulum, amplitude 170°, 10¼ periods";
    let started = header(title);
    let sys = Pendulum::<f64> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let theta0 = 170f64.to_radians();
    let period = pendulum_period(sys.l, sys.g, theta0);
    let t_end = 10.25 * period;
    let closure_check = (pendulum_angle(sys.l, sys.g, theta0, 10.0 * period) - theta0).abs();
    println!("  closed form at 10 periods: |θ − θ0| = {closure_check:.1e}");
    // Gauss needs ∂T/∂q, zero here (M = m l² is constant).
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run([theta0], [0.0], 0.0..t_end)
    })
    .exact(move |t| SVector::from([pendulum_angle(sys.l, sys.g, theta0, t)]))
    .sweep(rk4(0.1, 8))
    .sweep(dopri5(3, 12))
    .sweep(dop853(3, 13))
    .sweep(verlet(0.05, 8))
    .sweep(gauss(0.1, 7))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "pendulum",
        title: title.into(),
        study,
        notes: vec![format!(
            "θ0 = 170° from rest, l = 1, g = 9.81. Exact period T = 4K(sin(θ0/2))/ω0 = \
             {period:.12} s (K by the arithmetic–geometric mean); the error is |θ − θ_exact| \
             at t_end = 10¼ T = {t_end:.6} s, with θ_exact = 2 asin(k sn(K − ω0 t | k²)) \
             (sn by descending Landen; at 10 T it returns θ0 to {closure_check:.0e}). \
             Measuring at a whole number of periods would put t_end at a turning point, \
             where a phase error δt shows only as ½|θ̈|δt² and every method looks twice \
             its order. M = m l² is constant: Störmer–Verlet is symplectic here."
        )],
    })
}

/// The Kepler problem at e = 0.6 over 10 orbits; exact positions from Kepler's
/// equation. t_end is a pericentre passage, where the speed is largest, so the
/// phase error shows fully.
pub(crate) fn kepler() -> Result<Scene, Error> {
    let title = "Kepler problem, e = 0.6, 10 orbits";
    let started = header(title);
    let sys = Kepler { m: 1.0, k: 1.0 };
    let orbit = KeplerOrbit {
        a: 1.0,
        e: 0.6,
        mu: sys.k / sys.m,
    };
    let (q0, v0) = orbit.initial();
    let t_end = 10.0 * orbit.period();
    let study =
        WorkPrecision::new(|m: Method| Simulation::new(&sys).integrator(m).run(q0, v0, 0.0..t_end))
            .exact(move |t| SVector::from(orbit.position(t)))
            .sweep(rk4(0.05, 8))
            .sweep(dopri5(3, 12))
            .sweep(dop853(3, 13))
            .sweep(verlet(0.02, 8))
            .sweep(gauss(0.05, 7))
            .sweep(radau5(3, 10))
            .repeats(REPEATS, REPEAT_BUDGET)
            .on_row(progress)
            .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "kepler",
        title: title.into(),
        study,
        notes: vec![format!(
            "Cartesian (x, y), V = −k/r, m = k = 1, semi-major axis 1, e = 0.6, from \
             pericentre (r = 0.4, v = 2); t_end = 10 orbits = {t_end:.6}. Exact position: \
             E − e sin E = n t by Newton, x = a(cos E − e), y = a√(1−e²) sin E. Constant M: \
             Störmer–Verlet and Gauss are symplectic; the integral is the energy."
        )],
    })
}

/// C1, the spherical pendulum in (θ, φ): no closed form, DOP853 reference.
pub(crate) fn spherical() -> Result<Scene, Error> {
    let title = "Spherical pendulum (θ, φ), 20 s";
    let started = header(title);
    let sys = SphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run([1.0, 0.0], [0.0, 2.0], 0.0..20.0)
    })
    .sweep(rk4(0.05, 8))
    .sweep(dopri5(3, 12))
    .sweep(dop853(3, 13))
    .sweep(gauss(0.05, 7))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "spherical",
        title: title.into(),
        study,
        notes: vec![
            "m = l = 1, g = 9.81, θ0 = 1, θ̇0 = 0, φ̇0 = 2 (the bob stays away from the \
             poles, where this chart is singular). M(θ) is not constant, so Störmer–Verlet \
             would not be symplectic and is left out; Gauss runs in (q, p) with the \
             hand-written ∂T/∂q = m l² sin θ cos θ φ̇²."
                .into(),
        ],
    })
}

/// max_i |a_i(t) − b_i(t)| on a grid of `n` + 1 times over [0, t_end].
fn divergence(
    a: &Trajectory<f64, 2>,
    b: &Trajectory<f64, 2>,
    t_end: f64,
    n: usize,
) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|k| {
            let t = t_end * k as f64 / n as f64;
            let (qa, _) = a.state_at(t).expect("inside the span");
            let (qb, _) = b.state_at(t).expect("inside the span");
            (t, (qa - qb).amax())
        })
        .collect()
}

/// The double pendulum's predictability: two DOP853 runs at 1e-13 and 1e-14
/// start identical and separate like e^(λt) once their local errors differ.
/// Returns (λ, time at which they differ by 1e-2 rad, the printed table).
fn lyapunov(sys: &DoublePendulum, q0: [f64; 2], t_end: f64) -> Result<(f64, f64, String), Error> {
    let run = |tol| {
        Simulation::new(sys)
            .integrator(Dop853::tol(tol).max_steps(BUDGET))
            .run(q0, [0.0, 0.0], 0.0..t_end)
    };
    let d = divergence(&run(1e-13)?, &run(1e-14)?, t_end, 600);
    // Least squares ln d = c + λ t over the exponential phase: above the
    // round-off floor, below saturation.
    let fit: Vec<(f64, f64)> = d
        .iter()
        .filter(|(_, x)| (1e-11..1e-3).contains(x))
        .map(|&(t, x)| (t, x.ln()))
        .collect();
    let n = fit.len() as f64;
    let (st, sy) = fit.iter().fold((0.0, 0.0), |(a, b), (t, y)| (a + t, b + y));
    let (mt, my) = (st / n, sy / n);
    let (num, den) = fit.iter().fold((0.0, 0.0), |(a, b), (t, y)| {
        (a + (t - mt) * (y - my), b + (t - mt) * (t - mt))
    });
    let lambda = num / den;
    let horizon = d
        .iter()
        .find(|(_, x)| *x > 1e-2)
        .map_or(f64::INFINITY, |p| p.0);
    let mut table =
        String::from("| t | max_i \\|q_i(tol 1e-13) − q_i(tol 1e-14)\\| |\n|---|---|\n");
    for &(t, x) in d.iter().step_by(50) {
        table += &format!("| {t:.0} | {x:.1e} |\n");
    }
    Ok((lambda, horizon, table))
}

/// The double pendulum from rest at (2, 2) rad: chaotic. Two horizons.
pub(crate) fn double_pendulum() -> Result<Vec<Scene>, Error> {
    let sys = DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    };
    let q0 = [2.0, 2.0];
    let started = header("Double pendulum: predictability of the reference");
    let (lambda, horizon, table) = lyapunov(&sys, q0, 60.0)?;
    println!(
        "  λ ≈ {lambda:.2} /s (Lyapunov time {:.2} s); the 1e-13 and 1e-14 references differ by 1e-2 at t = {horizon:.1} s ({:.1} s)",
        1.0 / lambda,
        started.elapsed().as_secs_f64()
    );
    let mut scenes = Vec::new();
    for (slug, t_end) in [
        ("double-pendulum-short", 5.0),
        ("double-pendulum-long", 40.0),
    ] {
        let title = format!("Double pendulum from rest at (2, 2) rad, {t_end} s");
        let started = header(&title);
        let study = WorkPrecision::new(|m: Method| {
            Simulation::new(&sys)
                .integrator(m)
                .run(q0, [0.0, 0.0], 0.0..t_end)
        })
        .sweep(rk4(0.02, 8))
        .sweep(dopri5(3, 12))
        .sweep(dop853(3, 13))
        .sweep(gauss(0.02, 7))
        .sweep(radau5(3, 10))
        .repeats(REPEATS, REPEAT_BUDGET)
        .on_row(progress)
        .run()?;
        println!("  done in {:.1} s", started.elapsed().as_secs_f64());
        let mut notes = vec![format!(
            "m1 = m2 = l1 = l2 = 1, g = 9.81, from rest at θ1 = θ2 = 2 rad (energy well \
             above the chaotic threshold). Two DOP853 runs at 1e-13 and 1e-14 separate at \
             the largest Lyapunov exponent λ ≈ {lambda:.2} /s (Lyapunov time {:.2} s): they \
             differ by 1e-2 rad at t ≈ {horizon:.1} s. Beyond that no reference exists and a \
             method's 'error' only measures chaos; every method's trajectory is then one \
             of many equally valid shadows, and only statistics and conserved quantities \
             (the drift column) mean anything.",
            1.0 / lambda
        )];
        if slug.ends_with("long") {
            notes.push(format!(
                "Divergence of the two references (sampled every 5 s):\n\n{table}"
            ));
        }
        scenes.push(Scene {
            slug,
            title,
            study,
            notes,
        });
    }
    Ok(scenes)
}

/// The world-frame angular velocity of a body with Euler angles z-x-z
/// (ψ, θ, φ) and rates v.
fn omega_world(q: &[f64], v: &[f64]) -> [f64; 3] {
    let (psi, theta) = (q[0], q[1]);
    let (psid, thetad, phid) = (v[0], v[1], v[2]);
    [
        thetad * psi.cos() + phid * theta.sin() * psi.sin(),
        thetad * psi.sin() - phid * theta.sin() * psi.cos(),
        psid + phid * theta.cos(),
    ]
}

/// C5 reduced: the rolling sphere, nonholonomic, in independent speeds.
pub(crate) fn rolling_sphere() -> Result<Scene, Error> {
    let title = "Rolling sphere (C5, reduced form), 10 s";
    let started = header(title);
    let (m, a) = (2.0, 0.3);
    let sys = RollingSphereReduced {
        m,
        j: 0.4 * m * a * a,
        a,
        g: 9.81,
    };
    let (angles, rates) = ([0.2, 0.9, 0.1], [1.5, -0.7, 4.0]);
    let w = omega_world(&angles, &rates);
    let q0 = [0.0, 0.0, angles[0], angles[1], angles[2]];
    let v0 = [a * w[1], -a * w[0], rates[0], rates[1], rates[2]];
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run_reduced(q0, v0, 0.0..10.0)
    })
    .sweep(rk4(0.05, 8))
    .sweep(dopri5(3, 12))
    .sweep(dop853(3, 13))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: "rolling-sphere",
        title: title.into(),
        study,
        notes: vec![
            "RollingSphereReduced (m = 2, a = 0.3, J = 2/5 m a²) by `run_reduced`: Euler \
             angles (0.2, 0.9, 0.1), rates (1.5, −0.7, 4.0), rolling velocity consistent. The \
             error is over all five coordinates (x, y and the Euler angles). The reduced \
             nonholonomic equations have no Hamiltonian form, so the symplectic Gauss \
             method does not apply (it would stop with a typed error)."
                .into(),
        ],
    })
}

/// A free body flipping about its intermediate axis, its orientation a
/// quaternion: errors on the group (the angle between the rotations), the
/// drift of its energy, over 4 flips and over 200.
pub(crate) fn tumbling() -> Result<[Scene; 2], Error> {
    Ok([tumbling_over(4, 13)?, tumbling_over(200, 11)?])
}

/// The tumbling body over `flips` half-periods, adaptive tolerances down to
/// 10^-`tightest`.
fn tumbling_over(flips: u32, tightest: i32) -> Result<Scene, Error> {
    let title = format!("Tumbling body (quaternion), {flips} intermediate-axis flips");
    let started = header(&title);
    let (sys, omega) = (TumblingBody::PLATE, TumblingBody::SPIN);
    let half = flip_half_period([sys.i1, sys.i2, sys.i3], omega);
    let t_end = f64::from(flips) * half;
    let study = WorkPrecision::new(|m: Method| {
        Simulation::new(&sys)
            .integrator(m)
            .run([1.0, 0.0, 0.0, 0.0], omega, 0.0..t_end)
    })
    .orientations(TumblingBody::ORIENTATIONS)
    .sweep(rk4(0.2, 7))
    .sweep(dopri5(3, tightest - 1))
    .sweep(dop853(3, tightest))
    .sweep(verlet(0.2, 6))
    .sweep(gauss(0.4, 6))
    .sweep(radau5(3, 10))
    .repeats(REPEATS, REPEAT_BUDGET)
    .on_row(progress)
    .run()?;
    println!("  done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(Scene {
        slug: if flips == 4 {
            "tumbling"
        } else {
            "tumbling-long"
        },
        title,
        study,
        notes: vec![format!(
            "TumblingBody (principal moments 1, 2, 3) from the identity with ω = (0.3, 1, 0.3) \
             in body axes: the flip's half-period is {half:.9} s (Landau–Lifshitz §37, elliptic \
             K), t_end = {flips} half-periods. The configuration is a unit quaternion (nq = 4, nv = 3); \
             the error is the angle between the run's rotation and the reference's. Every \
             method steps the quaternion on the group; Gauss integrates Hamilton's form with \
             the quaternion as four coordinates and four momenta (symplectic, unit norm kept \
             exactly); Störmer–Verlet's first kick is implicit with orientations (order 2; on \
             Euler's equations the implicit midpoint rule, which keeps the kinetic energy)."
        )],
    })
}
