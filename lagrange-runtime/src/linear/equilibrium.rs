//! Equilibria and trim: a state where the driven system does not accelerate,
//! q̈(q, v, u, t) = 0, found from a guess by varying the coordinates and
//! inputs that are not held.
//!
//! With v = 0 that is an equilibrium (a pendulum at rest, a robot holding a
//! pose against gravity, a hover); with the speeds given it is a steady
//! motion (a steady turn, a spinning top's precession at constant rate), the
//! velocities held as given. The unknowns are the free coordinates (an
//! orientation moves in its tangent space, q ⊕ δ, as the linearisations do)
//! and the free inputs; the equations are the N accelerations. The iteration
//! is Gauss–Newton with the minimum-norm step through the SVD of
//! J = [∂q̈/∂δ | ∂q̈/∂u] (from [`Linearizer::tangent_driven`]), and a
//! backtracking line search on |q̈|: where more unknowns than needed are
//! free, the step is the smallest change from the guess. At the end the
//! inputs' change from the guess is made the smallest that holds the
//! configuration found (q̈ is affine in u: the part of the change that
//! ∂q̈/∂u does not see, which steps taken while q moved can leave behind,
//! is projected out), so a guess with zero inputs gives the least-norm
//! inputs that hold the equilibrium. A constrained system's equilibria
//! are [`Trim::solve_constrained`]'s (`equilibrium_constrained`).

use super::settings::{Linearizer, OperatingPoint};
use super::tangent::Held;
use crate::error::{
    Error, LinearError, SettingsError, StatePoint, check_finite_inputs, check_tolerance,
    unit_quaternions,
};
use crate::mechanics::Dynamics;
use crate::numeric::orientation;
use crate::numeric::orientation::Orientation;
use crate::system::Driven;
use nalgebra::{DMatrix, DVector, SVector};

/// How to look for an equilibrium: which coordinates and inputs stay at the
/// guess, the tolerance on q̈ and the iteration budget. By default everything
/// is free, the tolerance is 1e-10 (in the accelerations' units) and the
/// budget 50 iterations.
///
/// ```
/// # use lagrange_runtime::{Driven, Lagrangian};
/// # use nalgebra::{Matrix1, SMatrix, Vector1};
/// # struct Pendulum;
/// # impl Lagrangian<f64, 1> for Pendulum {
/// #     const COORDINATES: [&'static str; 1] = ["theta"];
/// #     const RHEONOMIC: bool = false;
/// #     fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> { Matrix1::new(1.0) }
/// #     fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> { Vector1::zeros() }
/// #     fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
/// #         Vector1::new(-9.81 * q[0].sin())
/// #     }
/// #     fn mass_matrix_and_rhs(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> (Matrix1<f64>, Vector1<f64>) {
/// #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
/// #     }
/// #     fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 { 0.5 * v[0] * v[0] }
/// #     fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 { -9.81 * q[0].cos() }
/// #     fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
/// #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
/// #     }
/// # }
/// # impl Driven<f64, 1, 1> for Pendulum {
/// #     const INPUTS: [&'static str; 1] = ["torque"];
/// #     fn input_forces(&self, _: &Vector1<f64>, _: &Vector1<f64>, u: &Vector1<f64>, _: f64) -> Vector1<f64> { *u }
/// #     fn input_jacobians(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: &Vector1<f64>, _: f64)
/// #         -> (SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>) {
/// #         (SMatrix::identity(), SMatrix::zeros(), SMatrix::zeros())
/// #     }
/// # }
/// use lagrange_runtime::linear::{OperatingPoint, Trim};
///
/// // A unit pendulum (θ̈ = −g sin θ + torque) held out at θ = 0.5: the torque
/// // that holds it there is g sin 0.5.
/// let at = OperatingPoint::new(Vector1::new(0.5), Vector1::new(0.0));
/// let held = Trim::new().hold(&["theta"]).solve(&Pendulum, &at)?;
/// assert!((held.u[0] - 9.81 * 0.5_f64.sin()).abs() < 1e-12);
/// # Ok::<(), lagrange_runtime::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Trim {
    held: Vec<String>,
    held_inputs: Vec<String>,
    tolerance: f64,
    max_iterations: usize,
    pub(super) linearizer: Linearizer,
}

