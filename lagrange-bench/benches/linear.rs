//! Linearising the Whipple bicycle about upright rolling at 5 m/s: from the
//! emitted symbolic derivatives (`emit(jacobians)`) vs central differences of
//! the nonlinear multiplier-form dynamics, timed in the same run. The accuracy
//! of each against the benchmark's published matrices is printed first.

#[path = "../../examples/catalog/mod.rs"]
mod catalog;

use catalog::bicycle::{Bicycle, published};
use criterion::{Criterion, criterion_group, criterion_main};
use lagrange::linear::Linearizer;
use lagrange::nalgebra::{DMatrix, SVector};
use lagrange::{ConstrainedDynamics, Error};
use std::hint::black_box;

const SPEED: f64 = 5.0;
const COORDINATES: [&str; 7] = ["x", "y", "psi", "phi", "theta_r", "delta", "theta_f"];
const SPEEDS: [&str; 3] = ["phi", "theta_r", "delta"];

/// The lateral A (roll, steer and their rates) from the symbolic derivatives.
fn symbolic(b: &Bicycle) -> Result<DMatrix<f64>, Error> {
    Ok(b.lateral(SPEED)?.a().clone())
}

/// The same A by central differences with step `h`: perturb one lateral state,
/// complete the dependent pitch and velocities, solve the saddle-point system.
fn central_differences(b: &Bicycle, h: f64) -> Result<DMatrix<f64>, Error> {
    let lz = Linearizer::new().coordinates(&COORDINATES).speeds(&SPEEDS);
    let accel = |x: [f64; 4]| -> Result<[f64; 2], Error> {
        let (q0, v0) = b.upright(SPEED);
        let (mut q, mut v) = (SVector::<f64, 8>::from(q0), SVector::<f64, 8>::from(v0));
        (q[3], q[6], v[3], v[6]) = (x[0], x[1], x[2], x[3]);
        let (q, v) = lz.complete_state(b, q, v, 0.0)?;
        let a = ConstrainedDynamics::<_, f64, 5>::new(b)
            .solve(0.0, &q, &v)?
            .accelerations;
        Ok([a[3], a[6]])
    };
    let mut a = DMatrix::zeros(4, 4);
    a[(0, 2)] = 1.0;
    a[(1, 3)] = 1.0;
    for j in 0..4 {
        let (mut xp, mut xm) = ([0.0; 4], [0.0; 4]);
        xp[j] = h;
        xm[j] = -h;
        let (fp, fm) = (accel(xp)?, accel(xm)?);
        for i in 0..2 {
            a[(2 + i, j)] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    Ok(a)
}

/// A from the published M, C1, K0, K2 (steer sign flipped to these axes).
fn published_a(b: &Bicycle) -> DMatrix<f64> {
    let s = [1.0, -1.0];
    let m = |x: [[f64; 2]; 2]| DMatrix::from_fn(2, 2, |i, j| s[i] * s[j] * x[i][j]);
    let minv = m(published::M)
        .try_inverse()
        .expect("published M is regular");
    let k = m(published::K0) * b.g + m(published::K2) * (SPEED * SPEED);
    let c = m(published::C1) * SPEED;
    let mut a = DMatrix::zeros(4, 4);
    a[(0, 2)] = 1.0;
    a[(1, 3)] = 1.0;
    a.view_mut((2, 0), (2, 2)).copy_from(&(-(&minv * k)));
    a.view_mut((2, 2), (2, 2)).copy_from(&(-(&minv * c)));
    a
}

fn bench(c: &mut Criterion) {
    let b = Bicycle::benchmark();
    let reference = published_a(&b);
    let error = |a: &DMatrix<f64>| (a - &reference).abs().max() / reference.abs().max();
    println!(
        "bicycle at {SPEED} m/s, max |A − A_published| / max |A_published|: symbolic {:.1e}",
        error(&symbolic(&b).unwrap())
    );
    for h in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7] {
        println!(
            "  central differences, h = {h:.0e}: {:.1e}",
            error(&central_differences(&b, h).unwrap())
        );
    }
    let mut g = c.benchmark_group("bicycle_linearise");
    g.bench_function("symbolic", |x| x.iter(|| symbolic(black_box(&b)).unwrap()));
    g.bench_function("central_differences", |x| {
        x.iter(|| central_differences(black_box(&b), 1e-5).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
