//! Linear state feedback on stack matrices: what applying an LQR gain needs,
//! without building a dynamic vector from the state at every stage.

use super::InputSource;
use crate::error::Error;
use crate::error::SettingsError;
use crate::linear::{Linear, OperatingPoint, tangent_states};
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation};
use crate::system::Lagrangian;
use nalgebra::{DMatrix, SMatrix, SVector};

/// The linear law u = u0 − K_q (q ⊖ q0) − K_v (v − v0) about an operating
/// point (q ⊖ q0 is q − q0 for ordinary coordinates and, for an orientation,
/// the rotation vector δθ in body axes with q = q0 ⊗ exp(δθ): the tangent
/// linearisation's states), with the gain split into its coordinate and velocity columns so that
/// evaluating it is two small matrix-vector products on the stack: no
/// allocation per call, as the integrators promise.
///
/// Build it from a gain designed on a [`Linear`] model
/// ([`from_gain`](Self::from_gain), e.g. [`Lqr::gain`](crate::linear::Lqr);
/// for a system with orientations, on its tangent linearisation:
/// [`from_tangent_gain`](Self::from_tangent_gain)),
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
pub struct StateFeedback<T: Real, const N: usize, const P: usize, const Q: usize = N> {
    k_q: SMatrix<T, P, N>,
    k_v: SMatrix<T, P, N>,
    q0: SVector<T, Q>,
    v0: SVector<T, N>,
    u0: SVector<T, P>,
    /// Where q's quaternions sit: what q ⊖ q0 reads.
    layout: &'static [Orientation],
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
            layout: &[],
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
    /// [`Error::Settings`] if the gain is not P × (the model's
    /// states), an entry is not finite, or a state is neither a coordinate
    /// nor a coordinate's rate (a reduced model's speed: feed it back with a
    /// controller of your own).
    pub fn from_gain(
        gain: &DMatrix<f64>,
        model: &Linear,
        coordinates: &[&str; N],
    ) -> Result<Self, Error> {
        let mut law = Self::new(SMatrix::zeros(), SMatrix::zeros());
        law.fill(gain, model, |state| {
            let (name, rate) = match state.strip_suffix('\'') {
                Some(name) => (name, true),
                None => (state, false),
            };
            let i = coordinates.iter().position(|c| *c == name)?;
            Some(if rate { N + i } else { i })
        })?;
        Ok(law)
    }
}

impl<T: Real, const N: usize, const P: usize, const Q: usize> StateFeedback<T, N, P, Q> {
    /// The gain `gain` (inputs × states, the law u = −K x) designed on the
    /// tangent linearisation `model` of `S`
    /// ([`Linearizer::tangent_driven`](crate::linear::Linearizer::tangent_driven):
    /// states δ and δv, a coordinate's name, an orientation's `<name>.θx`, …,
    /// then the rates, `x'`, `<name>.wx`, …), about the state (q0, v0)
    /// with inputs u0. States the model does not have get no feedback.
    ///
    /// A model of a constrained system from
    /// [`Linearizer::constrained_tangent`](crate::linear::Linearizer::constrained_tangent)
    /// (or [`reduced_tangent`](crate::linear::Linearizer::reduced_tangent))
    /// names its independent states the same way, and its dependent ones get
    /// no feedback. At a point at rest its axes (the body's at the point,
    /// fixed in space) and the law's (q ⊖ q0, v − v0) agree to first order,
    /// so the law is the model's: a rod balanced on a pin made of three
    /// holonomic rows follows its linear closed loop to second order in the
    /// error (`tests/constrained_control.rs`). About a moving point (a spin
    /// ω0 ≠ 0) they differ at first order, and q0 stays where it was.
    ///
    /// # Errors
    /// [`Error::Settings`] if the gain is not P × (the model's
    /// states), an entry is not finite, or a state is not one of `S`'s
    /// tangent states.
    pub fn from_tangent_gain<S: Lagrangian<T, N, Q>>(
        gain: &DMatrix<f64>,
        model: &Linear,
        (q0, v0, u0): (SVector<T, Q>, SVector<T, N>, SVector<T, P>),
    ) -> Result<Self, Error> {
        let names = tangent_states::<S, T, N, Q>();
        let mut law = Self {
            k_q: SMatrix::zeros(),
            k_v: SMatrix::zeros(),
            q0,
            v0,
            u0,
            layout: S::ORIENTATIONS,
        };
        law.fill(gain, model, |state| names.iter().position(|n| n == state))?;
        Ok(law)
    }

    /// Puts the gain's columns where `index` says (a state's position among
    /// the N tangent directions, then the N rates).
    fn fill(
        &mut self,
        gain: &DMatrix<f64>,
        model: &Linear,
        index: impl Fn(&str) -> Option<usize>,
    ) -> Result<(), Error> {
        let states = model.states();
        if gain.shape() != (P, states.len()) || !gain.iter().all(|x| x.is_finite()) {
            return Err(SettingsError::Shape {
                owner: "StateFeedback",
                name: "the gain",
                expected: (P, states.len()),
                got: gain.shape(),
                finite: gain.iter().all(|x| x.is_finite()),
                meaning: "inputs x the model's states",
            }
            .into());
        }
        for (j, state) in states.iter().enumerate() {
            let i = index(state).ok_or_else(|| {
                Error::from(SettingsError::Data {
                    owner: "StateFeedback",
                    problem: format!(
                        "state `{state}` of the model is neither a coordinate nor a \
                         coordinate's rate of this system"
                    ),
                })
            })?;
            let (column, i) = if i < N {
                (&mut self.k_q, i)
            } else {
                (&mut self.k_v, i - N)
            };
            for r in 0..P {
                column[(r, i)] = T::lit(gain[(r, j)]);
            }
        }
        Ok(())
    }

    /// u at (q, v).
    #[inline]
    pub fn input(&self, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        let mut delta = SVector::<T, N>::zeros();
        orientation::difference(
            self.layout,
            self.q0.as_slice(),
            q.as_slice(),
            delta.as_mut_slice(),
        );
        self.u0 - self.k_q * delta - self.k_v * (v - self.v0)
    }
}

impl<T: Real, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for StateFeedback<T, N, P, Q>
{
    #[inline]
    fn input(&self, _: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        StateFeedback::input(self, q, v)
    }
}
