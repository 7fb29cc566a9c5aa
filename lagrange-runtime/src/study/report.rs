//! A study as text: a markdown table for people, CSV for other tools.

use super::{ReferenceKind, Study};
use crate::error::Error;
use std::io::Write;
use std::path::Path;
use std::time::Duration;

/// The markdown table's columns, in order.
pub const MARKDOWN_COLUMNS: [&str; 11] = [
    "method",
    "setting",
    "error in q at t_end",
    "relative",
    "error in q̇",
    "max integral drift",
    "max residual",
    "RHS evaluations",
    "steps",
    "wall time",
    "note",
];

/// The CSV header's columns, in order.
pub const CSV_COLUMNS: [&str; 17] = [
    "method",
    "setting",
    "value",
    "error",
    "relative_error",
    "velocity_error",
    "residual",
    "resolved",
    "drift",
    "evaluations",
    "steps",
    "accepted",
    "rejected",
    "jacobians",
    "factorizations",
    "wall_time_s",
    "failure",
];

impl Study {
    /// A line on the reference, then a markdown table with the columns
    /// [`MARKDOWN_COLUMNS`]. A failed run shows its error in the note column;
    /// an error below the reference's own estimated error is marked as not
    /// resolved.
    pub fn to_markdown(&self) -> String {
        let mut out = format!("{}\n\n", self.reference_line());
        out += &format!("| {} |\n", MARKDOWN_COLUMNS.join(" | "));
        out += &format!("|{}\n", "---|".repeat(MARKDOWN_COLUMNS.len()));
        for row in &self.rows {
            let cells = match &row.outcome {
                Ok(m) => {
                    let note = if m.resolved {
                        ""
                    } else {
                        "below the reference's accuracy"
                    };
                    [
                        format!("{:.2e}", m.error),
                        format!("{:.2e}", m.relative_error),
                        m.velocity_error.map_or("–".into(), |e| format!("{e:.2e}")),
                        m.drift.map_or("–".into(), |d| format!("{d:.2e}")),
                        format!("{:.1e}", m.residual),
                        m.stats.evaluations.to_string(),
                        m.stats.steps().to_string(),
                        duration(m.wall_time),
                        note.to_string(),
                    ]
                }
                Err(e) => {
                    let dash = || "–".to_string();
                    [
                        dash(),
                        dash(),
                        dash(),
                        dash(),
                        dash(),
                        dash(),
                        dash(),
                        dash(),
                        format!("failed: {}", e.to_string().replace('|', "\\|")),
                    ]
                }
            };
            out += &format!(
                "| {} | {} | {} |\n",
                row.method.replace('|', "\\|"),
                row.setting,
                cells.join(" | ")
            );
        }
        out
    }

    fn reference_line(&self) -> String {
        let given = |u: Option<f64>| match u {
            Some(u) => format!(
                "Reference: a trajectory supplied by the caller, uncertainty {u:.2e} (errors below that are not resolved)."
            ),
            None => "Reference: a trajectory supplied by the caller.".into(),
        };
        match self.reference {
            ReferenceKind::Exact => "Reference: closed-form solution.".into(),
            ReferenceKind::Given => given(self.uncertainty),
            ReferenceKind::Computed {
                tolerance,
                evaluations,
                wall_time,
                uncertainty,
            } => {
                let mut s = format!(
                    "Reference: DOP853 at tolerance {tolerance:e} ({evaluations} RHS evaluations, {}).",
                    duration(wall_time)
                );
                if let Some(u) = uncertainty {
                    s += &format!(
                        " Its distance at t_end from a run at tolerance {:e}: {u:.2e} \
                         (errors below that are not resolved).",
                        10.0 * tolerance
                    );
                }
                s
            }
        }
    }

    /// Writes the rows as CSV with the header [`CSV_COLUMNS`]; the numbers of a
    /// failed run are empty and `failure` holds its error message.
    ///
    /// # Errors
    /// [`Error::Io`] if writing fails.
    pub fn write_csv_to(&self, mut w: impl Write) -> Result<(), Error> {
        writeln!(w, "{}", CSV_COLUMNS.join(","))?;
        for row in &self.rows {
            write!(
                w,
                "{},{},{}",
                csv_field(&row.method),
                row.setting.kind(),
                row.setting.value()
            )?;
            match &row.outcome {
                Ok(m) => {
                    let s = &m.stats;
                    writeln!(
                        w,
                        ",{},{},{},{},{},{},{},{},{},{},{},{},{},",
                        m.error,
                        m.relative_error,
                        m.velocity_error.map_or(String::new(), |e| e.to_string()),
                        m.residual,
                        m.resolved,
                        m.drift.map_or(String::new(), |d| d.to_string()),
                        s.evaluations,
                        s.steps(),
                        s.accepted,
                        s.rejected,
                        s.jacobians,
                        s.factorizations,
                        m.wall_time.as_secs_f64()
                    )?;
                }
                Err(e) => writeln!(w, ",,,,,,,,,,,,,,{}", csv_field(&e.to_string()))?,
            }
        }
        w.flush()?;
        Ok(())
    }

    /// [`write_csv_to`](Self::write_csv_to) a new file at `path`.
    ///
    /// # Errors
    /// [`Error::Io`] if the file cannot be created or written.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<(), Error> {
        let file = std::fs::File::create(path)?;
        self.write_csv_to(std::io::BufWriter::new(file))
    }
}

/// RFC 4180 quoting when the field needs it.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// 3 significant digits in µs, ms or s.
pub(crate) fn duration(d: Duration) -> String {
    let s = d.as_secs_f64();
    let (x, unit) = if s < 1e-3 {
        (s * 1e6, "µs")
    } else if s < 1.0 {
        (s * 1e3, "ms")
    } else {
        (s, "s")
    };
    let decimals = if x >= 100.0 {
        0
    } else if x >= 10.0 {
        1
    } else {
        2
    };
    format!("{x:.decimals$} {unit}")
}
