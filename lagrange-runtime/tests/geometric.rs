//! Long-run behaviour of the geometric integrators against RK4 at the same step.

mod common;

use common::{Pendulum, sv};
use lagrange_runtime::{Rk4, Simulation, StormerVerlet};

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
