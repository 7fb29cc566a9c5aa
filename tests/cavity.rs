//! C10: a heavy point inside a spherical cavity (seed 001, unilateral
//! constraint |x| ≤ R): impacts located as events, Newton's impact law,
//! sliding contact with the multiplier's sign deciding release.

use crate::catalog;

use catalog::cavity::{Cavity, Phase};
use lagrange::prelude::*;

const G: f64 = 9.81;
const R: f64 = 0.75;

fn energy(cavity: &Cavity, q: &Vector3<f64>, v: &Vector3<f64>) -> f64 {
    cavity.particle.integral(q, v, 0.0)
}

/// How far outside the point may get: free flight stops at the wall on the
/// inside (the event time is taken on the old side of the crossing); sliding
/// keeps ||x|² − R²| below the projection tolerance 1e-14 R², so |x| − R stays
/// below ~1e-14 R.
const OUTSIDE: f64 = 4e-14 * R;

/// max (|x| − R) over the recorded points and the impacts.
fn outside(run: &catalog::cavity::CavityRun) -> f64 {
    let points = run.points().map(|(_, q, _)| q.norm() - R);
    let impacts = run.impacts.iter().map(|i| i.q.norm() - R);
    points.chain(impacts).fold(f64::MIN, f64::max)
}

/// Dropped from rest at the centre: free fall to the bottom, reached at
/// t = √(2R/g).
#[test]
fn dropped_from_the_centre_hits_at_sqrt_2r_over_g() {
    let cavity = Cavity::new(1.0, G, R, 0.5);
    let run = cavity
        .simulate(Vector3::zeros(), Vector3::zeros(), 0.0..0.5)
        .unwrap();
    let first = run.impacts[0];
    let exact = (2.0 * R / G).sqrt();
    assert!((first.t - exact).abs() < 1e-10, "{} vs {exact}", first.t);
    assert!(
        (first.q - Vector3::new(0.0, 0.0, -R)).norm() < 1e-12,
        "{}",
        first.q
    );
    assert!((first.v_before[2] + G * exact).abs() < 1e-10);
    assert!((first.v_after[2] - 0.5 * G * exact).abs() < 1e-10);
}

/// e = 1: every impact keeps the energy; over many impacts it stays constant to
/// 1e-9 relative, and the point never leaves the cavity.
#[test]
fn elastic_impacts_conserve_energy() {
    let cavity = Cavity::new(1.3, G, R, 1.0);
    let (q0, v0) = (Vector3::new(0.2, -0.1, 0.3), Vector3::new(1.1, 0.7, -0.4));
    let run = cavity.simulate(q0, v0, 0.0..10.0).unwrap();
    assert!(run.impacts.len() > 20, "{} impacts", run.impacts.len());
    assert!(run.slides.is_empty());
    let e0 = energy(&cavity, &q0, &v0);
    let worst = run
        .points()
        .map(|(_, q, v)| (energy(&cavity, q, v) - e0).abs() / e0.abs())
        .fold(0.0, f64::max);
    eprintln!(
        "e = 1: {} impacts, energy error {worst:.1e}",
        run.impacts.len()
    );
    assert!(worst < 1e-9, "{worst:e}");
    for i in &run.impacts {
        let (before, after) = i.normal_speeds();
        assert!(before > 0.0 && (after + before).abs() < 1e-9 * before.abs().max(1.0));
    }
    let out = outside(&run);
    assert!(out < OUTSIDE, "outside by {out:e}");
}

