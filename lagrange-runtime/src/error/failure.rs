//! A run that stopped before its end: the error and the partial result.

use super::Error;
use std::fmt;

/// A run that stopped before its end: the typed error, and everything computed
/// before it (`partial`: the accepted steps, their dense output and the run's
/// statistics), as DifferentialEquations.jl's return codes keep the solution.
///
/// `?` turns it into the bare [`Error`] where a function returns
/// `Result<_, Error>`; match on `error` to tell the cases apart:
///
/// ```
/// # use lagrange_runtime::{Error, Failure, Trajectory};
/// fn report(result: Result<Trajectory<f64, 1>, Failure<Trajectory<f64, 1>>>) {
///     match result {
///         Ok(traj) => println!("reached t = {:?}", traj.times().last()),
///         Err(Failure { error: Error::TooManySteps { .. }, partial }) => {
///             println!("out of steps at t = {:?}", partial.times().last())
///         }
///         Err(failure) => println!("{failure}"),
///     }
/// }
/// ```
///
/// Its `Display` and `Debug` are a line or two whatever the length of the
/// run (the error, and how far the run got: its number of points and the
/// last time), so that `?` in a `main` returning `Result<(), Box<dyn
/// std::error::Error>>` prints that and not the whole partial run; the run
/// itself is in [`partial`](Self::partial). As a [`std::error::Error`] its
/// [`source`](std::error::Error::source) is the [`Error`].
#[derive(Clone)]
pub struct Failure<P> {
    /// What went wrong, where and when.
    pub error: Error,
    /// What was computed before it: for a trajectory, every step accepted up
    /// to the failure (at least the initial state), with its statistics.
    /// Boxed, so that a `Result` carrying it is no larger than its `Ok`.
    pub partial: Box<P>,
}

/// How far a partial result got, for a [`Failure`]'s message: implemented by
/// the results of runs ([`Trajectory`](crate::Trajectory),
/// [`EventRun`](crate::EventRun), [`ControlRun`](crate::ControlRun)).
pub trait Progress {
    /// The number of points computed (stored) and the last time among them
    /// (as `f64`), if there is one.
    fn progress(&self) -> (usize, Option<f64>);

    /// What the partial result is and how far it got, for the failure's
    /// message. By default a run's: "the run stopped early: 12 points
    /// computed, the last at t = 0.5; the partial run is in
    /// `Failure::partial`". Results that are not runs (a plan, an inverse
    /// kinematics solution) say what they are instead.
    fn describe(&self) -> String {
        format!(
            "the run stopped early: {}; the partial run is in `Failure::partial`",
            Summary(self.progress())
        )
    }
}

impl<P> Failure<P> {
    /// The failure of a run that got as far as `partial`.
    pub fn new(error: Error, partial: P) -> Self {
        Self {
            error,
            partial: Box::new(partial),
        }
    }

    /// The error and the partial result.
    pub fn into_parts(self) -> (Error, P) {
        (self.error, *self.partial)
    }

    /// The partial result mapped (e.g. a trajectory into a run record).
    pub fn map<Q>(self, f: impl FnOnce(P) -> Q) -> Failure<Q> {
        Failure::new(self.error, f(*self.partial))
    }
}

/// "12 points, the last at t = 0.5", the summary of a partial run.
struct Summary((usize, Option<f64>));

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            (n, Some(t)) => write!(f, "{n} points computed, the last at t = {t}"),
            (n, None) => write!(f, "{n} points computed"),
        }
    }
}

impl<P: Progress> fmt::Display for Failure<P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}\n({})", self.error, self.partial.describe())
    }
}

impl<P: Progress> fmt::Debug for Failure<P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Failure")
            .field("error", &self.error)
            .field(
                "partial",
                &format_args!("<{}>", Summary(self.partial.progress())),
            )
            .finish()
    }
}

impl<P: Progress> std::error::Error for Failure<P> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

impl<P> From<Failure<P>> for Error {
    fn from(f: Failure<P>) -> Self {
        f.error
    }
}
