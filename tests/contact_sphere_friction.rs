//! Coulomb friction between two spheres (`contact(.., against = other,
//! friction = μ)`), against closed forms: a sphere resting on a fixed dome
//! sticks or slides by tan α against μ (on both charts of the tangents),
//! slides in its vertical plane whatever the tangents; a disk rolling off a
//! fixed drum starts to slip where sin α = μ (7 cos α − 4 cos α₀); and an
//! oblique impact of two spinning disks takes the tangential impulse that
//! stops their slip, or μ times the normal one.

use lagrange::prelude::*;
use lagrange::{ChangeKind, Compliant, ContactRun, Contacts, Dop853, MoreauJean, Radau5};

const G: f64 = 9.81;

/// A small sphere (a point of radius r, which does not turn) on a fixed
/// dome of radius R centred at the origin.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    point(bead, mass = m, at = [x, y, z]),
    point(dome, mass = 0, at = [0, 0, 0]),
    gravity = [0, 0, -g],
    contact(touch, on = bead, radius = r, against = dome, against_radius = rd,
            restitution = 0, friction = 0.5),
)]
struct Bead {
    m: f64,
    r: f64,
    rd: f64,
    g: f64,
}

/// The bead on a frictionless dome.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, z),
    point(bead, mass = m, at = [x, y, z]),
    point(dome, mass = 0, at = [0, 0, 0]),
    gravity = [0, 0, -g],
    contact(touch, on = bead, radius = r, against = dome, against_radius = rd, restitution = 0),
)]
struct SlickBead {
    m: f64,
    r: f64,
    rd: f64,
    g: f64,
}

/// A uniform disk (I = m r²/2) in the vertical plane on a fixed drum of
/// radius R, rolling or slipping.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(x, y, phi),
    body(disk, mass = m, inertia = [0, 0, 0.5 * m * r * r], at = [x, y, 0],
         rotation = rot_z(phi)),
    point(drum, mass = 0, at = [0, 0, 0]),
    gravity = [0, -g, 0],
    contact(touch, on = disk, radius = r, against = drum, against_radius = rd,
            restitution = 0, friction = 0.2),
)]
struct Drum {
    m: f64,
    r: f64,
    rd: f64,
    g: f64,
}

/// Two equal uniform disks in the plane, no gravity.
#[derive(Lagrangian, Clone, Copy)]
#[lagrange(
    coordinates(xa, ya, pa, xb, yb, pb),
    body(a, mass = m, inertia = [0, 0, 0.5 * m * r * r], at = [xa, ya, 0], rotation = rot_z(pa)),
    body(b, mass = m, inertia = [0, 0, 0.5 * m * r * r], at = [xb, yb, 0], rotation = rot_z(pb)),
    contact(hit, on = a, radius = r, against = b, against_radius = r,
            restitution = 0.5, friction = 0.3),
)]
struct Disks {
    m: f64,
    r: f64,
}

const BEAD: Bead = Bead {
    m: 0.2,
    r: 0.05,
    rd: 1.0,
    g: G,
};

/// The bead resting on the dome at polar angle α, azimuth β.
fn on_dome(alpha: f64, beta: f64) -> [f64; 3] {
    let d = BEAD.r + BEAD.rd;
    [
        d * alpha.sin() * beta.cos(),
        d * alpha.sin() * beta.sin(),
        d * alpha.cos(),
    ]
}

fn bead_run(alpha: f64, beta: f64, until: f64) -> ContactRun<f64, 3> {
    Simulation::new(&BEAD)
        .integrator(Dop853::tol(1e-12))
        .run_contacts(on_dome(alpha, beta), [0.0; 3], 0.0..until)
        .unwrap()
}

