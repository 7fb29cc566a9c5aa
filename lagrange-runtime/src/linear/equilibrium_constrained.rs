//! Equilibria and steady motions of a constrained system: a point on the
//! constraints where the multiplier form's accelerations vanish.
//!
//! The unknowns are those of [`Trim::solve`] (the free tangent directions
//! and inputs). The residual stacks the multiplier form's q̈ (the reactions
//! taking what the constraints hold) read along the directions the
//! constraints leave free, γ (so that G q̈ = γ allows q̈ = 0), the holonomic
//! constraints Φ(q, t) and the velocity rows G v + g at the velocities held
//! (all three zero at rest on scleronomic constraints; for a steady motion
//! the guess's speeds must stay admissible as q moves). The guess need not
//! lie on the constraints: the search brings it there.
//!
//! Why q̈ along the free directions, not all of q̈: the multiplier form's q̈
//! always lies in the null space of G(q), which turns with q. Differentiated
//! whole, q̈ = n α would demand α n′ δq = 0 of the step as well as α + δα =
//! 0, an equation no equilibrium needs, which pins the configuration while
//! q̈ is not yet zero (a two-link arm whose tool a wall holds stalls off the
//! wall with ever larger torques). Read in a basis of the null space taken
//! at the iterate and held through its step, q̈'s rows say only what they
//! should.
//!
//! The Jacobian is taken by central differences on the group (each step the
//! cube root of the machine epsilon, times max(1, |u_k|) for an input), as
//! [`Linearizer::constrained_tangent`](super::Linearizer::constrained_tangent)
//! takes its own; the minimum-norm step then gives, for a pose held by more
//! inputs than it needs (a closed chain driven at every joint, a robot whose
//! tool is held by the constraint), the least-norm inputs: what the
//! constraints can hold, they hold.

use super::equilibrium::{Equilibrium, Problem, Residual, Trim};
use super::partition::holonomic;
use super::settings::OperatingPoint;
use super::tangent::Held;
use crate::error::{Error, check_finite_inputs, unit_quaternions};
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::numeric::orientation;
use crate::system::{Constrained, Driven};
use nalgebra::{DMatrix, DVector, SMatrix, SVector, SymmetricEigen};
use std::cell::RefCell;

impl Trim {
    /// The equilibrium (v = 0 in `guess`) or steady motion (the speeds of
    /// `guess`) of a constrained system nearest `guess`, varying what is
    /// not held, on its constraints: the multiplier form's q̈ is zero there
    /// (the constraints' reactions hold what they can), Φ(q, t) = 0 and the
    /// velocities held satisfy the velocity rows. The tolerance applies to
    /// q̈ and to the constraints' residuals alike, in their own units.
    ///
    /// Guide chapter 10 holds a pendulum out on its rod, and a two-link arm
    /// with its tool held on a wall by the least-norm torques.
    ///
    /// # Errors
    /// As [`solve`](Self::solve), and the multiplier form's errors at the
    /// guess (redundant constraints, a singular mass matrix); in
    /// [`LinearError::NoEquilibrium`](crate::LinearError::NoEquilibrium)
    /// `worst` names `q̈ along the constraints`, a constraint (`constraint
    /// `rod``), its velocity row (`velocity of constraint `rod``) or its
    /// γ (`acceleration of constraint `rod``).
    pub fn solve_constrained<
        S,
        const N: usize,
        const K: usize,
        const P: usize,
        const U: usize,
        const Q: usize,
    >(
        &self,
        sys: &S,
        guess: &OperatingPoint<f64, N, U, Q>,
    ) -> Result<Equilibrium<N, P, Q>, Error>
    where
        S: Constrained<f64, N, K, Q> + Driven<f64, N, P, Q>,
    {
        self.check_settings()?;
        let unknowns = self.unknowns::<S, N, P, Q>()?;
        let (v, t) = (guess.v, guess.t);
        let u = guess.inputs::<P>();
        check_finite_inputs(&S::INPUTS, t, &guess.q, &v, &u)?;
        let q = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, guess.q)?;
        let free = RefCell::new(free_directions(&sys.constraint_jacobian(&q, t).0));
        let residual = |q: &SVector<f64, Q>, u: &SVector<f64, P>| {
            let free = free.borrow();
            self.constrained_residual::<S, N, K, P, Q>(sys, &free, (q, &v, u, t))
        };
        let jacobian = |at: &Equilibrium<N, P, Q>, _: &DVector<f64>| {
            differences::<N, P, Q>(&residual, at, S::ORIENTATIONS)
        };
        let rebase = |q: &SVector<f64, Q>| {
            *free.borrow_mut() = free_directions(&sys.constraint_jacobian(q, t).0);
        };
        let worst = |i: usize| residual_name::<S, N, K, P, Q>(i, free.borrow().ncols());
        let problem = Problem {
            residual: &residual,
            jacobian: &jacobian,
            worst: &worst,
            orientations: S::ORIENTATIONS,
            rebase: Some(&rebase),
        };
        self.search(&problem, Equilibrium::start(q, v, u, t), &unknowns)
    }

    /// [Fᵀ q̈ of the multiplier form, F the free directions; γ; Φ's
    /// holonomic rows; G v + g] at (q, v) under the inputs u held.
    fn constrained_residual<S, const N: usize, const K: usize, const P: usize, const Q: usize>(
        &self,
        sys: &S,
        free: &DMatrix<f64>,
        (q, v, u, t): (&SVector<f64, Q>, &SVector<f64, N>, &SVector<f64, P>, f64),
    ) -> Result<DVector<f64>, Error>
    where
        S: Constrained<f64, N, K, Q> + Driven<f64, N, P, Q>,
    {
        let tolerances = &self.linearizer.tolerances;
        let held = Held { system: sys, u: *u };
        let solution = ConstrainedDynamics::<_, _, K>::new(sys)
            .with_singular_tolerance(tolerances.singular)
            .with_redundant_tolerance(tolerances.redundant)
            .with_forcing(held)
            .solve(t, q, v)?;
        let along = free.transpose() * solution.accelerations;
        let gamma = sys.constraint_rhs(q, v, t);
        let h = holonomic::<S, f64, N, K, Q>();
        let phi = sys.constraint_positions(q, t);
        let (g, g0) = sys.constraint_jacobian(q, t);
        let rate = g * v + g0;
        let rows = (along.iter().chain(gamma.iter()))
            .chain(phi.iter().take(h))
            .chain(rate.iter());
        Ok(DVector::from_iterator(
            along.len() + 2 * K + h,
            rows.copied(),
        ))
    }
}

