use super::report::{CSV_COLUMNS, MARKDOWN_COLUMNS};
use super::*;
use crate::error::SettingsError;
use crate::ode::test_problems::Oscillator;
use crate::ode::{Dopri5, Integrator, Rk4};
use nalgebra::Vector1;

const T_END: f64 = 10.0;

/// The oscillator q̈ = −q from (1, 0) over [0, 10], run by the given method.
fn oscillator<'a>() -> WorkPrecision<'a, f64, 1> {
    WorkPrecision::new(|m: Method| {
        m.integrate(
            &Oscillator { omega: 1.0 },
            0.0,
            T_END,
            Vector1::new(1.0),
            Vector1::new(0.0),
        )
    })
    .repeats(1, Duration::ZERO)
}

fn errors(study: &Study, method: &str) -> Vec<f64> {
    study
        .rows()
        .iter()
        .filter(|r| r.method == method)
        .map(|r| r.measurement().expect("run succeeded").error)
        .collect()
}

#[test]
fn errors_fall_with_tolerance_and_step() {
    let study = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .sweep(Sweep::tolerances(
            "DOPRI5",
            &[1e-4, 1e-6, 1e-8, 1e-10],
            Dopri5::tol,
        ))
        .sweep(Sweep::steps("RK4", &[0.2, 0.1, 0.05], Rk4::step))
        .run()
        .unwrap();
    assert_eq!(study.reference(), &ReferenceKind::Exact);
    let dopri = errors(&study, "DOPRI5");
    assert_eq!(dopri.len(), 4);
    for w in dopri.windows(2) {
        assert!(w[1] < w[0] / 10.0, "DOPRI5 errors {dopri:?}");
    }
    // Fourth order: halving h divides the global error by about 16.
    let rk4 = errors(&study, "RK4");
    for w in rk4.windows(2) {
        let ratio = w[0] / w[1];
        assert!((12.0..20.0).contains(&ratio), "RK4 errors {rk4:?}");
    }
    // The oscillator's energy is conserved: the drift is measured and small for
    // the tightest tolerance, and cost grows as the tolerance tightens.
    let rows: Vec<&Measurement> = study.rows().iter().filter_map(Row::measurement).collect();
    assert!(rows[3].drift.unwrap() < 1e-8, "{:?}", rows[3].drift);
    assert!(rows[3].stats.evaluations > rows[0].stats.evaluations);
    assert!(rows.iter().all(|m| m.wall_time > Duration::ZERO));
}

#[test]
fn computed_reference_agrees_with_the_closed_form() {
    let study = oscillator()
        .sweep(Sweep::tolerances("DOPRI5", &[1e-5, 1e-9], Dopri5::tol))
        .run()
        .unwrap();
    let ReferenceKind::Computed {
        tolerance,
        evaluations,
        uncertainty: Some(u),
        ..
    } = *study.reference()
    else {
        panic!(
            "expected a checked DOP853 reference, got {:?}",
            study.reference()
        );
    };
    assert_eq!(tolerance, REFERENCE_TOLERANCE);
    assert!(evaluations > 0 && u < 1e-11, "uncertainty {u:e}");
    let exact = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .sweep(Sweep::tolerances("DOPRI5", &[1e-5, 1e-9], Dopri5::tol))
        .run()
        .unwrap();
    for (a, b) in errors(&study, "DOPRI5")
        .iter()
        .zip(errors(&exact, "DOPRI5"))
    {
        assert!((a - b).abs() < 1e-11, "{a:e} vs {b:e}");
    }
}

