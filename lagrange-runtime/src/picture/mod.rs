//! Pictures without a browser (feature `plot`): PNGs drawn with plotters and
//! the bundled font.
//!
//! - [`Table::plot_png`](crate::Table::plot_png): chosen columns of a run's
//!   table against t, by the names the table gives them ([`TablePlot`]);
//! - [`Scene::still_png`](crate::Scene::still_png): a scene's still at a time,
//!   at equal scales on both axes, seen from a chosen
//!   [`View`](crate::scene::View) ([`StillPicture`]), and [`segments_png`] for
//!   segments already computed;
//! - the work-precision plot of a study,
//!   [`Study::plot_png`](crate::Study::plot_png).
//!
//! plotters' default text rendering asks the system for fonts (fontconfig);
//! many build machines and containers have none, so the `plot` feature enables
//! plotters' `ab_glyph` text backend and registers DejaVu Sans, shipped in
//! `fonts/` with its licence, as the "sans-serif" family
//! ([`register_font`], which every drawing here calls first).

mod series;
mod still;

pub use series::TablePlot;
pub use still::{StillPicture, segments_png};

use crate::error::Error;
use plotters::style::{FontStyle, RGBColor};
use std::sync::OnceLock;

const FONT: &[u8] = include_bytes!("../../fonts/DejaVuSans.ttf");

/// The colours of the series, in order (Tableau 10: distinguishable, and
/// legible on white).
pub const COLORS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Registers the bundled DejaVu Sans as plotters' "sans-serif" family, once
/// per process, for pictures drawn with plotters beside the library's (the
/// gallery's panels). The outcome is remembered, so a failure is reported on
/// every call rather than only the first.
///
/// # Errors
/// [`Error::Io`] if the font cannot be parsed.
pub fn register_font() -> Result<(), Error> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(plot_error(
            "the bundled font DejaVuSans.ttf could not be parsed",
        ))
    }
}

/// A drawing's failure as [`Error::Io`].
pub(crate) fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Io(std::io::Error::other(format!("plot: {e}")))
}

/// A picture's size refused: plotters draws nothing into zero pixels.
fn check_size(owner: &'static str, (w, h): (u32, u32)) -> Result<(), Error> {
    if w < 32 || h < 32 {
        return Err(crate::error::SettingsError::Data {
            owner,
            problem: format!("a picture of {w} × {h} pixels: at least 32 × 32"),
        }
        .into());
    }
    Ok(())
}

#[cfg(test)]
mod tests;
