//! Against SciPy 1.17.1 (`cont2discrete(.., method="zoh")`,
//! `solve_discrete_are`), closed forms and the continuous LQR; the values
//! below are printed by `lagrange-bench/peer/scipy_discrete.py`.

use super::*;
use crate::linear::lqr;

struct Case {
    a: &'static [f64],
    b: &'static [f64],
    inputs: usize,
    period: f64,
    q: &'static [f64],
    r: &'static [f64],
    ad: &'static [f64],
    bd: &'static [f64],
    p: &'static [f64],
    k: &'static [f64],
}

const DOUBLE_INTEGRATOR: Case = Case {
    a: &[0.0, 1.0, 0.0, 0.0],
    b: &[0.0, 1.0],
    inputs: 1,
    period: 0.1,
    q: &[1.0, 0.0, 0.0, 0.5],
    r: &[0.2],
    ad: &[1.0, 0.1, 0.0, 1.0],
    bd: &[0.005000000000000001, 0.1],
    p: &[
        12.33096751008262,
        4.48608961123157,
        4.48608961123157,
        5.557478043780033,
    ],
    k: &[1.9597706178637198, 2.4165867816092264],
};

const CART_POLE: Case = Case {
    a: &[
        0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -0.981, 0.0, 0.0, 0.0, 21.582, 0.0, 0.0,
    ],
    b: &[0.0, 0.0, 1.0, -2.0],
    inputs: 1,
    period: 0.02,
    q: &[
        10.0, 0.0, 0.0, 0.0, 0.0, 100.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ],
    r: &[0.1],
    ad: &[
        1.0,
        -0.0001963411869025155,
        0.020000000000000004,
        -1.308564701180354e-06,
        0.0,
        1.0043195061118553,
        0.0,
        0.02002878842342597,
        0.0,
        -0.019648241443380877,
        1.0,
        -0.00019634118690251543,
        0.0,
        0.43226131175437915,
        0.0,
        1.0043195061118553,
    ],
    bd: &[
        0.00020001308376448116,
        -0.00040028784281858384,
        0.020002617129402364,
        -0.040057576846851926,
    ],
    p: &[
        586.4735513001342,
        738.563399603476,
        313.08649086157806,
        181.72598601307203,
        738.563399603476,
        2881.982877298973,
        677.0653359944263,
        519.8381365388635,
        313.08649086157806,
        677.0653359944263,
        289.316238460331,
        173.66969918729814,
        181.72598601307203,
        519.8381365388635,
        173.66969918729814,
        124.41285137395971,
    ],
    k: &[
        -8.366177473884335,
        -63.14505833241097,
        -9.813083627831316,
        -12.98033966552124,
    ],
};

const TWO_INPUTS: Case = Case {
    a: &[
        0.0, 1.0, 0.0, 0.0, 2.0, -0.1, 0.5, 0.0, 0.0, 0.0, 0.0, 1.0, 0.3, 0.0, -4.0, -0.05,
    ],
    b: &[0.0, 0.0, 1.0, 0.2, 0.0, 0.0, 0.1, 1.0],
    inputs: 2,
    period: 0.05,
    q: &[
        2.0, 0.1, 0.0, 0.0, 0.1, 1.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.2, 0.0, 0.0, 0.2, 0.5,
    ],
    r: &[1.0, 0.1, 0.1, 0.5],
    ad: &[
        1.002496917299613,
        0.049916781510964806,
        0.0006236996093846686,
        1.0394558209501855e-05,
        0.09983668138939247,
        0.9975052391485165,
        0.024916812522644403,
        0.0006231798814741937,
        0.0003745316023770862,
        6.236734925701111e-06,
        0.9950083641637132,
        0.04985436480059822,
        0.014968782910030865,
        0.0003739079288845159,
        -0.19941434083492995,
        0.9925156459236832,
    ],
    bd: &[
        0.0012484521502295878,
        0.00024981782175345407,
        0.04991782096678577,
        0.009993750860402465,
        0.00012486986576668927,
        0.0012479343074216734,
        0.004991673214985524,
        0.04985561214758334,
    ],
    p: &[
        154.0963745916259,
        87.01108972990403,
        17.030918757683658,
        1.0684994069907505,
        87.01108972990403,
        60.23974633142843,
        12.782268625894257,
        0.0687923298925962,
        17.030918757683658,
        12.782268625894257,
        71.53149675103174,
        7.193936706792488,
        1.0684994069907505,
        0.0687923298925962,
        7.193936706792488,
        15.268859589581993,
    ],
    k: &[
        4.081095609876658,
        2.8058024909910864,
        0.5803606025793273,
        -0.07226827833102449,
        0.9176053296627137,
        0.5601791822145795,
        0.6599448714429231,
        1.4741221056239424,
    ],
};