/// An equilibrium or steady motion found by [`Trim::solve`]: the state, the
/// inputs, and how close q̈ came to zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Equilibrium<const N: usize, const P: usize, const Q: usize = N> {
    /// The configuration (unit quaternions for orientations).
    pub q: SVector<f64, Q>,
    /// The velocities, as given (they are held).
    pub v: SVector<f64, N>,
    /// The inputs.
    pub u: SVector<f64, P>,
    /// The time, as given.
    pub t: f64,
    /// max |q̈| there.
    pub residual: f64,
    /// Gauss–Newton iterations done.
    pub iterations: usize,
}

impl<const N: usize, const P: usize, const Q: usize> Equilibrium<N, P, Q> {
    /// The point to linearise about (inputs included).
    pub fn operating_point(&self) -> OperatingPoint<f64, N, P, Q> {
        OperatingPoint {
            q: self.q,
            v: self.v,
            u: self.u,
            t: self.t,
        }
    }
}

impl Default for Trim {
    fn default() -> Self {
        Self::new()
    }
}

/// Which tangent directions and inputs vary.
pub(super) struct Unknowns {
    tangent: Vec<usize>,
    inputs: Vec<usize>,
}

impl Trim {
    /// Everything free, tolerance 1e-10, 50 iterations, the default
    /// [`Linearizer`] for the Jacobians.
    pub fn new() -> Self {
        Self {
            held: Vec::new(),
            held_inputs: Vec::new(),
            tolerance: 1e-10,
            max_iterations: 50,
            linearizer: Linearizer::new(),
        }
    }

    /// Holds these coordinates at the guess: ordinary coordinates by name, an
    /// orientation by its name (all three of its directions). Added to the
    /// ones held before.
    pub fn hold(mut self, coordinates: &[&str]) -> Self {
        self.held.extend(coordinates.iter().map(|s| s.to_string()));
        self
    }

    /// Holds these inputs at the guess's values.
    pub fn hold_inputs(mut self, inputs: &[&str]) -> Self {
        self.held_inputs
            .extend(inputs.iter().map(|s| s.to_string()));
        self
    }

