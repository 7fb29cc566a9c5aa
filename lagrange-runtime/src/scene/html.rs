//! The page: the template, the viewer script and the scene as JSON, written
//! by hand (a few arrays of numbers need no serializer). Numbers are written
//! with a fixed number of decimals chosen from the scene's size, so a frame
//! costs a few bytes per number whatever the run's length.

use std::fmt::Write;

use super::sample::Frames;
use super::shapes::Drawn;
use crate::pose::{Anchor, Solid};

const TEMPLATE: &str = include_str!("page.html");
const VIEWER: &str = include_str!("viewer.js");
const SIDE_BY_SIDE: &str = " Side by side: each run after the first is drawn moved under the first, one lane to its left, so that their motions compare; positions are the first run's.";

/// What the page shows besides the frames.
pub(super) struct Static<'a> {
    pub title: &'a str,
    pub bodies: &'a [&'a str],
    pub points: &'a [&'a str],
    pub shapes: &'a [Drawn],
    pub plot: &'a [&'a str],
    pub planar: bool,
    /// Runs after the first drawn beside it, following it ([`super::Scene::side_by_side`]).
    pub side_by_side: bool,
}

/// One run as the page gets it.
pub(super) struct RunData<'a> {
    pub label: &'a str,
    pub color: &'a str,
    pub opacity: f64,
    pub frames: &'a Frames,
}

/// The decimals for a quantity of magnitude `scale`: about five significant
/// digits (a tenth of a millimetre on a metre-sized scene).
pub(super) fn decimals(scale: f64) -> usize {
    if !(scale > 0.0 && scale.is_finite()) {
        return 4;
    }
    (4 - scale.log10().floor() as i64).clamp(1, 12) as usize
}

/// `x` with `d` decimals, trailing zeros dropped (and no `-0`).
fn number(out: &mut String, x: f64, d: usize) {
    let start = out.len();
    let _ = write!(out, "{x:.d$}");
    if out[start..].contains('.') {
        let trimmed = out[start..]
            .trim_end_matches('0')
            .trim_end_matches('.')
            .len();
        out.truncate(start + trimmed);
    }
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
    }
}

fn numbers(out: &mut String, xs: impl IntoIterator<Item = f64>, d: usize) {
    out.push('[');
    for (i, x) in xs.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        number(out, x, d);
    }
    out.push(']');
}

