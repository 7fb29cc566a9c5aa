//! A gallery row that fits the model to the machine: the UR5 from its URDF
//! carries a payload it was not told about, moves along an exciting
//! trajectory (`identify::exciting_trajectory`), and its torques, measured
//! with noise, give back its base parameters (`identify`) and, with the
//! arm's own parameters known, the payload's mass and centre
//! (`identify_subset`), estimated again as each sample comes in.

use crate::figure::Extra;
use crate::operational::Ur5;
use crate::row::{Row, TOL, row};
use lagrange::identify::{
    BaseParameters, Excitation, JointLimits, Sample, add_to_body, body_from_parameters,
    body_parameters, exciting_trajectory, identify, identify_subset,
};
use lagrange::nalgebra::{DVector, Matrix3, SVector, Vector3};
use lagrange::prelude::*;

/// The payload the arm does not know of: 1.3 kg, a 10 cm cube centred off
/// the flange.
const MASS: f64 = 1.3;
const CENTRE: [f64; 3] = [0.02, 0.15, -0.01];
/// The torque sensors' noise, N·m (one standard deviation).
const NOISE: f64 = 0.05;
/// Samples over the trajectory's one period.
const SAMPLES: usize = 240;

pub(crate) fn ur5_payload(system: &'static str) -> Result<Row, Error> {
    let ur5 = Ur5 {};
    let base = BaseParameters::of(&ur5)?;
    let limits = JointLimits::new(
        SVector::repeat(-2.0),
        SVector::repeat(2.0),
        SVector::repeat(1.2),
        SVector::repeat(3.0),
    )?;
    let settings = Excitation {
        harmonics: 2,
        period: 8.0,
        samples: 24,
        iterations: 300,
        restarts: 1,
        ..Excitation::default()
    };
    let excited = exciting_trajectory(&ur5, &base, &limits, &settings)?;
    let known = ur5
        .inertial_parameters()
        .ok_or_else(|| crate::gallery_error("no π"))?;
    let actual = with_payload(&known)?;
    let mut samples = excited.trajectory.samples(&ur5, &actual, SAMPLES)?;
    add_noise(&mut samples);
    let noise = SVector::repeat(NOISE);
    let fit = identify(&ur5, &base, &samples, &noise)?;
    let truth = base.of_parameters(&actual)?;
    let worst_sigma = ((&fit.values - &truth).component_div(&fit.standard_deviations())).amax();
    let running = running_payload(&ur5, &samples, &known, excited.trajectory.period())?;
    let (m, sigma, c) = running
        .last()
        .map_or((f64::NAN, f64::NAN, [f64::NAN; 3]), |r| {
            (r.mass, r.sigma, r.centre)
        });
    let centre_miss = (Vector3::from(c) - Vector3::from(CENTRE)).amax();
    let note = format!(
        "cond(W_b) {:.0} (from {:.0}); {} base parameters, worst error {worst_sigma:.1}σ; \
         payload {m:.4} ± {sigma:.4} kg (truth {MASS}), centre within {centre_miss:.1e} m",
        excited.condition,
        excited.start_condition,
        base.len(),
    );
    let period = excited.trajectory.period();
    let trajectory = excited.trajectory.clone();
    let mut flown = row(
        system,
        &ur5,
        0.0..period,
        false,
        || {
            // The arm flown along the trajectory by computed torque through
            // its own inverse dynamics (the payload's share is what the
            // samples measure).
            Simulation::new(&ur5)
                .integrator(Dopri5::tol(TOL))
                .sampled(0.005, |t, q, v| {
                    let (qd, vd, ad) = trajectory.state(t);
                    let a = ad + (qd - q) * 400.0 + (vd - v) * 40.0;
                    ur5.inverse_dynamics(q, v, &a, 0.0)
                })
                .run(
                    trajectory.position(0.0),
                    trajectory.velocity(0.0),
                    0.0..period,
                )
                .map(|run| run.into_trajectory())
        },
        |_| note,
    )?;
    if let Some(figure) = &mut flown.figure {
        figure.extra = panels(&running);
    }
    Ok(flown)
}

/// The arm's π with the payload added to its last link's ten parameters.
fn with_payload(known: &DVector<f64>) -> Result<DVector<f64>, Error> {
    // A solid cube of side 0.1 m: I = m s²/6 about its centre.
    let cube = Matrix3::identity() * (MASS * 0.01 / 6.0);
    let payload = body_parameters(MASS, Vector3::from(CENTRE), cube)?;
    let mut actual = known.clone();
    add_to_body(
        &mut actual,
        Ur5::REGRESSOR_PARAMETERS,
        "wrist_3_link",
        &payload,
    )?;
    Ok(actual)
}

/// Gaussian noise of `NOISE` on every torque, from a fixed seed (SplitMix64
/// and Box–Muller), so the row is the same on every run.
fn add_noise(samples: &mut [Sample<6>]) {
    let mut seed = 0x5eed_u64;
    let mut uniform = move || {
        seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    for s in samples {
        for tau in s.tau.iter_mut() {
            let (u, w) = (uniform(), uniform());
            *tau += NOISE * (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * w).cos();
        }
    }
}

/// The payload as estimated from the samples up to `t`.
struct Payload {
    t: f64,
    mass: f64,
    sigma: f64,
    centre: [f64; 3],
}

/// The payload estimated every tenth sample, the arm's own parameters
/// known; times whose samples cannot yet separate the payload's ten
/// parameters are skipped.
type Running = Vec<Payload>;

fn running_payload(
    ur5: &Ur5,
    samples: &[Sample<6>],
    known: &DVector<f64>,
    period: f64,
) -> Result<Running, Error> {
    let noise = SVector::repeat(NOISE);
    let mut out = Vec::new();
    for k in (10..=samples.len()).step_by(10) {
        let Ok(fit) = identify_subset(ur5, &samples[..k], &noise, &["wrist_3_link"], known) else {
            continue;
        };
        let change = fit.change_from(known)?;
        let block: [f64; 10] = std::array::from_fn(|j| change[j]);
        let Some((mass, centre, _)) = body_from_parameters(&block) else {
            continue;
        };
        let sigma = fit.standard_deviations()[0];
        out.push(Payload {
            t: period * k as f64 / samples.len() as f64,
            mass,
            sigma,
            centre: centre.into(),
        });
    }
    Ok(out)
}

/// The estimates against the truth, as the figure's panels below the
/// motion.
fn panels(running: &Running) -> Vec<Extra> {
    let t: Vec<f64> = running.iter().map(|r| r.t).collect();
    let series = |f: &dyn Fn(&Payload) -> f64| running.iter().map(f).collect();
    let count = t.len();
    let flat = |x: f64| vec![x; count];
    vec![
        Extra {
            y_label: "payload mass (kg)",
            t: t.clone(),
            series: vec![
                ("estimate".into(), series(&|r| r.mass)),
                ("estimate + 3σ".into(), series(&|r| r.mass + 3.0 * r.sigma)),
                ("estimate − 3σ".into(), series(&|r| r.mass - 3.0 * r.sigma)),
                ("truth".into(), flat(MASS)),
            ],
        },
        Extra {
            y_label: "centre estimate − truth (mm)",
            t,
            series: vec![
                ("x".into(), series(&|r| 1e3 * (r.centre[0] - CENTRE[0]))),
                ("y".into(), series(&|r| 1e3 * (r.centre[1] - CENTRE[1]))),
                ("z".into(), series(&|r| 1e3 * (r.centre[2] - CENTRE[2]))),
                ("zero".into(), flat(0.0)),
            ],
        },
    ]
}
