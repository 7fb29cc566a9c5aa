//! Forward dynamics of a nonholonomic system in reduced form (independent speeds).
//!
//! The integrators carry (q, q̇), not (q, u): the reduced form then plugs into every
//! integrator unchanged, and trajectories look the same whichever form produced
//! them. The price is that a Runge–Kutta combination of q̇'s need not lie in the
//! image of W u + w when W depends on q; u = U q̇ + u₀ reads off the speeds anyway,
//! and [`SecondOrder::project`] rebuilds q̇ from them after every step, which keeps
//! the velocity constraints at round-off (it reports a change, and so costs an
//! FSAL integrator an evaluation, only when q̇ moved by more than a few ulps).

use crate::cholesky::Cholesky;
use crate::control::{Forcing, NoForcing};
use crate::dynamics::{DEFAULT_SINGULAR_TOLERANCE, all_finite};
use crate::error::{Error, to_vec};
use crate::func::abs;
use crate::ode::SecondOrder;
use crate::real::Real;
use crate::system::Reduced;
use nalgebra::SVector;

/// The forward dynamics of a [`Reduced`] system with K independent speeds:
/// u = speeds(q, q̇), M* u̇ = F* by Cholesky, q̈ = W u̇ + κ.
///
/// `F` is an extra generalized force ΔQ(t, q, q̇) (see
/// [`Dynamics`](crate::Dynamics) and [`with_forcing`](Self::with_forcing)),
/// projected onto the speeds: F* += Wᵀ ΔQ. The default [`NoForcing`] adds nothing.
#[derive(Debug)]
pub struct ReducedDynamics<'a, S, T, const K: usize, F = NoForcing> {
    system: &'a S,
    singular_tolerance: T,
    forcing: F,
}

// Manual impls: derive would demand `S: Clone`, but only a reference is held.
impl<S, T: Copy, const K: usize, F: Copy> Clone for ReducedDynamics<'_, S, T, K, F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, T: Copy, const K: usize, F: Copy> Copy for ReducedDynamics<'_, S, T, K, F> {}

impl<'a, S, T: Real, const K: usize> ReducedDynamics<'a, S, T, K> {
    /// Dynamics of `system` with the default singular tolerance (1e-12), unforced.
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            singular_tolerance: T::lit(DEFAULT_SINGULAR_TOLERANCE),
            forcing: NoForcing,
        }
    }
}

