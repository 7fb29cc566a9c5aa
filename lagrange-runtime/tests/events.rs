//! Events: bouncing ball against closed forms with every integrator, the
//! pendulum period from event times, terminal events, the crossing directions,
//! the midpoint guard, and the typed errors of a misbehaving event.

mod common;

use common::{Ball, Pendulum, pendulum_period, sv};
use lagrange_runtime::Failure;
use lagrange_runtime::{
    Direction, Dop853, Dopri5, Error, Event, Events, Gauss, Integrator, Radau5, Rk4, SecondOrder,
    Simulation, StormerVerlet,
};
use nalgebra::SVector;

/// q̈ = −ω² q as a bare `SecondOrder` system (no Lagrangian behind it).
struct Spring {
    omega: f64,
}

impl SecondOrder<f64, 1> for Spring {
    fn acceleration(
        &self,
        _t: f64,
        q: &SVector<f64, 1>,
        _v: &SVector<f64, 1>,
    ) -> Result<SVector<f64, 1>, Error> {
        Ok(q * -(self.omega * self.omega))
    }
}

/// A block sliding with Coulomb friction, q̈ = −sign(q̇) (sign(0) = 0): the
/// acceleration jumps where q̇ changes sign.
struct Friction;

impl SecondOrder<f64, 1> for Friction {
    fn acceleration(
        &self,
        _t: f64,
        _q: &SVector<f64, 1>,
        v: &SVector<f64, 1>,
    ) -> Result<SVector<f64, 1>, Error> {
        let s = if v[0] > 0.0 {
            1.0
        } else if v[0] < 0.0 {
            -1.0
        } else {
            0.0
        };
        Ok(sv([-s]))
    }
}

/// Closed form of a ball dropped from rest at height h0 with restitution e:
/// impact k (k = 0, 1, ...) at t_k = t0 + Σ_{j=1..k} 2 e^j u/g with t0 = √(2h0/g)
/// and u = g t0 the first impact speed; the apex after impact k at
/// t_k + e^{k+1} u/g with height e^{2(k+1)} h0.
fn closed_form(h0: f64, g: f64, e: f64, k: usize) -> (f64, f64, f64) {
    let t0 = (2.0 * h0 / g).sqrt();
    let u = g * t0;
    let tk = t0 + (1..=k).map(|j| 2.0 * e.powi(j as i32) * u / g).sum::<f64>();
    let e1 = e.powi(k as i32 + 1);
    (tk, tk + e1 * u / g, e1 * e1 * h0)
}

/// Bounce times and apex heights against the closed form; every integrator
/// honours the stop hook. Free fall is a quadratic, which all of these methods
/// and their dense outputs reproduce exactly, so the only errors are the event
/// location's and round-off.
fn bouncing_ball_with(method: impl Integrator, name: &str) {
    let (g, e, h0) = (9.81, 0.8, 1.5);
    let ball = Ball { g };
    // The impacts accumulate at t0 + 2ue/(g(1 − e)) = 4.977 (Zeno): stop before.
    let t_end = 4.0;
    let run = Simulation::new(&ball)
        .integrator(method)
        .event(
            Event::new(|_, q, _| q[0])
                .falling()
                .named("floor")
                .action(move |_, _, v: &mut SVector<f64, 1>| *v *= -e),
        )
        .event(
            Event::new(|_, _, v: &SVector<f64, 1>| v[0])
                .falling()
                .named("apex"),
        )
        .run([h0], [0.0], 0.0..t_end)
        .unwrap();
    let impacts = run.times(0);
    let apexes: Vec<_> = run.of(1).collect();
    assert!(impacts.len() >= 7, "{name}: {} impacts", impacts.len());
    for (k, &t) in impacts.iter().enumerate() {
        let (tk, _, _) = closed_form(h0, g, e, k);
        assert!(
            (t - tk).abs() < 1e-9,
            "{name}: impact {k} at {t}, exact {tk}"
        );
    }
    for (k, o) in apexes.iter().enumerate() {
        let (_, ta, ha) = closed_form(h0, g, e, k);
        assert!(
            (o.t - ta).abs() < 1e-9,
            "{name}: apex {k} at {}, exact {ta}",
            o.t
        );
        assert!(
            (o.q[0] - ha).abs() < 1e-9,
            "{name}: apex {k} height {}, exact {ha}",
            o.q[0]
        );
    }
    assert_eq!(apexes.len(), impacts.len(), "{name}");
    // Each impact: the ball is at the floor, and the action reversed and scaled
    // the velocity; the trajectory records the state after it.
    for o in run.of(0) {
        assert!(o.q[0].abs() < 1e-12, "{name}: impact at height {}", o.q[0]);
        assert!(o.v[0] < 0.0 && (o.v_after[0] + e * o.v[0]).abs() < 1e-15);
        let (q, v) = run.trajectory.state_at(o.t).unwrap();
        assert_eq!((q, v), (o.q_after, o.v_after), "{name}");
    }
    // Never below the floor by more than round-off, and the run reaches t_end.
    let lowest = run
        .trajectory
        .positions()
        .iter()
        .map(|q| q[0])
        .fold(f64::MAX, f64::min);
    assert!(lowest > -1e-12, "{name}: lowest point {lowest}");
    assert_eq!(*run.trajectory.times().last().unwrap(), t_end, "{name}");
    assert!(
        run.trajectory.times().windows(2).all(|w| w[0] < w[1]),
        "{name}"
    );
    assert_eq!(run.terminated_by, None);
}

