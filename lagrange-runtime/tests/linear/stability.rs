//! Eigen-analysis and stability boundaries on the published linear bicycle, and
//! LQR against closed forms (tests of the `linear` binary).

use crate::common::numeric::Lcg;
use lagrange_runtime::Error;
use lagrange_runtime::linear::{Linear, LinearError, Verdict, lqr, sweep};
use nalgebra::DMatrix;

// -------------------------------------------------------------------- bicycle

/// The Whipple bicycle benchmark (Meijaard et al. 2007): M q̈ + v C1 q̇ +
/// (g K0 + v² K2) q = 0 in q = (roll φ, steer δ).
fn bicycle(v: f64) -> Result<Linear, Error> {
    let m = DMatrix::from_row_slice(
        2,
        2,
        &[
            80.81722,
            2.31941332208709,
            2.31941332208709,
            0.29784188199686,
        ],
    );
    let c1 = DMatrix::from_row_slice(
        2,
        2,
        &[0.0, 33.86641391492494, -0.85035641456978, 1.68540397397560],
    );
    let k0 = DMatrix::from_row_slice(
        2,
        2,
        &[
            -80.95,
            -2.59951685249872,
            -2.59951685249872,
            -0.80329488458618,
        ],
    );
    let k2 = DMatrix::from_row_slice(2, 2, &[0.0, 76.59734589573222, 0.0, 2.65431523794604]);
    let g = 9.81;
    Linear::from_second_order(
        m,
        c1 * v,
        k0 * g + k2 * (v * v),
        DMatrix::zeros(2, 0),
        &["phi", "delta"],
        &[],
    )
}

#[test]
fn bicycle_weave_and_capsize_speeds() {
    let speeds: Vec<f64> = (0..=200).map(|i| 0.05 * i as f64).collect();
    let mut eigen = sweep(&speeds, bicycle).unwrap();
    let bounds = eigen.boundaries(1e-12, 1e-12).unwrap();
    let (weave, capsize) = (4.292_382_536_3, 6.024_262_015_4);
    for b in &bounds {
        eprintln!(
            "boundary at v = {:.12} m/s (bracket width {:e}), critical eigenvalue {}, \
             oscillatory {}, destabilising {}",
            b.parameter,
            b.bracket.1 - b.bracket.0,
            b.eigenvalue,
            b.oscillatory,
            b.destabilising
        );
    }
    assert_eq!(bounds.len(), 2);
    let rel = |x: f64, y: f64| (x - y).abs() / y;
    eprintln!(
        "weave rel error {:e}, capsize rel error {:e}",
        rel(bounds[0].parameter, weave),
        rel(bounds[1].parameter, capsize)
    );
    assert!(rel(bounds[0].parameter, weave) < 1e-8);
    assert!(rel(bounds[1].parameter, capsize) < 1e-8);
    assert!(
        bounds[0].oscillatory && !bounds[0].destabilising,
        "weave: a pair stabilises"
    );
    assert!(
        !bounds[1].oscillatory && bounds[1].destabilising,
        "capsize: a real root"
    );
    assert!((bounds[0].bracket.1 - bounds[0].bracket.0) <= 1e-12 * weave);
    // Stable in between, unstable outside.
    let verdict = |v: f64| bicycle(v).unwrap().stability(1e-12).unwrap().verdict;
    assert_eq!(verdict(5.0), Verdict::AsymptoticallyStable);
    assert_eq!(verdict(3.0), Verdict::Unstable);
    assert_eq!(verdict(7.0), Verdict::Unstable);
    // Inside the stable band every eigenvalue is in the left half-plane (the
    // boundary speeds above are the quantitative check).
    assert!(
        bicycle(5.0)
            .unwrap()
            .eigenvalues()
            .iter()
            .all(|z| z.re < 0.0)
    );
}

// ------------------------------------------------------------------------ LQR

#[test]
fn lqr_double_integrator_closed_form() {
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, 0.0]);
    let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    let design = lqr(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1)).unwrap();
    let s3 = 3f64.sqrt();
    let exact = DMatrix::from_row_slice(2, 2, &[s3, 1.0, 1.0, s3]);
    let err = (&design.riccati - &exact).amax();
    eprintln!(
        "double integrator: |P - P_exact| = {err:e}, residual {:e}, {} sign iterations, \
         {} Newton steps, K = {}",
        design.residual, design.iterations, design.newton_steps, design.gain
    );
    assert!(err < 1e-13);
    assert!((design.gain[(0, 0)] - 1.0).abs() < 1e-13 && (design.gain[(0, 1)] - s3).abs() < 1e-13);
    assert!(design.closed_loop.iter().all(|z| z.re < 0.0));
}

#[test]
fn lqr_random_stabilisable_system() {
    let mut rng = Lcg(101);
    let a = DMatrix::from_fn(4, 4, |_, _| rng.uniform(-2.0, 2.0));
    let b = DMatrix::from_fn(4, 2, |_, _| rng.uniform(-1.0, 1.0));
    let l = DMatrix::from_fn(4, 4, |_, _| rng.uniform(-1.0, 1.0));
    let q = &l * l.transpose() + DMatrix::identity(4, 4) * 0.1;
    let r = DMatrix::from_row_slice(2, 2, &[2.0, 0.3, 0.3, 1.0]);
    let open = Linear::new(
        a.clone(),
        b.clone(),
        &["a", "b", "c", "d"],
        &["u1", "u2"],
        0,
    )
    .unwrap();
    let design = open.lqr(&q, &r).unwrap();
    let p = &design.riccati;
    let s = &b * r.clone().try_inverse().unwrap() * b.transpose();
    let res = a.transpose() * p + p * &a - p * &s * p + &q;
    let rel = res.norm() / (q.norm() + 2.0 * (a.transpose() * p).norm() + (p * &s * p).norm());
    let open_max = open.stability(0.0).unwrap().max_real;
    let closed_max = design.closed_loop[0].re;
    eprintln!(
        "random 4-state LQR: relative residual {rel:e} (reported {:e}), open-loop max Re {open_max}, \
         closed-loop max Re {closed_max}, {} sign iterations, {} Newton steps",
        design.residual, design.iterations, design.newton_steps
    );
    assert!(rel <= 1e-10 && design.residual <= 1e-10);
    assert!(closed_max < 0.0);
    // P is symmetric positive definite.
    assert!((p - p.transpose()).amax() == 0.0);
    assert!(p.clone().symmetric_eigenvalues().min() > 0.0);
    // The closed loop of the gain is what it reports.
    let closed = &a - &b * &design.gain;
    let ev = Linear::new(closed, DMatrix::zeros(4, 0), &["a", "b", "c", "d"], &[], 0)
        .unwrap()
        .eigenvalues();
    assert!((ev[0] - design.closed_loop[0]).norm() < 1e-10);
}

#[test]
fn lqr_refuses_an_unstabilisable_pair() {
    // An unstable mode (eigenvalue 1) that the input cannot reach.
    let a = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, -1.0]);
    let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    let e = lqr(&a, &b, &DMatrix::identity(2, 2), &DMatrix::identity(1, 1)).unwrap_err();
    eprintln!("{e}");
    assert!(matches!(
        e,
        Error::Linear(LinearError::NotStabilisable { re, .. }) if (re - 1.0).abs() < 1e-12
    ));
}
