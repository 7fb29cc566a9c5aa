//! The linearisations with the default [`Linearizer`] settings.

use super::Linear;
use super::settings::{Linearizer, OperatingPoint};
use crate::error::Error;
use crate::numeric::Real;
use crate::system::{Constrained, Driven, Lagrangian, Reduced};
use nalgebra::SVector;

/// [`Linearizer::unconstrained`] with the default settings: ẋ = A x + B u
/// about `op`, for a system without constraints.
///
/// A system with free orientations takes its point on the rotation group,
/// [`OperatingPoint::on_group`] (each quaternion's four numbers in q, the
/// body-axis angular velocities in v), and is linearised in its tangent
/// space, as [`Linearizer::tangent_driven`] does:
///
/// ```
/// # use lagrange_runtime::{Driven, Lagrangian, Orientation};
/// # use nalgebra::{SMatrix, SVector};
/// # struct Ball;
/// # impl Lagrangian<f64, 3, 4> for Ball {
/// #     const COORDINATES: [&'static str; 4] = ["ball.w", "ball.x", "ball.y", "ball.z"];
/// #     const VELOCITIES: [&'static str; 3] = ["ball.wx", "ball.wy", "ball.wz"];
/// #     const ORIENTATIONS: &'static [Orientation] = &[Orientation { q: 0, v: 0 }];
/// #     const RHEONOMIC: bool = false;
/// #     fn mass_matrix(&self, _: &SVector<f64, 4>, _: f64) -> SMatrix<f64, 3, 3> { SMatrix::identity() }
/// #     fn bias(&self, _: &SVector<f64, 4>, _: &SVector<f64, 3>, _: f64) -> SVector<f64, 3> { SVector::zeros() }
/// #     fn generalized_forces(&self, _: &SVector<f64, 4>, _: &SVector<f64, 3>, _: f64) -> SVector<f64, 3> { SVector::zeros() }
/// #     fn mass_matrix_and_rhs(&self, q: &SVector<f64, 4>, v: &SVector<f64, 3>, t: f64) -> (SMatrix<f64, 3, 3>, SVector<f64, 3>) {
/// #         (self.mass_matrix(q, t), SVector::zeros())
/// #     }
/// #     fn kinetic_energy(&self, _: &SVector<f64, 4>, v: &SVector<f64, 3>, _: f64) -> f64 { v.norm_squared() / 2.0 }
/// #     fn potential_energy(&self, _: &SVector<f64, 4>, _: f64) -> f64 { 0.0 }
/// #     fn integral(&self, q: &SVector<f64, 4>, v: &SVector<f64, 3>, t: f64) -> f64 { self.kinetic_energy(q, v, t) }
/// # }
/// # impl Driven<f64, 3, 0, 4> for Ball {}
/// use lagrange_runtime::linear::{OperatingPoint, linearize};
/// use lagrange_runtime::orientation;
/// // A free ball of unit inertia, at rest in some attitude.
/// let attitude = orientation::from_axis_angle(&nalgebra::Vector3::x(), 0.5)?;
/// let lin = linearize(&Ball, &OperatingPoint::on_group(attitude, SVector::zeros()))?;
/// assert_eq!(lin.states()[0], "ball.θx"); // δθ in body axes, then δω
/// assert_eq!(lin.a().nrows(), 6);
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
///
/// # Errors
/// As [`Linearizer::unconstrained`].
pub fn linearize<S, T, const N: usize, const P: usize, const U: usize, const Q: usize>(
    sys: &S,
    op: &OperatingPoint<T, N, U, Q>,
) -> Result<Linear, Error>
where
    S: Driven<T, N, P, Q>,
    T: Real,
{
    Linearizer::new().unconstrained(sys, op)
}

/// [`Linearizer::constrained`] with the default settings (automatic independent
/// coordinates and speeds).
///
/// # Errors
/// As [`Linearizer::constrained`].
pub fn linearize_constrained<S, T, const N: usize, const K: usize, const P: usize, const U: usize>(
    sys: &S,
    op: &OperatingPoint<T, N, U>,
) -> Result<Linear, Error>
where
    S: Constrained<T, N, K> + Driven<T, N, P>,
    T: Real,
{
    Linearizer::new().constrained(sys, op)
}

/// [`Linearizer::reduced`] with the default settings.
///
/// # Errors
/// As [`Linearizer::reduced`].
pub fn linearize_reduced<S, T, const N: usize, const K: usize, const P: usize, const U: usize>(
    sys: &S,
    op: &OperatingPoint<T, N, U>,
) -> Result<Linear, Error>
where
    S: Reduced<T, N, K> + Driven<T, N, P>,
    T: Real,
{
    Linearizer::new().reduced(sys, op)
}

/// [`Linearizer::complete_state`] with the given independent coordinates and
/// speeds (empty slices for the automatic choice) and default tolerances.
///
/// # Errors
/// As [`Linearizer::complete_state`].
pub fn complete_state<S, T, const N: usize>(
    sys: &S,
    q: SVector<T, N>,
    v: SVector<T, N>,
    t: T,
    coordinates: &[&str],
    speeds: &[&str],
) -> Result<(SVector<T, N>, SVector<T, N>), Error>
where
    S: Lagrangian<T, N>,
    T: Real,
{
    let mut lin = Linearizer::new();
    if !coordinates.is_empty() {
        lin = lin.coordinates(coordinates);
    }
    if !speeds.is_empty() {
        lin = lin.speeds(speeds);
    }
    lin.complete_state(sys, q, v, t)
}
