//! Linear state feedback on stack matrices: what applying an LQR gain needs,
//! without building a dynamic vector from the state at every stage.

use super::InputSource;
use crate::error::Error;
use crate::linear::{Linear, OperatingPoint};
use crate::numeric::Real;
use nalgebra::{DMatrix, SMatrix, SVector};

/// The linear law u = u0 − K_q (q − q0) − K_v (q̇ − q̇0) about an operating
/// point, with the gain split into its coordinate and velocity columns so that
/// evaluating it is two small matrix-vector products on the stack: no
/// allocation per call, as the integrators promise.
///
/// Build it from a gain designed on a [`Linear`] model
/// ([`from_gain`](Self::from_gain), e.g. [`Lqr::gain`](crate::linear::Lqr)),
/// and pass it to [`Simulation::control`](crate::Simulation::control), or call
/// [`input`](Self::input) inside a controller of your own.
///
/// ```
/// # use lagrange_runtime::control::StateFeedback;
/// # use nalgebra::{SMatrix, Vector2, Vector1};
/// // u = −(2 x + 3 θ + 0.5 ẋ + 0.1 θ̇) about the origin.
/// let k = StateFeedback::<f64, 2, 1>::new(
///     SMatrix::<f64, 1, 2>::new(2.0, 3.0),
///     SMatrix::<f64, 1, 2>::new(0.5, 0.1),
/// );
/// let u = k.input(&Vector2::new(1.0, 0.0), &Vector2::new(0.0, 1.0));
/// assert_eq!(u, Vector1::new(-2.1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateFeedback<T: Real, const N: usize, const P: usize> {
    k_q: SMatrix<T, P, N>,
    k_v: SMatrix<T, P, N>,
    q0: SVector<T, N>,
    v0: SVector<T, N>,
    u0: SVector<T, P>,
}

impl<T: Real, const N: usize, const P: usize> StateFeedback<T, N, P> {
    /// The law u = −K_q q − K_v q̇ (about the origin, with zero inputs there).
    pub fn new(k_q: SMatrix<T, P, N>, k_v: SMatrix<T, P, N>) -> Self {
        Self {
            k_q,
            k_v,
            q0: SVector::zeros(),
            v0: SVector::zeros(),
            u0: SVector::zeros(),
        }
    }

    /// The same gain about the operating point `op`: its state, and its
    /// inputs as u0 (zero when it has none).
    pub fn about<const U: usize>(mut self, op: &OperatingPoint<T, N, U>) -> Self {
        self.q0 = op.q;
        self.v0 = op.v;
        self.u0 = op.inputs::<P>();
        self
    }

    /// The gain `gain` (inputs × states, the law u = −K x) designed on
    /// `model`, whose states are named by `coordinates` (a coordinate `x`,
    /// or its rate `x'`). States the model does not have (dropped by
    /// [`Linear::select`], or dependent in a constrained model) get no
    /// feedback.
    ///
    /// # Errors
    /// [`Error::InvalidSettings`] if the gain is not P × (the model's
    /// states), an entry is not finite, or a state is neither a coordinate
    /// nor a coordinate's rate (a reduced model's speed: feed it back with a
    /// controller of your own).
    pub fn from_gain(
        gain: &DMatrix<f64>,
        model: &Linear,
        coordinates: &[&str; N],
    ) -> Result<Self, Error> {
        let states = model.states();
        if gain.shape() != (P, states.len()) || !gain.iter().all(|x| x.is_finite()) {
            return Err(Error::InvalidSettings(format!(
                "a state-feedback gain must be a finite {P} x {} matrix (inputs x the model's \
                 states), got {} x {}",
                states.len(),
                gain.nrows(),
                gain.ncols()
            )));
        }
        let mut law = Self::new(SMatrix::zeros(), SMatrix::zeros());
        for (j, state) in states.iter().enumerate() {
            let (name, rate) = match state.strip_suffix('\'') {
                Some(name) => (name, true),
                None => (state.as_str(), false),
            };
            let i = coordinates.iter().position(|c| *c == name).ok_or_else(|| {
                Error::InvalidSettings(format!(
                    "state `{state}` of the model is neither a coordinate of {coordinates:?} \
                     nor a coordinate's rate"
                ))
            })?;
            let column = if rate { &mut law.k_v } else { &mut law.k_q };
            for r in 0..P {
                column[(r, i)] = T::lit(gain[(r, j)]);
            }
        }
        Ok(law)
    }

    /// u at (q, q̇).
    #[inline]
    pub fn input(&self, q: &SVector<T, N>, v: &SVector<T, N>) -> SVector<T, P> {
        self.u0 - self.k_q * (q - self.q0) - self.k_v * (v - self.v0)
    }
}

impl<T: Real, const N: usize, const P: usize> InputSource<T, N, P> for StateFeedback<T, N, P> {
    #[inline]
    fn input(&self, _: T, q: &SVector<T, N>, v: &SVector<T, N>) -> SVector<T, P> {
        StateFeedback::input(self, q, v)
    }
}