#[test]
fn bouncing_ball_matches_closed_form_with_every_integrator() {
    bouncing_ball_with(Dopri5::tol(1e-10), "DOPRI5");
    bouncing_ball_with(Dop853::tol(1e-10), "DOP853");
    bouncing_ball_with(Radau5::tol(1e-8), "Radau5");
    bouncing_ball_with(Rk4::step(0.05), "RK4");
    bouncing_ball_with(StormerVerlet::step(0.05), "Störmer–Verlet");
    bouncing_ball_with(Gauss::step(0.05), "Gauss");
}

/// With e = 1 the energy is the same after every impact (the action keeps |v|).
#[test]
fn elastic_ball_conserves_energy_across_impacts() {
    let ball = Ball { g: 9.81 };
    let run = Simulation::new(&ball)
        .integrator(Dopri5::tol(1e-12))
        .event(
            Event::new(|_, q, _| q[0])
                .falling()
                .action(|_, _, v: &mut SVector<f64, 1>| *v = -*v),
        )
        .run([2.0], [0.0], 0.0..20.0)
        .unwrap();
    assert!(run.occurrences.len() > 10);
    assert!(
        run.trajectory.integral_drift() < 1e-12,
        "{:e}",
        run.trajectory.integral_drift()
    );
}

/// The pendulum period from the rising crossings of θ (a non-terminal event
/// without action), against 4√(l/g) K(sin(θ0/2)) — and the observer does not
/// disturb the integration: same steps as a run without the event.
#[test]
fn pendulum_period_from_events() {
    let sys = Pendulum::standard();
    for deg in [30.0f64, 120.0, 170.0] {
        let th0 = deg.to_radians();
        let exact = pendulum_period(sys.l, sys.g, th0);
        let sim = Simulation::new(&sys).integrator(Dop853::tol(1e-12));
        let run = sim
            .clone()
            .event(Event::new(|_, q: &SVector<f64, 1>, _| q[0]).rising())
            .run(sv([th0]), sv([0.0]), 0.0..5.3 * exact)
            .unwrap();
        let ups = run.times(0);
        // Released at θ0 > 0: θ rises through 0 at 3/4, 7/4, ... periods.
        assert_eq!(ups.len(), 5, "{deg}°: {ups:?}");
        for (k, t) in ups.iter().enumerate() {
            let expected = (0.75 + k as f64) * exact;
            let rel = (t - expected).abs() / exact;
            assert!(
                rel < 1e-9,
                "{deg}°: crossing {k} at {t}, expected {expected} ({rel:e})"
            );
        }
        let period = (ups[4] - ups[0]) / 4.0;
        let rel = (period - exact).abs() / exact;
        eprintln!("{deg}°: period from events {period:.15}, exact {exact:.15}, rel {rel:.1e}");
        assert!(rel < 1e-9, "{deg}°: {rel:e}");
        for o in &run.occurrences {
            assert!(o.q[0].abs() < 1e-12 && o.v[0] > 0.0 && o.v_after == o.v);
        }
        let plain = sim.run(sv([th0]), sv([0.0]), 0.0..5.3 * exact).unwrap();
        assert_eq!(plain.times(), run.trajectory.times(), "{deg}°");
    }
}

