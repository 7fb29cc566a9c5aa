//! Step-size settings shared by the adaptive integrators (DOPRI5, DOP853,
//! RADAU5): tolerances, initial and largest step, and the step budget, with one
//! validation and one set of builder methods instead of a copy per method.

use crate::error::Error;
use crate::error::SettingsError;

/// Tolerances and step limits of an adaptive method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StepControl {
    pub rtol: f64,
    pub atol: f64,
    pub h0: Option<f64>,
    pub hmax: Option<f64>,
    pub max_steps: usize,
}

impl StepControl {
    /// The given tolerances, no step limits, 100 000 attempted steps.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            rtol,
            atol,
            h0: None,
            hmax: None,
            max_steps: 100_000,
        }
    }

    /// rtol must exceed `min_rtol`; atol must be ≥ 0 (> 0 with `positive_atol`);
    /// h0 and hmax, if set, positive and finite; the step budget positive.
    pub fn validate(
        &self,
        method: &'static str,
        min_rtol: f64,
        positive_atol: bool,
    ) -> Result<(), Error> {
        let bad = |setting, requirement: String, value| {
            Err(SettingsError::Value {
                owner: method,
                setting,
                value,
                requirement,
            }
            .into())
        };
        if !(self.rtol.is_finite() && self.rtol > min_rtol) {
            let requirement = format!("finite and above {min_rtol}");
            return bad("rtol", requirement, self.rtol);
        }
        let atol_ok = if positive_atol {
            self.atol > 0.0
        } else {
            self.atol >= 0.0
        };
        if !(self.atol.is_finite() && atol_ok) {
            let what = if positive_atol {
                "positive"
            } else {
                "non-negative"
            };
            return bad("atol", format!("{what} and finite"), self.atol);
        }
        for (name, x) in [("h0", self.h0), ("hmax", self.hmax)] {
            if let Some(x) = x.filter(|x| !(x.is_finite() && *x > 0.0)) {
                return bad(name, "positive and finite".into(), x);
            }
        }
        if self.max_steps == 0 {
            let setting = "max_steps";
            return Err(SettingsError::ZeroCount {
                owner: method,
                setting,
            }
            .into());
        }
        Ok(())
    }
}

impl StepControl {
    /// The relative tolerance must be one the scalar can meet at all. The
    /// local error estimate h Σ eᵢ kᵢ carries round-off of about ε h |k|, and the
    /// smallest step the methods take is about 16 ε t, so below ~16 ε² (2.3e-13 in
    /// f32, 7.9e-31 in f64, for a problem of unit scale) no step size meets the
    /// tolerance and the run can only collapse (f32 at 1e-14 used to end in
    /// `TooManySteps` at t = 0.03): a settings error up front. Tolerances between
    /// that and ε are allowed: tiny steps still meet them locally, and the
    /// work-precision study measured f32's best DOPRI5 result at 1e-10.
    pub fn check_precision<T: crate::numeric::Real>(
        &self,
        method: &'static str,
    ) -> Result<(), Error> {
        let eps = T::default_epsilon().to_f64();
        let floor = 16.0 * eps * eps;
        if self.rtol < floor {
            let requirement = format!(
                "at least 16 ε² = {floor:.1e}, below which {} meets it with no step size; \
                 loosen the tolerance or compute in a wider type",
                std::any::type_name::<T>()
            );
            return Err(SettingsError::Value {
                owner: method,
                setting: "rtol",
                value: self.rtol,
                requirement,
            }
            .into());
        }
        Ok(())
    }
}

/// The builder methods of [`StepControl`] for an integrator with a `control`
/// field; `$h0` documents what happens when no initial step is given.
macro_rules! step_control_builders {
    ($h0:literal) => {
        /// Sets the relative tolerance (must be > 0).
        pub fn rtol(mut self, rtol: f64) -> Self {
            self.control.rtol = rtol;
            self
        }

        /// Sets the absolute tolerance (must be ≥ 0).
        pub fn atol(mut self, atol: f64) -> Self {
            self.control.atol = atol;
            self
        }

        #[doc = concat!("Sets the initial step size; by default ", $h0, ".")]
        pub fn h0(mut self, h0: f64) -> Self {
            self.control.h0 = Some(h0);
            self
        }

        /// Sets the largest step size; by default the length of the time span.
        pub fn hmax(mut self, hmax: f64) -> Self {
            self.control.hmax = Some(hmax);
            self
        }

        /// Sets the budget of attempted steps (accepted + rejected); default 100 000.
        pub fn max_steps(mut self, n: usize) -> Self {
            self.control.max_steps = n;
            self
        }
    };
}

pub(crate) use step_control_builders;
