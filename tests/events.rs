//! Events on derived systems: the catalog pendulum's period from event times.
//! (The runtime's own tests, lagrange-runtime/tests/events.rs, cover the
//! bouncing ball with every integrator, terminal events and the errors.)

use crate::catalog;

use catalog::{Pendulum, elliptic_k};
use lagrange::Dop853;
use lagrange::prelude::*;

/// Rising crossings of θ (non-terminal, no action) are one period apart:
/// 4√(l/g) K(sin(θ0/2)) to 1e-9 relative, up to θ0 = 175°.
#[test]
fn derived_pendulum_period_from_rising_crossings() {
    let sys = Pendulum::<f64> {
        m: 0.7,
        l: 1.3,
        g: 9.81,
    };
    for deg in [5.0f64, 60.0, 135.0, 175.0] {
        let th0 = deg.to_radians();
        let exact = 4.0 * (sys.l / sys.g).sqrt() * elliptic_k((th0 / 2.0).sin());
        let run = Simulation::new(&sys)
            .integrator(Dop853::tol(1e-13))
            .event(Event::new(|_, q: &Vector1<f64>, _| q[0]).rising())
            .run([th0], [0.0], 0.0..6.5 * exact)
            .unwrap();
        let ups = run.times(0);
        assert_eq!(ups.len(), 6, "{deg}°: {ups:?}");
        let rel = ((ups[5] - ups[0]) / 5.0 - exact).abs() / exact;
        eprintln!("{deg}°: period rel. error {rel:.1e}");
        assert!(rel < 1e-9, "{deg}°: {rel:e}");
        // Released at rest from θ0 > 0, θ first rises through 0 at 3/4 period.
        let rel = (ups[0] - 0.75 * exact).abs() / exact;
        assert!(rel < 1e-9, "{deg}°: first crossing {rel:e}");
    }
}

/// An event in f32: the generic derived system and the event layer work in
/// single precision too (to single-precision accuracy).
#[test]
fn derived_pendulum_event_in_f32() {
    let sys = Pendulum::<f32> {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let exact = 4.0 * (1.0f64 / 9.81).sqrt() * elliptic_k(0.25f64.sin());
    let run = Simulation::new(&sys)
        .integrator(Dopri5::tol(1e-6))
        .event(
            Event::new(|_, q: &Vector1<f32>, _| q[0])
                .falling()
                .terminal(),
        )
        .run([0.5f32], [0.0f32], 0.0..10.0)
        .unwrap();
    assert_eq!(run.terminated_by, Some(0));
    let t = f64::from(run.occurrences[0].t);
    assert!((t - exact / 4.0).abs() < 1e-5, "{t} vs {}", exact / 4.0);
}