/// A terminal event ends the run at the event time: the trajectory's last point
/// is the state at the crossing.
#[test]
fn terminal_event_stops_the_run_at_the_event() {
    let sys = Pendulum::standard();
    let th0 = 1.0f64;
    let exact = pendulum_period(sys.l, sys.g, th0);
    for method in [0, 1] {
        let sim = Simulation::new(&sys);
        let event = Event::new(|_, q: &SVector<f64, 1>, _| q[0])
            .falling()
            .terminal();
        let run = if method == 0 {
            sim.integrator(Dopri5::tol(1e-12))
                .event(event)
                .run(sv([th0]), sv([0.0]), 0.0..10.0)
        } else {
            sim.integrator(Rk4::step(1e-3))
                .event(event)
                .run(sv([th0]), sv([0.0]), 0.0..10.0)
        }
        .unwrap();
        // The first downward crossing of θ = 0 is a quarter period after release.
        let t_end = *run.trajectory.times().last().unwrap();
        assert_eq!(run.terminated_by, Some(0));
        assert_eq!(run.occurrences.len(), 1);
        assert_eq!(run.occurrences[0].t, t_end);
        let tol = if method == 0 { 1e-10 } else { 1e-8 };
        assert!(
            (t_end - exact / 4.0).abs() < tol,
            "{t_end} vs {}",
            exact / 4.0
        );
        let (q, v) = run.trajectory.final_state();
        assert!(q[0].abs() < 1e-12 && v[0] < 0.0, "{q} {v}");
        assert_eq!(run.trajectory.segments().last().unwrap().end(), t_end);
    }
}

/// q = cos t crosses −0.95 at π ∓ acos(0.95), 0.64 apart: with RK4 steps of 1
/// both crossings fall in the step [2.5, 3.5], where the end values have the
/// same sign; the dense-output midpoint still sees them. Also: directions.
#[test]
fn two_crossings_in_one_step_and_directions() {
    let osc = Spring { omega: 1.0 };
    let level = -0.95f64;
    let (down, up) = (
        std::f64::consts::PI - 0.95f64.acos(),
        std::f64::consts::PI + 0.95f64.acos(),
    );
    let count = |direction: Direction| {
        Events::new()
            .with(Event::new(move |_, q: &SVector<f64, 1>, _| q[0] - level).direction(direction))
            .integrate(
                &Rk4::step(1.0),
                &osc,
                0.5,
                4.5,
                sv([0.5f64.cos()]),
                sv([-0.5f64.sin()]),
            )
            .unwrap()
            .times(0)
    };
    let both = count(Direction::Both);
    assert_eq!(both.len(), 2, "{both:?}");
    // RK4 with h = 1 (and its cubic Hermite dense output) is only good to a few
    // hundredths here; the point is that both crossings are seen.
    assert!(
        (both[0] - down).abs() < 0.1 && (both[1] - up).abs() < 0.1,
        "{both:?}"
    );
    assert_eq!(count(Direction::Falling), vec![both[0]]);
    assert_eq!(count(Direction::Rising), vec![both[1]]);
}

