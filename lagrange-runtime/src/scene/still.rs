//! A still of a scene without a browser: the shapes of one run at one time and
//! the paths its bodies and points trace over the run, as line segments
//! projected orthographically along the page's starting view (a planar
//! description in its plane), for pictures drawn by other means (the gallery's
//! table draws them with plotters).

use nalgebra::{Matrix3, Vector2, Vector3};

use super::sample;
use super::shapes::{self, Drawn};
use crate::error::Error;
use crate::numeric::Real;
use crate::ode::Trajectory;
use crate::pose::{Anchor, BodyPose, Posed, Solid};

/// A segment on the picture plane: x to the right, y up.
pub type Segment = [Vector2<f64>; 2];

/// Where a still is seen from: an orthographic projection onto the picture
/// plane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The page's starting camera (azimuth −1, elevation 0.35, z up), or, for
    /// a planar description (points only, all in z = 0), its own plane.
    #[default]
    Camera,
    /// The x–y plane seen from +z: x right, y up.
    Xy,
    /// The x–z plane seen from −y: x right, z up (a pendulum swinging under
    /// gravity along −z).
    Xz,
    /// The y–z plane seen from +x: y right, z up.
    Yz,
}

impl View {
    /// Rows: the picture's right and up directions, then the direction
    /// towards the viewer.
    fn rows(self, planar: bool) -> Matrix3<f64> {
        match self {
            View::Camera if planar => Matrix3::identity(),
            View::Camera => view(),
            View::Xy => Matrix3::identity(),
            View::Xz => Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0),
            View::Yz => Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0),
        }
    }
}

/// The poses at `t` in f64.
struct Frame {
    bodies: Vec<BodyPose<f64>>,
    points: Vec<Vector3<f64>>,
}

impl Frame {
    fn at(&self, a: Anchor) -> Vector3<f64> {
        match a {
            Anchor::Body(i) => self.bodies[i].origin,
            Anchor::Point(i) => self.points[i],
        }
    }
}

fn frame<T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q>>(
    sys: &S,
    traj: &Trajectory<T, N, Q>,
    t: f64,
) -> Frame {
    let q = sample::state_at(traj, t);
    let mut bodies = vec![BodyPose::default(); S::BODIES.len()];
    let mut points = vec![Vector3::zeros(); S::POINTS.len()];
    sys.poses(&q, T::lit(t), &mut bodies, &mut points);
    Frame {
        bodies: bodies.iter().map(sample::to_f64).collect(),
        points: points.iter().map(|p| p.map(|x| x.to_f64())).collect(),
    }
}

/// The still's segments, projected.
pub(super) fn segments<T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q>>(
    sys: &S,
    traj: &Trajectory<T, N, Q>,
    t: f64,
    seen: View,
) -> Result<Vec<Segment>, Error> {
    let f = frame(sys, traj, t);
    let centres: Vec<Vector3<f64>> = f
        .bodies
        .iter()
        .map(|b| b.rotation.transpose() * (b.centre - b.origin))
        .collect();
    let drawn = shapes::drawn(sys, &centres)?;
    let mut out: Vec<[Vector3<f64>; 2]> = Vec::new();
    for d in &drawn {
        solid(&f, d, &mut out);
    }
    // The paths, unless the system travels far beyond its own size (a
    // bicycle's 40 m would shrink the bicycle to a dot), as the page then
    // follows it rather than framing the whole run.
    let mut paths = Vec::new();
    trails(sys, traj, &mut paths);
    let size = spread(&out);
    if !(size > 0.0 && spread(&paths) > 4.0 * size) {
        out.extend(paths);
    }
    if drawn.iter().all(|d| d.default) {
        crosses(&f, &mut out);
    }
    let planar = S::BODIES.is_empty() && f.points.iter().all(|p| p.z == 0.0);
    let view = seen.rows(planar);
    let project = |p: &Vector3<f64>| {
        let v = view * p;
        Vector2::new(v.x, v.y)
    };
    Ok(out.iter().map(|[a, b]| [project(a), project(b)]).collect())
}

/// The largest distance of the segments' ends from their mean.
fn spread(segments: &[[Vector3<f64>; 2]]) -> f64 {
    let n = (2 * segments.len()).max(1) as f64;
    let mean = segments.iter().flatten().sum::<Vector3<f64>>() / n;
    segments
        .iter()
        .flatten()
        .map(|p| (p - mean).norm())
        .fold(0.0, f64::max)
}

