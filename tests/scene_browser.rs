//! The scene page as a person sees it: written, opened in headless Chromium,
//! and read back through its `window.lagrangeScene` hook. A probe script
//! appended to the page sets two times, hashes the canvas at each, reads where
//! a body is drawn and collects the page's errors into the DOM, which
//! `--dump-dom` prints.
//!
//! Checked, on a test system and on the gallery's 3D systems (the bicycle at
//! two speeds side by side, the threaded tops, the rolling disk, the planar
//! arm): the page loads with no error; the frames drawn at two times differ;
//! the position the page draws for a body or point at a chosen time is the
//! one the system's poses give on the trajectory there (to the page's
//! rounding); a body's screen position is inside the canvas and moves.
//!
//! Needs `chromium` (or `chromium-browser`, `google-chrome`) on the PATH;
//! `.ci/run` installs it. Without one the test prints why it skipped and
//! passes: the page's contents are checked without a browser in `tests/scene.rs`.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::catalog;

use catalog::bicycle::Bicycle;
use catalog::constrained::{RollingDisk, ThreadedTops};
use catalog::control::TwoLinkArm;
use lagrange::nalgebra::Vector3;
use lagrange::pose::{BodyPose, Posed};
use lagrange::prelude::*;

/// A top on a pendulum arm, with shapes of every kind.
#[derive(Lagrangian)]
#[lagrange(
    coordinates(theta, phi),
    body(arm, mass = m, inertia = [a, b, c], at = [l * sin(theta), 0, -l * cos(theta)],
         rotation = rot_y(-theta) * rot_z(phi)),
    point(tip, on = arm, at = [0, 0, -r]),
    gravity = [0, 0, -g],
    shape(arm, cylinder(radius = r, length = r / 4, axis = z)),
    shape(arm, capsule(radius = 0.02, length = l, axis = x)),
    shape(tip, sphere(radius = r / 10)),
    shape(line(arm, tip)),
)]
pub struct Top {
    pub m: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub l: f64,
    pub r: f64,
    pub g: f64,
}

fn browser() -> Option<PathBuf> {
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find_map(|name| {
            let found = Command::new("sh")
                .args(["-c", &format!("command -v {name}")])
                .output()
                .ok()?;
            let path = String::from_utf8(found.stdout).ok()?;
            (found.status.success() && !path.trim().is_empty()).then(|| PathBuf::from(path.trim()))
        })
}

/// Reads the page's hook at two times into `<pre id="probe">` as `key=value;`;
/// `KIND` is `body` or `point`, `NAME` the one whose position is read.
const PROBE: &str = r#"<script>
(function () {
  var out = [];
  try {
    var s = window.lagrangeScene;
    out.push('ready=' + s.ready, 'frames=' + s.frameCount);
    s.setTime(T1);
    var world = s.KINDWorldPosition('NAME');
    out.push('hash1=' + s.pixelHash(), 'world=' + world);
    if ('KIND' === 'body') out.push('screen1=' + s.bodyScreenPosition('NAME'));
    s.setTime(T2);
    out.push('hash2=' + s.pixelHash());
    if ('KIND' === 'body') out.push('screen2=' + s.bodyScreenPosition('NAME'));
  } catch (e) { out.push('exception=' + e); }
  out.push('errors=' + window.lagrangeErrors.length + ':' + window.lagrangeErrors.join('|'));
  var pre = document.createElement('pre');
  pre.id = 'probe';
  pre.textContent = out.join(';');
  document.body.appendChild(pre);
})();
</script>
</body>"#;

fn dump_dom(chromium: &Path, page: &Path) -> String {
    let out = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--virtual-time-budget=2000",
            "--dump-dom",
        ])
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium runs");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The probe's `key=value` pairs.
fn probe(dom: &str) -> Vec<(String, String)> {
    let start = dom.find("<pre id=\"probe\">").expect("the probe ran") + 16;
    let end = start + dom[start..].find("</pre>").expect("probe closed");
    dom[start..end]
        .split(';')
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

fn get<'a>(pairs: &'a [(String, String)], key: &str) -> &'a str {
    pairs
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("no `{key}` in {pairs:?}"))
}