/// An action that leaves the state crossing (here: none at all) cannot loop
/// forever; nor can a ball that comes to rest (Zeno): typed errors at the point.
#[test]
fn accumulating_events_are_typed_errors() {
    let ball = Ball { g: 9.81 };
    let sim = Simulation::new(&ball).integrator(Dopri5::tol(1e-10));
    let stuck = sim
        .clone()
        .event(
            Event::new(|_, q: &SVector<f64, 1>, _| q[0])
                .falling()
                .named("floor")
                .action(|_, _, _| {}),
        )
        .run([1.0], [0.0], 0.0..2.0)
        .unwrap_err();
    assert!(
        matches!(&stuck.error, Error::EventsAccumulate { event, t, .. } if event == "floor" && (t - (2.0f64 / 9.81).sqrt()).abs() < 1e-9),
        "{stuck}"
    );
    // A ball with e < 1 comes to rest after infinitely many impacts in finite
    // time (e = 0.8 from 1.5 m: at 4.977 s); the run stops with a typed error
    // near that point instead of hanging.
    let (e, h0, g) = (0.8f64, 1.5f64, 9.81f64);
    let t_rest = (2.0 * h0 / g).sqrt() * (1.0 + 2.0 * e / (1.0 - e));
    let rest = sim
        .clone()
        .event(
            Event::new(|_, q: &SVector<f64, 1>, _| q[0])
                .falling()
                .action(move |_, _, v| *v *= -e),
        )
        .run([h0], [0.0], 0.0..5.0)
        .unwrap_err();
    assert!(
        matches!(&rest.error, Error::EventsAccumulate { t, .. } if (t - t_rest).abs() < 1e-6),
        "{rest} (Zeno point {t_rest})"
    );
    let zeno = sim
        .clone()
        .event(
            Event::new(|_, q: &SVector<f64, 1>, _| q[0])
                .falling()
                .action(|_, _, v| *v *= -0.5),
        )
        .max_events(20)
        .run([1.0], [0.0], 0.0..10.0)
        .unwrap_err();
    assert!(
        matches!(&zeno.error, Error::TooManyEvents { event, max_events: 20, .. } if event == "event #0"),
        "{zeno}"
    );
}

/// A NaN event function is a typed error naming the event; an action that
/// makes the state non-finite and a zero event budget are typed errors too.
#[test]
fn misbehaving_events_are_typed_errors() {
    let ball = Ball { g: 9.81 };
    let sim = Simulation::new(&ball).integrator(Dopri5::tol(1e-10));
    let nan = sim
        .clone()
        .event(
            Event::new(|t, q: &SVector<f64, 1>, _| if t > 0.3 { f64::NAN } else { q[0] })
                .named("sensor"),
        )
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    assert!(
        matches!(&nan.error, Error::EventFunction { event, t, .. } if event == "sensor" && *t > 0.3),
        "{nan}"
    );
    assert!(nan.to_string().contains("`sensor` is not finite"), "{nan}");
    let bad = sim
        .event(Event::new(|_, q: &SVector<f64, 1>, _| q[0]).action(|_, q, _| q[0] = f64::NAN))
        .run([1.0], [0.0], 0.0..1.0)
        .unwrap_err();
    assert!(matches!(bad.error, Error::NonFiniteState { .. }), "{bad}");
    let zero = Events::new()
        .with(Event::new(|_, q: &SVector<f64, 1>, _| q[0]))
        .max_events(0)
        .integrate(
            &Rk4::step(0.1),
            &Spring { omega: 1.0 },
            0.0,
            1.0,
            sv([1.0]),
            sv([0.0]),
        );
    assert!(matches!(
        zero,
        Err(Failure {
            error: Error::Settings(_),
            ..
        })
    ));
}

/// Events drive any `SecondOrder` system, not only `Lagrangian` ones.
#[test]
fn events_on_a_plain_second_order_system() {
    let osc = Spring { omega: 2.0 };
    assert_eq!(
        osc.acceleration(0.0, &sv([1.0]), &sv([0.0])).unwrap()[0],
        -4.0
    );
    let run = Events::new()
        .with(Event::new(|_, q: &SVector<f64, 1>, _| q[0]).falling())
        .integrate(&Dopri5::tol(1e-12), &osc, 0.0, 10.0, sv([1.0]), sv([0.0]))
        .unwrap();
    // cos 2t falls through 0 at π/4 + kπ.
    let t = run.times(0);
    assert_eq!(t.len(), 3);
    for (k, t) in t.iter().enumerate() {
        let exact = std::f64::consts::FRAC_PI_4 + k as f64 * std::f64::consts::PI;
        assert!((t - exact).abs() < 1e-10, "{t} vs {exact}");
    }
}

