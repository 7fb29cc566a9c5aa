//! A run as a CSV table with every column a user needs, named in the header:
//! t, the coordinates and their rates (by the system's names), the inputs of
//! a controlled run, the kinetic and potential energy, the conserved integral,
//! the constraint residuals |Φ| and |G q̇ + g|, and, when asked for, the
//! multipliers ν (by the constraints' names). Written with the `csv` crate.
//!
//! ```no_run
//! # use lagrange_runtime::{Error, Trajectory, Lagrangian, Constrained};
//! # fn demo<S: Constrained<f64, 3, 1>>(sys: &S, traj: &Trajectory<f64, 3>) -> Result<(), Error> {
//! traj.table(sys).multipliers(sys)?.save("run.csv")?;
//! # Ok(()) }
//! ```

use crate::error::Error;
use crate::error::SettingsError;
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::system::{Constrained, Lagrangian};
use std::borrow::Cow;
use std::io::Write;
use std::path::Path;

/// The columns of a run, built from a trajectory and what the system adds.
#[derive(Clone, Debug)]
pub struct Table<'a, T: Real, const N: usize, const Q: usize = N> {
    /// Borrowed, or built for the table (a run through the atlas in the
    /// user's coordinates).
    traj: Cow<'a, Trajectory<T, N, Q>>,
    /// The columns of q (Q of them).
    names: Vec<String>,
    /// The columns of v (N of them).
    rates: Vec<String>,
    /// (T, V) per point.
    energies: Option<Vec<(T, T)>>,
    /// Named extra column groups, one value per point each (inputs, ν).
    extra: Vec<(Vec<String>, Vec<Vec<T>>)>,
    /// Cells written empty, by row, in row order: a value that does not
    /// exist there (a rate at its chart's singular set).
    blank: Vec<(usize, Cell)>,
}

/// A cell of a row that may be left empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cell {
    /// The rate of velocity j.
    Rate(usize),
    /// The kinetic energy.
    Kinetic,
}

impl<'a, T: Real, const N: usize, const Q: usize> Table<'a, T, N, Q> {
    /// The trajectory's own columns, the entries of q named `names` (Q of
    /// them, or none for q0, q1, …); the velocities are `dot_<name>`, or
    /// v0, v1, … when q holds quaternions (Q ≠ N).
    ///
    /// # Errors
    /// [`Error::Settings`] for a wrong number of names.
    pub fn new(traj: &'a Trajectory<T, N, Q>, names: &[&str]) -> Result<Self, Error> {
        let names: Vec<String> = match names.len() {
            0 => (0..Q).map(|i| format!("q{i}")).collect(),
            n if n == Q => names.iter().map(|s| s.to_string()).collect(),
            n => {
                return Err(csv(format!("{n} coordinate names for {Q} entries of q")));
            }
        };
        let rates = if Q == N {
            names.iter().map(|n| format!("dot_{n}")).collect()
        } else {
            (0..N).map(|j| format!("v{j}")).collect()
        };
        Ok(Self {
            traj: Cow::Borrowed(traj),
            names,
            rates,
            energies: None,
            extra: Vec::new(),
            blank: Vec::new(),
        })
    }

    /// The columns with the system's names (q by
    /// [`COORDINATES`](Lagrangian::COORDINATES), a coordinate's rate as
    /// `dot_<name>`, an orientation's angular velocity by its
    /// [`VELOCITIES`](Lagrangian::VELOCITIES) name, `turn.wx`) and its kinetic
    /// and potential energy at every point.
    pub fn of<S: Lagrangian<T, N, Q>>(traj: &'a Trajectory<T, N, Q>, sys: &S) -> Self {
        Self::of_cow(Cow::Borrowed(traj), sys)
    }

