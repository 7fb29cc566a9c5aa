//! The dynamics of one chart in the form its description asked for: the
//! unconstrained equations, or constraints kept by multipliers, holonomic
//! rows first, then nonholonomic ones (the user's description and its twin
//! carry the same rows, the twin's written on its free orientation). The
//! reduced form has no place in the atlas: the derive refuses a
//! description emitted only in it, and one emitted in both forms answers
//! `multipliers` to the visitors here.

use crate::error::Error;
use crate::error::SettingsError;
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::mechanics::{Dynamics, Forcing};
use crate::numeric::Real;
use crate::ode::SecondOrder;
use crate::system::{Constrained, FormVisitor, Lagrangian, Reduced};
use nalgebra::{DMatrix, DVector, SVector};

/// A state of a chart: q of Q entries (with the twin's quaternions), v.
#[derive(Clone, Copy)]
pub(crate) struct At<'x, T: Real, const N: usize, const Q: usize> {
    pub t: T,
    pub q: &'x SVector<T, Q>,
    pub v: &'x SVector<T, N>,
}

/// The form's accelerations at a state, with a forcing.
pub(crate) struct Acceleration<'x, T: Real, const N: usize, const Q: usize, G> {
    pub at: At<'x, T, N, Q>,
    pub tolerance: T,
    pub forcing: G,
}

fn refused() -> Error {
    SettingsError::Unsupported {
        owner: "the atlas",
        needs: "constraints in the multiplier form".into(),
        remedy: "it does not run the reduced form; emit `formulation(multipliers)`".into(),
    }
    .into()
}

impl<T, L, G, const N: usize, const Q: usize> FormVisitor<T, N, L, Q>
    for Acceleration<'_, T, N, Q, G>
where
    T: Real,
    L: Lagrangian<T, N, Q>,
    G: Forcing<T, N, Q>,
{
    type Output = Result<SVector<T, N>, Error>;

    fn unconstrained(self, system: &L) -> Self::Output {
        let dynamics = Dynamics::new(system).with_singular_tolerance(self.tolerance);
        let At { t, q, v } = self.at;
        dynamics.with_forcing(self.forcing).acceleration(t, q, v)
    }

    fn multipliers<const K: usize>(self, system: &L) -> Self::Output
    where
        L: Constrained<T, N, K, Q>,
    {
        let dynamics = ConstrainedDynamics::<L, T, K>::new(system)
            .with_singular_tolerance(self.tolerance)
            .with_forcing(self.forcing);
        let At { t, q, v } = self.at;
        SecondOrder::acceleration(&dynamics, t, q, v)
    }

    fn reduced<const K: usize>(self, _: &L) -> Self::Output
    where
        L: Reduced<T, N, K, Q>,
    {
        Err(refused())
    }
}

/// The user's accelerations in the user's charts: the dynamics of the run
/// (its parameter terms computed once) without constraints, or the
/// multiplier form with the same forcing.
pub(crate) struct UserAcceleration<'d, 'x, S, T: Real, const N: usize, G> {
    pub dynamics: &'d Dynamics<'d, S, T, G>,
    pub at: At<'x, T, N, N>,
}

impl<S, T, G, const N: usize> FormVisitor<T, N, S> for UserAcceleration<'_, '_, S, T, N, G>
where
    T: Real,
    S: Lagrangian<T, N>,
    G: Forcing<T, N>,
{
    type Output = Result<SVector<T, N>, Error>;

    fn unconstrained(self, _: &S) -> Self::Output {
        let At { t, q, v } = self.at;
        self.dynamics.acceleration(t, q, v)
    }

    fn multipliers<const K: usize>(self, system: &S) -> Self::Output
    where
        S: Constrained<T, N, K>,
    {
        let dynamics = ConstrainedDynamics::<S, T, K>::new(system)
            .with_singular_tolerance(self.dynamics.singular_tolerance())
            .with_forcing(self.dynamics.forcing());
        let At { t, q, v } = self.at;
        SecondOrder::acceleration(&dynamics, t, q, v)
    }

    fn reduced<const K: usize>(self, _: &S) -> Self::Output
    where
        S: Reduced<T, N, K>,
    {
        Err(refused())
    }
}

