//! The Whipple bicycle (Meijaard, Papadopoulos, Ruina & Schwab 2007).

use crate::catalog;

use catalog::bicycle::{Bicycle, published};
use lagrange::linear::{Verdict, sweep};
use lagrange::nalgebra::{DMatrix, SMatrix};
use lagrange::prelude::*;

#[test]
fn upright_reference_is_consistent() {
    let b = Bicycle::benchmark();
    let (q, v) = b.upright(5.0);
    let (q, v) = (SVector::<f64, 8>::from(q), SVector::<f64, 8>::from(v));
    let phi = b.constraint_positions(&q, 0.0);
    let (g, g0) = b.constraint_jacobian(&q, 0.0);
    let vel = g * v + g0;
    assert!(phi.abs().max() < 1e-15, "{phi}");
    assert!(vel.abs().max() < 1e-14, "{vel}");
}

/// Roll rate 0.5 rad/s from upright; returns |φ| + |δ| over the last second.
fn roll_perturbation(speed: f64, seconds: f64) -> (f64, f64) {
    let b = Bicycle::benchmark();
    let (q, mut v) = b.upright(speed);
    v[3] = 0.5;
    let traj = Simulation::new(&b)
        .integrator(Dopri5::tol(1e-9))
        .drift(Drift::projection())
        .project_initial(true)
        .run_constrained(q, v, 0.0..seconds)
        .unwrap();
    let [phi_res, vel_res] = traj.max_residuals();
    assert!(phi_res < 1e-10 && vel_res < 1e-10, "{phi_res} {vel_res}");
    let amplitude = |from: f64, to: f64| {
        traj.times()
            .iter()
            .zip(traj.positions())
            .filter(|(t, _)| **t >= from && **t <= to)
            .map(|(_, q)| q[3].abs() + q[6].abs())
            .fold(0.0f64, f64::max)
    };
    (amplitude(0.0, 1.0), amplitude(seconds - 1.0, seconds))
}

#[test]
fn self_stable_at_5_unstable_at_3() {
    let (early, late) = roll_perturbation(5.0, 8.0);
    eprintln!("5 m/s: {early:.3e} -> {late:.3e}");
    assert!(late < 0.2 * early);
    let (early, late) = roll_perturbation(3.0, 4.0);
    eprintln!("3 m/s: {early:.3e} -> {late:.3e}");
    assert!(late > 2.0 * early);
}

/// Published matrices in our sign convention: the steer angle is positive to
/// the left here (to the right in the paper), which flips the off-diagonal
/// entries.
fn published_in_our_signs(m: [[f64; 2]; 2]) -> DMatrix<f64> {
    let s = [1.0, -1.0];
    DMatrix::from_fn(2, 2, |i, j| s[i] * s[j] * m[i][j])
}

/// The derived model's linearisation is the benchmark's: A = [[0, I],
/// [−M⁻¹K, −M⁻¹C]] with the published M, C = v C1, K = g K0 + v² K2, at three
/// speeds (the v and v² dependences are then both checked).
#[test]
fn lateral_dynamics_match_the_published_matrices() {
    let b = Bicycle::benchmark();
    let m = published_in_our_signs(published::M);
    let minv = m.clone().try_inverse().unwrap();
    for v in [1.0, 5.0, 8.0] {
        let lin = b.lateral(v).unwrap();
        assert_eq!(lin.states(), ["phi", "delta", "phi'", "delta'"]);
        let c = published_in_our_signs(published::C1) * v;
        let k = published_in_our_signs(published::K0) * b.g
            + published_in_our_signs(published::K2) * (v * v);
        let a = lin.a();
        let a21 = -(&minv * &k);
        let a22 = -(&minv * &c);
        let err21 = (a.view((2, 0), (2, 2)) - &a21).abs().max() / a21.abs().max();
        let err22 = (a.view((2, 2), (2, 2)) - &a22).abs().max() / a22.abs().max();
        eprintln!("v = {v}: A21 rel. error {err21:.1e}, A22 {err22:.1e}");
        // M11 is published to 7 significant digits, the rest to 15.
        assert!(err21 < 1e-7 && err22 < 1e-7, "{a}");
        // The projected second-order form is the paper's, term by term.
        let so = lin.second_order().expect("speeds are rates of coordinates");
        let rel = |x: &DMatrix<f64>, y: &DMatrix<f64>| (x - y).abs().max() / y.abs().max();
        let (em, ec, ek) = (
            rel(&so.mass, &m),
            rel(&so.damping, &c),
            rel(&so.stiffness, &k),
        );
        eprintln!("v = {v}: M {em:.1e}, C {ec:.1e}, K {ek:.1e}");
        assert!(em < 1e-7 && ec < 1e-7 && ek < 1e-7, "{so:?}");
    }
}