const CASES: [(&str, Case); 3] = [
    ("double integrator", DOUBLE_INTEGRATOR),
    ("cart-pole", CART_POLE),
    ("two inputs", TWO_INPUTS),
];

fn rows(r: usize, c: usize, x: &[f64]) -> DMatrix<f64> {
    DMatrix::from_row_slice(r, c, x)
}

impl Case {
    fn n(&self) -> usize {
        self.b.len() / self.inputs
    }
    fn a(&self) -> DMatrix<f64> {
        rows(self.n(), self.n(), self.a)
    }
    fn b(&self) -> DMatrix<f64> {
        rows(self.n(), self.inputs, self.b)
    }
    fn q(&self) -> DMatrix<f64> {
        rows(self.n(), self.n(), self.q)
    }
    fn r(&self) -> DMatrix<f64> {
        rows(self.inputs, self.inputs, self.r)
    }
}

/// ‖x − y‖_max / max(1, ‖y‖_max).
fn distance(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1.0)
}

#[test]
fn zero_order_hold_matches_scipy() {
    for (name, c) in CASES {
        let (ad, bd) = zero_order_hold(&c.a(), &c.b(), c.period).unwrap();
        let n = c.n();
        let (ead, ebd) = (
            distance(&ad, &rows(n, n, c.ad)),
            distance(&bd, &rows(n, c.inputs, c.bd)),
        );
        assert!(
            ead < 1e-14 && ebd < 1e-14,
            "{name}: A_d off by {ead:e}, B_d by {ebd:e}"
        );
    }
}

#[test]
fn discrete_riccati_matches_scipy() {
    for (name, c) in CASES {
        let (ad, bd) = zero_order_hold(&c.a(), &c.b(), c.period).unwrap();
        let design = dlqr(&ad, &bd, &c.q(), &c.r()).unwrap();
        let n = c.n();
        let ep = distance(&design.riccati, &rows(n, n, c.p));
        let ek = distance(&design.gain, &rows(c.inputs, n, c.k));
        assert!(
            ep < 1e-10 && ek < 1e-10,
            "{name}: P off by {ep:e}, K by {ek:e}"
        );
        assert!(
            design.residual < 1e-13,
            "{name}: residual {:e}",
            design.residual
        );
        assert!(
            design.iterations < 20,
            "{name}: {} doubling steps",
            design.iterations
        );
        assert!(design.closed_loop.iter().all(|z| z.norm() < 1.0));
        assert_eq!(design.riccati, design.riccati.transpose());
    }
}

/// A double integrator held for h: A_d = [[1, h], [0, 1]], B_d = [h²/2, h],
/// for any h (the block exponential is a polynomial here).
#[test]
fn double_integrator_in_closed_form() {
    let (a, b) = (DOUBLE_INTEGRATOR.a(), DOUBLE_INTEGRATOR.b());
    for h in [1e-6, 0.01, 0.37, 5.0] {
        let (ad, bd) = zero_order_hold(&a, &b, h).unwrap();
        let expected_a = rows(2, 2, &[1.0, h, 0.0, 1.0]);
        let expected_b = rows(2, 1, &[h * h / 2.0, h]);
        assert!(distance(&ad, &expected_a) < 1e-15, "h = {h}: {ad}");
        assert!(
            (&bd - &expected_b).amax() <= 4.0 * f64::EPSILON * h.max(h * h),
            "h = {h}: {bd}"
        );
    }
}

