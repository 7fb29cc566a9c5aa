//! Hairer's step-size controller for DOPRI5: a PI controller with Lund
//! stabilisation,
//!
//! ```text
//! h_new = h · clamp(safe / (err^(1/5 − 0.75β) · err_old^β), fac1, fac2)
//! ```
//!
//! with err_old the error of the last *accepted* step. The integral part alone
//! (β = 0) is the textbook controller; the β term damps the oscillation of h that
//! the textbook controller shows when the step is limited by stability rather than
//! accuracy. After a rejection h is only reduced, using the I part alone, and the
//! next accepted step may not grow.

use crate::numeric::Real;

#[derive(Clone, Copy, Debug)]
pub(crate) struct PiController<T> {
    safe: T,
    /// 1/fac1: the largest allowed h/h_new (fac1 = 0.2: shrink by at most 5).
    facc1: T,
    /// 1/fac2: the smallest allowed h/h_new (fac2 = 10: grow by at most 10).
    facc2: T,
    beta: T,
    expo1: T,
    /// The error of the last accepted step, floored at 1e-4.
    facold: T,
    /// err^expo1 of the last step tried.
    fac11: T,
}

impl<T: Real> PiController<T> {
    /// Hairer's defaults: safe = 0.9, fac1 = 0.2, fac2 = 10, β = 0.04.
    pub fn dopri5() -> Self {
        Self::new(0.9, 0.2, 10.0, 0.04)
    }

    /// Hairer's DOP853 defaults: safe = 0.9, fac1 = 0.333, fac2 = 6, β = 0, and the
    /// exponent 1/8 − 0.2β that belongs to its 8th-order error estimate.
    pub fn dop853() -> Self {
        let beta = 0.0;
        Self::new(0.9, 0.333, 6.0, beta).with_exponent(1.0 / 8.0 - 0.2 * beta)
    }

    /// Replaces the integral exponent 1/5 − 0.75β chosen by [`new`](Self::new)
    /// (DOPRI5's) with `expo1`.
    pub fn with_exponent(mut self, expo1: f64) -> Self {
        self.expo1 = T::lit(expo1);
        self
    }

    pub fn new(safe: f64, fac1: f64, fac2: f64, beta: f64) -> Self {
        Self {
            safe: T::lit(safe),
            facc1: T::lit(1.0 / fac1),
            facc2: T::lit(1.0 / fac2),
            beta: T::lit(beta),
            expo1: T::lit(0.2 - 0.75 * beta),
            facold: T::lit(1e-4),
            fac11: T::zero(),
        }
    }

    /// The step size proposed after a step of size `h` with error norm `err`,
    /// should the step be accepted.
    pub fn propose(&mut self, h: T, err: T) -> T {
        self.fac11 = err.powf(self.expo1);
        let fac = self.fac11 / self.facold.powf(self.beta);
        let fac = self.facc2.max(self.facc1.min(fac / self.safe));
        h / fac
    }

    /// Records an accepted step with error `err`.
    pub fn accept(&mut self, err: T) {
        self.facold = err.max(T::lit(1e-4));
    }

    /// The step size to retry with after rejecting a step of size `h` (uses the
    /// error of the last [`propose`](Self::propose)).
    pub fn reject(&self, h: T) -> T {
        h / self.facc1.min(self.fac11 / self.safe)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_and_rejection() {
        let mut c = PiController::<f64>::dopri5();
        // Zero error: grow by the maximum factor 10.
        assert!((c.propose(1.0, 0.0) - 10.0).abs() < 1e-15);
        // Enormous error: shrink by at most 5 on acceptance proposal and rejection.
        assert!((c.propose(1.0, 1e30) - 0.2).abs() < 1e-15);
        assert!((c.reject(1.0) - 0.2).abs() < 1e-15);
        // err = 1 with facold = 1: h · 0.9.
        c.accept(1.0);
        assert!((c.propose(1.0, 1.0) - 0.9).abs() < 1e-15);
        // Rejection just above 1: shrink by ~0.9, no β term.
        let _ = c.propose(1.0, 2.0);
        assert!((c.reject(1.0) - 0.9 / 2f64.powf(0.17)).abs() < 1e-15);
    }
}
