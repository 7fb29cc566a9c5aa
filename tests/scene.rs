//! The scene of a derived system: the poses the derive emits, the shapes (visual
//! only: the equations are the same with and without them), and the page's
//! size and errors.

use lagrange::nalgebra::{Matrix3, Vector2, Vector3};
use lagrange::pose::{Anchor, BodyInertia, BodyPose, Posed, Shape, Solid};
use lagrange::prelude::*;
use lagrange::scene::MAX_FRAMES;

/// A top on a pendulum arm: a point pivot, a body with a full inertia tensor.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta, phi),
    body(arm, mass = m, inertia = [a, b, c], at = [l * sin(theta), 0, -l * cos(theta)],
         rotation = rot_y(-theta) * rot_z(phi)),
    point(tip, on = arm, at = [0, 0, -r]),
    gravity = [0, 0, -g],
)]
pub struct Plain {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub l: f64,
    pub r: f64,
    pub g: f64,
}

/// The same system with shapes of every kind.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta, phi),
    body(arm, mass = m, inertia = [a, b, c], at = [l * sin(theta), 0, -l * cos(theta)],
         rotation = rot_y(-theta) * rot_z(phi)),
    point(tip, on = arm, at = [0, 0, -r]),
    gravity = [0, 0, -g],
    shape(arm, cylinder(radius = r, length = r / 4, axis = z)),
    shape(arm, box(size = [r, 2 * r, 0.05]), at = [0, 0, r / 2]),
    shape(arm, capsule(radius = 0.02, length = l, axis = x)),
    shape(tip, sphere(radius = r / 10)),
    shape(line(arm, tip)),
)]
pub struct Drawn {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub l: f64,
    pub r: f64,
    pub g: f64,
}

const P: [f64; 7] = [2.0, 0.3, 0.4, 0.5, 1.5, 0.2, 9.81];

fn plain() -> Plain {
    let [m, a, b, c, l, r, g] = P;
    Plain {
        m,
        a,
        b,
        c,
        l,
        r,
        g,
    }
}

fn drawn() -> Drawn {
    let [m, a, b, c, l, r, g] = P;
    Drawn {
        m,
        a,
        b,
        c,
        l,
        r,
        g,
    }
}

#[test]
fn shapes_change_no_equation() {
    let (p, d) = (plain(), drawn());
    for k in 0..20 {
        let x = f64::from(k);
        let q = Vector2::new(0.37 * x - 3.0, 1.1 * x.sin());
        let v = Vector2::new(x.cos(), 0.5 - 0.1 * x);
        assert_eq!(p.mass_matrix(&q, 0.0), d.mass_matrix(&q, 0.0));
        assert_eq!(p.bias(&q, &v, 0.0), d.bias(&q, &v, 0.0));
        assert_eq!(
            p.generalized_forces(&q, &v, 0.0),
            d.generalized_forces(&q, &v, 0.0)
        );
    }
    assert_eq!(Plain::EQUATIONS, Drawn::EQUATIONS);
}

#[test]
fn poses_are_the_description_s() {
    let d = drawn();
    assert_eq!(Drawn::BODIES, ["arm"]);
    assert_eq!(Drawn::POINTS, ["tip"]);
    assert_eq!(Drawn::POINT_BODIES, [Some(0)]);
    let (theta, phi) = (0.4_f64, 1.3_f64);
    let mut bodies = [BodyPose::default()];
    let mut points = [Vector3::zeros()];
    d.poses(&Vector2::new(theta, phi), 0.0, &mut bodies, &mut points);
    let l = d.l;
    let origin = Vector3::new(l * theta.sin(), 0.0, -l * theta.cos());
    assert!((bodies[0].origin - origin).norm() < 1e-15);
    assert_eq!(bodies[0].centre, bodies[0].origin);
    let ry = Matrix3::new(
        theta.cos(),
        0.0,
        -theta.sin(),
        0.0,
        1.0,
        0.0,
        theta.sin(),
        0.0,
        theta.cos(),
    );
    let rz = Matrix3::new(
        phi.cos(),
        -phi.sin(),
        0.0,
        phi.sin(),
        phi.cos(),
        0.0,
        0.0,
        0.0,
        1.0,
    );
    let r = ry * rz;
    assert!(
        (bodies[0].rotation - r).norm() < 1e-15,
        "{}",
        bodies[0].rotation
    );
    let tip = origin + r * Vector3::new(0.0, 0.0, -d.r);
    assert!((points[0] - tip).norm() < 1e-15);
    let mut inertia = [BodyInertia::default()];
    d.inertias(&mut inertia);
    assert_eq!(inertia[0].mass, 2.0);
    assert_eq!(
        inertia[0].inertia,
        Matrix3::from_diagonal(&Vector3::new(0.3, 0.4, 0.5))
    );
}