    /// [`of`](Self::of) a borrowed or an owned trajectory.
    pub(crate) fn of_cow<S: Lagrangian<T, N, Q>>(
        traj: Cow<'a, Trajectory<T, N, Q>>,
        sys: &S,
    ) -> Self {
        let energies = traj
            .times()
            .iter()
            .zip(traj.positions().iter().zip(traj.velocities()))
            .map(|(&t, (q, v))| (sys.kinetic_energy(q, v, t), sys.potential_energy(q, t)))
            .collect();
        let names: Vec<String> = S::COORDINATES.iter().map(|s| s.to_string()).collect();
        let rates = S::VELOCITIES
            .iter()
            .map(|v| match names.contains(&v.to_string()) {
                true => format!("dot_{v}"),
                false => v.to_string(),
            })
            .collect();
        Self {
            traj,
            names,
            rates,
            energies: Some(energies),
            extra: Vec::new(),
            blank: Vec::new(),
        }
    }

    /// Leaves the given cells empty (`(row, cell)` in row order).
    pub(crate) fn blank(mut self, cells: Vec<(usize, Cell)>) -> Self {
        debug_assert!(cells.windows(2).all(|w| w[0].0 <= w[1].0));
        self.blank = cells;
        self
    }

    /// Adds the multipliers ν of the multiplier form at every point, one
    /// column per constraint (`nu_<name>`).
    ///
    /// # Errors
    /// What solving the saddle-point system reports at a point (a state the
    /// run recorded, so normally none).
    pub fn multipliers<S, const K: usize>(mut self, sys: &S) -> Result<Self, Error>
    where
        S: Constrained<T, N, K>,
    {
        // A constrained system has Q = N (`Constrained` extends `Lagrangian<T, N>`).
        let traj: &Trajectory<T, N, Q> = &self.traj;
        let Some(tr) = (traj as &dyn std::any::Any).downcast_ref::<Trajectory<T, N>>() else {
            return Err(csv(
                "multipliers of a run with orientations: no constrained form takes them".into(),
            ));
        };
        let dynamics = ConstrainedDynamics::<S, T, K>::new(sys);
        let values = (0..tr.len())
            .map(|k| {
                let sol = dynamics.solve(tr.times()[k], &tr.positions()[k], &tr.velocities()[k])?;
                Ok(sol.multipliers.iter().copied().collect())
            })
            .collect::<Result<Vec<Vec<T>>, Error>>()?;
        let names = S::CONSTRAINTS.iter().map(|c| format!("nu_{c}")).collect();
        self.extra.push((names, values));
        Ok(self)
    }

    /// Adds a named group of columns, one row of values per point (e.g. the
    /// inputs of a controlled run).
    ///
    /// # Errors
    /// [`Error::Settings`] if there is not one row per point, or a row
    /// has not one value per name.
    pub fn columns(mut self, names: Vec<String>, values: Vec<Vec<T>>) -> Result<Self, Error> {
        if values.len() != self.traj.len() || values.iter().any(|r| r.len() != names.len()) {
            return Err(csv(format!(
                "{} rows of {} values for {} points",
                values.len(),
                names.len(),
                self.traj.len()
            )));
        }
        self.extra.push((names, values));
        Ok(self)
    }

    /// The header: t, q…, dot_q…, extra groups, T and V (if known), the
    /// integral, the residuals.
    pub(crate) fn header(&self) -> Vec<String> {
        let mut h = vec!["t".to_string()];
        h.extend(self.names.iter().cloned());
        h.extend(self.rates.iter().cloned());
        for (names, _) in &self.extra {
            h.extend(names.iter().cloned());
        }
        if self.energies.is_some() {
            h.extend(["kinetic".to_string(), "potential".to_string()]);
        }
        h.extend(["integral", "residual_position", "residual_velocity"].map(String::from));
        if Q != N {
            h.push("unit_error".to_string());
        }
        h
    }

    /// Writes the table.
    ///
    /// # Errors
    /// [`Error::Io`] if writing fails.
    pub fn write(&self, w: impl Write) -> Result<(), Error> {
        let mut out = csv::Writer::from_writer(w);
        out.write_record(self.header()).map_err(io)?;
        for k in 0..self.traj.len() {
            let cells = self.row(k).into_iter().map(|x| match x {
                Some(x) => x.to_string(),
                None => String::new(),
            });
            out.write_record(cells).map_err(io)?;
        }
        out.flush()?;
        Ok(())
    }

    /// The number of rows: one a stored point.
    #[cfg(feature = "plot")]
    pub(crate) fn len(&self) -> usize {
        self.traj.len()
    }

