//! Hairer's stiffness test, shared by DOPRI5 and DOP853.

use crate::error::Error;
use crate::numeric::Real;
use crate::ode::Pair;

/// Hairer's stiffness test of DOPRI5 and DOP853: every `every` accepted steps,
/// and at every step while suspicion lasts, h·|λ| is estimated from the last
/// stage, |λ| ≈ ‖f(t₁, y₁) − f(t₁, ỹ)‖ / ‖y₁ − ỹ‖ with ỹ the argument of the
/// stage at t₁; beyond `boundary` (where the method's stability region ends on
/// the negative real axis) 15 times before 6 steps below it, the problem is
/// reported as stiff.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StiffnessTest {
    method: &'static str,
    every: usize,
    boundary: f64,
    suspicious: usize,
    clear: usize,
}

impl StiffnessTest {
    pub(crate) fn new(method: &'static str, every: usize, boundary: f64) -> Self {
        Self {
            method,
            every,
            boundary,
            suspicious: 0,
            clear: 0,
        }
    }

    /// Checks an accepted step of size `h` (the `accepted`-th) ending at `t`:
    /// `f_new` = f(t, y_new) and `f_stage` = f(t, y_stage).
    pub(crate) fn check<T: Real, const N: usize, const Q: usize>(
        &mut self,
        accepted: usize,
        t: T,
        h: T,
        [y_new, y_stage, f_new, f_stage]: [&Pair<T, N, Q>; 4],
    ) -> Result<(), Error> {
        if self.every == 0 || !(accepted.is_multiple_of(self.every) || self.suspicious > 0) {
            return Ok(());
        }
        let num = squared_distance(f_new, f_stage);
        let den = squared_distance(y_new, y_stage);
        if den <= 0.0 {
            return Ok(());
        }
        let h_lambda = h.to_f64().abs() * (num / den).sqrt();
        if h_lambda > self.boundary {
            self.clear = 0;
            self.suspicious += 1;
            if self.suspicious == 15 {
                return Err(Error::ProbablyStiff {
                    method: self.method,
                    t: t.to_f64(),
                    h_lambda,
                    tests: self.suspicious,
                });
            }
        } else {
            self.clear += 1;
            if self.clear == 6 {
                self.suspicious = 0;
            }
        }
        Ok(())
    }
}

fn squared_distance<T: Real, const N: usize, const Q: usize>(
    a: &Pair<T, N, Q>,
    b: &Pair<T, N, Q>,
) -> f64 {
    let d = a.sub(b);
    d.q.iter()
        .chain(d.v.iter())
        .map(|x| x.to_f64() * x.to_f64())
        .sum()
}