/// Weave and capsize speeds from the eigenvalues of the derived model: the
/// stability boundaries of a sweep over the forward speed, refined by Brent.
#[test]
fn weave_and_capsize_speeds_match_the_benchmark() {
    let b = Bicycle::benchmark();
    let speeds: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    let mut eigen = sweep(&speeds, |v| b.lateral(v)).unwrap();
    let found = eigen.boundaries(1e-12, 1e-13).unwrap();
    assert_eq!(found.len(), 2, "{found:?}");
    let (weave, capsize) = (found[0], found[1]);
    assert!(weave.oscillatory && !weave.destabilising);
    assert!(!capsize.oscillatory && capsize.destabilising);
    let rel = |x: f64, y: f64| (x - y).abs() / y;
    eprintln!(
        "weave {:.12} ({:.1e}), capsize {:.12} ({:.1e})",
        weave.parameter,
        rel(weave.parameter, published::WEAVE_SPEED),
        capsize.parameter,
        rel(capsize.parameter, published::CAPSIZE_SPEED)
    );
    assert!(rel(weave.parameter, published::WEAVE_SPEED) < 1e-8);
    assert!(rel(capsize.parameter, published::CAPSIZE_SPEED) < 1e-8);
    // Self-stable in between, unstable outside.
    let verdict = |v: f64| b.lateral(v).unwrap().stability(1e-12).unwrap().verdict;
    assert_eq!(verdict(5.0), Verdict::AsymptoticallyStable);
    assert_eq!(verdict(3.0), Verdict::Unstable);
    assert_eq!(verdict(7.0), Verdict::Unstable);
}

/// The independent speeds that fix the forward speed, and the rolling
/// constraints' dependence on roll and steer (which makes the dependent
/// velocities vary with the coordinates about a steady motion), checked against
/// central differences of the nonlinear multiplier-form dynamics: perturb one
/// lateral state, complete the dependent pitch (Newton) and velocities (the
/// constraints), solve the saddle-point system.
#[test]
fn lateral_dynamics_match_central_differences() {
    let b = Bicycle::benchmark();
    let speed = 4.0;
    let lin = b.lateral(speed).unwrap();
    let accel = |x: [f64; 4]| -> [f64; 2] {
        let (q0, v0) = b.upright(speed);
        let (mut q, mut v) = (SVector::<f64, 8>::from(q0), SVector::<f64, 8>::from(v0));
        q[3] = x[0];
        q[6] = x[1];
        v[3] = x[2];
        v[6] = x[3];
        let (q, v) = lagrange::linear::Linearizer::new()
            .coordinates(&["x", "y", "psi", "phi", "theta_r", "delta", "theta_f"])
            .speeds(&["phi", "theta_r", "delta"])
            .complete_state(&b, q, v, 0.0)
            .unwrap();
        let a = ConstrainedDynamics::<_, f64, 5>::new(&b)
            .solve(0.0, &q, &v)
            .unwrap()
            .accelerations;
        [a[3], a[6]]
    };
    let h = 1e-5;
    let mut fd = SMatrix::<f64, 2, 4>::zeros();
    for j in 0..4 {
        let (mut xp, mut xm) = ([0.0; 4], [0.0; 4]);
        xp[j] = h;
        xm[j] = -h;
        let (fp, fm) = (accel(xp), accel(xm));
        for i in 0..2 {
            fd[(i, j)] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    let sym = lin.a().view((2, 0), (2, 4)).into_owned();
    let err = (0..2)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| (sym[(i, j)] - fd[(i, j)]).abs())
        .fold(0.0f64, f64::max)
        / sym.abs().max();
    eprintln!("symbolic vs central differences: {err:.1e}");
    assert!(err < 1e-7, "{sym} vs {fd}");
}

/// The reduced form (roll, rear wheel and steer rates) against the multiplier
/// form: accelerations upright, straight ahead at heading 0 (where a symbolic
/// solve of the rolling rows gave 0/0), at headings π/2 and π, leaning and
/// steered; then the roll-rate kick of `self_stable_at_5_unstable_at_3` run in
/// both forms.
#[test]
fn reduced_form_agrees_with_the_multiplier_form() {
    let b = Bicycle::benchmark();
    let reduced = ReducedDynamics::<_, f64, 3>::new(&b);
    let multipliers = ConstrainedDynamics::<_, f64, 5>::new(&b);
    let mut worst: f64 = 0.0;
    for (psi, phi, delta) in [
        (0.0, 0.0, 0.0),
        (std::f64::consts::FRAC_PI_2, 0.0, 0.0),
        (std::f64::consts::PI, 0.1, 0.0),
    ] {
        let (mut q, mut v) = b.upright(4.0);
        (q[2], q[3], q[6], v[3], v[6]) = (psi, phi, delta, 0.3, -0.2);
        let (q, v) = (SVector::<f64, 8>::from(q), SVector::<f64, 8>::from(v));
        let v = reduced.consistent_velocities(0.0, &q, &v).unwrap();
        let (_, a) = reduced.solve(0.0, &q, &v).unwrap();
        let m = multipliers.solve(0.0, &q, &v).unwrap().accelerations;
        worst = worst.max((a - m).amax() / m.amax());
    }
    eprintln!("bicycle, reduced vs multiplier accelerations: {worst:.1e}");
    assert!(worst < 1e-11, "{worst:e}");

    let (q, mut v) = b.upright(5.0);
    v[3] = 0.5;
    let sim = Simulation::new(&b).integrator(Dopri5::tol(1e-10));
    let r = sim.run_reduced(q, v, 0.0..2.0).unwrap();
    let c = sim
        .drift(Drift::projection())
        .project_initial(true)
        .run_constrained(q, v, 0.0..2.0)
        .unwrap();
    let gap = (r.final_state().0 - c.final_state().0).amax();
    eprintln!("bicycle, 2 s roll kick, reduced vs multiplier: {gap:.1e}");
    assert!(gap < 1e-7, "{gap:e}");
}

/// The whole linearised bicycle, no states selected: the zeros of the
/// position, heading, wheel angles and forward speed are structural, so they
/// are exact and the verdict without them is the lateral one (stable at 5 m/s,
/// weave-unstable at 3 m/s), naming the states it left out; with them the
/// position drifts polynomially.
#[test]
fn unselected_bicycle_verdict_ignores_its_structural_zeros() {
    let b = Bicycle::benchmark();
    let full = |v: f64| {
        let (q, qd) = b.upright(v);
        let op = OperatingPoint::new(SVector::from(q), SVector::from(qd));
        Linearizer::new().constrained(&b, &op).unwrap()
    };
    let fast = full(5.0);
    let naive = fast.a().complex_eigenvalues();
    let naive_max = naive.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max);
    eprintln!("whole-matrix eigen-solver: max Re = {naive_max:e}");
    let stab = fast.stability(1e-12).unwrap();
    assert_eq!(
        stab.without_structural,
        Verdict::AsymptoticallyStable,
        "{stab:?}"
    );
    // The whole state is not: a heading kick moves the position like t.
    assert!(
        matches!(stab.verdict, Verdict::PolynomialGrowth { degree } if degree >= 1),
        "{stab:?}"
    );
    for name in ["x", "y", "psi", "theta_r", "theta_f"] {
        assert!(stab.structural.contains(&name.to_string()), "{stab:?}");
    }
    for name in ["phi", "delta", "phi'", "delta'"] {
        assert!(!stab.structural.contains(&name.to_string()), "{stab:?}");
    }
    let zeros = fast
        .eigenvalues()
        .iter()
        .filter(|z| z.norm() == 0.0)
        .count();
    assert_eq!(zeros, stab.structural.len());
    assert_eq!(
        full(3.0).stability(1e-12).unwrap().verdict,
        Verdict::Unstable
    );
}

