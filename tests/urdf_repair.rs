//! A URDF file with a placeholder inertia loads with `inertia = repair` (the
//! nearest physical inertia, listed in `URDF_REPAIRED`) or `inertia =
//! as_written` (unchecked); without either it is a compile error (see the
//! codegen tests).

use lagrange::prelude::*;

#[derive(Lagrangian)]
#[lagrange(urdf("tests/data/placeholder_inertia.urdf", inertia = repair), gravity = [0, 0, -9.81])]
struct Repaired {}

#[derive(Lagrangian)]
#[lagrange(urdf("tests/data/placeholder_inertia.urdf", inertia = as_written), gravity = [0, 0, -9.81])]
struct AsWritten {}

/// Every entry 1e-6 is 1e-6·(1 1 1)(1 1 1)ᵀ: moments (3, 0, 0)·1e-6 on the
/// axis n = (1, 1, 1)/√3 and any two across it. Their projection onto
/// a ≤ b + c moves each by a third of the excess 3: (2, 1, 1)·1e-6, so the
/// tensor is 1e-6·(E + n nᵀ): 4/3·1e-6 on the diagonal, 1/3·1e-6 off it.
#[test]
fn a_placeholder_inertia_is_repaired_to_the_hand_computed_one() {
    let [(link, written, used)] = Repaired::URDF_REPAIRED else {
        panic!("{:?}", Repaired::URDF_REPAIRED)
    };
    assert_eq!(*link, "base");
    assert_eq!(*written, [1e-6; 6]);
    let (d, o) = (4.0 / 3.0 * 1e-6, 1.0 / 3.0 * 1e-6);
    let want = [d, d, d, o, o, o];
    assert!(
        used.iter().zip(&want).all(|(u, w)| (u - w).abs() < 1e-20),
        "{used:?}"
    );
    assert!(AsWritten::URDF_REPAIRED.is_empty());
}

/// Both load and run: the leg swings the same way (the base is fixed, so
/// its inertia does not enter the equations).
#[test]
fn both_load_and_run_alike() {
    let span = 0.0..0.5;
    let a = Simulation::new(&Repaired {})
        .run([0.5], [0.0], span.clone())
        .unwrap();
    let b = Simulation::new(&AsWritten {})
        .run([0.5], [0.0], span)
        .unwrap();
    assert_eq!(a.final_state(), b.final_state());
}
