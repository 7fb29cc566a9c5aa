//! Animations made of a scene's stills at successive times (`Scene::still`),
//! all at one scale; the single still of each system's row is drawn by the
//! library (`lagrange::picture::segments_png`).

use lagrange::Error;
use lagrange::scene::Segment;
use plotters::prelude::*;
use std::path::Path;

fn err(e: impl std::fmt::Display) -> Error {
    Error::Io(std::io::Error::other(format!("gallery still: {e}")))
}

/// An animation of a scene: one frame per set of segments (the scene's
/// still at successive times), all at one scale so that the motion shows,
/// `caption(k)` above frame k.
pub(crate) fn gif(
    path: &Path,
    frames: &[Vec<Segment>],
    caption: impl Fn(usize) -> String,
) -> Result<(), Error> {
    let (w, h) = (360_u32, 300_u32);
    let root = BitMapBackend::gif(path, (w, h), 50)
        .map_err(err)?
        .into_drawing_area();
    let Some(view) = View::fitting(frames.iter().flatten(), (w, h - 24)) else {
        return Ok(());
    };
    for (k, segments) in frames.iter().enumerate() {
        root.fill(&WHITE).map_err(err)?;
        root.draw(&Text::new(caption(k), (8, 4), ("sans-serif", 15)))
            .map_err(err)?;
        let below = root.margin(24, 0, 0, 0);
        draw(&below, &view, segments)?;
        root.present().map_err(err)?;
    }
    Ok(())
}

/// One scale for both axes, the larger extent filling its side.
struct View {
    scale: f64,
    centre: [f64; 2],
    size: (u32, u32),
}

impl View {
    fn fitting<'a>(segments: impl Iterator<Item = &'a Segment>, size: (u32, u32)) -> Option<Self> {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in segments.flatten() {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !(lo[0] < hi[0] || lo[1] < hi[1]) {
            return None;
        }
        let (w, h) = (f64::from(size.0 - 12), f64::from(size.1 - 12));
        Some(View {
            scale: ((hi[0] - lo[0]) / w).max((hi[1] - lo[1]) / h),
            centre: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0],
            size,
        })
    }

    fn pixel(&self, p: &lagrange::nalgebra::Vector2<f64>) -> (i32, i32) {
        let x = f64::from(self.size.0) / 2.0 + (p[0] - self.centre[0]) / self.scale;
        let y = f64::from(self.size.1) / 2.0 - (p[1] - self.centre[1]) / self.scale;
        (x.round() as i32, y.round() as i32)
    }
}

fn draw(
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    view: &View,
    segments: &[Segment],
) -> Result<(), Error> {
    let ink = RGBColor(58, 111, 176);
    for [a, b] in segments {
        area.draw(&PathElement::new(
            vec![view.pixel(a), view.pixel(b)],
            ink.stroke_width(1),
        ))
        .map_err(err)?;
    }
    Ok(())
}
