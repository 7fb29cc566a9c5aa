//! Applying an LQR gain with `StateFeedback`: the same law as building the
//! state vector by hand, on stack matrices (no allocation per call), and a
//! controller the simulation takes as it is.

#[path = "../examples/catalog/mod.rs"]
mod catalog;

use catalog::control::CartPole;
use lagrange::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: defers to the system allocator; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn lqr_gain_as_state_feedback() {
    let cart = CartPole::standard();
    let lin = cart.upright().unwrap();
    let (q_w, r_w) = CartPole::lqr_weights();
    let gain = lin.lqr(&q_w, &r_w).unwrap().gain;
    let law = StateFeedback::<f64, 2, 1>::from_gain(&gain, &lin, &CartPole::COORDINATES).unwrap();
    let (q, v) = (Vector2::new(0.3, -0.2), Vector2::new(0.7, 1.1));
    let x = lagrange::nalgebra::DVector::from_row_slice(&[q[0], q[1], v[0], v[1]]);
    let by_hand = [-(&gain * x)[0]];
    let before = ALLOCATIONS.with(Cell::get);
    let u = law.input(&q, &v);
    assert_eq!(
        ALLOCATIONS.with(Cell::get),
        before,
        "no allocation per call"
    );
    assert!((u[0] - by_hand[0]).abs() < 1e-12, "{u} vs {by_hand:?}");
    assert_eq!(cart.lqr_feedback().unwrap(), law);

    // The simulation takes it as a controller: the pendulum is caught.
    let run = Simulation::new(&cart)
        .integrator(Dopri5::tol(1e-10))
        .control(law)
        .run([0.0, 0.2], [0.0, 0.0], 0.0..8.0)
        .unwrap();
    let (q_end, v_end) = run.trajectory().final_state();
    assert!(
        q_end.amax() < 1e-3 && v_end.amax() < 1e-3,
        "{q_end} {v_end}"
    );

    // A gain of the wrong shape, or a state the system does not have.
    let wrong = lagrange::nalgebra::DMatrix::zeros(1, 3);
    assert!(StateFeedback::<f64, 2, 1>::from_gain(&wrong, &lin, &CartPole::COORDINATES).is_err());
    let e = StateFeedback::<f64, 2, 1>::from_gain(&gain, &lin, &["x", "phi"]).unwrap_err();
    assert!(e.to_string().contains("`theta`"), "{e}");
}