fn numbers(s: &str) -> Vec<f64> {
    s.split(',').map(|x| x.parse().expect("a number")).collect()
}

/// What a page is checked for: the body or point read back, at which time
/// (a frame time), against which trajectory, to what tolerance (the page's
/// rounding of positions).
struct Check<'a, const N: usize> {
    name: &'a str,
    traj: &'a Trajectory<f64, N>,
    t1: f64,
    t2: f64,
    tol: f64,
}

/// Loads `page` in Chromium and checks it: no page errors, a different
/// picture at two times, and the named body or point drawn where the
/// trajectory's pose puts it at `t1`.
fn check_page<S: Posed<f64, N>, const N: usize>(
    chromium: &Path,
    sys: &S,
    page: &str,
    c: &Check<N>,
) -> Vec<(String, String)> {
    let body = S::BODIES.iter().position(|b| *b == c.name);
    let kind = if body.is_some() { "body" } else { "point" };
    let script = PROBE
        .replace("T1", &c.t1.to_string())
        .replace("T2", &c.t2.to_string())
        .replace("KIND", kind)
        .replace("NAME", c.name);
    let path = std::env::temp_dir().join(format!(
        "lagrange-scene-{}-{}.html",
        std::process::id(),
        c.name
    ));
    std::fs::write(&path, page.replace("</body>", &script)).expect("the page is written");
    let dom = dump_dom(chromium, &path);
    let _ = std::fs::remove_file(&path);
    let pairs = probe(&dom);
    println!("{}: {pairs:?}", c.name);
    assert_eq!(get(&pairs, "errors"), "0:", "the page reported errors");
    assert_eq!(get(&pairs, "ready"), "true");
    assert_ne!(
        get(&pairs, "hash1"),
        get(&pairs, "hash2"),
        "two times, one picture"
    );
    let (q, _) = c.traj.state_at(c.t1).expect("inside the run");
    let mut bodies = vec![BodyPose::default(); S::BODIES.len()];
    let mut points = vec![Vector3::zeros(); S::POINTS.len()];
    sys.poses(&q, c.t1, &mut bodies, &mut points);
    let want = match body {
        Some(i) => bodies[i].origin,
        None => {
            points[S::POINTS
                .iter()
                .position(|p| *p == c.name)
                .expect("a point")]
        }
    };
    let drawn = Vector3::from_vec(numbers(get(&pairs, "world")));
    assert!(
        (drawn - want).amax() < c.tol,
        "{}: drawn at {drawn}, pose {want}",
        c.name
    );
    pairs
}

#[test]
fn the_page_draws_the_trajectory() -> Result<(), Error> {
    let Some(chromium) = browser() else {
        println!("{SKIPPED}");
        return Ok(());
    };
    let sys = Top {
        m: 2.0,
        a: 0.3,
        b: 0.4,
        c: 0.5,
        l: 1.5,
        r: 0.2,
        g: 9.81,
    };
    let traj = Simulation::new(&sys).integrator(Dopri5::tol(1e-10)).run(
        [0.8, 0.0],
        [0.0, 5.0],
        0.0..4.0,
    )?;
    // Frame 30 of 121 (30 frames a second): a frame time, where the page
    // shows the sampled pose itself. Positions have four decimals here.
    let check = Check {
        name: "arm",
        traj: &traj,
        t1: 1.0,
        t2: 2.5,
        tol: 1e-4,
    };
    let pairs = check_page(&chromium, &sys, &traj.scene(&sys).to_html()?, &check);
    assert_eq!(get(&pairs, "frames"), "121");
    let (s1, s2) = (
        numbers(get(&pairs, "screen1")),
        numbers(get(&pairs, "screen2")),
    );
    let inside = |s: &[f64]| (0.0..960.0).contains(&s[0]) && (0.0..540.0).contains(&s[1]);
    assert!(inside(&s1) && inside(&s2), "{s1:?} {s2:?}");
    assert!(
        (s1[0] - s2[0]).abs() + (s1[1] - s2[1]).abs() > 1.0,
        "the body moves on screen"
    );
    Ok(())
}