/// e < 1: the normal velocity after each impact is −e times the one before, the
/// tangential velocity is unchanged; the bounces die out and the point slides
/// on the wall, pushed (λ < 0) by it, with constant energy, never outside.
#[test]
fn inelastic_impacts_then_sliding() {
    let e = 0.6;
    let cavity = Cavity::new(0.8, G, R, e);
    let (q0, v0) = (Vector3::new(0.1, 0.2, 0.0), Vector3::new(0.9, -0.3, 0.5));
    let run = cavity.simulate(q0, v0, 0.0..6.0).unwrap();
    assert!(run.impacts.len() > 10, "{} impacts", run.impacts.len());
    for (k, i) in run.impacts.iter().enumerate() {
        let (before, after) = i.normal_speeds();
        assert!(before > 0.0, "impact {k}: moving outwards before");
        assert!(
            (after + e * before).abs() < 1e-9,
            "impact {k}: {after} vs {}",
            -e * before
        );
        let (tb, ta) = i.tangential();
        assert!(
            (tb - ta).norm() < 1e-9,
            "impact {k}: tangential {tb} -> {ta}"
        );
    }
    // Sliding started after the last impact and lasts to the end.
    assert_eq!(run.slides.len(), 1, "{:?}", run.slides);
    assert!(run.slides[0] >= run.impacts.last().unwrap().t);
    let Some(Phase::Sliding(slide)) = run.phases.last() else {
        panic!("the run should end sliding")
    };
    let e_slide = energy(&cavity, &slide.positions()[0], &slide.velocities()[0]);
    for ((&t, q), v) in slide
        .times()
        .iter()
        .zip(slide.positions())
        .zip(slide.velocities())
    {
        assert!(
            (q.norm() - R).abs() < 1e-13,
            "t = {t}: |x| − R = {:e}",
            q.norm() - R
        );
        assert!(
            q.dot(v).abs() < 1e-10,
            "t = {t}: normal velocity {}",
            q.dot(v) / R
        );
        assert!(
            cavity.multiplier(t, q, v).unwrap() < 0.0,
            "t = {t}: wall pulls"
        );
        let de = (energy(&cavity, q, v) - e_slide).abs() / e_slide.abs();
        assert!(de < 1e-9, "t = {t}: energy {de:e}");
    }
    let out = outside(&run);
    eprintln!(
        "e = {e}: {} impacts, slides from t = {}, outside by {out:.1e}",
        run.impacts.len(),
        run.slides[0]
    );
    assert!(out < OUTSIDE, "outside by {out:e}");
}

/// Started at the bottom on the wall with speed u along it in a vertical plane,
/// the point slides; the wall's push vanishes where m(|v|² − g z)/R = 0, which
/// with energy conservation gives z* = (u² − 2gR)/(3g): here u² = 3.5 gR, so
/// z* = R/2. There it is released and flies freely inside the cavity.
#[test]
fn sliding_point_is_released_where_the_reaction_vanishes() {
    let cavity = Cavity::new(1.0, G, R, 0.5);
    let u = (3.5 * G * R).sqrt();
    let run = cavity
        .simulate(
            Vector3::new(0.0, 0.0, -R),
            Vector3::new(u, 0.0, 0.0),
            0.0..2.0,
        )
        .unwrap();
    assert_eq!(run.slides[0], 0.0, "starts sliding");
    let t_release = run.releases[0];
    let Phase::Sliding(slide) = &run.phases[0] else {
        panic!("first phase should be sliding")
    };
    let (q, v) = slide.final_state();
    assert_eq!(*slide.times().last().unwrap(), t_release);
    assert!(
        (q[2] - R / 2.0).abs() < 1e-9,
        "released at z = {}, expected {}",
        q[2],
        R / 2.0
    );
    assert!(cavity.multiplier(t_release, &q, &v).unwrap().abs() < 1e-9);
    // Then free flight, inside, until the next impact.
    assert!(matches!(run.phases[1], Phase::Free(_)));
    assert!(run.impacts[0].t > t_release);
    let out = outside(&run);
    eprintln!(
        "release at z = R/2 + {:.1e}, outside by {out:.1e}",
        q[2] - R / 2.0
    );
    assert!(out < OUTSIDE, "outside by {out:e}");
}

#[test]
fn start_outside_is_a_typed_error() {
    let cavity = Cavity::new(1.0, G, R, 0.5);
    let err = cavity
        .simulate(
            Vector3::new(0.0, 0.0, -1.01 * R),
            Vector3::zeros(),
            0.0..1.0,
        )
        .unwrap_err();
    assert!(
        matches!(&err, Error::Settings(s) if s.to_string().contains("outside")),
        "{err}"
    );
}
