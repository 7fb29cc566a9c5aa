//! What the gallery keeps of each run to show it: the motion sampled at every
//! step, the drift of the conserved quantity, the constraint residuals, and the
//! trajectory as CSV.

use lagrange::prelude::*;

/// One run, reduced to plain columns (the systems differ in N).
pub(crate) struct Figure {
    /// Names of the generalized coordinates, in order.
    pub names: Vec<String>,
    pub t: Vec<f64>,
    /// `q[i][k]`: coordinate i at step k.
    pub q: Vec<Vec<f64>>,
    /// `v[i][k]`: the rate of coordinate i at step k.
    pub v: Vec<Vec<f64>>,
    /// Which coordinates are cyclic (drawn as rates on a panel of their own).
    pub cyclic: Vec<bool>,
    /// |I(t) − I(0)| / max(|I(0)|, 1e-300), when a quantity is conserved.
    pub drift: Option<Vec<f64>>,
    /// (|Φ|, |G q̇ + g|) per step, when the system has constraints.
    pub residuals: Option<Vec<[f64; 2]>>,
    /// The trajectory as CSV (t, q, q̇, integral, residuals).
    pub csv: String,
    /// Panels a row adds below the motion (an estimate against the truth),
    /// each over times of its own.
    pub extra: Vec<Extra>,
}

/// A panel of series over their own times, below a row's motion.
pub(crate) struct Extra {
    pub y_label: &'static str,
    pub t: Vec<f64>,
    pub series: Vec<(String, Vec<f64>)>,
}

impl Figure {
    pub(crate) fn of<const N: usize>(
        traj: &Trajectory<f64, N>,
        names: &[&str],
        cyclic: &[bool; N],
        conservative: bool,
    ) -> Result<Self, Error> {
        let q = (0..N)
            .map(|i| traj.positions().iter().map(|p| p[i]).collect())
            .collect();
        let v = (0..N)
            .map(|i| traj.velocities().iter().map(|p| p[i]).collect())
            .collect();
        let i0 = traj.integrals()[0];
        let scale = i0.abs().max(1e-300);
        let drift = conservative.then(|| {
            traj.integrals()
                .iter()
                .map(|i| (i - i0).abs() / scale)
                .collect()
        });
        let residuals = traj
            .residuals()
            .iter()
            .any(|r| *r != [0.0; 2])
            .then(|| traj.residuals().to_vec());
        let mut csv = Vec::new();
        traj.write_csv(&mut csv, names)?;
        Ok(Figure {
            names: names.iter().map(|s| s.to_string()).collect(),
            t: traj.times().to_vec(),
            q,
            v,
            cyclic: cyclic.to_vec(),
            drift,
            residuals,
            csv: String::from_utf8_lossy(&csv).into_owned(),
            extra: Vec::new(),
        })
    }

    /// A figure from recorded points (t, q, q̇) of a run made of several
    /// phases (the cavity's flights and slide); nothing conserved is drawn and
    /// no coordinate is taken as cyclic.
    pub(crate) fn from_points<const N: usize>(
        names: &[&str; N],
        points: &[(f64, [f64; N], [f64; N])],
    ) -> Self {
        let mut csv = format!(
            "t,{},{}\n",
            names.join(","),
            names.map(|n| format!("dot_{n}")).join(",")
        );
        for (t, q, v) in points {
            let values: Vec<String> = q.iter().chain(v).map(|x| x.to_string()).collect();
            csv += &format!("{t},{}\n", values.join(","));
        }
        Figure {
            names: names.iter().map(|s| s.to_string()).collect(),
            t: points.iter().map(|p| p.0).collect(),
            q: (0..N)
                .map(|i| points.iter().map(|p| p.1[i]).collect())
                .collect(),
            v: (0..N)
                .map(|i| points.iter().map(|p| p.2[i]).collect())
                .collect(),
            cyclic: vec![false; N],
            drift: None,
            residuals: None,
            csv,
            extra: Vec::new(),
        }
    }

    /// The coordinates at time t, linearly interpolated between steps (for
    /// animation frames; the steps are dense enough to draw).
    pub(crate) fn at(&self, t: f64) -> Vec<f64> {
        let k = self
            .t
            .partition_point(|&s| s <= t)
            .clamp(1, self.t.len() - 1);
        let (t0, t1) = (self.t[k - 1], self.t[k]);
        let w = if t1 > t0 {
            ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        self.q
            .iter()
            .map(|c| c[k - 1] + w * (c[k] - c[k - 1]))
            .collect()
    }

    /// The span of the run.
    pub(crate) fn span(&self) -> (f64, f64) {
        (self.t[0], *self.t.last().unwrap_or(&self.t[0]))
    }
}
