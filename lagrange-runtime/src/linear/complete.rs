//! A consistent state from a guess, in whichever form the system runs: the
//! dependent coordinates by Newton on Φ(q, t) = 0 with the independent ones
//! held, then the velocities the constraints allow.

use super::dense::{dm, dv, finite};
use super::partition::{complete_coordinates, holonomic, indices};
use super::settings::Linearizer;
use crate::error::SettingsError;
use crate::error::{Error, LinearError, to_vec};
use crate::mechanics::reduced::ReducedDynamics;
use crate::numeric::Real;
use crate::system::{Constrained, FormVisitor, Lagrangian, Reduced};
use nalgebra::{DMatrix, DVector, SVector};

/// A state: coordinates and velocities.
type State<T, const N: usize> = (SVector<T, N>, SVector<T, N>);

impl Linearizer {
    /// A consistent state from the independent coordinates and speeds of
    /// (q, v), for any system in the form it runs in:
    ///
    /// - multipliers: the dependent coordinates by Newton on Φ(q, t) = 0 with
    ///   the independent ones held fixed (starting from the dependent values in
    ///   `q`), then the dependent velocities from G q̇ + g = 0 with the
    ///   independent speeds held fixed; the partition is the named one
    ///   ([`coordinates`](Self::coordinates), [`speeds`](Self::speeds)), or
    ///   completed automatically at the given q;
    /// - reduced: the same Newton on the holonomic constraints
    ///   ([`Reduced::holonomic_positions`]), then the velocities W u + w with
    ///   the speeds u of `v` (the description's speeds: named
    ///   [`speeds`](Self::speeds) play no part);
    /// - unconstrained: (q, v) as given.
    ///
    /// # Errors
    /// [`Error::ProjectionFailed`] (where, the residual, the iterations) if Newton
    /// does not reach the tolerance; [`LinearError::InvalidPartition`],
    /// [`LinearError::SingularPartition`], [`Error::RedundantConstraints`] for the
    /// partition; [`Error::NonFiniteState`]; [`Error::Settings`] for a
    /// hand-written system that has constraints but does not name its form
    /// (implement [`Lagrangian::visit_form`]).
    ///
    /// [`LinearError::InvalidPartition`]: crate::LinearError::InvalidPartition
    /// [`LinearError::SingularPartition`]: crate::LinearError::SingularPartition
    pub fn complete_state<S, T, const N: usize>(
        &self,
        sys: &S,
        q: SVector<T, N>,
        v: SVector<T, N>,
        t: T,
    ) -> Result<State<T, N>, Error>
    where
        S: Lagrangian<T, N>,
        T: Real,
    {
        self.check_settings()?;
        if !(t.is_finite() && finite(&dm(&q)) && finite(&dm(&v))) {
            return Err(Error::non_finite(t, &q, &v));
        }
        sys.visit_form(Completion {
            settings: self,
            q,
            v,
            t,
        })
    }

