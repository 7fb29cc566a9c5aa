use super::series::{self, pieces};
use super::still::{self, Fit};
use super::{StillPicture, TablePlot, segments_png};
use crate::error::{Error, SettingsError};
use crate::ode::test_problems::Oscillator;
use crate::ode::{Dopri5, Integrator, Rk4, Trajectory};
use crate::pose::{Anchor, BodyInertia, BodyPose, Posed, Shape, Solid};
use crate::scene::{Scene, View};
use crate::system::Lagrangian;
use crate::table::Table;
use nalgebra::{Matrix1, SVector, Vector1, Vector2, Vector3};
use plotters::prelude::*;

const W: u32 = 400;
const H: u32 = 300;

fn rgb(buffer: &[u8], (x, y): (i32, i32)) -> [u8; 3] {
    assert!(
        x >= 0 && y >= 0 && x < W as i32 && y < H as i32,
        "({x}, {y}) is off the picture"
    );
    let k = 3 * (y as usize * W as usize + x as usize);
    [buffer[k], buffer[k + 1], buffer[k + 2]]
}

/// Whether a pixel within `r` of `p` has the colour `c` (within a few levels).
fn near(buffer: &[u8], p: (i32, i32), r: i32, c: [u8; 3]) -> bool {
    (-r..=r).any(|dx| {
        (-r..=r).any(|dy| {
            let q = (p.0 + dx, p.1 + dy);
            let inside = q.0 >= 0 && q.1 >= 0 && q.0 < W as i32 && q.1 < H as i32;
            inside
                && rgb(buffer, q)
                    .iter()
                    .zip(c)
                    .all(|(a, b)| a.abs_diff(b) <= 8)
        })
    })
}

fn dark(buffer: &[u8], p: (i32, i32)) -> bool {
    (-1..=1).any(|dx| {
        (-1..=1).any(|dy| {
            let [r, g, b] = rgb(buffer, (p.0 + dx, p.1 + dy));
            u32::from(r) + u32::from(g) + u32::from(b) < 3 * 200
        })
    })
}

const WHITE_RGB: [u8; 3] = [255, 255, 255];

fn oscillator_run() -> Trajectory<f64, 1> {
    let rhs = Oscillator { omega: 1.0 };
    Rk4::step(0.01)
        .integrate(&rhs, 0.0, 6.0, Vector1::new(1.0), Vector1::new(0.0))
        .unwrap()
}

#[test]
fn a_column_is_drawn_through_its_values() {
    let run = oscillator_run();
    let table = Table::new(&run, &["x"]).unwrap();
    let plot = TablePlot::new()
        .columns(&["x", "dot_x"])
        .title("oscillator");
    let curves = table.curves(&plot).unwrap();
    let mut buffer = vec![0u8; (3 * W * H) as usize];
    let to_pixel = {
        let root = BitMapBackend::with_buffer(&mut buffer, (W, H)).into_drawing_area();
        let spec = series::draw(&root, &plot, &curves).unwrap();
        root.present().unwrap();
        spec
    };
    let [x, v] = [COLOR_X, COLOR_V];
    // x = cos t: at t = π it is −1, drawn in the first colour; v = −sin t
    // at t = π/2 is −1, in the second (both low, away from the legend).
    let k = run.times().partition_point(|&t| t < std::f64::consts::PI);
    let at = |t: f64, y: f64| to_pixel.translate(&(t, y));
    let (t, q) = (run.times()[k], run.positions()[k][0]);
    assert!(near(&buffer, at(t, q), 1, x), "x at t = {t}");
    let k = run
        .times()
        .partition_point(|&t| t < 0.5 * std::f64::consts::PI);
    let (t, dq) = (run.times()[k], run.velocities()[k][0]);
    assert!(near(&buffer, at(t, dq), 1, v), "dot_x at t = {t}");
    // Off the curves, inside the plot: white. x > 0.9 only near t = 0 and 2π.
    assert!(!near(&buffer, at(3.0, 0.9), 2, x));
    assert_eq!(rgb(&buffer, (W as i32 - 1, H as i32 - 1)), WHITE_RGB);
}

