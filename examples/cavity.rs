//! C10: a heavy point inside a spherical cavity. Prints every impact (time,
//! speed and normal velocity before and after), the switch to sliding once the
//! bounces die out, releases from the wall, and the energy at the end.
//!
//!     cargo run --release --example cavity [e]

mod catalog;

use catalog::cavity::{Cavity, Phase};
use lagrange::prelude::*;

fn main() -> Result<(), Error> {
    let e: f64 = std::env::args()
        .nth(1)
        .map_or(Ok(0.7), |s| s.parse())
        .map_err(|err| {
            Error::Settings(SettingsError::Data {
                owner: "restitution",
                problem: format!("{err}"),
            })
        })?;
    let cavity = Cavity::new(1.0, 9.81, 1.0, e);
    let (q0, v0) = (Vector3::new(0.3, 0.0, 0.2), Vector3::new(0.5, 2.0, 1.0));
    let energy = |q: &Vector3<f64>, v: &Vector3<f64>| cavity.particle.integral(q, v, 0.0);
    println!(
        "point in a sphere of radius {} m, restitution e = {e}, g = {} m/s²",
        cavity.r, cavity.particle.g
    );
    println!(
        "start q0 = {q0:?}, v0 = {v0:?}, energy {:.6} J\n",
        energy(&q0, &v0)
    );
    let started = std::time::Instant::now();
    let run = cavity.simulate(q0, v0, 0.0..8.0)?;
    let elapsed = started.elapsed();
    println!(
        "{:>4} {:>14} {:>11} {:>11} {:>12} {:>12}",
        "#", "t [s]", "|v| before", "|v| after", "v·n before", "v·n after"
    );
    for (k, i) in run.impacts.iter().enumerate() {
        let (before, after) = i.normal_speeds();
        println!(
            "{k:>4} {:>14.9} {:>11.6} {:>11.6} {before:>12.3e} {after:>12.3e}",
            i.t,
            i.v_before.norm(),
            i.v_after.norm()
        );
    }
    for &t in &run.slides {
        println!("sliding on the wall from t = {t:.9} s");
    }
    for &t in &run.releases {
        println!("released from the wall at t = {t:.9} s");
    }
    let (q, v) = run.final_state();
    let sliding = matches!(run.phases.last(), Some(Phase::Sliding(_)));
    println!(
        "\nend: t = 8 s, |x| = {:.15} m ({}), energy {:.6} J; {} phases, {} impacts, {:.1?}",
        q.norm(),
        if sliding { "sliding" } else { "free" },
        energy(&q, &v),
        run.phases.len(),
        run.impacts.len(),
        elapsed
    );
    Ok(())
}