    /// Stops when max |q̈| ≤ `tolerance` (non-negative and finite).
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// At most this many Gauss–Newton iterations (at least one).
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The linearisation settings the Jacobians are taken with (its
    /// tolerances judge a singular mass matrix).
    pub fn linearizer(mut self, linearizer: Linearizer) -> Self {
        self.linearizer = linearizer;
        self
    }

    /// The equilibrium (v = 0 in `guess`) or steady motion (the speeds of
    /// `guess`) nearest `guess`, varying what is not held. The guess's
    /// inputs start the search (zero when it has none).
    ///
    /// # Errors
    /// [`Error::Settings`] for a bad tolerance or budget and for a name
    /// that is no coordinate, orientation or input of the system;
    /// [`Error::NonFiniteState`], [`Error::NonFiniteInput`] or
    /// [`Error::NonUnitQuaternion`] for a bad guess; the dynamics' errors at
    /// the guess (a singular mass matrix); [`LinearError::NoEquilibrium`],
    /// holding the best point reached, when q̈ cannot be brought below the
    /// tolerance.
    pub fn solve<S, const N: usize, const P: usize, const U: usize, const Q: usize>(
        &self,
        sys: &S,
        guess: &OperatingPoint<f64, N, U, Q>,
    ) -> Result<Equilibrium<N, P, Q>, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        self.check_settings()?;
        let unknowns = self.unknowns::<S, N, P, Q>()?;
        let (v, t) = (guess.v, guess.t);
        let u = guess.inputs::<P>();
        check_finite_inputs(&S::INPUTS, t, &guess.q, &v, &u)?;
        let q = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, guess.q)?;
        let residual = |q: &SVector<f64, Q>, u: &SVector<f64, P>| {
            let a = accelerations(sys, q, &v, u, t)?;
            Ok(DVector::from_column_slice(a.as_slice()))
        };
        let jacobian = |at: &Equilibrium<N, P, Q>, _: &DVector<f64>| {
            let lin = (self.linearizer).tangent_driven(sys, &at.q, &at.v, &at.u, at.t)?;
            Ok(DMatrix::from_fn(N, N + P, |i, c| match c < N {
                true => lin.a()[(N + i, c)],
                false => lin.b()[(N + i, c - N)],
            }))
        };
        let worst = |i: usize| S::VELOCITIES[i].to_string();
        let problem = Problem {
            residual: &residual,
            jacobian: &jacobian,
            worst: &worst,
            orientations: S::ORIENTATIONS,
            rebase: None,
        };
        self.search(&problem, Equilibrium::start(q, v, u, t), &unknowns)
    }

    /// A bad tolerance or budget.
    pub(super) fn check_settings(&self) -> Result<(), Error> {
        check_tolerance("Trim", "tolerance", self.tolerance)?;
        if self.max_iterations == 0 {
            return Err(SettingsError::ZeroCount {
                owner: "Trim",
                setting: "max_iterations",
            }
            .into());
        }
        Ok(())
    }

    /// Gauss–Newton from `best` (its residual not yet measured) until the
    /// residual's largest entry is within the tolerance.
    pub(super) fn search<const N: usize, const P: usize, const Q: usize>(
        &self,
        problem: &Problem<'_, N, P, Q>,
        mut best: Equilibrium<N, P, Q>,
        unknowns: &Unknowns,
    ) -> Result<Equilibrium<N, P, Q>, Error> {
        let guessed = best.u;
        let mut r = (problem.residual)(&best.q, &best.u)?;
        if r.iter().any(|x| !x.is_finite()) {
            best.residual = f64::NAN;
            let why = "the residual is not finite at the guess (an acceleration or a constraint \
                       the system cannot evaluate there)";
            return Err(self.failed(&best, &r, problem, why));
        }
        best.residual = r.amax();
        while best.residual > self.tolerance {
            if best.iterations == self.max_iterations {
                return Err(self.failed(&best, &r, problem, "out of iterations"));
            }
            if unknowns.tangent.is_empty() && unknowns.inputs.is_empty() {
                return Err(self.failed(&best, &r, problem, "everything is held"));
            }
            best.iterations += 1;
            if let Some(rebase) = problem.rebase {
                rebase(&best.q);
                r = (problem.residual)(&best.q, &best.u)?;
            }
            let jacobian = (problem.jacobian)(&best, &r)?;
            let step = min_norm_step::<N, P>(&jacobian, &r, unknowns);
            let Some((next, r_next)) = line_search(problem, &best, &r, &step) else {
                let why = "no step along the Gauss–Newton direction lowers the residual \
                           (a minimum that is not zero: hold fewer coordinates or inputs, \
                           or start elsewhere)";
                return Err(self.failed(&best, &r, problem, why));
            };
            best = next;
            r = r_next;
        }
        match best.iterations {
            0 => Ok(best),
            _ => self.least_norm_inputs(problem, best, &guessed, unknowns),
        }
    }

    /// The equilibrium found with its free inputs' change from the guess
    /// made the smallest that holds it: q̈ is affine in u, so at the
    /// configuration found the inputs that hold it are the guess's plus a
    /// particular change plus anything in the null space of ∂r/∂u; that
    /// part, which steps taken while q moved can leave behind, is projected
    /// out. Kept only where the residual stays within the tolerance.
    fn least_norm_inputs<const N: usize, const P: usize, const Q: usize>(
        &self,
        problem: &Problem<'_, N, P, Q>,
        best: Equilibrium<N, P, Q>,
        guessed: &SVector<f64, P>,
        unknowns: &Unknowns,
    ) -> Result<Equilibrium<N, P, Q>, Error> {
        if unknowns.inputs.is_empty() {
            return Ok(best);
        }
        if let Some(rebase) = problem.rebase {
            rebase(&best.q);
        }
        let r = (problem.residual)(&best.q, &best.u)?;
        let full = (problem.jacobian)(&best, &r)?;
        let inputs = &unknowns.inputs;
        let by_input = DMatrix::from_fn(r.len(), inputs.len(), |i, c| full[(i, N + inputs[c])]);
        let change =
            DVector::from_iterator(inputs.len(), inputs.iter().map(|&k| best.u[k] - guessed[k]));
        let svd = by_input.svd(false, true);
        let Some(rows) = svd.v_t else {
            return Ok(best);
        };
        let cutoff = 1e-12 * svd.singular_values.max();
        let mut kept = DVector::zeros(inputs.len());
        for (k, sigma) in svd.singular_values.iter().enumerate() {
            if *sigma > cutoff {
                let direction = rows.row(k).transpose();
                kept += &direction * direction.dot(&change);
            }
        }
        let mut u = *guessed;
        (inputs.iter().enumerate()).for_each(|(c, &k)| u[k] = guessed[k] + kept[c]);
        let residual = (problem.residual)(&best.q, &u)?.amax();
        Ok(match residual <= self.tolerance.max(best.residual) {
            true => Equilibrium {
                u,
                residual,
                ..best
            },
            false => best,
        })
    }

    /// The tangent directions and inputs not held, or the first unknown name.
    pub(super) fn unknowns<S, const N: usize, const P: usize, const Q: usize>(
        &self,
    ) -> Result<Unknowns, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        let mut held_tangent = [false; N];
        for name in &self.held {
            let columns = tangent_columns::<S, N, P, Q>(name).ok_or_else(|| {
                unknown_name(
                    name,
                    "coordinate or orientation",
                    S::VELOCITIES
                        .iter()
                        .filter(|v| S::COORDINATES.contains(v))
                        .copied()
                        .chain(
                            S::ORIENTATIONS
                                .iter()
                                .map(|o| orientation_name::<S, N, P, Q>(o.q)),
                        )
                        .collect(),
                )
            })?;
            columns.into_iter().for_each(|j| held_tangent[j] = true);
        }
        let mut held_input = [false; P];
        for name in &self.held_inputs {
            let k = S::INPUTS.iter().position(|i| i == name);
            let k = k.ok_or_else(|| unknown_name(name, "input", S::INPUTS.to_vec()))?;
            held_input[k] = true;
        }
        Ok(Unknowns {
            tangent: (0..N).filter(|&j| !held_tangent[j]).collect(),
            inputs: (0..P).filter(|&k| !held_input[k]).collect(),
        })
    }

    /// The error for a search that stopped at `best` (where the residual is
    /// `r`), naming its largest entry.
    fn failed<const N: usize, const P: usize, const Q: usize>(
        &self,
        best: &Equilibrium<N, P, Q>,
        r: &DVector<f64>,
        problem: &Problem<'_, N, P, Q>,
        why: &str,
    ) -> Error {
        LinearError::NoEquilibrium {
            residual: best.residual,
            worst: (problem.worst)(r.iamax()),
            tolerance: self.tolerance,
            iterations: best.iterations,
            why: why.into(),
            best: Box::new(StatePoint {
                q: best.q.iter().copied().collect(),
                v: best.v.iter().copied().collect(),
                u: best.u.iter().copied().collect(),
            }),
        }
        .into()
    }
}

