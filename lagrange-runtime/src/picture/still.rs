//! A scene's still drawn as a PNG: the segments of [`Scene::still_from`] at one
//! scale on both axes, fitted to the picture.

use super::{check_size, plot_error, register_font};
use crate::error::Error;
use crate::numeric::Real;
use crate::pose::Posed;
use crate::scene::{Scene, Segment, View};
use crate::system::Lagrangian;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// The owner named in a still's errors.
const OWNER: &str = "still picture";

/// The segments' colour: the scene's first run's.
const INK: RGBColor = RGBColor(58, 111, 176);

/// Room above the still for its title, in pixels.
const TITLE_HEIGHT: u32 = 26;

/// How [`Scene::still_png`] and [`segments_png`] draw a still: from where, how
/// big, with what title and line width.
///
/// ```
/// use lagrange_runtime::picture::StillPicture;
/// use lagrange_runtime::scene::View;
/// let side = StillPicture::new().view(View::Xz).size(400, 300).title("t = 2.5 s");
/// # let _ = side;
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct StillPicture {
    view: View,
    size: (u32, u32),
    title: Option<String>,
    line_width: u32,
}

impl Default for StillPicture {
    fn default() -> Self {
        Self::new()
    }
}

impl StillPicture {
    /// Seen from the page's starting camera ([`View::Camera`]), 480 × 360
    /// pixels, lines 2 pixels wide, no title.
    pub fn new() -> Self {
        Self {
            view: View::Camera,
            size: (480, 360),
            title: None,
            line_width: 2,
        }
    }

    /// Where the still is seen from (used by [`Scene::still_png`]; segments
    /// given to [`segments_png`] are already projected).
    pub fn view(mut self, view: View) -> Self {
        self.view = view;
        self
    }

    /// The picture's size in pixels (at least 32 × 32).
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// The title above the still.
    pub fn title(mut self, title: impl Into<String>) -> Self {
        self.title = Some(title.into());
        self
    }

    /// The segments' width in pixels (default 2).
    pub fn line_width(mut self, pixels: u32) -> Self {
        self.line_width = pixels;
        self
    }
}

impl<T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q> + Lagrangian<T, N, Q>>
    Scene<'_, T, N, S, Q>
{
    /// Draws the still of the first run at time `t` (its shapes' edges and
    /// the paths over the run, [`Scene::still_from`] seen from the picture's
    /// view) as a PNG at `path`, at one scale on both axes, fitted to the
    /// picture, on white.
    ///
    /// ```no_run
    /// # use lagrange_runtime::{Error, Lagrangian, Posed, Trajectory};
    /// use lagrange_runtime::picture::StillPicture;
    /// use lagrange_runtime::scene::View;
    /// # fn demo<S: Lagrangian<f64, 2> + Posed<f64, 2>>(sys: &S, run: &Trajectory<f64, 2>) -> Result<(), Error> {
    /// run.scene(sys).still_png("still.png", 1.0, &StillPicture::new().view(View::Xz))?;
    /// # Ok(()) }
    /// ```
    ///
    /// # Errors
    /// As [`Scene::still`]; [`Error::Settings`] for a size below 32 × 32
    /// pixels; [`Error::Io`] if the file cannot be written.
    pub fn still_png(
        &self,
        path: impl AsRef<Path>,
        t: f64,
        picture: &StillPicture,
    ) -> Result<(), Error> {
        let segments = self.still_from(t, picture.view)?;
        segments_png(path, &segments, picture)
    }
}

/// Draws `segments` (a still, already projected: x right, y up) as a PNG at
/// `path`, as [`Scene::still_png`] does; the picture's view is not used.
/// Segments that all meet in one point (or none) leave the picture blank.
///
/// # Errors
/// [`Error::Settings`] for a size below 32 × 32 pixels; [`Error::Io`] if
/// the file cannot be written.
pub fn segments_png(
    path: impl AsRef<Path>,
    segments: &[Segment],
    picture: &StillPicture,
) -> Result<(), Error> {
    check_size(OWNER, picture.size)?;
    let root = BitMapBackend::new(path.as_ref(), picture.size).into_drawing_area();
    draw(&root, segments, picture)?;
    root.present().map_err(plot_error)
}

/// The still on `area`, on white (the font registered first, for the title).
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    segments: &[Segment],
    picture: &StillPicture,
) -> Result<Option<Fit>, Error> {
    register_font()?;
    area.fill(&WHITE).map_err(plot_error)?;
    let below = match &picture.title {
        Some(title) => {
            let style = ("sans-serif", 16).into_font().color(&BLACK);
            area.draw(&Text::new(title.clone(), (8, 5), style))
                .map_err(plot_error)?;
            area.margin(TITLE_HEIGHT, 0, 0, 0)
        }
        None => area.clone(),
    };
    let Some(fit) = Fit::of(segments, below.dim_in_pixel()) else {
        return Ok(None);
    };
    let style = INK.stroke_width(picture.line_width.max(1));
    for [a, b] in segments {
        let path = vec![fit.pixel(a), fit.pixel(b)];
        below
            .draw(&PathElement::new(path, style))
            .map_err(plot_error)?;
    }
    Ok(Some(fit))
}

/// One scale for both axes, the larger extent filling its side, with a
/// margin of 6 pixels.
#[derive(Clone, Copy, Debug)]
pub(super) struct Fit {
    scale: f64,
    centre: [f64; 2],
    size: (u32, u32),
}

impl Fit {
    /// The fit of `segments` into `size`; `None` when they have no extent.
    pub(super) fn of(segments: &[Segment], size: (u32, u32)) -> Option<Self> {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in segments
            .iter()
            .flatten()
            .filter(|p| p.iter().all(|x| x.is_finite()))
        {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !(lo[0] < hi[0] || lo[1] < hi[1]) {
            return None;
        }
        let w = f64::from(size.0.saturating_sub(12).max(1));
        let h = f64::from(size.1.saturating_sub(12).max(1));
        Some(Fit {
            scale: ((hi[0] - lo[0]) / w).max((hi[1] - lo[1]) / h),
            centre: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0],
            size,
        })
    }

    /// The pixel of a point of the picture plane (y up, so rows counted down).
    pub(super) fn pixel(&self, p: &nalgebra::Vector2<f64>) -> (i32, i32) {
        let x = f64::from(self.size.0) / 2.0 + (p[0] - self.centre[0]) / self.scale;
        let y = f64::from(self.size.1) / 2.0 - (p[1] - self.centre[1]) / self.scale;
        (x.round() as i32, y.round() as i32)
    }
}
