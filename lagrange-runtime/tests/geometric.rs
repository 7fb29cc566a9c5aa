//! Long-run behaviour of the geometric integrators against RK4 at the same step.

mod common;

use common::{Pendulum, sv};
use lagrange_runtime::{Dop853, Error, Gauss, Lagrangian, Rk4, Simulation, StormerVerlet};
use nalgebra::{Matrix1, Matrix2, Vector1, Vector2};

#[test]
fn verlet_energy_stays_bounded_where_rk4_drifts() {
    // 10⁵ steps of h = 0.1 (some 4 000 periods) of a pendulum released at 2 rad.
    let sys = Pendulum::standard();
    let steps = 100_000;
    let h = 0.1;
    let span = 0.0..h * steps as f64;
    let verlet = Simulation::new(&sys)
        .integrator(StormerVerlet::step(h))
        .run(sv([2.0]), sv([0.0]), span.clone())
        .unwrap();
    let rk4 = Simulation::new(&sys)
        .integrator(Rk4::step(h))
        .run(sv([2.0]), sv([0.0]), span)
        .unwrap();
    let e0 = verlet.integrals()[0].abs();
    // Verlet: the worst error over the whole run, and over the first 1 % of it —
    // bounded means the two are the same size.
    let worst = |e: &[f64]| e.iter().map(|&x| (x - e[0]).abs() / e0).fold(0.0, f64::max);
    let v_all = worst(verlet.integrals());
    let v_early = worst(&verlet.integrals()[..steps / 100]);
    let rk4_end = (rk4.integrals()[steps] - rk4.integrals()[0]).abs() / e0;
    let rk4_early = worst(&rk4.integrals()[..steps / 100]);
    eprintln!(
        "pendulum, h = {h}, 1e5 steps: Verlet energy error {v_early:e} (first 1 %), {v_all:e} (all); \
         RK4 {rk4_early:e} (first 1 %), {rk4_end:e} (end)"
    );
    assert!(
        v_all < 2.0 * v_early,
        "Verlet drifts: {v_early:e} -> {v_all:e}"
    );
    assert!(
        rk4_end > 20.0 * rk4_early,
        "RK4 does not drift: {rk4_early:e} -> {rk4_end:e}"
    );
    assert!(rk4_end > v_all, "RK4 {rk4_end:e} vs Verlet {v_all:e}");
}

/// A pendulum written by hand with ∂T/∂q (zero: M is constant), so that the
/// symplectic Gauss integrator can run it.
struct HamiltonPendulum;