/// Left at rest at α = 20° and 25° (the tangents' x̂ × n chart, n within
/// 45° of z), tan α < μ = 0.5: it holds with the friction m g sin α,
/// the normal force m g cos α, and does not move.
#[test]
fn a_bead_on_a_dome_sticks_below_tan_alpha_equal_to_mu() {
    for alpha in [20f64.to_radians(), 25f64.to_radians()] {
        let start = SVector::from(on_dome(alpha, 0.7));
        let run = bead_run(alpha, 0.7, 0.5);
        let f = run.forces(&BEAD, 0.0, &start, &SVector::zeros()).unwrap()[0];
        let weight = BEAD.m * G;
        let friction = (f.tangential[0].powi(2) + f.tangential[1].powi(2)).sqrt();
        assert!(
            (f.normal - weight * alpha.cos()).abs() < 1e-12,
            "N = {}",
            f.normal
        );
        assert!(
            (friction - weight * alpha.sin()).abs() < 1e-12,
            "F = {friction}"
        );
        let (q, v) = run.trajectory.final_state();
        assert!(
            (q - start).amax() < 1e-12 && v.amax() < 1e-12,
            "moved: {q:?}"
        );
    }
}

/// At α = 40° (x̂ × n chart) and 60° (ẑ × n chart), tan α > μ: it slides
/// from the start with the friction μ m g cos α, straight down the dome in
/// its vertical plane at azimuth β (the cone is isotropic: the tangents'
/// directions, and their change of chart at 45°, move nothing).
#[test]
fn a_bead_on_a_dome_slides_down_its_vertical_plane_above_tan_alpha_equal_to_mu() {
    let beta = 0.7;
    for alpha in [40f64.to_radians(), 60f64.to_radians()] {
        let start = SVector::from(on_dome(alpha, beta));
        let run = bead_run(alpha, beta, 0.3);
        let f = run.forces(&BEAD, 0.0, &start, &SVector::zeros()).unwrap()[0];
        let friction = (f.tangential[0].powi(2) + f.tangential[1].powi(2)).sqrt();
        let normal = BEAD.m * G * alpha.cos();
        assert!((f.normal - normal).abs() < 1e-12, "N = {}", f.normal);
        assert!((friction - 0.5 * normal).abs() < 1e-12, "F = {friction}");
        let (q, _) = run.trajectory.final_state();
        let polar = (q[0].hypot(q[1]) / q[2]).atan();
        eprintln!(
            "bead from {:.0}°: at {:.1}° after 0.3 s, off its plane by {:.1e} rad",
            alpha.to_degrees(),
            polar.to_degrees(),
            q[1].atan2(q[0]) - beta
        );
        assert!(polar > alpha + 0.05, "did not slide: {polar}");
        assert!((q[1].atan2(q[0]) - beta).abs() < 1e-10);
    }
}