/// A JSON string (the labels and names are the user's).
fn string(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            // `</script>` must not close the data block.
            '<' => out.push_str("\\u003c"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn strings(out: &mut String, xs: &[&str]) {
    out.push('[');
    for (i, x) in xs.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        string(out, x);
    }
    out.push(']');
}

fn anchor(out: &mut String, a: Anchor) {
    let _ = match a {
        Anchor::Body(i) => write!(out, "[\"b\",{i}]"),
        Anchor::Point(i) => write!(out, "[\"p\",{i}]"),
    };
}

fn shape(out: &mut String, s: &Drawn, d: usize) {
    out.push_str("{\"on\":");
    anchor(out, s.on);
    out.push_str(",\"at\":");
    numbers(out, s.at.iter().copied(), d);
    out.push_str(",\"axes\":");
    numbers(out, s.axes.transpose().iter().copied(), 6);
    let _ = write!(out, ",\"default\":{}", s.default);
    match s.solid {
        Solid::Box { size } => {
            out.push_str(",\"kind\":\"box\",\"size\":");
            numbers(out, size.iter().copied(), d);
        }
        Solid::Sphere { radius } => {
            out.push_str(",\"kind\":\"sphere\",\"radius\":");
            number(out, radius, d);
        }
        Solid::Cylinder {
            radius,
            length,
            axis,
        }
        | Solid::Capsule {
            radius,
            length,
            axis,
        } => {
            let kind = match s.solid {
                Solid::Cylinder { .. } => "cylinder",
                _ => "capsule",
            };
            let _ = write!(out, ",\"kind\":\"{kind}\",\"axis\":{axis},\"radius\":");
            number(out, radius, d);
            out.push_str(",\"length\":");
            number(out, length, d);
        }
        Solid::Line { to } => {
            out.push_str(",\"kind\":\"line\",\"to\":");
            anchor(out, to);
        }
    }
    out.push('}');
}

/// The run's frames: positions with `d` decimals, quaternions with five.
fn run(out: &mut String, r: &RunData, d: usize, plot_d: usize) {
    let f = r.frames;
    out.push_str("{\"label\":");
    string(out, r.label);
    out.push_str(",\"color\":");
    string(out, r.color);
    let _ = write!(
        out,
        ",\"opacity\":{},\"count\":{},\"t0\":",
        r.opacity, f.count
    );
    number(out, f.t0, 12);
    out.push_str(",\"dt\":");
    number(out, f.dt, 15);
    out.push_str(",\"bodies\":");
    let digits = f
        .bodies
        .iter()
        .enumerate()
        .map(|(i, &x)| (x, if i % 7 < 3 { d } else { 5 }));
    out.push('[');
    for (i, (x, digits)) in digits.enumerate() {
        if i > 0 {
            out.push(',');
        }
        number(out, x, digits);
    }
    out.push_str("],\"points\":");
    numbers(out, f.points.iter().copied(), d);
    out.push_str(",\"plot\":");
    numbers(out, f.plotted.iter().copied(), plot_d);
    out.push('}');
}

/// The size of the scene: the largest position or shape size, for the decimals.
fn extent(runs: &[RunData], shapes: &[Drawn]) -> f64 {
    let positions = runs.iter().flat_map(|r| {
        let bodies = r.frames.bodies.chunks(7).flat_map(|c| c[..3].iter());
        bodies.chain(r.frames.points.iter())
    });
    let sizes = shapes.iter().map(|s| s.at.amax().max(size(&s.solid)));
    positions.map(|x| x.abs()).chain(sizes).fold(0.0, f64::max)
}

fn size(s: &Solid<f64>) -> f64 {
    match *s {
        Solid::Box { size } => size.amax(),
        Solid::Sphere { radius } => radius,
        Solid::Cylinder { radius, length, .. } | Solid::Capsule { radius, length, .. } => {
            radius.max(length)
        }
        Solid::Line { .. } => 0.0,
    }
}

/// The whole page.
pub(super) fn page(s: &Static, runs: &[RunData]) -> String {
    let d = decimals(extent(runs, s.shapes));
    let plot_scale = runs
        .iter()
        .flat_map(|r| r.frames.plotted.iter())
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut data = String::new();
    let _ = write!(
        data,
        "{{\"planar\":{},\"sideBySide\":{}",
        s.planar, s.side_by_side
    );
    data.push_str(",\"bodies\":");
    strings(&mut data, s.bodies);
    data.push_str(",\"points\":");
    strings(&mut data, s.points);
    data.push_str(",\"plot\":");
    strings(&mut data, s.plot);
    // A point is a dot unless the description draws shapes of its own (then
    // it chose what to show: the bicycle's helper points stay hidden).
    let own_shapes = s.shapes.iter().any(|x| !x.default);
    let dots = vec![(!own_shapes).to_string(); s.points.len()];
    let _ = write!(data, ",\"pointDots\":[{}]", dots.join(","));
    data.push_str(",\"shapes\":[");
    for (i, x) in s.shapes.iter().enumerate() {
        if i > 0 {
            data.push(',');
        }
        shape(&mut data, x, d);
    }
    data.push_str("],\"runs\":[");
    for (i, r) in runs.iter().enumerate() {
        if i > 0 {
            data.push(',');
        }
        run(&mut data, r, d, decimals(plot_scale));
    }
    data.push_str("]}");
    let mut title = String::new();
    for c in s.title.chars() {
        match c {
            '<' => title.push_str("&lt;"),
            '>' => title.push_str("&gt;"),
            '&' => title.push_str("&amp;"),
            c => title.push(c),
        }
    }
    TEMPLATE
        .replace("{{TITLE}}", &title)
        .replace("{{NOTE}}", if s.side_by_side { SIDE_BY_SIDE } else { "" })
        .replace("{{SCRIPT}}", VIEWER)
        .replace("{{DATA}}", &data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        let mut out = String::new();
        numbers(&mut out, [1.0, -0.0000001, 0.25, 1234.56789, -2.5], 4);
        assert_eq!(out, "[1,0,0.25,1234.5679,-2.5]");
        assert_eq!(decimals(1.0), 4);
        assert_eq!(decimals(50.0), 3);
        assert_eq!(decimals(0.01), 6);
    }

    #[test]
    fn strings_cannot_close_the_script() {
        let mut out = String::new();
        string(&mut out, "a \"b\" </script>\n");
        assert_eq!(out, "\"a \\\"b\\\" \\u003c/script>\\u000a\"");
    }

    /// The page reads the axes row by row (nalgebra stores columns).
    #[test]
    fn axes_are_written_row_by_row() {
        let drawn = Drawn {
            on: Anchor::Body(0),
            at: nalgebra::Vector3::zeros(),
            axes: nalgebra::Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0),
            solid: Solid::Sphere { radius: 0.5 },
            default: false,
        };
        let mut out = String::new();
        shape(&mut out, &drawn, 3);
        assert!(out.contains("\"axes\":[1,2,3,4,5,6,7,8,9]"), "{out}");
        assert!(out.contains("\"kind\":\"sphere\",\"radius\":0.5"), "{out}");
    }
}