/// `terminal_if` ends the run at the first impact whose rebound speed is below
/// a threshold (here 1 m/s): with e = 0.8 from 1.5 m (first impact at 5.42 m/s)
/// that is impact k with 5.42·0.8^(k+1) < 1, k = 7; and the small bounces
/// before it, shorter than the integrator's restart step, are all seen.
#[test]
fn terminal_if_decides_after_the_action() {
    let (g, e, h0) = (9.81, 0.8, 1.5);
    let run = Simulation::new(&Ball { g })
        .integrator(Dopri5::tol(1e-10))
        .event(
            Event::new(|_, q: &SVector<f64, 1>, _| q[0])
                .falling()
                .action(move |_, _, v| *v *= -e)
                .terminal_if(|_, _, v| v[0] < 1.0),
        )
        .run([h0], [0.0], 0.0..10.0)
        .unwrap();
    assert_eq!(run.terminated_by, Some(0));
    assert_eq!(run.occurrences.len(), 8);
    let (tk, _, _) = closed_form(h0, g, e, 7);
    assert!((run.occurrences[7].t - tk).abs() < 1e-9);
    assert_eq!(
        *run.trajectory.times().last().unwrap(),
        run.occurrences[7].t
    );
    let (_, v) = run.trajectory.final_state();
    assert!(v[0] < 1.0 && v[0] > 0.0);
}

/// `restart` cuts the integration at every crossing and restarts it just past
/// the surface with the state unchanged: each crossing is recorded once, the
/// state after lies on the new side, no dense-output segment straddles the
/// surface, and the motion is the undisturbed one. A motion that turns back at
/// the surface at once (a sliding mode: friction holding a block at rest)
/// accumulates restarts and ends with the typed error.
#[test]
fn restart_cuts_the_steps_at_the_surface() {
    let osc = Spring { omega: 2.0 };
    let run = Events::new()
        .with(Event::new(|_, q: &SVector<f64, 1>, _| q[0]).restart())
        .integrate(&Dopri5::tol(1e-12), &osc, 0.0, 10.0, sv([1.0]), sv([0.0]))
        .unwrap();
    // cos 2t is zero at π/4 + kπ/2: six times before t = 10.
    assert_eq!(run.occurrences.len(), 6);
    for (k, o) in run.occurrences.iter().enumerate() {
        let exact = std::f64::consts::FRAC_PI_4 + k as f64 * std::f64::consts::FRAC_PI_2;
        assert!((o.t - exact).abs() < 1e-10, "{} vs {exact}", o.t);
        assert_eq!((o.q, o.v), (o.q_after, o.v_after));
        // Falling through zero at even k, rising at odd k; the restart state is
        // already on the far side (or on the surface).
        let far = if k % 2 == 0 { -o.q[0] } else { o.q[0] };
        assert!((0.0..1e-12).contains(&far), "k = {k}: q = {:e}", o.q[0]);
    }
    for seg in run.trajectory.segments() {
        let (a, b) = (seg.start(), seg.end());
        let signs: Vec<bool> = (1..10)
            .map(|i| seg.eval(a + (b - a) * i as f64 / 10.0).0[0] > 0.0)
            .collect();
        assert!(
            signs.iter().all(|&s| s == signs[0]),
            "segment [{a}, {b}] straddles q = 0"
        );
    }
    let (q, _) = run.trajectory.final_state();
    assert!((q[0] - 20.0f64.cos()).abs() < 1e-9, "{q}");
    // The block stops at t = 1 and friction would hold it: restarting there
    // only finds the surface again.
    let stuck = Events::new()
        .with(
            Event::new(|_, _, v: &SVector<f64, 1>| v[0])
                .named("sticks")
                .restart(),
        )
        .integrate(
            &Dopri5::tol(1e-10),
            &Friction,
            0.0,
            3.0,
            sv([0.0]),
            sv([1.0]),
        )
        .unwrap_err();
    assert!(
        matches!(&stuck.error, Error::EventsAccumulate { event, t, .. } if event == "sticks" && (t - 1.0).abs() < 1e-8),
        "{stuck}"
    );
}
