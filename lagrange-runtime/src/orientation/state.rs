//! ⊕ and ⊖ over a whole configuration in a system's layout, and the
//! tangent-space error of a run.

use crate::error::{Error, unit_quaternions};
use crate::numeric::Real;
use crate::numeric::orientation as group;
use crate::ode::Trajectory;
use crate::system::Lagrangian;
use nalgebra::SVector;

/// q ⊕ δ for a configuration of `sys`: every ordinary coordinate moved by
/// its entry of δ, every orientation turned by its three (a rotation vector
/// in body axes, [`plus`](super::plus)). δ has N entries in the order of
/// [`VELOCITIES`](Lagrangian::VELOCITIES).
///
/// (Chapter 4 of the guide, *Orientation utilities*, has an example.)
///
/// # Errors
/// [`Error::NonUnitQuaternion`] for a quaternion of q off the unit sphere
/// (one within 1e-6 of it is normalised first); [`Error::Settings`] for a
/// non-finite entry.
pub fn configuration_plus<S, T, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    delta: &SVector<T, N>,
) -> Result<SVector<T, Q>, Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    let _ = sys;
    let q = checked::<S, T, N, Q>(q, delta)?;
    Ok(group::plus(S::ORIENTATIONS, &q, delta))
}

/// q ⊖ q₀ for configurations of `sys`: δ (N entries) with q₀ ⊕ δ = q, an
/// orientation's the short way round ([`minus`](super::minus)). The state
/// a linear model of `sys` ([`Linearizer::tangent_driven`]) has in its
/// first N entries, and what a [`StateFeedback`] from a tangent gain feeds
/// back.
///
/// [`Linearizer::tangent_driven`]: crate::linear::Linearizer::tangent_driven
/// [`StateFeedback`]: crate::StateFeedback
///
/// # Errors
/// As [`configuration_plus`], for q and q₀.
pub fn configuration_minus<S, T, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    q0: &SVector<T, Q>,
) -> Result<SVector<T, N>, Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    let _ = sys;
    let q = checked::<S, T, N, Q>(q, &SVector::zeros())?;
    let q0 = checked::<S, T, N, Q>(q0, &SVector::zeros())?;
    let mut delta = SVector::<T, N>::zeros();
    group::difference(
        S::ORIENTATIONS,
        q0.as_slice(),
        q.as_slice(),
        delta.as_mut_slice(),
    );
    Ok(delta)
}

/// x ⊖ x₀ for states x = (q, v) of `sys`: (q ⊖ q₀, v − v₀), the 2·N
/// states of its tangent linearisation, in their order.
///
/// # Errors
/// As [`configuration_minus`]; [`Error::Settings`] for a non-finite v.
pub fn state_minus<S, T, const N: usize, const Q: usize>(
    sys: &S,
    (q, v): (&SVector<T, Q>, &SVector<T, N>),
    (q0, v0): (&SVector<T, Q>, &SVector<T, N>),
) -> Result<(SVector<T, N>, SVector<T, N>), Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    checked::<S, T, N, Q>(q, v)?;
    checked::<S, T, N, Q>(q0, v0)?;
    Ok((configuration_minus(sys, q, q0)?, v - v0))
}

/// The error of one point of a run in the tangent space of its reference:
/// (q ⊖ q_ref, v − v_ref) at time `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentError<T: Real, const N: usize> {
    /// The point's time.
    pub t: T,
    /// q ⊖ q_ref: an ordinary coordinate's difference, an orientation's
    /// rotation vector in the reference's body axes.
    pub position: SVector<T, N>,
    /// v − v_ref (an orientation's angular velocities in body axes).
    pub velocity: SVector<T, N>,
}

/// The tangent-space error of a run lives here, beside ⊖, so that the
/// integrators' solution type knows nothing of systems.
impl<T: Real, const N: usize, const Q: usize> Trajectory<T, N, Q> {
    /// At every recorded point, the state's difference from the fixed
    /// state (q_ref, v_ref) in the tangent space: [`state_minus`], e.g. a
    /// controlled run's distance from its set-point.
    ///
    /// # Errors
    /// As [`state_minus`], for the reference (the run's own points are on
    /// the unit sphere).
    pub fn tangent_error<S: Lagrangian<T, N, Q>>(
        &self,
        sys: &S,
        (q_ref, v_ref): (&SVector<T, Q>, &SVector<T, N>),
    ) -> Result<Vec<TangentError<T, N>>, Error> {
        self.errors(sys, |_| Some((*q_ref, *v_ref)))
    }

    /// At every recorded point at time t, the state's difference from the
    /// state of `reference` at t (read from its dense output, so the two
    /// runs need not share their times) in the tangent space: two
    /// integrators' or two tolerances' runs of one start compared point by
    /// point.
    ///
    /// # Errors
    /// [`Error::Settings`] if a point's time lies outside `reference`'s
    /// span.
    pub fn tangent_error_along<S: Lagrangian<T, N, Q>>(
        &self,
        sys: &S,
        reference: &Trajectory<T, N, Q>,
    ) -> Result<Vec<TangentError<T, N>>, Error> {
        self.errors(sys, |t| reference.state_at(t))
    }

    fn errors<S: Lagrangian<T, N, Q>>(
        &self,
        sys: &S,
        reference: impl Fn(T) -> Option<(SVector<T, Q>, SVector<T, N>)>,
    ) -> Result<Vec<TangentError<T, N>>, Error> {
        let points = self.positions().iter().zip(self.velocities());
        self.times()
            .iter()
            .zip(points)
            .map(|(&t, (q, v))| {
                let (q_ref, v_ref) = reference(t).ok_or_else(|| {
                    super::invalid(
                        "Trajectory::tangent_error_along",
                        format!("t = {} lies outside the reference run", t.to_f64()),
                    )
                })?;
                let (position, velocity) = state_minus(sys, (q, v), (&q_ref, &v_ref))?;
                Ok(TangentError {
                    t,
                    position,
                    velocity,
                })
            })
            .collect()
    }
}

/// q checked and normalised as a run's initial state is (finite, its
/// quaternions unit), with a finite tangent vector or velocity.
fn checked<S, T, const N: usize, const Q: usize>(
    q: &SVector<T, Q>,
    delta: &SVector<T, N>,
) -> Result<SVector<T, Q>, Error>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    if !q.iter().chain(delta.iter()).all(|x| x.is_finite()) {
        return Err(super::invalid(
            "orientation",
            format!(
                "a configuration or tangent vector is not finite: q = {:?}, δ = {:?}",
                q.iter().map(|x| x.to_f64()).collect::<Vec<_>>(),
                delta.iter().map(|x| x.to_f64()).collect::<Vec<_>>()
            ),
        ));
    }
    unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, *q)
}
