//! Linearisation of a system with orientations, in the tangent space.
//!
//! A state near (q*, v*) is written q = q* ⊕ δ (an ordinary coordinate moved
//! by its δ, an orientation turned by the rotation vector δθ in body axes:
//! q* ⊗ exp(δθ), Pinocchio's `integrate`) and v = v* + δv, so the state of
//! the linear model is (δ, δv), 2·N numbers, not the quaternions' four
//! components. With body-axis angular velocities, q̇ = ½ q ⊗ (0, ω) gives to
//! first order
//!
//! ```text
//! δθ̇ = δω − ω* × δθ,     δq̇_i = δv_i,     δv̇ = ∂a/∂δ δ + ∂a/∂v δv
//! ```
//!
//! (the −ω* × δθ term is what makes a steady spin, the sleeping top's,
//! a relative equilibrium with a constant A). ∂a/∂δ and ∂a/∂v are
//! M⁻¹ J_q and M⁻¹ J_v when the system has the right-hand side's Jacobians
//! ([`Lagrangian::rhs_jacobians`], `emit(jacobians)`: on a tree the
//! derivatives of recursive Newton–Euler in the tangent space, exact), else
//! central differences of the forward dynamics along δ and v, each step the
//! cube root of the machine epsilon times the entry's scale: a relative error
//! about 1e-10.

use super::Linear;
use super::difference::{column, unit};
use super::settings::Linearizer;
use crate::error::{Error, check_finite_inputs, check_tolerance, unit_quaternions};
use crate::mechanics::{Dynamics, ForceJacobians, Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation;
use crate::system::{Driven, Lagrangian};
use nalgebra::{DMatrix, SVector};

impl Linearizer {
    /// Linearises an unconstrained system whose configuration holds
    /// orientations (unit quaternions, `orientation(..)` in a description)
    /// about the state (q, v) at time t, in the tangent space: the states are
    /// δ (the coordinates' changes and each orientation's rotation vector in
    /// body axes, named `<name>.θx`, …) and δv (an ordinary coordinate's rate
    /// named with a prime, `x'`, an angular velocity by its name, `<name>.wx`), 2·N in
    /// all. A steady motion (a spinning body) linearises to a constant A when
    /// it is a relative equilibrium, and its stability reads off A's
    /// eigenvalues as for an equilibrium.
    ///
    /// # Errors
    /// [`Error::NonUnitQuaternion`] for a quaternion further than the
    /// tolerance from unit norm; [`Error::Settings`] for a bad singular
    /// tolerance; [`Error::NonPhysicalParameter`] from
    /// [`check_parameters`](Lagrangian::check_parameters); whatever the forward
    /// dynamics report at a perturbed state ([`Error::SingularMassMatrix`],
    /// [`Error::NonFiniteState`]).
    pub fn tangent<S, T, const N: usize, const Q: usize>(
        &self,
        sys: &S,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
    ) -> Result<Linear, Error>
    where
        S: Lagrangian<T, N, Q>,
        T: Real,
    {
        let (_, a) = self.tangent_a(sys, q, v, t, (NoForcing, None))?;
        Ok(Linear::from_parts(
            a,
            DMatrix::zeros(2 * N, 0),
            states::<S, T, N, Q>(),
            Vec::new(),
            N,
            None,
        ))
    }

    /// [`tangent`](Self::tangent) of a [`Driven`] system at the inputs `u`
    /// (held at u in A): B (2·N × P) has rows zero in δ and M⁻¹ ∂Q/∂u in δv,
    /// from the system's input Jacobian (an orientation's rows are the
    /// body-axis torques' share of ω̇).
    ///
    /// # Errors
    /// As [`tangent`](Self::tangent); [`Error::NonFiniteInput`] for a
    /// non-finite u.
    pub fn tangent_driven<S, T, const N: usize, const P: usize, const Q: usize>(
        &self,
        sys: &S,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
        t: T,
    ) -> Result<Linear, Error>
    where
        S: Driven<T, N, P, Q>,
        T: Real,
    {
        check_finite_inputs(&S::INPUTS, t, q, v, u)?;
        let q = &unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, *q)?;
        let (du, dq, dv) = sys.input_jacobians(q, v, u, t);
        let held = Held { system: sys, u: *u };
        let (q, a) = self.tangent_a(sys, q, v, t, (held, Some((dq, dv))))?;
        let m = sys.mass_matrix(&q, t);
        let chol = Cholesky::new(m, T::lit(self.tolerances.singular))
            .map_err(|ratio| Error::singular_mass(t, &q, ratio, &m, (&S::VELOCITIES, S::ATLAS)))?;
        let mut b = DMatrix::zeros(2 * N, P);
        for k in 0..P {
            let column = chol.solve(du.column(k).into_owned());
            for i in 0..N {
                b[(N + i, k)] = column[i].to_f64();
            }
        }
        if !b.iter().all(|x| x.is_finite()) {
            return Err(Error::non_finite(t, &q, v));
        }
        let inputs = S::INPUTS.iter().map(|s| s.to_string()).collect();
        Ok(Linear::from_parts(
            a,
            b,
            states::<S, T, N, Q>(),
            inputs,
            N,
            None,
        ))
    }

    /// The unit-normalised q and A (2·N × 2·N) of the tangent linearisation
    /// of the dynamics with `forcing` added, whose own Jacobians
    /// (∂ΔQ/∂δ, ∂ΔQ/∂v) are given when it has any.
    fn tangent_a<S, T, F, const N: usize, const Q: usize>(
        &self,
        sys: &S,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        t: T,
        (forcing, forced): (F, Option<ForceJacobians<T, N>>),
    ) -> Result<(SVector<T, Q>, DMatrix<f64>), Error>
    where
        S: Lagrangian<T, N, Q>,
        T: Real,
        F: Forcing<T, N, Q>,
    {
        check_tolerance("Linearizer", "singular tolerance", self.tolerances.singular)?;
        sys.check_parameters()?;
        let q = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, *q)?;
        let dynamics = Dynamics::new(sys)
            .with_singular_tolerance(T::lit(self.tolerances.singular))
            .with_forcing(forcing);
        let accel = |q: &SVector<T, Q>, v: &SVector<T, N>| dynamics.acceleration(t, q, v);
        let mut a = DMatrix::zeros(2 * N, 2 * N);
        a.view_mut((0, N), (N, N)).fill_with_identity();
        for o in S::ORIENTATIONS {
            let w = [v[o.v], v[o.v + 1], v[o.v + 2]].map(|x| x.to_f64());
            // −[ω*]×
            let block = [[0.0, w[2], -w[1]], [-w[2], 0.0, w[0]], [w[1], -w[0], 0.0]];
            for (i, row) in block.iter().enumerate() {
                for (j, &x) in row.iter().enumerate() {
                    a[(o.v + i, o.v + j)] = x;
                }
            }
        }
        if let Some((dq, dv)) = dynamics.state_derivatives(t, &q, v, forced)? {
            for i in 0..N {
                for j in 0..N {
                    a[(N + i, j)] = dq[(i, j)].to_f64();
                    a[(N + i, N + j)] = dv[(i, j)].to_f64();
                }
            }
            return Ok((q, a));
        }
        for j in 0..N {
            let (h, e) = unit::<T, N>(j, v[j].to_f64());
            let along = |d: SVector<T, N>| accel(&orientation::plus(S::ORIENTATIONS, &q, &d), v);
            let dq = column(along(e)?, along(-e)?, h);
            let dv = column(accel(&q, &(v + e))?, accel(&q, &(v - e))?, h);
            for i in 0..N {
                a[(N + i, j)] = dq[i];
                a[(N + i, N + j)] = dv[i];
            }
        }
        Ok((q, a))
    }
}

