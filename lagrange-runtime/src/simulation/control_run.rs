//! The result of a controlled run and its output as a table or CSV.

use crate::error::{Error, Progress};
use crate::event::Occurrence;
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::system::Lagrangian;
use nalgebra::SVector;
use std::io::Write;
use std::path::Path;

/// The result of a controlled run: the trajectory, the inputs at its points,
/// and the event occurrences.
///
/// With the `serde` feature it serializes (not deserializes: its names are
/// the system's `&'static str`s) with the fields `trajectory`, `inputs` (one
/// per point), `occurrences`, `terminated_by`, `coordinates` and
/// `input_names`.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct ControlRun<T: Real, const N: usize, const P: usize, const Q: usize = N> {
    pub(crate) trajectory: Trajectory<T, N, Q>,
    pub(crate) inputs: Vec<SVector<T, P>>,
    pub(crate) occurrences: Vec<Occurrence<T, N, Q>>,
    pub(crate) terminated_by: Option<usize>,
    #[cfg_attr(feature = "serde", serde(serialize_with = "names"))]
    pub(super) coordinates: [&'static str; Q],
    /// The velocities' names, for the CSV header.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(super) velocities: [&'static str; N],
    #[cfg_attr(feature = "serde", serde(serialize_with = "names"))]
    pub(crate) input_names: [&'static str; P],
    /// The bounds the inputs were clamped into, if the run had limits.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) bounds: Option<([f64; P], [f64; P])>,
    /// The inputs' joints and no-load speeds, if the bounds narrowed with
    /// speed.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) speed_limits: Option<([usize; P], [f64; P])>,
}

/// Names as a sequence (serde has no impl for arrays of a generic length).
#[cfg(feature = "serde")]
fn names<S: serde::Serializer, const K: usize>(
    names: &[&'static str; K],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.collect_seq(names.iter())
}

impl<T: Real, const N: usize, const P: usize, const Q: usize> ControlRun<T, N, P, Q> {
    /// The motion, concatenated across the restarts (samples, breakpoints,
    /// event actions); its statistics sum the pieces' work.
    pub fn trajectory(&self) -> &Trajectory<T, N, Q> {
        &self.trajectory
    }

    /// The trajectory, dropping the rest.
    pub fn into_trajectory(self) -> Trajectory<T, N, Q> {
        self.trajectory
    }

    /// The inputs at the trajectory's [`times`](Trajectory::times), one per
    /// point: the source's value at the stored time and state for continuous
    /// sources; for held sources the value in force on the step that ends
    /// there, or the new sample at a sample instant (see the
    /// [module docs](crate::control)).
    pub fn inputs(&self) -> &[SVector<T, P>] {
        &self.inputs
    }

    /// The inputs' names ([`Driven::INPUTS`](crate::Driven::INPUTS)).
    pub fn input_names(&self) -> &[&'static str; P] {
        &self.input_names
    }

    /// Where the run held an input at one of its limits
    /// ([`Simulation::input_limits`](crate::Simulation::input_limits)), in
    /// time order: each stretch from the first recorded point at the limit
    /// to the first after it that is not. For a sampled controller both are
    /// sample instants, so the stretches are exact; for continuous feedback
    /// they are as fine as the recording (the limit is reached or left
    /// inside the step that ends there). Empty without limits.
    pub fn saturations(&self) -> Vec<crate::control::Saturation<T>> {
        self.bounds.map_or_else(Vec::new, |bounds| {
            let points = (self.trajectory.times(), self.trajectory.velocities());
            crate::control::stretches(points, &self.inputs, bounds, self.speed_limits)
        })
    }

    /// The coordinates' names ([`Lagrangian::COORDINATES`]).
    pub fn coordinate_names(&self) -> &[&'static str; Q] {
        &self.coordinates
    }

    /// Event occurrences, in time order.
    pub fn occurrences(&self) -> &[Occurrence<T, N, Q>] {
        &self.occurrences
    }

    /// The terminal event that ended the run, if one did.
    pub fn terminated_by(&self) -> Option<usize> {
        self.terminated_by
    }

    /// Writes the recorded points as CSV: the header
    /// `t,<coordinates>,<velocities>,<inputs>,…` (e.g.
    /// `t,x,theta,dot_x,dot_theta,force,…`; an orientation's angular velocity
    /// `turn.wx`, …, as [`table`](Self::table) names it) and one row per
    /// point, numbers in the shortest form that reads back exactly.
    ///
    /// # Errors
    /// [`Error::Io`] if writing fails.
    pub fn write_csv(&self, w: impl Write) -> Result<(), Error> {
        self.table_of(crate::table::Table::named(
            &self.trajectory,
            &self.coordinates,
            &self.velocities,
        ))?
        .write(w)
    }

    /// The run as a [`Table`](crate::Table) with the inputs, the system's
    /// energies at every point and the other columns of
    /// [`Trajectory::table`].
    ///
    /// # Errors
    /// [`Error::Settings`] if the inputs do not match the points (they
    /// always do for a run built here).
    pub fn table<S: Lagrangian<T, N, Q>>(
        &self,
        sys: &S,
    ) -> Result<crate::table::Table<'_, T, N, Q>, Error> {
        self.table_of(self.trajectory.table(sys))
    }

    fn table_of<'t>(
        &'t self,
        table: crate::table::Table<'t, T, N, Q>,
    ) -> Result<crate::table::Table<'t, T, N, Q>, Error> {
        let names = self.input_names.iter().map(|s| s.to_string()).collect();
        let values = self
            .inputs
            .iter()
            .map(|u| u.iter().copied().collect())
            .collect();
        table.columns(names, values)
    }

    /// [`write_csv`](Self::write_csv) to a new file at `path` (buffered).
    ///
    /// # Errors
    /// As [`write_csv`](Self::write_csv), plus failure to create the file.
    pub fn save_csv(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let file = std::fs::File::create(path)?;
        self.write_csv(std::io::BufWriter::new(file))
    }
}

impl<T: Real, const N: usize, const P: usize, const Q: usize> Progress for ControlRun<T, N, P, Q> {
    fn progress(&self) -> (usize, Option<f64>) {
        self.trajectory.progress()
    }
}