/// Rolling from rest at α₀ on the drum: v² = (4/3) g (R + r)(cos α₀ − cos α),
/// N = m g ((7/3) cos α − (4/3) cos α₀) and the friction that keeps it
/// rolling m g sin α / 3, so it slips where sin α = μ (7 cos α − 4 cos α₀).
#[test]
fn a_disk_rolls_off_a_drum_and_slips_where_friction_runs_out() {
    let p = Drum {
        m: 0.4,
        r: 0.1,
        rd: 0.5,
        g: G,
    };
    let (a0, mu) = (0.1f64, 0.2);
    let d = p.r + p.rd;
    let run = Simulation::new(&p)
        .integrator(Dop853::tol(1e-13))
        .run_contacts([d * a0.sin(), d * a0.cos(), 0.0], [0.0; 3], 0.0..1.5)
        .unwrap();
    let slips = (run.changes.iter())
        .find(|c| matches!(c.kind, ChangeKind::Slips))
        .expect("it slips");
    let (q, v) = run.trajectory.state_at(slips.t).unwrap();
    let alpha = q[0].atan2(q[1]);
    // The closed form's angle, by bisection.
    let excess = |a: f64| a.sin() - mu * (7.0 * a.cos() - 4.0 * a0.cos());
    let (mut lo, mut hi) = (a0, 1.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if excess(mid) < 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    // Rolling kept the energy and the contact point still.
    let speed2 = v[0] * v[0] + v[1] * v[1];
    let energy =
        |y: f64, v2: f64, w: f64| 0.5 * p.m * v2 + 0.25 * p.m * p.r * p.r * w * w + p.m * G * y;
    let lost = energy(d * a0.cos(), 0.0, 0.0) - energy(q[1], speed2, v[2]);
    let (n, t) = ([q[0] / d, q[1] / d], [-q[1] / d, q[0] / d]);
    let slip = t[0] * v[0] + t[1] * v[1] - p.r * v[2];
    eprintln!(
        "drum: slips at α = {alpha:.12} (closed form {lo:.12}); energy lost {lost:.1e} J, slip {slip:.1e} m/s"
    );
    assert!((alpha - lo).abs() < 1e-9, "{alpha} vs {lo}");
    assert!(lost.abs() < 1e-10 && slip.abs() < 1e-10);
    assert!((speed2 - 4.0 / 3.0 * G * d * (a0.cos() - alpha.cos())).abs() < 1e-9);
    assert!(n[0] > 0.0);
}

/// Disk a, spinning at ω₀, hits disk b at rest off-centre: with n along
/// the line of centres and t = ẑ × n, Newton's law gives the normal
/// impulse P = (1 + e) w m/2, and the slip s = t·(v_a − v_b) − r (ω_a + ω_b)
/// is stopped by −s/K, K = 2/m + 2 r²/I = 6/m, where the cone holds it,
/// else met by −μ P sign s.
#[test]
fn spinning_disks_meet_with_the_impulse_that_stops_their_slip_or_mu_p() {
    let p = Disks { m: 1.0, r: 0.1 };
    let inertia = 0.5 * p.m * p.r * p.r;
    for (spin, sticks) in [(4.0, true), (60.0, false)] {
        let (u, offset) = (1.0, 0.08);
        let run = Simulation::new(&p)
            .integrator(Dop853::tol(1e-13))
            .run_contacts(
                [-0.5, offset, 0.0, 0.0, 0.0, 0.0],
                [u, 0.0, spin, 0.0, 0.0, 0.0],
                0.0..0.6,
            )
            .unwrap();
        let t = (run.changes.iter())
            .find(|c| matches!(c.kind, ChangeKind::Impact { .. }))
            .expect("an impact")
            .t;
        // Before the impact the disks coast: a at (−0.5 + u t, offset).
        let delta = [-0.5 + u * t, offset];
        let dist = delta[0].hypot(delta[1]);
        let (n, tg) = (
            [delta[0] / dist, delta[1] / dist],
            [-delta[1] / dist, delta[0] / dist],
        );
        let w = -(u * n[0]);
        let normal = (1.0 + 0.5) * w * p.m / 2.0;
        let s = u * tg[0] - p.r * spin;
        let k = 2.0 / p.m + 2.0 * p.r * p.r / inertia;
        let held = (s / k).abs() <= 0.3 * normal;
        assert_eq!(held, sticks, "the case is not the one meant");
        let tangential = if held {
            -s / k
        } else {
            -0.3 * normal * s.signum()
        };
        let impulse = [
            normal * n[0] + tangential * tg[0],
            normal * n[1] + tangential * tg[1],
        ];
        let want = [
            u + impulse[0] / p.m,
            impulse[1] / p.m,
            spin - p.r * tangential / inertia,
            -impulse[0] / p.m,
            -impulse[1] / p.m,
            -p.r * tangential / inertia,
        ];
        let (_, v) = run.trajectory.state_at(t + 0.05).unwrap();
        let off = (0..6).map(|i| (v[i] - want[i]).abs()).fold(0.0, f64::max);
        eprintln!(
            "disks, {}: velocities off by {off:.1e}",
            if held { "sticking" } else { "sliding" }
        );
        assert!(off < 1e-9, "{v:?} vs {want:?}");
        let rows = p
            .contact_rows(0, &run.trajectory.state_at(t).unwrap().0, &v, 0.0)
            .unwrap();
        assert!(
            rows.tangents[1].iter().all(|x| *x == 0.0),
            "a planar pair has one tangent"
        );
    }
}

/// Without friction the bead leaves the dome where cos α = (2/3) cos α₀,
/// tangentially, and flies clear: the two spheres' touch event does not
/// fire again.
#[test]
fn a_bead_leaves_a_slick_dome_at_two_thirds_of_cos_alpha0_and_flies_clear() {
    let p = SlickBead {
        m: BEAD.m,
        r: BEAD.r,
        rd: BEAD.rd,
        g: G,
    };
    let a0 = 0.2f64;
    let run = Simulation::new(&p)
        .integrator(Dop853::tol(1e-12))
        .run_contacts(on_dome(a0, 0.7), [0.0; 3], 0.0..1.5)
        .unwrap();
    let kinds: Vec<&ChangeKind<f64>> = run.changes.iter().map(|c| &c.kind).collect();
    assert!(
        matches!(kinds[..], [ChangeKind::Closes, ChangeKind::LiftsOff]),
        "{kinds:?}"
    );
    let (q, _) = run.trajectory.state_at(run.changes[1].t).unwrap();
    let cos_alpha = q[2] / q.norm();
    eprintln!(
        "slick dome: leaves at cos α = {cos_alpha:.12}, closed form {:.12}",
        2.0 / 3.0 * a0.cos()
    );
    assert!((cos_alpha - 2.0 / 3.0 * a0.cos()).abs() < 1e-9);
    let (q, _) = run.trajectory.final_state();
    assert!(q.norm() > p.r + p.rd + 0.1, "still on the dome: {q:?}");
}

/// The drum's roll and slip under the time stepper and the compliant model
/// (stiff: Radau5) approach the event-driven run's: the same disk at the
/// same time, the differences falling with the step, and with the
/// stiffness and the friction's creep speed ε together.
#[test]
fn the_drum_under_time_stepping_and_compliance_follows_the_exact_run() {
    let p = Drum {
        m: 0.4,
        r: 0.1,
        rd: 0.5,
        g: G,
    };
    let (a0, d, end) = (0.1f64, 0.6, 0.8);
    let (q0, v0) = ([d * a0.sin(), d * a0.cos(), 0.0], [0.0; 3]);
    let exact = Simulation::new(&p)
        .integrator(Dop853::tol(1e-13))
        .run_contacts(q0, v0, 0.0..end)
        .unwrap();
    let (qe, _) = exact.trajectory.final_state();
    let off = |run: ContactRun<f64, 3>| (run.trajectory.final_state().0 - qe).amax();
    let stepped: Vec<f64> = [1e-3, 1e-4]
        .map(|h| {
            let run = Simulation::new(&p).integrator(MoreauJean::step(h));
            off(run.run_contacts(q0, v0, 0.0..end).unwrap())
        })
        .into();
    let compliant: Vec<f64> = [(1e5, 1e-4), (1e7, 1e-6)]
        .map(|(k, creep)| {
            let law = Compliant::stiffness(k).slip_speed(creep);
            let run = Simulation::new(&p)
                .integrator(Radau5::tol(1e-10))
                .compliant_contacts(law);
            off(run.run_contacts(q0, v0, 0.0..end).unwrap())
        })
        .into();
    eprintln!(
        "drum at {end} s: Moreau–Jean h = 1e-3, 1e-4 off by {stepped:?}; compliant (k, ε) = (1e5, 1e-4), (1e7, 1e-6) off by {compliant:?}"
    );
    assert!(stepped[1] < stepped[0] && stepped[1] < 1e-3, "{stepped:?}");
    assert!(
        compliant[1] < compliant[0] && compliant[1] < 1e-3,
        "{compliant:?}"
    );
}