/// The inputs held at u: the generalized forces they add, at every state.
/// (The linearisation sits below the controllers; this is all it needs of
/// them.)
pub(super) struct Held<'s, S, T: Real, const P: usize> {
    pub(super) system: &'s S,
    pub(super) u: SVector<T, P>,
}

impl<S, T, const N: usize, const P: usize, const Q: usize> Forcing<T, N, Q> for Held<'_, S, T, P>
where
    S: Driven<T, N, P, Q>,
    T: Real,
{
    fn force(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> Result<SVector<T, N>, Error> {
        Ok(self.system.input_forces(q, v, &self.u, t))
    }
}

/// The states' names: each velocity's tangent direction (an ordinary
/// coordinate's own name, an orientation's `<name>.θx`, …), then the
/// velocities: an ordinary coordinate's rate with a prime (`x'`), an
/// orientation's angular velocity by its own name (`<name>.wx`, …: it is
/// the rate of `<name>.θx` at the operating point, and `<name>.wx'` would
/// read as ω's rate).
pub(crate) fn states<S: Lagrangian<T, N, Q>, T: Real, const N: usize, const Q: usize>()
-> Vec<String> {
    let mut tangent: Vec<String> = S::VELOCITIES.iter().map(|v| v.to_string()).collect();
    for o in S::ORIENTATIONS {
        let w = S::COORDINATES[o.q];
        let body = w.strip_suffix(".w").unwrap_or(w);
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            tangent[o.v + k] = format!("{body}.θ{axis}");
        }
    }
    let mut speeds: Vec<String> = S::VELOCITIES.iter().map(|v| format!("{v}'")).collect();
    for o in S::ORIENTATIONS {
        for k in 0..3 {
            speeds[o.v + k] = S::VELOCITIES[o.v + k].to_string();
        }
    }
    tangent.into_iter().chain(speeds).collect()
}

#[cfg(test)]
mod tests {
    use crate::linear::{Linearizer, OperatingPoint, linearize};
    use crate::orientation::identity;
    use crate::orientation::tests::{CartAndBall, configuration};
    use nalgebra::SVector;

    #[test]
    fn an_angular_velocity_state_is_named_as_the_velocity_it_is() {
        let q = configuration(0.0, identity());
        let v = SVector::<f64, 4>::from([0.0, 0.0, 0.0, 1.5]);
        let lin = Linearizer::new()
            .tangent(&CartAndBall, &q, &v, 0.0)
            .unwrap();
        let states = [
            "x", "ball.θx", "ball.θy", "ball.θz", "x'", "ball.wx", "ball.wy", "ball.wz",
        ];
        assert_eq!(lin.states(), states);
        // The former spelling of an angular velocity still finds it; a
        // coordinate's rate keeps its prime.
        assert_eq!(lin.state_index("ball.wz'"), Some(7));
        assert_eq!(lin.state_index("x'"), Some(4));
        assert_eq!(lin.state_index("ball.θx'"), None);
        assert_eq!(lin.select(&["x", "x'"]).unwrap().states(), ["x", "x'"]);
        // `linearize` at the point on the group is the same model.
        let same = linearize(&CartAndBall, &OperatingPoint::on_group(q, v)).unwrap();
        assert_eq!(same.a(), lin.a());
        assert_eq!(same.states(), lin.states());
    }
}