/// Naming only the states of interest: the linearizer completes the
/// independent coordinates and speeds, and the lateral block is the one the
/// fully named partition gives.
#[test]
fn linearizer_completes_a_partial_partition() {
    let b = Bicycle::benchmark();
    let (q, qd) = b.upright(4.0);
    let op = OperatingPoint::new(SVector::from(q), SVector::from(qd));
    let lin = Linearizer::new()
        .coordinates(&["phi", "delta"])
        .speeds(&["phi", "delta"])
        .constrained(&b, &op)
        .unwrap();
    assert_eq!(lin.states()[..2], ["phi", "delta"]);
    assert_eq!(
        lin.completed().len(),
        lin.states().len() - 4,
        "{:?}",
        lin.completed()
    );
    let lateral = lin.select(&["phi", "delta", "phi'", "delta'"]).unwrap();
    let named = b.lateral(4.0).unwrap();
    assert!(
        (lateral.a() - named.a()).amax() < 1e-10,
        "{}\n{}",
        lateral.a(),
        named.a()
    );
    let too_many = Linearizer::new()
        .coordinates(&[
            "x", "y", "psi", "phi", "theta_r", "delta", "theta_f", "pitch",
        ])
        .constrained(&b, &op)
        .unwrap_err();
    assert!(too_many.to_string().contains("at most 7"), "{too_many}");
}

#[test]
fn a_negative_stability_tolerance_is_refused() {
    let lateral = Bicycle::benchmark().lateral(5.0).unwrap();
    let e = lateral.stability(-1e-9).unwrap_err();
    assert!(
        e.to_string().contains("must be non-negative and finite"),
        "{e}"
    );
    assert!(lateral.stability(f64::NAN).is_err());
}

/// The rear contact (x, y) and both wheels' rotations are cyclic; yaw (read by
/// the rolling constraints), roll, pitch and steer are not.
#[test]
fn contact_point_and_wheel_angles_are_cyclic() {
    let cyclic = <Bicycle as Lagrangian<f64, 8>>::CYCLIC;
    // x, y, psi, phi, pitch, theta_r, delta, theta_f
    assert_eq!(cyclic, [true, true, false, false, false, true, false, true]);
}