#[test]
fn shapes_take_their_sizes_from_the_parameters() {
    let mut shapes = Vec::new();
    drawn().shapes(&mut |s| shapes.push(s));
    let r = 0.2;
    let at = |z: f64| Vector3::new(0.0, 0.0, z);
    let want = [
        Shape {
            on: Anchor::Body(0),
            at: at(0.0),
            solid: Solid::Cylinder {
                radius: r,
                length: r / 4.0,
                axis: 2,
            },
        },
        Shape {
            on: Anchor::Body(0),
            at: at(r / 2.0),
            solid: Solid::Box {
                size: Vector3::new(r, 2.0 * r, 0.05),
            },
        },
        Shape {
            on: Anchor::Body(0),
            at: at(0.0),
            solid: Solid::Capsule {
                radius: 0.02,
                length: 1.5,
                axis: 0,
            },
        },
        Shape {
            on: Anchor::Point(0),
            at: at(0.0),
            solid: Solid::Sphere { radius: r * 0.1 },
        }, // r / 10 is emitted as r · 0.1
        Shape {
            on: Anchor::Body(0),
            at: at(0.0),
            solid: Solid::Line {
                to: Anchor::Point(0),
            },
        },
    ];
    assert_eq!(shapes, want);
    let mut none = Vec::new();
    plain().shapes(&mut |s| none.push(s));
    assert!(none.is_empty());
}

/// A planar pendulum: points in the plane come out with z = 0.
#[derive(Lagrangian)]
#[lagrange(coordinates(theta), point(bob, mass = m, at = [l * sin(theta), -l * cos(theta)]), gravity = [0, -g])]
pub struct Planar {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn a_planar_point_lies_in_z_0() {
    let sys = Planar {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    let mut points = [Vector3::new(1.0, 1.0, 1.0)];
    sys.poses(
        &lagrange::nalgebra::Vector1::new(0.5),
        0.0,
        &mut [],
        &mut points,
    );
    let want = Vector3::new(2.0 * 0.5_f64.sin(), -2.0 * 0.5_f64.cos(), 0.0);
    assert!((points[0] - want).norm() < 1e-15);
}

/// 10⁵ RK4 steps make a page of at most `MAX_FRAMES` frames: its size does
/// not grow with the steps.
#[test]
fn a_long_run_makes_a_bounded_page() -> Result<(), Error> {
    let sys = drawn();
    let traj = Simulation::new(&sys).integrator(Rk4::step(1e-3)).run(
        [0.5, 0.0],
        [0.0, 3.0],
        0.0..100.0,
    )?;
    assert_eq!(traj.len(), 100_001);
    let page = traj.scene(&sys).to_html()?;
    let frames = MAX_FRAMES.to_string();
    assert!(
        page.contains(&format!("\"count\":{frames}")),
        "frames capped"
    );
    // Per frame: a body (3 + 4 numbers), a point (3), two plotted coordinates,
    // each at most about 9 bytes with its comma; plus the viewer (~20 kB).
    let bound = MAX_FRAMES * (7 + 3 + 2) * 9 + 40_000;
    println!(
        "page of a run of 1e5 steps: {} bytes (bound {bound})",
        page.len()
    );
    assert!(page.len() < bound, "{} bytes", page.len());
    // A short run is sampled at 30 frames per second of simulated time.
    let short = Simulation::new(&sys).run([0.5, 0.0], [0.0, 3.0], 0.0..2.0)?;
    assert!(short.scene(&sys).to_html()?.contains("\"count\":61,"));
    Ok(())
}

#[test]
fn errors_are_typed() -> Result<(), Error> {
    let sys = drawn();
    let traj = Simulation::new(&sys).run([0.5, 0.0], [0.0, 3.0], 0.0..1.0)?;
    let missing = std::env::temp_dir().join("lagrange-no-such-dir/x/scene.html");
    assert!(matches!(
        traj.scene(&sys).write_html(&missing),
        Err(Error::Io(_))
    ));
    let nan = Drawn {
        l: f64::NAN,
        ..drawn()
    };
    let e = traj.scene(&nan).to_html();
    assert!(
        matches!(&e, Err(Error::NonFinitePose { name, .. }) if name == "arm"),
        "{e:?}"
    );
    let negative = Drawn { r: -0.2, ..drawn() };
    assert!(matches!(
        traj.scene(&negative).to_html(),
        Err(Error::Settings(_))
    ));
    let unknown = traj.scene(&sys).plot(&["psi"]).to_html();
    assert!(matches!(unknown, Err(Error::Settings(m)) if m.to_string().contains("psi")));
    let style = traj.scene(&sys).style("red", 1.0).to_html();
    assert!(matches!(style, Err(Error::Settings(_))));
    Ok(())
}

#[test]
fn runs_overlay_with_their_own_styles() -> Result<(), Error> {
    let sys = drawn();
    let a = Simulation::new(&sys).run([0.5, 0.0], [0.0, 3.0], 0.0..1.0)?;
    let b = Simulation::new(&sys).run([0.6, 0.0], [0.0, 3.0], 0.0..1.5)?;
    let page = Scene::new(&sys)
        .run(&a, "first")
        .run(&b, "second")
        .style("#123456", 0.4)
        .plot(&["phi"])
        .title("two runs")
        .to_html()?;
    assert!(page.contains("\"label\":\"first\",\"color\":\"#3a6fb0\",\"opacity\":1,"));
    assert!(page.contains("\"label\":\"second\",\"color\":\"#123456\",\"opacity\":0.4,"));
    assert!(page.contains("\"plot\":[\"phi\"]"));
    assert!(page.contains("<title>two runs</title>"));
    Ok(())
}