/// Rows: the page's starting camera's right and up directions (azimuth −1,
/// elevation 0.35, z up).
fn view() -> Matrix3<f64> {
    let az = -1.0_f64;
    let el = 0.35_f64;
    let eye = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
    let right = (-eye).cross(&Vector3::z()).normalize();
    let up = right.cross(&(-eye));
    Matrix3::from_rows(&[right.transpose(), up.transpose(), eye.transpose()])
}

/// The path of every body's reference point and every point over the run,
/// through 48 evenly spaced times.
fn trails<T: Real, const N: usize, const Q: usize, S: Posed<T, N, Q>>(
    sys: &S,
    traj: &Trajectory<T, N, Q>,
    out: &mut Vec<[Vector3<f64>; 2]>,
) {
    let times = traj.times();
    let t0 = times[0].to_f64();
    let t1 = times[times.len() - 1].to_f64();
    let frames: Vec<Frame> = (0..=48)
        .map(|k| frame(sys, traj, t0 + (t1 - t0) * f64::from(k) / 48.0))
        .collect();
    let anchors = (0..S::BODIES.len())
        .map(Anchor::Body)
        .chain((0..S::POINTS.len()).map(Anchor::Point));
    for a in anchors {
        for pair in frames.windows(2) {
            out.push([pair[0].at(a), pair[1].at(a)]);
        }
    }
}

/// A small cross at every point (a description without shapes of its own).
fn crosses(f: &Frame, out: &mut Vec<[Vector3<f64>; 2]>) {
    let all: Vec<Vector3<f64>> = f
        .points
        .iter()
        .chain(f.bodies.iter().map(|b| &b.origin))
        .copied()
        .collect();
    let centre = all.iter().sum::<Vector3<f64>>() / all.len().max(1) as f64;
    let size = all.iter().map(|p| (p - centre).norm()).fold(0.1, f64::max) * 0.04;
    for p in &f.points {
        for axis in [Vector3::x(), Vector3::y(), Vector3::z()] {
            out.push([p - axis * size, p + axis * size]);
        }
    }
}

/// The edges of one shape.
fn solid(f: &Frame, d: &Drawn, out: &mut Vec<[Vector3<f64>; 2]>) {
    let (origin, rotation) = match d.on {
        Anchor::Body(i) => (f.bodies[i].origin, f.bodies[i].rotation),
        Anchor::Point(i) => (f.points[i], Matrix3::identity()),
    };
    let centre = origin + rotation * d.at;
    let axes = rotation * d.axes;
    match d.solid {
        Solid::Box { size } => box_edges(centre, &axes, &size, out),
        Solid::Sphere { radius } => {
            for k in 0..3 {
                ring(centre, &axes, k, radius, out);
            }
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
            let along = axes.column(axis) * (length / 2.0);
            for end in [centre + along, centre - along] {
                ring(end, &axes, axis, radius, out);
            }
            let u = axes.column((axis + 1) % 3);
            let v = axes.column((axis + 2) % 3);
            for side in [u * radius, -u * radius, v * radius, -v * radius] {
                out.push([centre + along + side, centre - along + side]);
            }
        }
        Solid::Line { to } => out.push([origin, f.at(to)]),
    }
}

fn box_edges(
    c: Vector3<f64>,
    axes: &Matrix3<f64>,
    size: &Vector3<f64>,
    out: &mut Vec<[Vector3<f64>; 2]>,
) {
    let e: Vec<Vector3<f64>> = (0..3).map(|j| axes.column(j) * (size[j] / 2.0)).collect();
    for j in 0..3 {
        let u = e[(j + 1) % 3];
        let v = e[(j + 2) % 3];
        for (a, b) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let mid = c + u * a + v * b;
            out.push([mid - e[j], mid + e[j]]);
        }
    }
}

/// A circle of `radius` about body axis `axis`, as 16 chords.
fn ring(
    c: Vector3<f64>,
    axes: &Matrix3<f64>,
    axis: usize,
    radius: f64,
    out: &mut Vec<[Vector3<f64>; 2]>,
) {
    let u = axes.column((axis + 1) % 3);
    let v = axes.column((axis + 2) % 3);
    let at = |k: usize| {
        let th = std::f64::consts::TAU * k as f64 / 16.0;
        c + u * (radius * th.cos()) + v * (radius * th.sin())
    };
    for k in 0..16 {
        out.push([at(k), at(k + 1)]);
    }
}
