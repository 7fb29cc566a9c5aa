//! Forward dynamics: q̈ = M⁻¹ (Q − h + ΔQ), ΔQ an optional [`Forcing`]
//! (the inputs of a driven system; nothing by default).
//!
//! The mass matrix is factorised by the stack Cholesky of [`crate::cholesky`], whose
//! pivot ratio tells a *near*-singular mass matrix (a chart singularity such as the
//! pole of a spherical pendulum) from a healthy one.

use crate::error::{Error, check_tolerance};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation::{self, Orientation};
use crate::ode::SecondOrder;
use crate::system::Lagrangian;
use nalgebra::{SMatrix, SVector};

/// Default threshold on min_i L_ii² / max_i L_ii² below which the mass matrix is
/// declared singular.
pub const DEFAULT_SINGULAR_TOLERANCE: f64 = 1e-12;

/// The forward dynamics of a [`Lagrangian`] system, as a right-hand side for the
/// integrators.
///
/// `F` is an extra generalized force ΔQ(t, q, q̇) added to Q − h, e.g. the
/// forces of a controller's inputs ([`InputForces`](crate::InputForces)); set it
/// with [`with_forcing`](Self::with_forcing). The default, [`NoForcing`], adds
/// nothing and costs nothing (the branch is removed at compile time).
///
/// The singularity test compares the squared pivots of the Cholesky factor. It is a
/// cheap lower bound on the conditioning, not the condition number itself, and it is
/// not invariant under rescaling a single coordinate: for coordinates with very
/// different units (metres and radians, say) choose the tolerance accordingly.
#[derive(Debug)]
pub struct Dynamics<'a, S, T, F = NoForcing> {
    system: &'a S,
    singular_tolerance: T,
    forcing: F,
    /// The system's parameter-only terms, if computed once for this run (see
    /// [`with_parameter_terms`](Dynamics::with_parameter_terms)).
    terms: &'a [T],
}

// Manual impls: derive would demand `S: Clone`, but only a reference is held.
impl<S, T: Copy, F: Copy> Clone for Dynamics<'_, S, T, F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, T: Copy, F: Copy> Copy for Dynamics<'_, S, T, F> {}

impl<'a, S, T: Real> Dynamics<'a, S, T> {
    /// Dynamics of `system` with the default singular tolerance (1e-12), unforced.
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            singular_tolerance: T::lit(DEFAULT_SINGULAR_TOLERANCE),
            forcing: NoForcing,
            terms: &[],
        }
    }
}

