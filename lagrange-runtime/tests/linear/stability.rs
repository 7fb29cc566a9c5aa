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

// ------------------------------------------------------ growth on the axis

/// A model of ẋ = A x with states named s0, s1, ….
fn model(a: DMatrix<f64>) -> Linear {
    let n = a.nrows();
    let names: Vec<String> = (0..n).map(|i| format!("s{i}")).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    Linear::new(a, DMatrix::zeros(n, 0), &names, &[], n / 2).unwrap()
}

/// A chain of n integrators: s0' = s1, s1' = s2, …
fn chain(n: usize) -> DMatrix<f64> {
    DMatrix::from_fn(n, n, |i, j| if j == i + 1 { 1.0 } else { 0.0 })
}

/// Chains of integrators grow polynomially (the double integrator like t,
/// the triple like t²); an undamped oscillator, a cyclic coordinate with
/// damped velocity and the zero matrix are bounded.
#[test]
fn jordan_blocks_on_the_axis_are_polynomial_growth() {
    let verdict = |a: DMatrix<f64>| model(a).stability(1e-9).unwrap();
    let double = verdict(chain(2));
    assert_eq!(double.verdict, Verdict::PolynomialGrowth { degree: 1 });
    assert_eq!((double.growth, double.structural.len()), (1, 2));
    assert_eq!(double.without_structural, Verdict::Marginal);
    assert_eq!(
        verdict(chain(3)).verdict,
        Verdict::PolynomialGrowth { degree: 2 }
    );
    let w = 2.5;
    let oscillator = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, 0.0]);
    let bounded = verdict(oscillator.clone());
    assert_eq!((bounded.verdict, bounded.growth), (Verdict::Marginal, 0));
    // Two equal oscillators, one driving the other's position: resonance, t.
    let mut driven = DMatrix::zeros(4, 4);
    driven.view_mut((0, 0), (2, 2)).copy_from(&oscillator);
    driven.view_mut((2, 2), (2, 2)).copy_from(&oscillator);
    driven[(1, 2)] = 1.0;
    assert_eq!(
        verdict(driven).verdict,
        Verdict::PolynomialGrowth { degree: 1 }
    );
    // Two equal uncoupled oscillators: a double ±iω, semisimple.
    let mut twins = DMatrix::zeros(4, 4);
    twins.view_mut((0, 0), (2, 2)).copy_from(&oscillator);
    twins.view_mut((2, 2), (2, 2)).copy_from(&oscillator);
    assert_eq!(verdict(twins).verdict, Verdict::Marginal);
    let damped = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 0.0, -0.7]);
    let cyclic = verdict(damped);
    assert_eq!(cyclic.verdict, Verdict::Marginal);
    assert_eq!(cyclic.structural, ["s0"]);
    assert_eq!(cyclic.without_structural, Verdict::AsymptoticallyStable);
    assert_eq!(verdict(DMatrix::zeros(3, 3)).verdict, Verdict::Marginal);
    // A damped pendulum stays asymptotically stable; an inverted one unstable.
    let pendulum = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.3]);
    assert_eq!(verdict(pendulum).verdict, Verdict::AsymptoticallyStable);
    let inverted = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, 4.0, 0.0]);
    assert_eq!(verdict(inverted).verdict, Verdict::Unstable);
}

/// The open-loop hover of a quadrotor, its 12 states (x, y, z, φ, θ, ψ and
/// their rates): position ← velocity ← attitude ← rate, a chain of four
/// integrators, so a rate perturbation grows like t³ (once reported
/// Marginal, all 12 states structural).
#[test]
fn a_quadrotor_hover_grows_like_t_cubed() {
    let g = 9.81;
    let a = hover_matrix(g);
    let hover = model(a.clone()).stability(1e-9).unwrap();
    assert_eq!(hover.verdict, Verdict::PolynomialGrowth { degree: 3 });
    assert_eq!((hover.growth, hover.structural.len()), (3, 12));
    // The degree is the motion's: A is nilpotent (A⁴ = 0), so e^(At) is a
    // cubic in t, and a pitch-rate kick ω moves x by g ω t³ / 6.
    let a4 = &a * &a * &a * &a;
    assert_eq!(a4.amax(), 0.0);
    assert!((&a * &a * &a).amax() > 0.0);
    let (omega, t) = (1e-3, 2.0);
    let mut kick = nalgebra::DVector::zeros(12);
    kick[10] = omega;
    let (mut term, mut x) = (kick.clone(), kick);
    for k in 1..4 {
        term = &a * term * (t / k as f64);
        x += &term;
    }
    assert!((x[0] - g * omega * t.powi(3) / 6.0).abs() < 1e-15);
}

/// The 12-state linear model of a quadrotor at hover, states (x, y, z, φ,
/// θ, ψ, ẋ, ẏ, ż, φ̇, θ̇, ψ̇): ẍ = g θ, ÿ = −g φ, the rest inputs only.
fn hover_matrix(g: f64) -> DMatrix<f64> {
    let mut a = DMatrix::zeros(12, 12);
    for i in 0..6 {
        a[(i, i + 6)] = 1.0;
    }
    a[(6, 4)] = g;
    a[(7, 3)] = -g;
    a
}
