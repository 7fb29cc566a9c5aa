//! A legged robot from its URDF with its feet on the ground: Solo 12 on a
//! free root (a quaternion), each foot a point contact with the file's
//! lateral friction 1.0, dropped from 6.5 cm above its standing height
//! and held up by PD control on its twelve joints. It lands, settles and
//! stands on its four feet, sticking; both rigid schemes agree on where.

use crate::legged::{Solo12Standing, dropped, pd};
use lagrange::prelude::*;
use lagrange::{ChangeKind, ContactRun, ContactState, Dop853, MoreauJean};

fn standing(run: &ContactRun<f64, 18, 19>, what: &str, end: f64) -> (f64, f64) {
    let (q, v) = run.trajectory.final_state();
    let states = run.states(end);
    eprintln!(
        "Solo 12 dropped, {what}: base at {:.4} m, speed {:.1e}, feet {states:?}, {} changes",
        q[2],
        v.norm(),
        run.changes.len()
    );
    assert!(
        states.iter().all(|s| *s == ContactState::Sticking),
        "{states:?}"
    );
    assert!(v.norm() < 1e-3, "{v}");
    (q[2], (q.fixed_rows::<4>(15).norm() - 1.0).abs())
}

/// Input k drives the joint at coordinate 3 + k.
#[test]
fn the_inputs_follow_the_joints_order() {
    let names = <Solo12Standing as Lagrangian<f64, 18, 19>>::COORDINATES;
    let joints =
        ["HAA", "HFE", "KFE"].map(|j| ["FL", "FR", "HL", "HR"].map(|l| format!("{l}_{j}")));
    let written: Vec<String> = joints.into_iter().flatten().collect();
    assert_eq!(
        names[3..15],
        written.iter().map(String::as_str).collect::<Vec<_>>()[..]
    );
}

#[test]
fn solo_12_dropped_stands_on_its_four_feet_under_pd() {
    let robot = Solo12Standing {};
    let law = |_: f64, q: &SVector<f64, 19>, v: &SVector<f64, 18>| pd(q, v);
    let stepped = Simulation::new(&robot)
        .integrator(MoreauJean::step(5e-4))
        .feedback(law)
        .run_contacts(dropped(0.30), SVector::zeros(), 0.0..1.5)
        .unwrap();
    let (height, unit) = standing(&stepped, "time-stepped", 1.5);
    // One plastic impact per foot, all four in one step, and nothing after:
    // each leaves along the midpoint's normal at round-off.
    assert_eq!(stepped.changes.len(), 4, "{:?}", stepped.changes);
    assert!(stepped.changes.iter().all(|c| match c.kind {
        ChangeKind::Impact { after, .. } => after.abs() < 1e-12,
        _ => false,
    }));
    assert!(height > 0.2 && height < 0.24, "{height}");
    assert!(unit < 1e-12);
    let exact = Simulation::new(&robot)
        .integrator(Dop853::tol(1e-9))
        .feedback(law)
        .run_contacts(dropped(0.30), SVector::zeros(), 0.0..1.5)
        .unwrap();
    let (exact_height, _) = standing(&exact, "event-driven", 1.5);
    eprintln!(
        "Solo 12: the schemes stand {:.1e} m apart",
        (exact_height - height).abs()
    );
    assert!(
        (exact_height - height).abs() < 1e-3,
        "{exact_height} vs {height}"
    );
}
