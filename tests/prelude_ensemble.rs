//! With the feature `parallel`, the prelude brings `Ensemble`.
#![cfg(feature = "parallel")]

use lagrange::prelude::*;

#[derive(Lagrangian)]
#[lagrange(coordinates(x), point(bob, mass = m, at = [x, 0]), potential = k / 2 * (x ^ 2))]
pub struct Spring {
    pub m: f64,
    pub k: f64,
}

#[test]
fn the_prelude_brings_ensemble() {
    let sys = Spring { m: 1.0, k: 4.0 };
    let amplitudes: Vec<f64> = (1..=8).map(f64::from).collect();
    let ends = Ensemble::new().progress(false).run(&amplitudes, |_, &a| {
        let traj = Simulation::new(&sys)
            .integrator(Dopri5::tol(1e-12))
            .run([a], [0.0], 0.0..1.0)
            .unwrap();
        traj.final_state().0[0]
    });
    for (a, x) in amplitudes.iter().zip(ends) {
        assert!((x - a * 2.0f64.cos()).abs() < 1e-9 * a, "{a}: {x}");
    }
}