/// An orthonormal basis of G's null space (the directions the constraints
/// leave free), from the eigenvectors of Gᵀ G: those whose eigenvalue is
/// below 1e-12 of the largest (a singular value below 1e-6 of G's largest).
/// All of them where G is zero, or not finite (a row the system cannot
/// evaluate there: the residual then is not finite either, and the search
/// refuses the point rather than iterate on it).
fn free_directions<const N: usize, const K: usize>(g: &SMatrix<f64, K, N>) -> DMatrix<f64> {
    let gram = DMatrix::from_fn(N, N, |i, j| g.column(i).dot(&g.column(j)));
    // Bounded: an iteration without a limit does not end on a NaN.
    let Some(eigen) = (gram.iter().all(|x| x.is_finite()))
        .then(|| SymmetricEigen::try_new(gram, f64::EPSILON, 1000))
        .flatten()
    else {
        return DMatrix::identity(N, N);
    };
    let largest = eigen.eigenvalues.amax();
    let free: Vec<DVector<f64>> = (0..N)
        .filter(|&k| eigen.eigenvalues[k] <= 1e-12 * largest)
        .map(|k| eigen.eigenvectors.column(k).into_owned())
        .collect();
    if free.is_empty() {
        return DMatrix::zeros(N, 0);
    }
    DMatrix::from_columns(&free)
}

/// The residual's Jacobian over every tangent direction and input by
/// central differences on the group.
fn differences<const N: usize, const P: usize, const Q: usize>(
    residual: &Residual<'_, P, Q>,
    at: &Equilibrium<N, P, Q>,
    orientations: &[orientation::Orientation],
) -> Result<DMatrix<f64>, Error> {
    let epsilon = f64::EPSILON.cbrt();
    let mut columns = Vec::with_capacity(N + P);
    for j in 0..N {
        let turned = |sign: f64| {
            let delta =
                SVector::<f64, N>::from_fn(|i, _| if i == j { sign * epsilon } else { 0.0 });
            orientation::plus(orientations, &at.q, &delta)
        };
        let (up, down) = (
            residual(&turned(1.0), &at.u)?,
            residual(&turned(-1.0), &at.u)?,
        );
        columns.push((up - down) / (2.0 * epsilon));
    }
    for k in 0..P {
        let step = epsilon * at.u[k].abs().max(1.0);
        let pushed = |sign: f64| {
            let mut u = at.u;
            u[k] += sign * step;
            u
        };
        let (up, down) = (
            residual(&at.q, &pushed(1.0))?,
            residual(&at.q, &pushed(-1.0))?,
        );
        columns.push((up - down) / (2.0 * step));
    }
    Ok(DMatrix::from_columns(&columns))
}

/// Entry i of the constrained residual (its first `free` rows q̈ along
/// the free directions), named.
fn residual_name<S, const N: usize, const K: usize, const P: usize, const Q: usize>(
    i: usize,
    free: usize,
) -> String
where
    S: Constrained<f64, N, K, Q> + Driven<f64, N, P, Q>,
{
    let h = holonomic::<S, f64, N, K, Q>();
    let name = |k: usize| S::CONSTRAINTS[k];
    match i {
        i if i < free => "q̈ along the constraints".to_string(),
        i if i < free + K => format!("acceleration of constraint `{}`", name(i - free)),
        i if i < free + K + h => format!("constraint `{}`", name(i - free - K)),
        i => format!("velocity of constraint `{}`", name(i - free - K - h)),
    }
}