impl<'a, S, T: Real, const K: usize, F> ReducedDynamics<'a, S, T, K, F> {
    /// The same dynamics with the generalized force `forcing` added to Q − h, so
    /// that F* gains Wᵀ ΔQ (replacing any forcing set before).
    pub fn with_forcing<G>(self, forcing: G) -> ReducedDynamics<'a, S, T, K, G> {
        ReducedDynamics {
            system: self.system,
            singular_tolerance: self.singular_tolerance,
            forcing,
        }
    }

    /// The forcing in use.
    pub fn forcing(&self) -> &F {
        &self.forcing
    }

    /// Sets the threshold on the pivot ratio of M* below which it is reported as
    /// singular.
    pub fn with_singular_tolerance(mut self, tolerance: T) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The speed derivatives u̇ and the accelerations q̈ at (t, q, v).
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] if the state, the reduced system or the result is
    /// not finite; [`Error::SingularMassMatrix`] if M* is not positive definite or
    /// its pivot ratio is below the singular tolerance; whatever the forcing
    /// reports (e.g. [`Error::NonFiniteInput`]).
    pub fn solve<const N: usize>(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<(SVector<T, K>, SVector<T, N>), Error>
    where
        S: Reduced<T, N, K>,
        F: Forcing<T, N>,
    {
        if !(t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let u = self.system.speeds(q, v, t);
        let (m, mut f, w, kappa) = self.system.reduced_system(q, &u, t);
        if F::ACTIVE {
            f += w.tr_mul(&self.forcing.force(t, q, v)?);
        }
        // The state is finite here: a non-finite W or κ is the reduction's
        // own pivot vanishing, unless the parameters are not finite.
        if !(all_finite(u.as_slice()) && all_finite(w.as_slice()) && all_finite(kappa.as_slice())) {
            return Err(self.non_finite_reduction(t, q, v));
        }
        if !(all_finite(m.as_slice()) && all_finite(f.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let du = Cholesky::new(m, self.singular_tolerance)
            .map_err(|ratio| Error::SingularMassMatrix {
                t: t.to_f64(),
                q: to_vec(q),
                ratio: ratio.to_f64(),
            })?
            .solve(f);
        let a = w * du + kappa;
        if !(all_finite(du.as_slice()) && all_finite(a.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok((du, a))
    }

    /// The velocities that satisfy the constraints with the speeds of v:
    /// velocities(q, speeds(q, v)).
    pub fn consistent_velocities<const N: usize>(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> SVector<T, N>
    where
        S: Reduced<T, N, K>,
    {
        let u = self.system.speeds(q, v, t);
        self.system.velocities(q, &u, t)
    }

    /// Why the reduction is not finite at a finite state: non-finite parameters
    /// show in the mass matrix too (the user's input), a vanishing pivot does
    /// not (the reduction's own breakdown).
    fn non_finite_reduction<const N: usize>(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Error
    where
        S: Reduced<T, N, K>,
    {
        if all_finite(self.system.mass_matrix(q, t).as_slice()) {
            breakdown::<S, T, N, K>(t, q)
        } else {
            Error::non_finite(t, q, v)
        }
    }

    /// The admissible initial velocities with the speeds of v, checked: they
    /// must be finite and reproduce those speeds (u = U W u + U w + u₀) to 1e-8
    /// relative. A symbolic pivot of the reduction that vanishes at q (a knife
    /// edge solved for ẋ heading along y, where cos θ = 6e-17 is not quite zero)
    /// fails the round trip, and the run stops before it starts instead of
    /// collapsing its step size on velocities of 1e16.
    ///
    /// # Errors
    /// [`Error::ReducedFormBreakdown`].
    pub fn initial_velocities<const N: usize>(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Reduced<T, N, K>,
    {
        let u = self.system.speeds(q, v, t);
        let w = self.system.velocities(q, &u, t);
        let back = self.system.speeds(q, &w, t);
        let scale = u.iter().fold(T::one(), |m, &x| m.max(abs(x)));
        let off = (back - u).iter().fold(T::zero(), |m, &x| m.max(abs(x)));
        if !all_finite(w.as_slice()) {
            return Err(self.non_finite_reduction(t, q, v));
        }
        if !off.is_finite() || off > T::lit(1e-8) * scale {
            return Err(breakdown::<S, T, N, K>(t, q));
        }
        Ok(w)
    }
}

impl<S, T, F, const N: usize, const K: usize> SecondOrder<T, N> for ReducedDynamics<'_, S, T, K, F>
where
    S: Reduced<T, N, K>,
    T: Real,
    F: Forcing<T, N>,
{
    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        Ok(self.solve(t, q, v)?.1)
    }

    fn integral(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> T {
        self.system.integral(q, v, t)
    }

    /// No position constraints are kept (they are built into the coordinates);
    /// the velocity residual is the distance of v from the admissible velocities,
    /// max |v − velocities(q, speeds(q, v))|, zero exactly when the velocity
    /// constraints hold (for U W = I).
    fn residuals(&self, t: T, q: &SVector<T, N>, v: &SVector<T, N>) -> [T; 2] {
        let d = self.consistent_velocities(t, q, v) - v;
        [T::zero(), d.iter().fold(T::zero(), |m, &x| m.max(abs(x)))]
    }

    fn project(&self, t: T, q: &mut SVector<T, N>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        let w = self.consistent_velocities(t, q, v);
        if !all_finite(w.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        // A round trip through the speeds moves an admissible v by a few ulps;
        // taking that as a change would cost FSAL integrators an evaluation per
        // step for nothing, so only a change beyond round-off counts.
        let scale = v.iter().fold(T::zero(), |m, &x| m.max(abs(x)));
        let change = (w - *v).iter().fold(T::zero(), |m, &x| m.max(abs(x)));
        if change <= T::lit(4.0) * T::default_epsilon() * scale {
            return Ok(false);
        }
        *v = w;
        Ok(true)
    }
}

/// The typed error for a reduced form that cannot be evaluated at a finite state.
pub(crate) fn breakdown<S: Reduced<T, N, K>, T: Real, const N: usize, const K: usize>(
    t: T,
    q: &SVector<T, N>,
) -> Error {
    Error::ReducedFormBreakdown {
        t: t.to_f64(),
        q: to_vec(q),
        coordinates: S::COORDINATES.to_vec(),
    }
}