impl<'a, S, T: Real, F> Dynamics<'a, S, T, F> {
    /// The same dynamics with the generalized force `forcing` added to Q − h
    /// (replacing any forcing set before).
    pub fn with_forcing<G>(self, forcing: G) -> Dynamics<'a, S, T, G> {
        Dynamics {
            system: self.system,
            singular_tolerance: self.singular_tolerance,
            forcing,
            terms: self.terms,
        }
    }

    /// The same dynamics reading the system's parameter-only terms from `terms`
    /// (from [`Lagrangian::parameter_terms`] of this system, computed once)
    /// instead of recomputing them at every call. The runs of
    /// [`Simulation`](crate::Simulation) do this themselves: the parameters are
    /// borrowed for the whole run, so the terms cannot go stale.
    pub fn with_parameter_terms<'b>(self, terms: &'b [T]) -> Dynamics<'b, S, T, F>
    where
        'a: 'b,
    {
        // Shortening the borrow is a coercion (the dynamics only hold
        // references), so the rest of the settings carry over as they are.
        let shorter: Dynamics<'b, S, T, F> = self;
        Dynamics { terms, ..shorter }
    }

    /// The forcing in use.
    pub fn forcing(&self) -> &F {
        &self.forcing
    }

    /// Sets the threshold on min L_ii² / max L_ii² below which the mass matrix is
    /// reported as singular; a negative or non-finite one is refused
    /// ([`Error::Settings`]) at the first evaluation.
    pub fn with_singular_tolerance(mut self, tolerance: T) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The singular tolerance in use.
    pub fn singular_tolerance(&self) -> T {
        self.singular_tolerance
    }

    /// The generalized accelerations q̈ at (t, q, v).
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] if the state, M, Q − h (+ ΔQ) or the result is not
    /// finite; [`Error::SingularMassMatrix`] if M is not positive definite or its
    /// pivot ratio is below the singular tolerance; whatever the forcing reports
    /// (e.g. [`Error::NonFiniteInput`]).
    pub fn acceleration<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (mut unit, mut tau) = (SVector::zeros(), SVector::zeros());
        self.check_into(t, q, v, (&mut unit, &mut tau))?;
        if let Some(a) = self.articulated(t, &unit, v, &tau)? {
            return Ok(a);
        }
        self.factorised(t, &unit, v, tau).map(|(_, a)| a)
    }

    /// q̈ at (t, q, v) through M and Q − h, M factorised at run time
    /// (Cholesky), even where the system emits q̈ as one program
    /// (`emit(articulated)`, which [`acceleration`](Self::acceleration)
    /// takes; [`Lagrangian::FORWARD_ROUTE`] says by which route). The two
    /// agree to round-off; this one is there to compare them, and to check
    /// one against the other.
    ///
    /// # Errors
    /// As [`acceleration`](Self::acceleration).
    pub fn acceleration_from_mass_matrix<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (unit, tau) = self.checked(t, q, v)?;
        self.factorised(t, &unit, v, tau).map(|(_, a)| a)
    }

    /// The state's checks (finite, the tolerance), q on the unit sphere (a
    /// Runge–Kutta stage leaves it by its local error: the equations see the
    /// rotation it is closest to) and the forcing's generalized forces.
    pub(super) fn checked<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<(SVector<T, Q>, SVector<T, N>), Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (mut unit, mut tau) = (SVector::zeros(), SVector::zeros());
        self.check_into(t, q, v, (&mut unit, &mut tau))?;
        Ok((unit, tau))
    }

    /// [`checked`](Self::checked), written over `unit` and `tau` where the
    /// caller keeps them: the state is not moved through a `Result` (on
    /// Solo 12, a chain of copies of q, some of them waiting for the stores
    /// just made, cost its q̈ 60 ns).
    #[inline(always)]
    pub(super) fn check_into<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        (unit, tau): (&mut SVector<T, Q>, &mut SVector<T, N>),
    ) -> Result<(), Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        refuse_constrained::<S, T, N, Q>();
        if !(t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        *unit = *q;
        orientation::normalise(S::ORIENTATIONS, unit.as_mut_slice());
        check_tolerance(
            "Dynamics",
            "singular tolerance",
            self.singular_tolerance.to_f64(),
        )?;
        *tau = if F::ACTIVE {
            self.forcing.force(t, unit, v)?
        } else {
            SVector::zeros()
        };
        Ok(())
    }

    /// M's Cholesky factor and q̈ = M⁻¹(Q − h + τ) at a checked state.
    /// Inlined, so that M and the factor are not copied between frames
    /// (`memcpy` calls of M's size, 15 % of a UR5's q̈ before).
    #[inline(always)]
    pub(super) fn factorised<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: SVector<T, N>,
    ) -> Result<(Cholesky<T, N>, SVector<T, N>), Error>
    where
        S: Lagrangian<T, N, Q>,
    {
        let (m, rhs) = self.system.mass_matrix_and_rhs_with(self.terms, q, v, t);
        let rhs = rhs + tau;
        if !(all_finite(m.as_slice()) && all_finite(rhs.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        let chol = Cholesky::new(m, self.singular_tolerance)
            .map_err(|ratio| Error::singular_mass(t, q, ratio, &m, (&S::VELOCITIES, S::ATLAS)))?;
        let a = chol.solve(rhs);
        // Finite M and rhs with acceptable pivots can still overflow.
        if !all_finite(a.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok((chol, a))
    }
}

impl<S, T: Real, F> Dynamics<'_, S, T, F> {
    /// q̈ by the system's articulated-body algorithm, if it emits one, with the
    /// forcing's generalized forces `tau`; its pivot ratio is checked against the
    /// same tolerance as the Cholesky factorisation's.
    fn articulated<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: &SVector<T, N>,
    ) -> Result<Option<SVector<T, N>>, Error>
    where
        S: Lagrangian<T, N, Q>,
    {
        let Some((a, ratio)) = self.system.forward_dynamics_with(self.terms, q, v, tau, t) else {
            return Ok(None);
        };
        // A NaN ratio (a NaN pivot) is refused too; the ratio is at most 1.
        if !ratio.is_finite() || ratio < self.singular_tolerance {
            let m = self.system.mass_matrix(q, t);
            return Err(Error::singular_mass(
                t,
                q,
                ratio,
                &m,
                (&S::VELOCITIES, S::ATLAS),
            ));
        }
        if !all_finite(a.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Some(a))
    }
}