/// The gallery's bicycle at two speeds side by side: the page draws the
/// first run where it is (the second is moved beside it for display only).
#[test]
fn the_bicycle_at_two_speeds_draws() -> Result<(), Error> {
    let Some(chromium) = browser() else {
        println!("{SKIPPED}");
        return Ok(());
    };
    let bike = Bicycle::benchmark();
    let ride = |v: f64| {
        let (q0, mut v0) = bike.upright(v);
        v0[3] = 0.5;
        Simulation::new(&bike)
            .integrator(Dopri5::tol(1e-8))
            .project_initial(true)
            .run_constrained(q0, v0, 0.0..1.5)
    };
    let (fast, slow) = (ride(5.0)?, ride(3.0)?);
    let page = Scene::new(&bike)
        .run(&fast, "5 m/s")
        .run(&slow, "3 m/s")
        .side_by_side(true)
        .to_html()?;
    // Scenes metres across, rolling 7 m: three decimals.
    let check = Check {
        name: "front_wheel",
        traj: &fast,
        t1: 1.0,
        t2: 1.4,
        tol: 1e-3,
    };
    check_page(&chromium, &bike, &page, &check);
    Ok(())
}

#[test]
fn the_threaded_tops_draw() -> Result<(), Error> {
    let Some(chromium) = browser() else {
        println!("{SKIPPED}");
        return Ok(());
    };
    let tops = ThreadedTops {
        m: 1.0,
        a: 0.3,
        b: 0.2,
        c: 0.5,
        l: 0.4,
        d: 2.0,
        g: 9.81,
    };
    // The gallery's start: spins that satisfy the thread's constraint.
    let (th1, th2) = (0.4_f64, 0.7_f64);
    let q0 = [0.0, th1, 0.0, 0.5, th2, 0.0];
    let v0 = [
        1.0,
        0.2,
        10.0 - th1.cos(),
        -0.5,
        -0.1,
        -10.0 + 0.5 * th2.cos(),
    ];
    let traj = Simulation::new(&tops)
        .integrator(Dopri5::tol(1e-8))
        .run_constrained(q0, v0, 0.0..1.0)?;
    let check = Check {
        name: "top2",
        traj: &traj,
        t1: 0.5,
        t2: 0.9,
        tol: 1e-4,
    };
    check_page(&chromium, &tops, &traj.scene(&tops).to_html()?, &check);
    Ok(())
}

#[test]
fn the_rolling_disk_draws() -> Result<(), Error> {
    let Some(chromium) = browser() else {
        println!("{SKIPPED}");
        return Ok(());
    };
    let disk = RollingDisk::thin(1.0, 0.3, 9.81);
    let (q0, v0) = disk.steady_circle(0.3, 2.0);
    let traj = Simulation::new(&disk)
        .integrator(Dopri5::tol(1e-8))
        .run_reduced(q0, v0, 0.0..1.0)?;
    let check = Check {
        name: "disk",
        traj: &traj,
        t1: 0.5,
        t2: 0.8,
        tol: 1e-4,
    };
    check_page(&chromium, &disk, &traj.scene(&disk).to_html()?, &check);
    Ok(())
}

/// A planar system is drawn in its plane; the hook reports z = 0.
#[test]
fn the_planar_arm_draws() -> Result<(), Error> {
    let Some(chromium) = browser() else {
        println!("{SKIPPED}");
        return Ok(());
    };
    let arm = TwoLinkArm::standard();
    let traj =
        Simulation::new(&arm)
            .open_loop(|_| [0.0, 0.0])
            .run([0.3, 0.4], [0.0, 0.0], 0.0..1.0)?;
    let traj = traj.into_trajectory();
    let check = Check {
        name: "hand",
        traj: &traj,
        t1: 0.5,
        t2: 0.9,
        tol: 1e-4,
    };
    check_page(&chromium, &arm, &traj.scene(&arm).to_html()?, &check);
    Ok(())
}

const SKIPPED: &str = "SKIPPED: no chromium on the PATH (`apt-get install -y chromium`); the page's contents are checked by tests/scene.rs";
