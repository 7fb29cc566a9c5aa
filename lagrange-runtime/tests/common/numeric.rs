//! Numerical helpers of the tests: a deterministic random generator, central
//! differences and a relative matrix difference.

use nalgebra::{DMatrix, DVector};

/// A small deterministic generator (no dependency): uniform in [lo, hi).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// Central differences of f at x with step h (scaled by 1 + |x_j|).
pub fn jacobian(
    f: impl Fn(&DVector<f64>) -> DVector<f64>,
    x: &DVector<f64>,
    h: f64,
) -> DMatrix<f64> {
    let n = x.len();
    let m = f(x).len();
    let mut jac = DMatrix::zeros(m, n);
    for j in 0..n {
        let step = h * (1.0 + x[j].abs());
        let (mut xp, mut xm) = (x.clone(), x.clone());
        xp[j] += step;
        xm[j] -= step;
        jac.set_column(j, &((f(&xp) - f(&xm)) / (2.0 * step)));
    }
    jac
}

/// max |X − Y| / max(1, max |Y|).
pub fn rel_diff(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    assert_eq!(x.shape(), y.shape());
    (x - y).amax() / y.amax().max(1.0)
}
