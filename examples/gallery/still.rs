//! The small picture of each system's scene in the index's table: the scene's
//! still (its shapes' edges at mid-run, `Scene::still`) drawn with plotters.

use lagrange::Error;
use lagrange::scene::Segment;
use plotters::prelude::*;
use std::path::Path;

fn err(e: impl std::fmt::Display) -> Error {
    Error::Io(std::io::Error::other(format!("gallery still: {e}")))
}

/// Draws the segments, equal scales on both axes, into a 180 × 120 PNG.
pub(crate) fn png(path: &Path, segments: &[Segment]) -> Result<(), Error> {
    let (w, h) = (180_u32, 120_u32);
    let root = BitMapBackend::new(path, (w, h)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in segments.iter().flatten() {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if !(lo[0] < hi[0] || lo[1] < hi[1]) {
        return root.present().map_err(err);
    }
    // One scale for both axes, the larger extent filling its side.
    let scale = ((hi[0] - lo[0]) / f64::from(w - 12)).max((hi[1] - lo[1]) / f64::from(h - 12));
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let pixel = |p: &lagrange::nalgebra::Vector2<f64>| {
        let x = f64::from(w) / 2.0 + (p[0] - centre[0]) / scale;
        let y = f64::from(h) / 2.0 - (p[1] - centre[1]) / scale;
        (x.round() as i32, y.round() as i32)
    };
    let ink = RGBColor(58, 111, 176);
    for [a, b] in segments {
        root.draw(&PathElement::new(
            vec![pixel(a), pixel(b)],
            ink.stroke_width(1),
        ))
        .map_err(err)?;
    }
    root.present().map_err(err)
}