impl<const N: usize, const P: usize, const Q: usize> Equilibrium<N, P, Q> {
    /// The search's start, its residual not yet measured.
    pub(super) fn start(
        q: SVector<f64, Q>,
        v: SVector<f64, N>,
        u: SVector<f64, P>,
        t: f64,
    ) -> Self {
        Equilibrium {
            q,
            v,
            u,
            t,
            residual: f64::INFINITY,
            iterations: 0,
        }
    }
}

/// What a search drives to zero at (q, u), the velocities and time fixed:
/// its residual, the residual's Jacobian over every tangent direction (N
/// columns) and input (P columns) at a point where the residual is the
/// second argument, the name of the residual's entry i, where q's
/// orientations are, and what to do at each iterate before the step (the
/// constrained residual's rows are read in axes taken there).
pub(super) struct Problem<'a, const N: usize, const P: usize, const Q: usize> {
    pub residual: &'a Residual<'a, P, Q>,
    pub jacobian: &'a Jacobian<'a, N, P, Q>,
    pub worst: &'a dyn Fn(usize) -> String,
    pub orientations: &'a [Orientation],
    pub rebase: Option<&'a Rebase<'a, Q>>,
}

/// A search's residual at (q, u).
pub(super) type Residual<'a, const P: usize, const Q: usize> =
    dyn Fn(&SVector<f64, Q>, &SVector<f64, P>) -> Result<DVector<f64>, Error> + 'a;

/// Its Jacobian at an iterate whose residual is the second argument.
pub(super) type Jacobian<'a, const N: usize, const P: usize, const Q: usize> =
    dyn Fn(&Equilibrium<N, P, Q>, &DVector<f64>) -> Result<DMatrix<f64>, Error> + 'a;

/// What to do at each iterate before its step.
pub(super) type Rebase<'a, const Q: usize> = dyn Fn(&SVector<f64, Q>) + 'a;