#[test]
fn failures_are_rows_not_panics() {
    let mut seen = Vec::new();
    let study = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .sweep(
            Sweep::new("RK4")
                .with(Setting::Step(1e-3), Rk4::step(1e-3).max_steps(10))
                .with(Setting::Step(0.1), Rk4::step(0.1)),
        )
        .on_row(|r| seen.push((r.setting, r.outcome.is_ok())))
        .run()
        .unwrap();
    assert_eq!(
        seen,
        [(Setting::Step(1e-3), false), (Setting::Step(0.1), true)]
    );
    let rows = study.rows();
    assert!(matches!(
        rows[0].outcome,
        Err(Error::TooManySteps { max_steps: 10, .. })
    ));
    assert!(rows[1].outcome.is_ok());
    assert!(
        study
            .cheapest(1e-3)
            .is_some_and(|r| r.setting == Setting::Step(0.1))
    );
    assert!(study.cheapest(1e-12).is_none());

    let md = study.to_markdown();
    assert!(
        md.contains(
            "| RK4 | h = 1e-3 | – | – | – | – | – | – | – | – | failed: the run needs 10000 steps but the step budget is 10"
        ),
        "{md}"
    );
    let mut csv = Vec::new();
    study.write_csv_to(&mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let failed = csv.lines().nth(1).unwrap();
    assert!(
        failed.starts_with("RK4,step,0.001,,,,,,,,,,,,,,"),
        "{failed}"
    );
    assert!(failed.contains("needs 10000 steps"), "{failed}");
}

#[test]
fn markdown_and_csv_have_the_expected_columns() {
    let study = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .conservative(false)
        .sweep(Sweep::tolerances("DOPRI5", &[1e-6], Dopri5::tol))
        .sweep(Sweep::steps("RK4", &[0.1, 0.05], Rk4::step))
        .run()
        .unwrap();
    let md = study.to_markdown();
    let mut lines = md.lines();
    assert_eq!(lines.next(), Some("Reference: closed-form solution."));
    assert_eq!(lines.next(), Some(""));
    assert_eq!(
        lines.next(),
        Some(
            "| method | setting | error in q at t_end | relative | error in q̇ | max integral drift | max residual | RHS evaluations | steps | wall time | note |"
        )
    );
    assert_eq!(
        lines.next(),
        Some("|---|---|---|---|---|---|---|---|---|---|---|")
    );
    let body: Vec<&str> = lines.collect();
    assert_eq!(body.len(), 3);
    for line in &body {
        // One cell per column; no velocity error against a closed form of the
        // positions, no drift for a non-conservative study.
        assert_eq!(
            line.matches('|').count(),
            MARKDOWN_COLUMNS.len() + 1,
            "{line}"
        );
        assert_eq!(line.split(" | ").nth(4), Some("–"), "{line}");
        assert_eq!(line.split(" | ").nth(5), Some("–"), "{line}");
    }
    // RK4 with h = 0.1 over [0, 10]: 100 steps, 4 evaluations each plus one.
    assert!(body[1].starts_with("| RK4 | h = 1e-1 | "), "{}", body[1]);
    assert!(body[1].contains(" | 401 | 100 | "), "{}", body[1]);

    let mut csv = Vec::new();
    study.write_csv_to(&mut csv).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some(CSV_COLUMNS.join(",").as_str()));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 3);
    for row in &rows {
        assert_eq!(row.len(), CSV_COLUMNS.len(), "{row:?}");
    }
    let rk4 = &rows[1];
    assert_eq!(&rk4[..3], ["RK4", "step", "0.1"]);
    let error: f64 = rk4[3].parse().unwrap();
    let m = study.rows()[1].measurement().unwrap();
    assert_eq!(error, m.error);
    // Relative to the motion's size |cos 10|; no velocity reference; resolved
    // against an exact reference; no drift; 401 evaluations, 100 steps.
    let relative: f64 = rk4[4].parse().unwrap();
    assert!((relative - m.error / 10f64.cos().abs()).abs() < 1e-15 * relative.abs().max(1e-300));
    assert_eq!((rk4[5], rk4[7], rk4[8]), ("", "true", ""));
    assert_eq!((rk4[9], rk4[10], rk4[16]), ("401", "100", ""));
    assert_eq!(m.final_state.0.len(), 1);
}