    /// Newton on the holonomic constraints Φ (values by `phi`, Jacobian rows by
    /// `jacobian`) over the coordinates `dependent`, the others held. Once
    /// within the tolerance, one more step polishes Φ to round-off (kept only
    /// if it does not increase the residual).
    fn project_holonomic<T: Real, const N: usize>(
        &self,
        (mut q, v, t): (SVector<T, N>, &SVector<T, N>, T),
        coordinates: [&'static str; N],
        dependent: &[usize],
        phi: impl Fn(&SVector<T, N>) -> DVector<f64>,
        jacobian: impl Fn(&SVector<T, N>) -> DMatrix<f64>,
    ) -> Result<SVector<T, N>, Error> {
        let mut polish: Option<(SVector<T, N>, f64)> = None;
        let mut iterations = 0;
        loop {
            let residual_vector = phi(&q);
            let residual = residual_vector.amax();
            if !residual.is_finite() {
                return Err(Error::non_finite(t, &q, v));
            }
            if let Some((previous, r)) = polish {
                return Ok(if residual <= r { q } else { previous });
            }
            if residual <= self.newton_tolerance {
                if residual == 0.0 {
                    return Ok(q);
                }
                polish = Some((q, residual));
            } else if iterations == self.newton_iterations {
                return Err(Error::ProjectionFailed {
                    t: t.to_f64(),
                    q: to_vec(&q),
                    coordinates: coordinates.to_vec(),
                    residual,
                    iterations,
                    tolerance: self.newton_tolerance,
                });
            }
            let jd = jacobian(&q).select_columns(dependent.iter());
            let step = jd.lu().solve(&-residual_vector);
            let step = step.ok_or_else(|| Error::non_finite(t, &q, v))?;
            for (k, &i) in dependent.iter().enumerate() {
                q[i] += T::lit(step[k]);
            }
            iterations += 1;
        }
    }

    fn complete_multipliers<S, T, const N: usize, const K: usize>(
        &self,
        sys: &S,
        q: SVector<T, N>,
        mut v: SVector<T, N>,
        t: T,
    ) -> Result<State<T, N>, Error>
    where
        S: Constrained<T, N, K>,
        T: Real,
    {
        let h = holonomic::<S, T, N, K, N>();
        let (g, _) = sys.constraint_jacobian(&q, t);
        let part = self.partition::<S, T, N, K, N>(&dm(&g), (&q, t), [&S::COORDINATES; 2])?;
        let phi = |q: &SVector<T, N>| dv(&sys.constraint_positions(q, t)).rows(0, h).into_owned();
        let jac = |q: &SVector<T, N>| {
            let g = sys.constraint_jacobian(q, t).0;
            DMatrix::from_fn(h, N, |i, j| g[(i, j)].to_f64())
        };
        let q = self.project_holonomic((q, &v, t), S::COORDINATES, &part.cd, phi, jac)?;
        let (g, g0) = sys.constraint_jacobian(&q, t);
        let g = dm(&g);
        for &i in &part.sd {
            v[i] = T::zero();
        }
        let r = &g * dv(&v) + dv(&g0);
        let gd = g.select_columns(part.sd.iter());
        let dvd = gd
            .lu()
            .solve(&-r)
            .ok_or_else(|| Error::non_finite(t, &q, &v))?;
        for (k, &i) in part.sd.iter().enumerate() {
            v[i] = T::lit(dvd[k]);
        }
        checked(t, q, v)
    }

    fn complete_reduced<S, T, const N: usize, const K: usize>(
        &self,
        sys: &S,
        q: SVector<T, N>,
        v: SVector<T, N>,
        t: T,
    ) -> Result<State<T, N>, Error>
    where
        S: Reduced<T, N, K>,
        T: Real,
    {
        let h = S::HOLONOMIC;
        // The holonomic rows of the stacked velocity rows are Φ_q.
        let jac = |q: &SVector<T, N>| dm(&sys.velocity_rows(q, t).0).rows(K, h).into_owned();
        let named = match &self.coordinates {
            Some(names) => indices("coordinates", names, N - h, &S::COORDINATES)?,
            None => Vec::new(),
        };
        let (_, dependent, ratio) = complete_coordinates(&jac(&q), &named, &named, N - h);
        if h > 0 && !(ratio >= self.tolerances.redundant) {
            // No well-conditioned choice of dependent coordinates among those
            // not named: the named ones (or redundant constraints) leave none.
            return Err(LinearError::SingularPartition {
                what: "coordinates",
                dependent: dependent
                    .iter()
                    .map(|&i| S::COORDINATES[i].into())
                    .collect(),
                ratio,
            }
            .into());
        }
        let phi = |q: &SVector<T, N>| dv(&sys.holonomic_positions(q, t)).rows(0, h).into_owned();
        let q = if h == 0 {
            q
        } else {
            self.project_holonomic((q, &v, t), S::COORDINATES, &dependent, phi, jac)?
        };
        let v = ReducedDynamics::new(sys)
            .with_singular_tolerance(T::lit(self.tolerances.singular))
            .consistent_velocities(t, &q, &v)?;
        checked(t, q, v)
    }
}

fn checked<T: Real, const N: usize>(
    t: T,
    q: SVector<T, N>,
    v: SVector<T, N>,
) -> Result<State<T, N>, Error> {
    if finite(&dm(&q)) && finite(&dm(&v)) {
        Ok((q, v))
    } else {
        Err(Error::non_finite(t, &q, &v))
    }
}

/// Completion waiting for the system to name its form.
struct Completion<'a, T, const N: usize> {
    settings: &'a Linearizer,
    q: SVector<T, N>,
    v: SVector<T, N>,
    t: T,
}

impl<S, T, const N: usize> FormVisitor<T, N, S> for Completion<'_, T, N>
where
    S: Lagrangian<T, N>,
    T: Real,
{
    type Output = Result<State<T, N>, Error>;

    fn unconstrained(self, _: &S) -> Self::Output {
        if S::CONSTRAINED {
            return Err(SettingsError::Unsupported {
                owner: "complete_state",
                needs: "the form a constrained system runs in".into(),
                remedy: "this system has constraints but does not name it; implement \
                         `Lagrangian::visit_form` (the derive does)"
                    .into(),
            }
            .into());
        }
        Ok((self.q, self.v))
    }

    fn multipliers<const K: usize>(self, sys: &S) -> Self::Output
    where
        S: Constrained<T, N, K>,
    {
        (self.settings).complete_multipliers::<S, T, N, K>(sys, self.q, self.v, self.t)
    }

    fn reduced<const K: usize>(self, sys: &S) -> Self::Output
    where
        S: Reduced<T, N, K>,
    {
        (self.settings).complete_reduced::<S, T, N, K>(sys, self.q, self.v, self.t)
    }
}
