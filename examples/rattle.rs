//! RATTLE vs RK4 without drift control on the derived Cartesian spherical
//! pendulum (C1 with a multiplier), 10⁶ steps of h = 0.01: RATTLE keeps the
//! thread length to round-off and its energy error bounded; RK4 drifts.
//!
//!     cargo run --release --example rattle

mod catalog;

use catalog::constrained::CartesianSphericalPendulum;
use lagrange::Rattle;
use lagrange::prelude::*;

fn report(name: &str, tr: &Trajectory<f64, 3>) {
    let e = tr.integrals();
    let decile = e.len() / 10;
    let err = |r: std::ops::Range<usize>| {
        e[r].iter()
            .map(|x| (x - e[0]).abs() / e[0].abs())
            .fold(0.0, f64::max)
    };
    let [phi, vel] = tr.max_residuals();
    println!(
        "{name:<26} energy error: first 10% {:.2e}, last 10% {:.2e}; max |Phi| {phi:.1e}, \
         max |G v| {vel:.1e}; {:.2?}",
        err(0..decile),
        err(e.len() - decile..e.len()),
        tr.stats().wall_time
    );
}

fn main() -> Result<(), Error> {
    let sys = CartesianSphericalPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    // On the sphere, velocity tangent to it: a conical-ish swing.
    let (th, l) = (1.1f64, sys.l);
    let q0 = Vector3::new(l * th.sin(), 0.0, -l * th.cos());
    let v0 = Vector3::new(0.5 * th.cos(), 2.0, 0.5 * th.sin());
    let (h, steps) = (0.01, 1_000_000);
    let t_end = h * steps as f64;
    println!("Cartesian spherical pendulum, h = {h}, {steps} steps (t = {t_end} s)");
    let rattle = Rattle::step(h).integrate(&sys, 0.0, t_end, q0, v0)?;
    report("RATTLE", &rattle);
    let rk4 = Simulation::new(&sys)
        .integrator(Rk4::step(h))
        .run_constrained(q0, v0, 0.0..t_end);
    match rk4 {
        Ok(tr) => report("RK4, no drift control", &tr),
        Err(e) => println!("RK4, no drift control: {e}"),
    }
    Ok(())
}
