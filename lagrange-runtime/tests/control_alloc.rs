//! The controller adds no allocation: a counting global allocator compares a
//! controlled run with the same run uncontrolled (fixed-step RK4, so both take
//! exactly the same steps). Counts are per thread, so the test harness's own
//! threads do not disturb them.

mod common;

use common::Oscillator;
use lagrange_runtime::{Dynamics, Feedback, InputForces, Integrator, Rk4, Simulation};
use nalgebra::Vector1;
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
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations (alloc + realloc) made by `f` on this thread.
fn allocations<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = ALLOCATIONS.with(Cell::get);
    let r = f();
    (ALLOCATIONS.with(Cell::get) - before, r)
}

#[test]
fn the_controller_adds_no_allocation() {
    let sys = Oscillator { m: 1.0, k: 4.0 };
    let calls = Cell::new(0usize);
    let law = |_: f64, q: &Vector1<f64>, v: &Vector1<f64>| {
        calls.set(calls.get() + 1);
        [-q[0] - 0.5 * v[0]]
    };
    let (q0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
    let mut per_run = Vec::new();
    for steps in [1000usize, 4000] {
        let rk4 = Rk4::step(1.0 / steps as f64);

        // The forward dynamics with and without the forcing: identical counts.
        let (plain, a) = allocations(|| {
            rk4.integrate(&Dynamics::new(&sys), 0.0, 1.0, q0, v0)
                .unwrap()
        });
        let forced = Dynamics::new(&sys).with_forcing(InputForces::new(&sys, Feedback::new(law)));
        calls.set(0);
        let (driven, b) = allocations(|| rk4.integrate(&forced, 0.0, 1.0, q0, v0).unwrap());
        let controller_calls = calls.get();
        assert_eq!(a.len(), steps + 1);
        assert_eq!(b.len(), steps + 1);
        assert_eq!(controller_calls, 4 * steps + 1);
        assert_ne!(a.final_state(), b.final_state(), "the controller acts");
        println!(
            "{steps} RK4 steps: integrate(Dynamics) {plain} allocations, \
             integrate(Dynamics + feedback) {driven} allocations, {controller_calls} controller calls"
        );
        assert_eq!(plain, driven);

        // Through the simulation builder: the controlled run also records the
        // inputs (one Vec), and nothing else.
        let (plain_sim, _) = allocations(|| {
            Simulation::new(&sys)
                .integrator(rk4)
                .run(q0, v0, 0.0..1.0)
                .unwrap()
        });
        calls.set(0);
        let (controlled_sim, run) = allocations(|| {
            Simulation::new(&sys)
                .integrator(rk4)
                .feedback(law)
                .run(q0, v0, 0.0..1.0)
                .unwrap()
        });
        assert_eq!(run.inputs().len(), steps + 1);
        // 4 per step + 1 at the start inside the integrator, 1 per stored point recorded.
        assert_eq!(calls.get(), 4 * steps + 1 + steps + 1);
        println!(
            "{steps} RK4 steps: Simulation::run {plain_sim} allocations, \
             .feedback(..).run {controlled_sim} allocations ({} controller calls)",
            calls.get()
        );
        per_run.push(controlled_sim - plain_sim);
    }
    // The difference is the inputs' Vec, the same for 1000 and 4000 steps.
    assert_eq!(per_run, vec![1, 1]);

    // A sampled run restarts at every sample: its allocations are those of one
    // trajectory piece per sample (plus the concatenation), whatever the
    // controller computes.
    let sampled = |samples: usize, gain: f64| {
        allocations(|| {
            Simulation::new(&sys)
                .integrator(Rk4::step(0.0025))
                .sampled(0.01, move |_, q, _| [-gain * q[0]])
                .run(q0, v0, 0.0..samples as f64 * 0.01)
                .unwrap()
        })
        .0
    };
    let (a, b, c) = (sampled(100, 1.0), sampled(200, 1.0), sampled(200, 0.0));
    println!("sampled, 4 RK4 steps per sample: {a} allocations for 100 samples, {b} for 200");
    assert_eq!(
        b, c,
        "the allocations do not depend on what the controller computes"
    );
}