impl<S, T, F, const N: usize, const Q: usize> SecondOrder<T, N, Q> for Dynamics<'_, S, T, F>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
    F: Forcing<T, N, Q>,
{
    const ORIENTATIONS: &'static [Orientation] = S::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        Dynamics::acceleration(self, t, q, v)
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.system.integral(&on_sphere::<S, T, N, Q>(q), v, t)
    }

    fn mechanical(&self) -> Option<&dyn crate::ode::Mechanical<T, N, Q>> {
        Some(self)
    }

    /// ∂q̈/∂q = M⁻¹ J_q and ∂q̈/∂q̇ = M⁻¹ J_v from the system's
    /// [`rhs_jacobians`](Lagrangian::rhs_jacobians), when it has them and the
    /// dynamics are unforced (a forcing's dependence on the state, such as a
    /// feedback law, is unknown here: forced dynamics fall back to finite
    /// differences). With orientations the system's Jacobians are in the
    /// tangent space, not in the quaternions' R⁴: finite differences too.
    fn jacobian(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Option<Result<(SMatrix<T, N, Q>, SMatrix<T, N, N>), Error>> {
        if F::ACTIVE || !S::ORIENTATIONS.is_empty() {
            return None;
        }
        let a = match Dynamics::acceleration(self, t, q, v) {
            Ok(a) => a,
            Err(e) => return Some(Err(e)),
        };
        let (jq, jv) = self.system.rhs_jacobians(q, v, &a, t)?;
        let m = self.system.mass_matrix(q, t);
        let chol = match Cholesky::new(m, self.singular_tolerance) {
            Ok(c) => c,
            Err(ratio) => {
                return Some(Err(Error::singular_mass(
                    t,
                    q,
                    ratio,
                    &m,
                    (&S::VELOCITIES, S::ATLAS),
                )));
            }
        };
        let solve = |j: SMatrix<T, N, N>| {
            let mut out = j;
            for (k, col) in j.column_iter().enumerate() {
                out.set_column(k, &chol.solve(col.into_owned()));
            }
            out
        };
        let dq = solve(jq);
        let dv = solve(jv);
        if !(all_finite(dq.as_slice()) && all_finite(dv.as_slice())) {
            return Some(Err(Error::non_finite(t, q, v)));
        }
        // Q = N here (no orientations): the same matrix, retyped.
        Some(Ok((SMatrix::from_fn(|i, j| dq[(i, j)]), dv)))
    }
}

/// The generalized accelerations of `sys` at (q, v, t) with the default singular
/// tolerance. See [`Dynamics::acceleration`].
///
/// # Errors
/// [`Error::NonFiniteState`] or [`Error::SingularMassMatrix`].
pub fn accelerations<S: Lagrangian<T, N, Q>, T: Real, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
    t: T,
) -> Result<SVector<T, N>, Error> {
    Dynamics::new(sys).acceleration(t, q, v)
}

/// Refuses at compile time a system whose constraints these dynamics would
/// ignore (see [`Lagrangian::CONSTRAINED`]): the error appears where the
/// unconstrained dynamics of such a system is instantiated.
#[inline(always)]
pub(crate) fn refuse_constrained<
    S: Lagrangian<T, N, Q>,
    T: Real,
    const N: usize,
    const Q: usize,
>() {
    const {
        assert!(
            !<S as Lagrangian<T, N, Q>>::CONSTRAINED,
            "this system has constraints, which the unconstrained dynamics would ignore: run it with `run_constrained` (multipliers) or `run_reduced` (independent speeds), and find its equilibria with `Trim::solve_constrained`"
        )
    };
}

/// q with its quaternions scaled to unit norm (q itself without orientations).
#[inline(always)]
pub(crate) fn on_sphere<S: Lagrangian<T, N, Q>, T: Real, const N: usize, const Q: usize>(
    q: &SVector<T, Q>,
) -> SVector<T, Q> {
    let mut unit = *q;
    orientation::normalise(S::ORIENTATIONS, unit.as_mut_slice());
    unit
}

pub(crate) fn all_finite<T: Real>(xs: &[T]) -> bool {
    xs.iter().all(|x| x.is_finite())
}