/// A form's constraint rows at a configuration, as numbers: Φ (the
/// holonomic rows' positions), G and g, how many rows are holonomic (the
/// first), and the rows' names.
pub(crate) struct ChartRows {
    pub phi: DVector<f64>,
    pub g: DMatrix<f64>,
    pub g0: DVector<f64>,
    pub holonomic: usize,
    pub names: Vec<&'static str>,
}

/// The constraint rows at `q` (none without constraints; the reduced form
/// has no place in the atlas).
pub(crate) struct Rows<'x, T: Real, const N: usize, const Q: usize>(pub At<'x, T, N, Q>);

impl<T, L, const N: usize, const Q: usize> FormVisitor<T, N, L, Q> for Rows<'_, T, N, Q>
where
    T: Real,
    L: Lagrangian<T, N, Q>,
{
    type Output = ChartRows;

    fn unconstrained(self, _: &L) -> ChartRows {
        ChartRows {
            phi: DVector::zeros(0),
            g: DMatrix::zeros(0, N),
            g0: DVector::zeros(0),
            holonomic: 0,
            names: Vec::new(),
        }
    }

    fn multipliers<const K: usize>(self, system: &L) -> ChartRows
    where
        L: Constrained<T, N, K, Q>,
    {
        let At { t, q, .. } = self.0;
        let (g, g0) = system.constraint_jacobian(q, t);
        let holonomic = L::HOLONOMIC.min(K);
        let phi = system.constraint_positions(q, t);
        ChartRows {
            phi: DVector::from_fn(holonomic, |i, _| phi[i].to_f64()),
            g: DMatrix::from_fn(K, N, |i, j| g[(i, j)].to_f64()),
            g0: DVector::from_fn(K, |i, _| g0[i].to_f64()),
            holonomic,
            names: L::CONSTRAINTS.to_vec(),
        }
    }

    fn reduced<const K: usize>(self, system: &L) -> ChartRows
    where
        L: Reduced<T, N, K, Q>,
    {
        self.unconstrained(system)
    }
}

/// The constraint residuals [max |Φ|, max |G v + g|] at a state (zero
/// without constraints).
pub(crate) struct Residuals<'x, T: Real, const N: usize, const Q: usize>(pub At<'x, T, N, Q>);

impl<T, L, const N: usize, const Q: usize> FormVisitor<T, N, L, Q> for Residuals<'_, T, N, Q>
where
    T: Real,
    L: Lagrangian<T, N, Q>,
{
    type Output = [T; 2];

    fn unconstrained(self, _: &L) -> [T; 2] {
        [T::zero(); 2]
    }

    fn multipliers<const K: usize>(self, system: &L) -> [T; 2]
    where
        L: Constrained<T, N, K, Q>,
    {
        let At { t, q, v } = self.0;
        SecondOrder::residuals(&ConstrainedDynamics::<L, T, K>::new(system), t, q, v)
    }

    fn reduced<const K: usize>(self, _: &L) -> [T; 2]
    where
        L: Reduced<T, N, K, Q>,
    {
        [T::zero(); 2]
    }
}

/// Whether a state satisfies the constraints to `tolerance` at both
/// levels: what a run through the atlas checks at its start, in the
/// user's coordinates.
pub(crate) struct Consistency<'x, T: Real, const N: usize> {
    pub at: At<'x, T, N, N>,
    pub tolerance: T,
}

impl<T, L, const N: usize> FormVisitor<T, N, L> for Consistency<'_, T, N>
where
    T: Real,
    L: Lagrangian<T, N>,
{
    type Output = Result<(), Error>;

    fn unconstrained(self, _: &L) -> Self::Output {
        Ok(())
    }

    fn multipliers<const K: usize>(self, system: &L) -> Self::Output
    where
        L: Constrained<T, N, K>,
    {
        let At { t, q, v } = self.at;
        let dynamics = ConstrainedDynamics::<L, T, K>::new(system);
        dynamics
            .check_consistency(t, q, v, self.tolerance)
            .map(|_| ())
    }

    fn reduced<const K: usize>(self, _: &L) -> Self::Output
    where
        L: Reduced<T, N, K>,
    {
        Err(refused())
    }
}