#[test]
fn reference_problems_are_errors_of_the_study() {
    let e = oscillator().repeats(0, Duration::ZERO).run().unwrap_err();
    assert!(
        matches!(
            e,
            Error::Settings(SettingsError::ZeroCount {
                setting: "repeats",
                ..
            })
        ),
        "{e}"
    );
    let e = oscillator()
        .computed_reference(-1.0, false)
        .run()
        .unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Value { value, .. }) if value == -1.0),
        "{e}"
    );
    // Below what f64 can attain: refused, naming the setting and the floor.
    let e = oscillator()
        .computed_reference(1e-20, false)
        .run()
        .unwrap_err();
    assert!(
        matches!(e, Error::Settings(SettingsError::Value { setting: "reference tolerance", value, .. }) if value == 1e-20)
            && e.to_string().contains("2.220446049250313e-16"),
        "{e}"
    );
    // At the floor it runs.
    assert!(
        oscillator()
            .computed_reference(f64::EPSILON, false)
            .run()
            .is_ok()
    );
    // A reference run that fails leaves the study without a yardstick.
    let boom = || SettingsError::ZeroCount {
        owner: "boom",
        setting: "boom",
    };
    let failing = WorkPrecision::<f64, 1>::new(|_| Err(Error::from(boom())));
    assert!(matches!(failing.run(), Err(Error::Settings(s)) if s == boom()));
    // A given reference that ends before the runs: the rows say so.
    let short = Dopri5::tol(1e-10)
        .integrate(
            &Oscillator { omega: 1.0 },
            0.0,
            T_END / 2.0,
            Vector1::new(1.0),
            Vector1::new(0.0),
        )
        .unwrap();
    let study = oscillator()
        .reference(short)
        .sweep(Sweep::tolerances("DOPRI5", &[1e-6], Dopri5::tol))
        .run()
        .unwrap();
    assert!(matches!(
        &study.rows()[0].outcome,
        Err(Error::Settings(SettingsError::Data { problem, .. })) if problem.contains("outside the reference")
    ));
}

#[test]
fn cheapest_per_method_and_merge() {
    let a = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .sweep(Sweep::tolerances(
            "DOPRI5",
            &[1e-4, 1e-8, 1e-10],
            Dopri5::tol,
        ))
        .run()
        .unwrap();
    let b = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .sweep(Sweep::steps("RK4", &[0.5, 0.01], Rk4::step))
        .run()
        .unwrap();
    let both = a.merge(b);
    assert_eq!(both.rows().len(), 5);
    let best = both.cheapest_per_method(1e-6);
    let mut names: Vec<&str> = best.iter().map(|r| r.method.as_str()).collect();
    names.sort();
    assert_eq!(names, ["DOPRI5", "RK4"]);
    for r in best {
        assert!(r.measurement().unwrap().error <= 1e-6);
    }
}

#[test]
fn durations_have_three_digits() {
    use super::report::duration;
    assert_eq!(duration(Duration::from_nanos(12_345)), "12.3 µs");
    assert_eq!(duration(Duration::from_micros(1_234)), "1.23 ms");
    assert_eq!(duration(Duration::from_millis(456)), "456 ms");
    assert_eq!(duration(Duration::from_millis(2_500)), "2.50 s");
}

#[cfg(feature = "plot")]
#[test]
fn plot_writes_a_png() {
    let study = oscillator()
        .exact(|t| Vector1::new(t.cos()))
        .sweep(Sweep::tolerances("DOPRI5", &[1e-4, 1e-8], Dopri5::tol))
        .sweep(
            Sweep::new("RK4")
                .with(Setting::Step(0.1), Rk4::step(0.1))
                .with(Setting::Step(1e-3), Rk4::step(1e-3).max_steps(10)),
        )
        .run()
        .unwrap();
    let path = std::env::temp_dir().join(format!("lagrange-study-{}.png", std::process::id()));
    study
        .plot_png(&path, "oscillator: work vs precision")
        .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: the image is 1500 × 500.
    assert_eq!(&bytes[16..24], &[0, 0, 5, 220, 0, 0, 1, 244]);
    // A directory that does not exist is an I/O error, not a panic.
    let e = study
        .plot_png(std::env::temp_dir().join("no-such-dir/x.png"), "t")
        .unwrap_err();
    assert!(matches!(e, Error::Io(_)), "{e}");
}

