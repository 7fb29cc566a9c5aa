//! RATTLE on a derived system: the catalog's Cartesian spherical pendulum (C1
//! with a multiplier). The long-run study is examples/rattle.rs; the runtime's
//! tests cover order, long runs against RK4 and the errors.

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::constrained::CartesianSphericalPendulum;
use lagrange::Rattle;
use lagrange::prelude::*;

#[test]
fn derived_spherical_pendulum_stays_on_the_sphere() {
    let sys = CartesianSphericalPendulum {
        m: 0.8,
        l: 1.3,
        g: 9.81,
    };
    let th = 1.1f64;
    let q0 = Vector3::new(sys.l * th.sin(), 0.0, -sys.l * th.cos());
    let v0 = Vector3::new(0.5 * th.cos(), 2.0, 0.5 * th.sin());
    let tr = Rattle::step(0.01)
        .integrate(&sys, 0.0, 100.0, q0, v0)
        .unwrap();
    let [phi, vel] = tr.max_residuals();
    assert!(phi < 1e-14 && vel < 1e-14, "{phi:e} {vel:e}");
    let e = tr.integrals();
    let half = e.len() / 2;
    let err = |s: &[f64]| {
        s.iter()
            .map(|x| (x - e[0]).abs() / e[0].abs())
            .fold(0.0, f64::max)
    };
    let (first, second) = (err(&e[..half]), err(&e[half..]));
    eprintln!("energy error: first half {first:.2e}, second half {second:.2e}");
    assert!(
        second < 1e-3 && second < 1.5 * first,
        "{first:e} -> {second:e}"
    );
}