/// The minimum-norm Gauss–Newton step −J⁺ r over the unknowns (J's columns
/// of the unknowns alone, through the SVD), as a tangent vector (N) and an
/// input change (P).
fn min_norm_step<const N: usize, const P: usize>(
    full: &DMatrix<f64>,
    r: &DVector<f64>,
    unknowns: &Unknowns,
) -> (SVector<f64, N>, SVector<f64, P>) {
    let (nt, ni) = (unknowns.tangent.len(), unknowns.inputs.len());
    let jacobian = DMatrix::from_fn(r.len(), nt + ni, |i, c| match c < nt {
        true => full[(i, unknowns.tangent[c])],
        false => full[(i, N + unknowns.inputs[c - nt])],
    });
    let svd = jacobian.svd(true, true);
    let cutoff = 1e-12 * svd.singular_values.max();
    // U and Vᵀ were asked for, so the solve cannot fail; a non-finite
    // Jacobian gives a non-finite step, which the line search rejects.
    let x = svd
        .solve(&-r, cutoff)
        .unwrap_or_else(|_| DVector::from_element(nt + ni, f64::NAN));
    let mut delta = SVector::zeros();
    let mut du = SVector::zeros();
    (unknowns.tangent.iter().enumerate()).for_each(|(c, &j)| delta[j] = x[c]);
    (unknowns.inputs.iter().enumerate()).for_each(|(c, &k)| du[k] = x[nt + c]);
    (delta, du)
}

/// q̈ of `sys` at (q, v) under the inputs u held.
fn accelerations<S, const N: usize, const P: usize, const Q: usize>(
    sys: &S,
    q: &SVector<f64, Q>,
    v: &SVector<f64, N>,
    u: &SVector<f64, P>,
    t: f64,
) -> Result<SVector<f64, N>, Error>
where
    S: Driven<f64, N, P, Q>,
{
    let held = Held { system: sys, u: *u };
    Dynamics::new(sys).with_forcing(held).acceleration(t, q, v)
}

/// The first of 1, ½, ¼, … (down to 2⁻³⁰) of `step` that lowers |r|
/// (Armijo's sufficient decrease on the Euclidean norm), with r there;
/// `None` if none does. A trial where the dynamics fail (a singular mass
/// matrix) counts as no decrease.
fn line_search<const N: usize, const P: usize, const Q: usize>(
    problem: &Problem<'_, N, P, Q>,
    at: &Equilibrium<N, P, Q>,
    r: &DVector<f64>,
    (delta, du): &(SVector<f64, N>, SVector<f64, P>),
) -> Option<(Equilibrium<N, P, Q>, DVector<f64>)> {
    let norm = r.norm();
    let mut alpha = 1.0;
    for _ in 0..=30 {
        let q = orientation::plus(problem.orientations, &at.q, &(delta * alpha));
        let u = at.u + du * alpha;
        if let Ok(trial) = (problem.residual)(&q, &u)
            && trial.norm() < (1.0 - 1e-4 * alpha) * norm
        {
            let next = Equilibrium {
                q,
                u,
                residual: trial.amax(),
                ..at.clone()
            };
            return Some((next, trial));
        }
        alpha *= 0.5;
    }
    None
}

/// The tangent directions of a coordinate or an orientation named `name`.
fn tangent_columns<S, const N: usize, const P: usize, const Q: usize>(
    name: &str,
) -> Option<Vec<usize>>
where
    S: Driven<f64, N, P, Q>,
{
    if S::COORDINATES.contains(&name)
        && let Some(j) = S::VELOCITIES.iter().position(|v| *v == name)
    {
        return Some(vec![j]);
    }
    let o = S::ORIENTATIONS
        .iter()
        .find(|o| orientation_name::<S, N, P, Q>(o.q) == name)?;
    Some(vec![o.v, o.v + 1, o.v + 2])
}

/// An orientation's name: its first entry of q is `<name>.w`.
fn orientation_name<S, const N: usize, const P: usize, const Q: usize>(at: usize) -> &'static str
where
    S: Driven<f64, N, P, Q>,
{
    let w = S::COORDINATES[at];
    w.strip_suffix(".w").unwrap_or(w)
}

fn unknown_name(name: &str, what: &str, known: Vec<&str>) -> Error {
    SettingsError::Data {
        owner: "Trim",
        problem: format!("no {what} named `{name}` to hold; the system has {known:?}"),
    }
    .into()
}

#[cfg(test)]
#[path = "equilibrium_tests.rs"]
mod tests;