/// Sampled ever faster with the weights scaled by h (Σ (xᵀQx + uᵀRu) h →
/// ∫ xᵀQx + uᵀRu dt), the discrete gain tends to the continuous one, at
/// first order in h: an independent check of both Riccati solvers.
#[test]
fn fast_sampling_tends_to_the_continuous_lqr() {
    for (name, c) in CASES {
        let continuous = lqr(&c.a(), &c.b(), &c.q(), &c.r()).unwrap().gain;
        let gap = |h: f64| {
            let (ad, bd) = zero_order_hold(&c.a(), &c.b(), h).unwrap();
            let discrete = dlqr(&ad, &bd, &(c.q() * h), &(c.r() * h)).unwrap().gain;
            distance(&discrete, &continuous)
        };
        let (coarse, fine) = (gap(1e-3), gap(1e-4));
        assert!(
            fine < 1e-2,
            "{name}: K_d(1e-4) differs from K_c by {fine:e}"
        );
        let order = (coarse / fine).log10();
        assert!((order - 1.0).abs() < 0.1, "{name}: observed order {order}");
    }
}

#[test]
fn a_model_keeps_its_names_and_period() {
    let c = CART_POLE;
    let model = Linear::new(c.a(), c.b(), &["x", "theta", "x'", "theta'"], &["force"], 2).unwrap();
    let sampled = model.discretize(c.period).unwrap();
    assert_eq!(sampled.states(), model.states());
    assert_eq!(sampled.inputs(), model.inputs());
    assert_eq!(sampled.period(), c.period);
    let design = sampled.lqr(&c.q(), &c.r()).unwrap();
    assert!(distance(&design.gain, &rows(1, 4, c.k)) < 1e-10);
}

#[test]
fn bad_periods_and_matrices_are_settings_errors() {
    let (a, b) = (DOUBLE_INTEGRATOR.a(), DOUBLE_INTEGRATOR.b());
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let e = zero_order_hold(&a, &b, h).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Settings(SettingsError::Value {
                    setting: "period",
                    ..
                })
            ),
            "h = {h}: {e}"
        );
    }
    let mut bad = a.clone();
    bad[(0, 0)] = f64::NAN;
    let e = zero_order_hold(&bad, &b, 0.1).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Settings(SettingsError::Shape {
                name: "A",
                finite: false,
                ..
            })
        ),
        "{e}"
    );
    let e = zero_order_hold(&a, &rows(1, 1, &[1.0]), 0.1).unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Shape { name: "B", .. })),
        "{e}"
    );
    let fast = rows(1, 1, &[1e4]);
    let e = zero_order_hold(&fast, &rows(1, 1, &[1.0]), 1.0).unwrap_err();
    assert!(e.to_string().contains("exp(A h) is finite"), "{e}");
    let e = dlqr(&a, &b, &DOUBLE_INTEGRATOR.q(), &rows(1, 1, &[-1.0])).unwrap_err();
    assert!(e.to_string().contains("R must be positive definite"), "{e}");
}

/// An unstable mode the input cannot reach is refused by name; a stable one
/// it cannot reach is not in the way.
#[test]
fn uncontrollable_modes() {
    let b = rows(2, 1, &[1.0, 0.0]);
    let (q, r) = (DMatrix::identity(2, 2), rows(1, 1, &[1.0]));
    let unstable = rows(2, 2, &[0.5, 0.0, 0.0, 1.2]);
    let e = dlqr(&unstable, &b, &q, &r).unwrap_err();
    match e {
        Error::Linear(LinearError::NotStabilisable { re, ratio, .. }) => {
            assert!(
                (re - 1.2).abs() < 1e-12 && ratio < 1e-9,
                "λ = {re}, ratio {ratio:e}"
            );
        }
        other => panic!("expected NotStabilisable, got {other}"),
    }
    let stable = rows(2, 2, &[1.5, 0.0, 0.0, 0.3]);
    let design = dlqr(&stable, &b, &q, &r).unwrap();
    assert!(design.closed_loop.iter().all(|z| z.norm() < 1.0));
    assert!((design.closed_loop[1].norm() - 0.3).abs() < 1e-12);
}
