//! A payload on a known robot: the UR5 with 1.3 kg held off its flange,
//! only the last link's ten parameters estimated with the rest of π known.
//! Noise-free, the payload's mass and centre of mass to 1e-9; with noise,
//! within three standard deviations of the reported covariance; the typed
//! errors of names that are not π's and of parameters the data cannot
//! separate.

use lagrange::identify::{Sample, identify_subset};
use lagrange::{IdentifyError, Lagrangian};
use nalgebra::{DVector, Matrix3, SVector, Vector3};

use crate::regressor::{Lcg, Ur5, state};

const MASS: f64 = 1.3;

/// The payload's centre in wrist_3_link's axes: beyond the flange (at y =
/// 0.0823) and off its axis.
fn centre() -> Vector3<f64> {
    Vector3::new(0.03, 0.15, -0.02)
}

/// The UR5's π with the payload (a small box about its centre) added to
/// wrist_3_link's block, carried to the link's frame by the parallel-axis
/// rule.
fn with_payload() -> (DVector<f64>, usize) {
    let mut pi = Ur5 {}.inertial_parameters().expect("π");
    let first = (Ur5::REGRESSOR_PARAMETERS.iter())
        .position(|n| *n == "wrist_3_link.m")
        .expect("the last link");
    let c = centre();
    let own = Matrix3::from_diagonal(&Vector3::new(0.002, 0.003, 0.0025));
    let i = own + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * MASS;
    let added = [
        MASS,
        MASS * c.x,
        MASS * c.y,
        MASS * c.z,
        i[(0, 0)],
        i[(0, 1)],
        i[(1, 1)],
        i[(0, 2)],
        i[(1, 2)],
        i[(2, 2)],
    ];
    for (k, x) in added.iter().enumerate() {
        pi[first + k] += x;
    }
    (pi, first)
}

fn samples(pi: &DVector<f64>, count: usize, noise: f64, rng: &mut Lcg) -> Vec<Sample<6>> {
    let ur5 = Ur5 {};
    (0..count)
        .map(|_| {
            let (q, v, a) = state::<Ur5, 6, 6>(rng);
            let y = ur5.regressor(&q, &v, &a, 0.0).expect("Y");
            let tau = SVector::from_iterator((y * pi).iter().copied())
                + SVector::<f64, 6>::from_fn(|_, _| noise * rng.normal());
            Sample { q, v, a, tau }
        })
        .collect()
}

#[test]
fn noise_free_payload_mass_and_centre_to_1e_9() {
    let ur5 = Ur5 {};
    let known = ur5.inertial_parameters().expect("π");
    let (truth, _) = with_payload();
    let data = samples(&truth, 40, 0.0, &mut Lcg(8));
    let fit = identify_subset(
        &ur5,
        &data,
        &SVector::repeat(0.05),
        &["wrist_3_link"],
        &known,
    )
    .expect("identifies");
    assert_eq!(fit.names.len(), 10);
    assert_eq!(fit.names[0], "wrist_3_link.m");
    let payload = fit.change_from(&known).expect("lengths");
    let centre_found = Vector3::new(payload[1], payload[2], payload[3]) / payload[0];
    eprintln!(
        "UR5 payload, noise-free: mass error {:.1e}, centre error {:.1e}",
        (payload[0] - MASS).abs(),
        (centre_found - centre()).amax()
    );
    assert!((payload[0] - MASS).abs() < 1e-9);
    assert!((centre_found - centre()).amax() < 1e-9);
    assert_eq!(
        fit.value("wrist_3_link.m"),
        Some(known[fit.indices[0]] + payload[0])
    );
}

#[test]
fn noisy_payload_within_three_standard_deviations() {
    let ur5 = Ur5 {};
    let known = ur5.inertial_parameters().expect("π");
    let (truth, first) = with_payload();
    let sigma = 0.05;
    let data = samples(&truth, 100, sigma, &mut Lcg(13));
    let fit = identify_subset(
        &ur5,
        &data,
        &SVector::repeat(sigma),
        &["wrist_3_link"],
        &known,
    )
    .expect("identifies");
    let sd = fit.standard_deviations();
    for k in 0..10 {
        let err = fit.values[k] - truth[first + k];
        assert!(
            err.abs() < 3.0 * sd[k],
            "{}: {err:e} vs σ {:e}",
            fit.names[k],
            sd[k]
        );
    }
    // The centre h/m, its covariance by the first-order rule.
    let payload = fit.change_from(&known).expect("lengths");
    let (m, h) = (payload[0], Vector3::new(payload[1], payload[2], payload[3]));
    let c = h / m;
    let cov = fit.covariance.view((0, 0), (4, 4));
    for i in 0..3 {
        let mut grad = nalgebra::Vector4::zeros();
        grad[0] = -h[i] / (m * m);
        grad[i + 1] = 1.0 / m;
        let sd_c = (grad.transpose() * cov * grad)[(0, 0)].sqrt();
        let err = c[i] - centre()[i];
        eprintln!("UR5 payload, σ = 0.05 N·m: centre[{i}] error {err:.1e}, σ {sd_c:.1e}");
        assert!(err.abs() < 3.0 * sd_c, "centre[{i}]: {err:e} vs σ {sd_c:e}");
    }
    assert!((fit.residual - 1.0).abs() < 0.2, "{}", fit.residual);
}

#[test]
fn names_not_in_pi_and_inseparable_parameters_are_typed_errors() {
    let ur5 = Ur5 {};
    let known = ur5.inertial_parameters().expect("π");
    let data = samples(&known, 20, 0.0, &mut Lcg(2));
    let sigma = SVector::repeat(0.05);
    match identify_subset(&ur5, &data, &sigma, &["wrist_4_link"], &known) {
        Err(IdentifyError::UnknownParameter { name }) => assert_eq!(name, "wrist_4_link"),
        other => panic!("{other:?}"),
    }
    // A frame fixed to the last link moves with it: its mass cannot be told
    // from the link's own parameters.
    match identify_subset(&ur5, &data, &sigma, &["wrist_3_link", "ee_link.m"], &known) {
        Err(IdentifyError::Inseparable { parameters }) => assert_eq!(parameters, ["ee_link.m"]),
        other => panic!("{other:?}"),
    }
    // Held still, the link's inertia shows nowhere.
    let mut still = data.clone();
    for s in &mut still {
        s.v = SVector::zeros();
        s.a = SVector::zeros();
    }
    match identify_subset(&ur5, &still, &sigma, &["wrist_3_link"], &known) {
        Err(IdentifyError::Inseparable { parameters }) => {
            assert!(
                parameters.contains(&"wrist_3_link.Izz".to_string()),
                "{parameters:?}"
            );
            let message = IdentifyError::Inseparable { parameters }.to_string();
            assert!(message.contains("cannot separate"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    let mut bad = known.clone();
    bad[0] = f64::NAN;
    assert!(matches!(
        identify_subset(&ur5, &data, &sigma, &["wrist_3_link"], &bad),
        Err(IdentifyError::NotFiniteValue { index: 0, .. })
    ));
}