#[cfg(feature = "plot")]
#[test]
fn a_setting_is_labelled_as_the_value_run() {
    use super::plot::setting_label;
    assert_eq!(setting_label(2.5e-4), "2.5e-4");
    assert_eq!(setting_label(1e-2), "1e-2");
    assert_eq!(setting_label(0.125), "1.25e-1");
    // Every label reads back as the value run, up to four digits.
    for x in [2.5e-4, 3e-4, 1.5e-3, 0.02, 7.25e-9] {
        assert_eq!(setting_label(x).parse::<f64>(), Ok(x), "{x}");
    }
    // More digits than that are rounded, not printed in full.
    assert_eq!(setting_label(0.1 / 3.0), "3.333e-2");
}

#[cfg(feature = "plot")]
#[test]
fn log_ticks_are_labelled_at_decades_only_and_as_many_as_fit() {
    use super::plot::{decade_label, labels_that_fit};
    assert_eq!(decade_label(1e-3), "1e-3");
    assert_eq!(decade_label(1e5), "1e5");
    assert_eq!(decade_label(1.0), "1e0");
    // A decade computed by repeated multiplication is still a decade.
    assert_eq!(decade_label(0.1 * 0.1 * 0.1), "1e-3");
    // The ticks plotters puts between decades get no label.
    assert_eq!(decade_label(2e-3), "");
    assert_eq!(decade_label(5e-3), "");
    assert_eq!(decade_label(0.0), "");
    assert_eq!(decade_label(f64::NAN), "");
    assert_eq!(labels_that_fit(500, 44), 11);
    assert_eq!(labels_that_fit(30, 44), 2);
}

#[test]
fn a_given_reference_with_its_uncertainty_marks_unresolved_runs() {
    let reference = Dop853::tol(1e-13)
        .integrate(
            &Oscillator { omega: 1.0 },
            0.0,
            T_END,
            Vector1::new(1.0),
            Vector1::new(0.0),
        )
        .unwrap();
    let study = oscillator()
        .reference(reference)
        .uncertainty(1e-7)
        .sweep(Sweep::tolerances("DOPRI5", &[1e-3, 1e-12], Dopri5::tol))
        .run()
        .unwrap();
    assert_eq!(study.uncertainty(), Some(1e-7));
    let (loose, tight) = (
        study.rows()[0].measurement().unwrap(),
        study.rows()[1].measurement().unwrap(),
    );
    assert!(loose.resolved && loose.error > 1e-7, "{loose:?}");
    assert!(!tight.resolved && tight.error < 1e-7, "{tight:?}");
    // A trajectory reference has velocities: the velocity error is measured,
    // and agrees with the exact −sin at the end to the reference's accuracy.
    let ve = loose.velocity_error.unwrap();
    let exact_ve = (loose.final_state.1[0] + T_END.sin()).abs();
    assert!((ve - exact_ve).abs() < 1e-9, "{ve} vs {exact_ve}");
    let md = study.to_markdown();
    assert!(md.contains("uncertainty 1.00e-7"), "{md}");
    assert!(md.contains("below the reference's accuracy"), "{md}");
}

#[test]
fn a_bad_uncertainty_is_refused() {
    for u in [-1.0, f64::NAN, f64::INFINITY] {
        let e = oscillator()
            .exact(|t| Vector1::new(t.cos()))
            .uncertainty(u)
            .run()
            .unwrap_err();
        assert!(
            matches!(e, Error::Settings(SettingsError::Value { setting, .. }) if setting.contains("uncertainty")),
            "{e}"
        );
    }
}
