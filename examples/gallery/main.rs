//! The main job: simulate every catalog system on built-in defaults and print, per
//! system, the integrator's work, the drift of its conserved quantity, the
//! constraint residuals and the wall time.
//!
//!     cargo run --release --example gallery
//!
//! The systems and what each shows are listed in `entries`; their runs live in
//! one module per family (`minimal`, `constrained`, `nonholonomic`, `cavity`, `contact`,
//! `control`, `planning`, `identification`); `row` is what a run reports, `figure` what it keeps to draw,
//! `layout` which coordinates go on which panel, `plot` the pictures, `output`
//! the files and index.html, `table` the printed summary.

#[path = "../catalog/mod.rs"]
mod catalog;
mod cavity;
mod constrained;
mod contact;
mod control;
mod entries;
mod figure;
mod free;
mod identification;
mod layout;
mod legged;
#[path = "../catalog/legged.rs"]
mod legged_robot;
mod minimal;
mod nonholonomic;
#[path = "../catalog/operational.rs"]
mod operational;
mod output;
mod planning;
mod plot;
mod row;
mod still;
mod table;

use lagrange::{Error, SettingsError};

fn main() -> Result<(), Error> {
    let out = output_dir()?;
    let rows = entries::ENTRIES
        .iter()
        .map(|entry| {
            let mut row = (entry.run)(entry.name)?;
            row.about = entry.about;
            Ok(row)
        })
        .collect::<Result<Vec<_>, Error>>()?;
    table::print(&rows);
    let find = |name: &str| rows.iter().find(|r| r.system == name);
    let double = minimal::DOUBLE_PENDULUM;
    let animations = output::Animations {
        double_pendulum: find(entries::DOUBLE_PENDULUM).map(|r| (r, double.l1, double.l2)),
        rolling_disk: find(entries::ROLLING_DISK).map(|r| (r, nonholonomic::DISK_RADIUS)),
        cavity: find(entries::CAVITY).map(|r| (r, cavity::RADIUS)),
    };
    let index = output::write(&out, &rows, &animations)?;
    println!("\nplots, animations and CSV files: {}", index.display());
    Ok(())
}

/// `--out DIR`, or `target/gallery` under the current directory.
fn output_dir() -> Result<std::path::PathBuf, Error> {
    let mut args = std::env::args().skip(1);
    match (args.next().as_deref(), args.next()) {
        (None, _) => Ok("target/gallery".into()),
        (Some("--out"), Some(dir)) => Ok(dir.into()),
        _ => Err(gallery_error(
            "usage: cargo run --release --example gallery [-- --out DIR]",
        )),
    }
}

/// A gallery entry that cannot be drawn, or a bad command line.
pub(crate) fn gallery_error(problem: &str) -> Error {
    Error::Settings(SettingsError::Data {
        owner: "gallery",
        problem: problem.into(),
    })
}