const COLOR_X: [u8; 3] = [31, 119, 180];
const COLOR_V: [u8; 3] = [255, 127, 14];

#[test]
fn the_default_plot_draws_the_coordinates() {
    let run = oscillator_run();
    let table = Table::new(&run, &["x"]).unwrap();
    let curves = table.curves(&TablePlot::new()).unwrap();
    assert_eq!(curves.len(), 1);
    assert_eq!(curves[0].name, "x");
    assert_eq!(curves[0].points.len(), run.len());
}

#[test]
fn an_unknown_column_or_a_bad_size_is_a_typed_error() {
    let run = oscillator_run();
    let table = Table::new(&run, &["x"]).unwrap();
    let path = std::env::temp_dir().join(format!("lagrange-plot-{}.png", std::process::id()));
    let e = table
        .plot_png(&path, &TablePlot::new().columns(&["x", "theta"]))
        .unwrap_err();
    match e {
        Error::Settings(SettingsError::Data { problem, .. }) => {
            assert!(problem.contains("`theta`"), "{problem}")
        }
        e => panic!("{e}"),
    }
    let e = table
        .plot_png(&path, &TablePlot::new().columns(&[]))
        .unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Data { .. })),
        "{e}"
    );
    let e = table
        .plot_png(&path, &TablePlot::new().size(0, 10))
        .unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Data { .. })),
        "{e}"
    );
    assert!(!path.exists(), "nothing is written for a refused plot");
    // A directory that does not exist: an I/O error, not a panic.
    let missing = std::env::temp_dir().join("no-such-dir-lagrange/plot.png");
    let e = table.plot_png(&missing, &TablePlot::new()).unwrap_err();
    assert!(matches!(e, Error::Io(_)), "{e}");
}

#[test]
fn a_plot_written_to_a_file_is_a_png_of_its_size() {
    let run = oscillator_run();
    let table = Table::new(&run, &["x"]).unwrap();
    let path = std::env::temp_dir().join(format!("lagrange-plot-ok-{}.png", std::process::id()));
    table
        .plot_png(&path, &TablePlot::new().size(640, 320))
        .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: 640 × 320.
    assert_eq!(&bytes[16..24], &[0, 0, 2, 128, 0, 0, 1, 64]);
}

#[test]
fn a_curve_breaks_at_empty_or_non_finite_cells() {
    let points = [
        (0.0, Some(1.0)),
        (1.0, Some(2.0)),
        (2.0, None),
        (3.0, Some(f64::NAN)),
        (4.0, Some(3.0)),
    ];
    assert_eq!(
        pieces(&points),
        vec![vec![(0.0, 1.0), (1.0, 2.0)], vec![(4.0, 3.0)]]
    );
    assert!(pieces(&[(0.0, None)]).is_empty());
}

/// A unit rod from a fixed pivot to a bob, swinging in the x–z plane:
/// θ'' = −sin θ, the bob at (sin θ, 0, −cos θ).
struct Rod;

