//! The base parameters: the fewest linear combinations of the standard
//! inertial parameters that determine τ, found numerically from the
//! regressor stacked at random states.

use std::fmt::Write as _;

use nalgebra::{DMatrix, DVector, SVector};

use super::columns::{RANK_TOLERANCE, independent};
use super::{State, random_states, stacked};
use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// The base parameters π_b = K π of a system: each named after the standard
/// parameter it keeps, with the ones that act only through it regrouped into
/// it, so that τ = Y π = Y_b π_b with Y_b the kept columns of Y.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseParameters {
    standard: Vec<String>,
    kept: Vec<usize>,
    map: DMatrix<f64>,
    expressions: Vec<String>,
    without_effect: Vec<String>,
}

impl BaseParameters {
    /// The base parameters of `sys`, from its regressor at random states
    /// (a fixed sequence, so the same on every run): twice as many
    /// equations as parameters, plus a few states.
    ///
    /// # Errors
    /// [`IdentifyError::NoRegressor`] unless the system was derived with
    /// `emit(regressor)`.
    pub fn of<S, const N: usize, const Q: usize>(sys: &S) -> Result<Self, IdentifyError>
    where
        S: Lagrangian<f64, N, Q>,
    {
        let count = (2 * S::REGRESSOR_PARAMETERS.len()).div_ceil(N.max(1)) + 4;
        Self::at_states(sys, &random_states::<S, N, Q>(count))
    }

    /// The base parameters that the states `states` (q, q̇, q̈) reveal: what
    /// a given set of motions can identify at most.
    ///
    /// # Errors
    /// [`IdentifyError::NoRegressor`] unless the system was derived with
    /// `emit(regressor)`; [`IdentifyError::NotFinite`] for a NaN or an
    /// infinity in a state.
    pub fn at_states<S, const N: usize, const Q: usize>(
        sys: &S,
        states: &[State<N, Q>],
    ) -> Result<Self, IdentifyError>
    where
        S: Lagrangian<f64, N, Q>,
    {
        for (k, (q, v, a)) in states.iter().enumerate() {
            super::estimate::finite(
                k,
                &[
                    ("q", q.as_slice()),
                    ("v", v.as_slice()),
                    ("a", a.as_slice()),
                ],
            )?;
        }
        let w = stacked(sys, states)?;
        let standard: Vec<String> = S::REGRESSOR_PARAMETERS
            .iter()
            .map(|s| s.to_string())
            .collect();
        Ok(Self::from_stacked(&w, standard))
    }

    /// From the stacked regressor `w` and π's names.
    fn from_stacked(w: &DMatrix<f64>, standard: Vec<String>) -> Self {
        let flags = independent(w);
        let kept: Vec<usize> = (0..flags.len()).filter(|&k| flags[k]).collect();
        let dropped: Vec<usize> = (0..flags.len()).filter(|&k| !flags[k]).collect();
        let w_kept = w.select_columns(&kept);
        let w_dropped = w.select_columns(&dropped);
        // W_dropped = W_kept β: the dropped columns in the kept ones.
        let beta = if kept.is_empty() || dropped.is_empty() {
            DMatrix::zeros(kept.len(), dropped.len())
        } else {
            let qr = w_kept.clone().qr();
            // The kept columns are independent: R's diagonal has no zero.
            (qr.r())
                .solve_upper_triangular(&(qr.q().transpose() * &w_dropped))
                .unwrap_or_else(|| DMatrix::zeros(kept.len(), dropped.len()))
        };
        let mut map = DMatrix::zeros(kept.len(), flags.len());
        for (i, &k) in kept.iter().enumerate() {
            map[(i, k)] = 1.0;
            for (j, &d) in dropped.iter().enumerate() {
                // What round-off leaves of an exact combination: a share of
                // the dropped column below the rank tolerance.
                let share = beta[(i, j)].abs() * w_kept.column(i).norm();
                if share > 1e-10 * w_dropped.column(j).norm() {
                    map[(i, d)] = beta[(i, j)];
                }
            }
        }
        let largest = w.column_iter().map(|c| c.norm()).fold(0.0, f64::max);
        let without_effect = (dropped.iter())
            .filter(|&&d| w.column(d).norm() <= RANK_TOLERANCE * largest)
            .map(|&d| standard[d].clone())
            .collect();
        let expressions = (0..kept.len())
            .map(|i| expression(&standard, map.row(i).iter().copied()))
            .collect();
        BaseParameters {
            standard,
            kept,
            map,
            expressions,
            without_effect,
        }
    }

    /// How many base parameters there are.
    pub fn len(&self) -> usize {
        self.kept.len()
    }

    /// Whether there are none (a system whose masses never move).
    pub fn is_empty(&self) -> bool {
        self.kept.is_empty()
    }

