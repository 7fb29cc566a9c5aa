//! The scene page as a person sees it: written, opened in headless Chromium,
//! and read back through its `window.lagrangeScene` hook. A probe script
//! appended to the page sets two times, hashes the canvas at each, reads where
//! a body is drawn and collects the page's errors into the DOM, which
//! `--dump-dom` prints.
//!
//! Checked: the page loads with no error; the frames drawn at two times
//! differ; the body's position the page draws at a chosen time is the one
//! the system's poses give on the trajectory there (to the page's rounding);
//! its screen position is inside the canvas and moves.
//!
//! Needs `chromium` (or `chromium-browser`, `google-chrome`) on the PATH;
//! `.ci/run` installs it. Without one the test prints why it skipped and
//! passes: the page's contents are checked without a browser in `tests/scene.rs`.

use std::path::{Path, PathBuf};
use std::process::Command;

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

/// Reads the page's hook at two times into `<pre id="probe">` as `key=value;`.
const PROBE: &str = r#"<script>
(function () {
  var out = [];
  try {
    var s = window.lagrangeScene;
    out.push('ready=' + s.ready, 'frames=' + s.frameCount);
    s.setTime(T1);
    out.push('hash1=' + s.pixelHash(), 'world=' + s.bodyWorldPosition('arm'),
             'point=' + s.pointWorldPosition('tip'), 'screen1=' + s.bodyScreenPosition('arm'));
    s.setTime(T2);
    out.push('hash2=' + s.pixelHash(), 'screen2=' + s.bodyScreenPosition('arm'));
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

#[test]
fn the_page_draws_the_trajectory() -> Result<(), Error> {
    let Some(chromium) = browser() else {
        println!(
            "SKIPPED: no chromium on the PATH (`apt-get install -y chromium`); the page's contents are checked by tests/scene.rs"
        );
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
    // shows the sampled pose itself.
    let (t1, t2) = (1.0, 2.5);
    let page = traj.scene(&sys).to_html()?;
    let probe_script = PROBE
        .replace("T1", &t1.to_string())
        .replace("T2", &t2.to_string());
    let page = page.replace("</body>", &probe_script);
    let path = std::env::temp_dir().join(format!("lagrange-scene-{}.html", std::process::id()));
    std::fs::write(&path, page)?;
    let dom = dump_dom(&chromium, &path);
    let _ = std::fs::remove_file(&path);
    let pairs = probe(&dom);
    println!("{pairs:?}");
    assert_eq!(get(&pairs, "errors"), "0:", "the page reported errors");
    assert_eq!(get(&pairs, "ready"), "true");
    assert_eq!(get(&pairs, "frames"), "121");
    assert_ne!(
        get(&pairs, "hash1"),
        get(&pairs, "hash2"),
        "two times, one picture"
    );

    let (q, _) = traj.state_at(t1).expect("inside the run");
    let mut bodies = [BodyPose::default()];
    let mut points = [Vector3::zeros()];
    sys.poses(&q, t1, &mut bodies, &mut points);
    let drawn = Vector3::from_vec(numbers(get(&pairs, "world")));
    let tip = Vector3::from_vec(numbers(get(&pairs, "point")));
    // Positions are written with four decimals on this metre-sized scene.
    assert!(
        (drawn - bodies[0].origin).amax() < 1e-4,
        "{drawn} vs {}",
        bodies[0].origin
    );
    assert!((tip - points[0]).amax() < 1e-4, "{tip} vs {}", points[0]);

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