    /// Row `k` in the header's order, `None` where the cell is written empty.
    pub(crate) fn row(&self, k: usize) -> Vec<Option<f64>> {
        let tr = &*self.traj;
        let kinetic = 1 + Q + N + self.extra.iter().map(|(n, _)| n.len()).sum::<usize>();
        let mut row: Vec<T> = vec![tr.times()[k]];
        row.extend(tr.positions()[k].iter().chain(tr.velocities()[k].iter()));
        for (_, values) in &self.extra {
            row.extend(values[k].iter().copied());
        }
        if let Some(e) = &self.energies {
            row.extend([e[k].0, e[k].1]);
        }
        row.push(tr.integrals()[k]);
        row.extend(tr.residuals()[k]);
        if Q != N {
            row.push(tr.unit_errors()[k]);
        }
        let mut cells: Vec<Option<f64>> = row.iter().map(|x| Some(x.to_f64())).collect();
        let from = self.blank.partition_point(|&(r, _)| r < k);
        for &(_, cell) in self.blank[from..].iter().take_while(|&&(r, _)| r == k) {
            let column = match cell {
                Cell::Rate(j) => 1 + Q + j,
                Cell::Kinetic => kinetic,
            };
            cells[column] = None;
        }
        cells
    }

    /// The names of the columns of q, the coordinates.
    #[cfg(feature = "plot")]
    pub(crate) fn coordinates(&self) -> &[String] {
        &self.names
    }

    /// [`write`](Self::write) to a new file at `path`.
    ///
    /// # Errors
    /// As [`write`](Self::write), plus failure to create the file.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let file = std::fs::File::create(path)?;
        self.write(std::io::BufWriter::new(file))
    }
}

fn io(e: csv::Error) -> Error {
    Error::Io(std::io::Error::other(e))
}

/// The CSV output of a run lives here, beside the table that writes it, so that
/// the integrators' solution type knows nothing of systems or files.
impl<T: Real, const N: usize, const Q: usize> Trajectory<T, N, Q> {
    /// Writes the recorded points as CSV: a header `t,<q names>,<v names>,
    /// integral,residual_position,residual_velocity` and one row per point,
    /// numbers in the shortest form that reads back exactly. (With the system
    /// at hand, [`table`](Self::table) adds the energies and the multipliers.)
    ///
    /// What it keeps and drops: the stored points read back bit for bit
    /// (every value is written in Rust's shortest round-trip form); the dense
    /// output, the statistics and the recording policy are not written, so a
    /// run read from CSV has no `state_at` between its points (serialize it
    /// with the `serde` feature to keep them).
    ///
    /// `names` are the coordinate names (e.g. [`Lagrangian::COORDINATES`]): the
    /// columns are then `t,theta,phi,dot_theta,dot_phi,integral,…`. An empty
    /// slice gives `q0,q1,..,dot_q0,dot_q1,..`.
    ///
    /// [`Lagrangian::COORDINATES`]: crate::Lagrangian::COORDINATES
    ///
    /// # Errors
    /// [`Error::Settings`] if `names` has neither Q nor 0 entries;
    /// [`Error::Io`] if writing fails.
    pub fn write_csv(&self, w: impl Write, names: &[&str]) -> Result<(), Error> {
        Table::new(self, names)?.write(w)
    }

    /// The run as a [`Table`](crate::Table) with the system's coordinate
    /// names and its kinetic and potential energy at every point (add the
    /// multipliers with [`Table::multipliers`](crate::Table::multipliers)).
    pub fn table<S: crate::system::Lagrangian<T, N, Q>>(&self, sys: &S) -> Table<'_, T, N, Q> {
        Table::of(self, sys)
    }

    /// [`write_csv`](Self::write_csv) to a new file at `path` (buffered).
    ///
    /// # Errors
    /// As [`write_csv`](Self::write_csv), plus failure to create the file.
    pub fn save_csv(&self, path: impl AsRef<Path>, names: &[&str]) -> Result<(), Error> {
        let file = std::fs::File::create(path)?;
        self.write_csv(std::io::BufWriter::new(file), names)
    }
}

/// A table whose columns do not fit its points.
fn csv(problem: String) -> Error {
    SettingsError::Data {
        owner: "CSV",
        problem,
    }
    .into()
}