    /// Each base parameter's name: the standard parameter it keeps.
    pub fn names(&self) -> Vec<&str> {
        self.kept
            .iter()
            .map(|&k| self.standard[k].as_str())
            .collect()
    }

    /// Each base parameter as a combination of the standard ones, e.g.
    /// `link1.Izz + 0.0841*link2.m + 0.58*link2.mx`.
    pub fn expressions(&self) -> &[String] {
        &self.expressions
    }

    /// The standard parameters that act on nothing (Y's zero columns: a
    /// body fixed in space, a body's inertia about an axis it never turns
    /// about).
    pub fn without_effect(&self) -> &[String] {
        &self.without_effect
    }

    /// K, base parameters × standard parameters: π_b = K π.
    pub fn map(&self) -> &DMatrix<f64> {
        &self.map
    }

    /// The columns of Y that Y_b keeps (indices into π).
    pub fn columns(&self) -> &[usize] {
        &self.kept
    }

    /// π_b = K π.
    ///
    /// # Errors
    /// [`IdentifyError::Lengths`] when π is not as long as the system's.
    pub fn of_parameters(&self, pi: &DVector<f64>) -> Result<DVector<f64>, IdentifyError> {
        if pi.len() != self.standard.len() {
            return Err(IdentifyError::Lengths {
                what: "π",
                got: pi.len(),
                expected: self.standard.len(),
            });
        }
        Ok(&self.map * pi)
    }

    /// Y_b(q, q̇, q̈): the columns of the regressor the base parameters keep,
    /// τ = Y_b π_b.
    ///
    /// # Errors
    /// [`IdentifyError::NoRegressor`] unless the system was derived with
    /// `emit(regressor)`; [`IdentifyError::Lengths`] when its regressor has
    /// not the columns these base parameters were found for (another
    /// system's).
    pub fn regressor<S, const N: usize, const Q: usize>(
        &self,
        sys: &S,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        a: &SVector<f64, N>,
    ) -> Result<DMatrix<f64>, IdentifyError>
    where
        S: Lagrangian<f64, N, Q>,
    {
        let y = super::regressor_at(sys, q, v, a)?;
        // Base parameters found for another system would pick the wrong
        // columns, or ones Y does not have.
        if y.ncols() != self.standard.len() {
            return Err(IdentifyError::Lengths {
                what: "the system's regressor",
                got: y.ncols(),
                expected: self.standard.len(),
            });
        }
        Ok(y.select_columns(&self.kept))
    }
}

/// `a + c*b + ...` from the coefficients of a row of K.
fn expression(names: &[String], row: impl Iterator<Item = f64>) -> String {
    let mut text = String::new();
    for (name, c) in names.iter().zip(row).filter(|(_, c)| *c != 0.0) {
        let sign = if c < 0.0 { '-' } else { '+' };
        let magnitude = c.abs();
        match (text.is_empty(), magnitude == 1.0) {
            (true, true) if c > 0.0 => text.push_str(name),
            (true, _) => {
                let _ = write!(text, "{c}*{name}");
            }
            (false, true) => {
                let _ = write!(text, " {sign} {name}");
            }
            (false, false) => {
                let _ = write!(text, " {sign} {magnitude}*{name}");
            }
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four columns: c0, c1 = 3 c0, c2 independent, c3 = c0 − 0.5 c2.
    #[test]
    fn dropped_columns_are_written_in_the_kept_ones() {
        let c0 = DVector::from_vec(vec![1.0, -2.0, 0.5, 4.0, 1.5]);
        let c2 = DVector::from_vec(vec![0.3, 1.0, -1.0, 0.0, 2.0]);
        let c1 = &c0 * 3.0;
        let c3 = &c0 - &c2 * 0.5;
        let w = DMatrix::from_columns(&[c0, c1, c2, c3]);
        let names = ["a.m", "a.mx", "b.m", "b.mx"].map(String::from).to_vec();
        let base = BaseParameters::from_stacked(&w, names);
        assert_eq!(base.names(), ["a.m", "b.m"]);
        let want = DMatrix::from_row_slice(2, 4, &[1.0, 3.0, 0.0, 1.0, 0.0, 0.0, 1.0, -0.5]);
        assert!((base.map() - want).abs().max() < 1e-14, "{}", base.map());
        // τ = W π = W_b π_b for any π.
        let pi = DVector::from_vec(vec![0.7, -1.1, 2.0, 0.4]);
        let pb = base.of_parameters(&pi).expect("π's length");
        let w_b = w.select_columns(base.columns());
        assert!((&w * &pi - w_b * pb).abs().max() < 1e-13);
        let text = &base.expressions()[1];
        assert!(
            text.starts_with("b.m - 0.") && text.ends_with("*b.mx"),
            "{text}"
        );
    }
}