impl Lagrangian<f64, 1> for Rod {
    const COORDINATES: [&'static str; 1] = ["theta"];
    const RHEONOMIC: bool = false;
    fn mass_matrix(&self, _: &Vector1<f64>, _: f64) -> Matrix1<f64> {
        Matrix1::new(1.0)
    }
    fn bias(&self, _: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::zeros()
    }
    fn generalized_forces(&self, q: &Vector1<f64>, _: &Vector1<f64>, _: f64) -> Vector1<f64> {
        Vector1::new(-q[0].sin())
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
        t: f64,
    ) -> (Matrix1<f64>, Vector1<f64>) {
        (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
    }
    fn kinetic_energy(&self, _: &Vector1<f64>, v: &Vector1<f64>, _: f64) -> f64 {
        0.5 * v[0] * v[0]
    }
    fn potential_energy(&self, q: &Vector1<f64>, _: f64) -> f64 {
        -q[0].cos()
    }
    fn integral(&self, q: &Vector1<f64>, v: &Vector1<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
}

impl Posed<f64, 1> for Rod {
    const BODIES: &'static [&'static str] = &[];
    const POINTS: &'static [&'static str] = &["pivot", "bob"];
    const POINT_BODIES: &'static [Option<usize>] = &[None, None];
    fn poses(&self, q: &SVector<f64, 1>, _: f64, _: &mut [BodyPose<f64>], p: &mut [Vector3<f64>]) {
        p[0] = Vector3::zeros();
        p[1] = Vector3::new(q[0].sin(), 0.0, -q[0].cos());
    }
    fn inertias(&self, _: &mut [BodyInertia<f64>]) {}
    fn shapes(&self, out: &mut dyn FnMut(Shape<f64>)) {
        let to = Anchor::Point(1);
        out(Shape {
            on: Anchor::Point(0),
            at: Vector3::zeros(),
            solid: Solid::Line { to },
        });
    }
}

#[test]
fn a_still_seen_from_the_side_draws_the_rod_below_its_pivot() {
    let dynamics = crate::mechanics::Dynamics::new(&Rod);
    let (q0, v0) = (Vector1::new(0.6), Vector1::new(0.0));
    let run = Dopri5::tol(1e-10)
        .integrate(&dynamics, 0.0, 3.0, q0, v0)
        .unwrap();
    let scene = Scene::new(&Rod).run(&run, "run");
    let t = 1.0;
    let picture = StillPicture::new().view(View::Xz).size(W, H);
    let segments = scene.still_from(t, View::Xz).unwrap();
    let mut buffer = vec![0u8; (3 * W * H) as usize];
    let fit: Fit = {
        let root = BitMapBackend::with_buffer(&mut buffer, (W, H)).into_drawing_area();
        let fit = still::draw(&root, &segments, &picture).unwrap().unwrap();
        root.present().unwrap();
        fit
    };
    let theta = run.state_at(t).unwrap().0[0];
    let bob = Vector2::new(theta.sin(), -theta.cos());
    let pivot = fit.pixel(&Vector2::zeros());
    let below = fit.pixel(&bob);
    // Seen from the side, z up: the bob hangs below the pivot.
    assert!(below.1 > pivot.1 + 50, "{pivot:?} {below:?}");
    // The rod is drawn: its ends and its middle are dark.
    let middle = fit.pixel(&(bob / 2.0));
    for p in [pivot, middle, below] {
        assert!(dark(&buffer, p), "{p:?} should be drawn");
    }
    // The background is white: a corner, and a point beside the rod.
    assert_eq!(rgb(&buffer, (0, 0)), WHITE_RGB);
    let beside = fit.pixel(&Vector2::new(-0.5, -0.3));
    assert_eq!(rgb(&buffer, beside), WHITE_RGB);
    // Equal scales: a unit rod is as long on the picture at any angle.
    let length = f64::from((below.0 - pivot.0).pow(2) + (below.1 - pivot.1).pow(2)).sqrt();
    let fit_scale = fit.pixel(&Vector2::new(1.0, 0.0)).0 - pivot.0;
    assert!(
        (length - f64::from(fit_scale)).abs() <= 2.0,
        "{length} vs {fit_scale}"
    );
    // From above (x–y), the same rod is a segment along x through the pivot.
    let top = scene.still_from(t, View::Xy).unwrap();
    assert!(top.iter().flatten().all(|p| p.y.abs() < 1e-12));
}

#[test]
fn a_still_is_written_with_its_size_and_refuses_a_bad_one() {
    let segments = [[Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.5)]];
    let path = std::env::temp_dir().join(format!("lagrange-still-{}.png", std::process::id()));
    segments_png(
        &path,
        &segments,
        &StillPicture::new().size(180, 120).title("t"),
    )
    .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(&bytes[16..24], &[0, 0, 0, 180, 0, 0, 0, 120]);
    let e = segments_png(&path, &segments, &StillPicture::new().size(8, 8)).unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Data { .. })),
        "{e}"
    );
    let missing = std::env::temp_dir().join("no-such-dir-lagrange/still.png");
    let e = segments_png(&missing, &segments, &StillPicture::new()).unwrap_err();
    assert!(matches!(e, Error::Io(_)), "{e}");
}
