//! The Whipple bicycle benchmark (Meijaard, Papadopoulos, Ruina & Schwab 2007):
//! the self-stable speed range from the eigenvalues of the derived model.
//!
//!     cargo run --release --example bicycle

mod catalog;

use catalog::bicycle::{Bicycle, published};
use lagrange::linear::sweep;
use lagrange::prelude::*;

fn main() -> Result<(), Error> {
    let bike = Bicycle::benchmark();
    let lin = bike.lateral(5.0)?;
    println!("lateral states {:?}", lin.states());
    println!("eigenvalues at 5 m/s:");
    let mut eig = lin.eigenvalues();
    eig.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
    for l in &eig {
        println!("  {:+.10} {:+.10}i", l.re, l.im);
    }
    let speeds: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    let boundaries = sweep(&speeds, |v| bike.lateral(v))?.boundaries(1e-12, 1e-13)?;
    for b in &boundaries {
        let (name, reference) = if b.oscillatory {
            ("weave", published::WEAVE_SPEED)
        } else {
            ("capsize", published::CAPSIZE_SPEED)
        };
        println!(
            "{name} speed: {:.12} m/s (published {reference}, rel. difference {:.1e})",
            b.parameter,
            (b.parameter - reference).abs() / reference
        );
    }
    Ok(())
}