impl Lagrangian<f64, 1> for HamiltonPendulum {
    const COORDINATES: [&'static str; 1] = ["theta"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _q: &Vector1<f64>, _t: f64) -> Matrix1<f64> {
        Matrix1::new(1.0)
    }
    fn bias(&self, _q: &Vector1<f64>, _v: &Vector1<f64>, _t: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<f64>, _v: &Vector1<f64>, _t: f64) -> Vector1<f64> {
        Vector1::new(-9.81 * q[0].sin())
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (Matrix1<f64>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _q: &Vector1<f64>, v: &Vector1<f64>, _t: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _t: f64) -> f64 {
        -9.81 * q[0].cos()
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
    fn kinetic_gradient(
        &self,
        _q: &Vector1<f64>,
        _v: &Vector1<f64>,
        _t: f64,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
}

/// A unit mass in polar coordinates (r, φ) around an attracting centre,
/// V = −k/r: M = diag(1, r²) depends on the configuration, the case that velocity
/// Verlet cannot handle symplectically.
struct PolarKepler {
    k: f64,
}

impl Lagrangian<f64, 2> for PolarKepler {
    const COORDINATES: [&'static str; 2] = ["r", "phi"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, q: &Vector2<f64>, _t: f64) -> Matrix2<f64> {
        Matrix2::new(1.0, 0.0, 0.0, q[0] * q[0])
    }
    fn bias(&self, q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::new(-q[0] * v[1] * v[1], 2.0 * q[0] * v[0] * v[1])
    }
    fn generalized_forces(&self, q: &Vector2<f64>, _v: &Vector2<f64>, _t: f64) -> Vector2<f64> {
        Vector2::new(-self.k / (q[0] * q[0]), 0.0)
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>) {
        (
            self.mass_matrix(q, t),
            self.generalized_forces(q, v, t) - self.bias(q, v, t),
        )
    }
    fn kinetic_energy(&self, q: &Vector2<f64>, v: &Vector2<f64>, _t: f64) -> f64 {
        0.5 * (v[0] * v[0] + q[0] * q[0] * v[1] * v[1])
    }
    fn potential_energy(&self, q: &Vector2<f64>, _t: f64) -> f64 {
        -self.k / q[0]
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
    fn kinetic_gradient(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        _t: f64,
    ) -> Option<Vector2<f64>> {
        Some(Vector2::new(q[0] * v[1] * v[1], 0.0))
    }
}

/// Relative energy error: the largest over the first `early` points, and the
/// largest over the whole run.
fn energy_errors(e: &[f64], early: usize) -> (f64, f64) {
    let worst = |e: &[f64], e0: f64| e.iter().map(|&x| ((x - e0) / e0).abs()).fold(0.0, f64::max);
    (worst(&e[..early], e[0]), worst(e, e[0]))
}

#[test]
fn gauss_energy_bounded_for_configuration_dependent_mass() {
    // An orbit of eccentricity ≈ 0.44 (period ≈ 15), 10⁴ steps of h = 0.2.
    let sys = PolarKepler { k: 1.0 };
    let (h, steps) = (0.2, 10_000);
    let (q0, v0) = (sv([1.0, 0.0]), sv([0.0, 1.2]));
    let span = 0.0..h * steps as f64;
    let gauss = Simulation::new(&sys)
        .integrator(Gauss::step(h))
        .run(q0, v0, span.clone())
        .unwrap();
    let rk4 = Simulation::new(&sys)
        .integrator(Rk4::step(h))
        .run(q0, v0, span.clone())
        .unwrap();
    let (g_early, g_all) = energy_errors(gauss.integrals(), steps / 100);
    let (r_early, r_all) = energy_errors(rk4.integrals(), steps / 100);
    // Angular momentum p_φ = r² φ̇ is a linear invariant in (q, p): conserved to
    // round-off by any Runge–Kutta method applied in (q, p).
    let p_phi = |k: usize| {
        let (q, v) = (gauss.positions()[k], gauss.velocities()[k]);
        q[0] * q[0] * v[1]
    };
    let l_drift = (0..gauss.len())
        .map(|k| (p_phi(k) - 1.2).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "polar Kepler, h = {h}, {steps} steps: Gauss energy error {g_early:e} (first 1 %), \
         {g_all:e} (all), p_phi drift {l_drift:e}, {:?}; RK4 {r_early:e} -> {r_all:e}",
        gauss.stats()
    );
    assert!(
        g_all < 2.0 * g_early,
        "Gauss drifts: {g_early:e} -> {g_all:e}"
    );
    assert!(
        r_all > 20.0 * r_early,
        "RK4 does not drift: {r_early:e} -> {r_all:e}"
    );
    assert!(r_all > 10.0 * g_all);
    assert!(l_drift < 1e-12, "{l_drift:e}");
    let s = gauss.stats();
    assert_eq!((s.jacobians, s.factorizations), (steps, steps));
}

#[test]
fn gauss_energy_bounded_on_the_pendulum() {
    let (h, steps) = (0.1, 10_000);
    let run = |m: Gauss| {
        Simulation::new(&HamiltonPendulum)
            .integrator(m)
            .run(sv([2.0]), sv([0.0]), 0.0..h * steps as f64)
            .unwrap()
    };
    for (name, tr) in [
        ("Gauss 2", run(Gauss::step(h))),
        ("midpoint", run(Gauss::midpoint(h))),
    ] {
        let (early, all) = energy_errors(tr.integrals(), steps / 100);
        eprintln!("pendulum {name}, h = {h}: energy error {early:e} (first 1 %), {all:e} (all)");
        assert!(all < 2.0 * early, "{name} drifts: {early:e} -> {all:e}");
    }
}

#[test]
fn gauss_orders() {
    // Final error at t = 6 on the polar Kepler orbit against a DOP853 reference.
    let sys = PolarKepler { k: 1.0 };
    let (q0, v0) = (sv([1.0, 0.0]), sv([0.0, 1.2]));
    let reference = Simulation::new(&sys)
        .integrator(Dop853::tol(1e-14))
        .run(q0, v0, 0.0..6.0)
        .unwrap()
        .final_state();
    let error = |m: Gauss| {
        let (q, v) = Simulation::new(&sys)
            .integrator(m)
            .run(q0, v0, 0.0..6.0)
            .unwrap()
            .final_state();
        (q - reference.0).amax().max((v - reference.1).amax())
    };
    let order4 = (error(Gauss::step(0.1)) / error(Gauss::step(0.05))).log2();
    let order2 = (error(Gauss::midpoint(0.02)) / error(Gauss::midpoint(0.01))).log2();
    eprintln!("Gauss observed orders: s = 2: {order4:.2}, midpoint: {order2:.2}");
    assert!((3.8..4.3).contains(&order4), "{order4}");
    assert!((1.9..2.1).contains(&order2), "{order2}");
}

#[test]
fn gauss_failures_are_typed() {
    // No ∂T/∂q: the common pendulum does not provide it.
    let e = Simulation::new(&Pendulum::standard())
        .integrator(Gauss::step(0.1))
        .run(sv([1.0]), sv([0.0]), 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(&e.error, Error::Settings(m)
            if m.to_string().contains("kinetic_gradient") && m.to_string().contains("emit(hamiltonian)")),
        "{e}"
    );
    // A step far too large for the nonlinearity with a small iteration budget.
    let e = Simulation::new(&HamiltonPendulum)
        .integrator(Gauss::step(5.0).max_iterations(4))
        .run(sv([3.0]), sv([5.0]), 0.0..10.0)
        .unwrap_err();
    assert!(
        matches!(e.error, Error::NewtonFailure { iterations: 4, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("did not converge"), "{e}");
}
