//! Physically consistent estimates: from noise-free data of a consistent π
//! the base parameters to 1e-8 with every body's pseudo-inertia positive
//! definite; from noisy data on which plain least squares gives a π_b that
//! no real arm has, a consistent π whose residual is close to the plain
//! one's; the typed errors.

use lagrange::identify::{
    BaseParameters, Consistency, Sample, identify, identify_consistent, inconsistent_bodies,
    is_physically_consistent,
};
use lagrange::{IdentifyError, Lagrangian};
use nalgebra::{DVector, SVector, Vector2};

use crate::identify_excite::{PLANAR, Planar};
use crate::regressor::{Lcg, Ur5, state};

/// Samples at random states with τ = Y π_true + noise.
fn samples<S: Lagrangian<f64, N>, const N: usize>(
    sys: &S,
    pi: &DVector<f64>,
    count: usize,
    noise: f64,
    rng: &mut Lcg,
) -> Vec<Sample<N>> {
    (0..count)
        .map(|_| {
            let (q, v, a) = state::<S, N, N>(rng);
            let y = sys.regressor(&q, &v, &a, 0.0).expect("Y");
            let tau = SVector::from_iterator((y * pi).iter().copied())
                + SVector::<f64, N>::from_fn(|_, _| noise * rng.normal());
            Sample { q, v, a, tau }
        })
        .collect()
}

/// The UR5's own π with each body's block scaled by its own factor (a
/// heavier or lighter copy of the same body: still physically consistent).
fn scaled_ur5() -> DVector<f64> {
    let mut pi = Ur5 {}.inertial_parameters().expect("π");
    for (b, block) in pi.as_mut_slice().chunks_mut(10).enumerate() {
        let factor = 1.0 + 0.15 * ((b % 4) as f64) - 0.1;
        block.iter_mut().for_each(|x| *x *= factor);
    }
    pi
}

#[test]
fn noise_free_data_give_the_base_parameters_and_a_real_arm() {
    let ur5 = Ur5 {};
    let base = BaseParameters::of(&ur5).expect("a regressor");
    let truth = scaled_ur5();
    assert!(
        inconsistent_bodies(Ur5::REGRESSOR_PARAMETERS, &truth)
            .expect("π")
            .is_empty()
    );
    let data = samples(&ur5, &truth, 60, 0.0, &mut Lcg(21));
    let prior = ur5.inertial_parameters().expect("π");
    let sigma = SVector::repeat(0.1);
    let want = base.of_parameters(&truth).expect("π's length");
    // The default pull toward the prior biases π_b by about 1e-5; a
    // smaller one by less.
    let fit = identify_consistent(&ur5, &base, &data, &sigma, &prior, &Consistency::default())
        .expect("converges");
    let err = (&fit.base - &want).amax() / want.amax();
    eprintln!("UR5, consistent, default regularisation: π_b error {err:.1e}");
    assert!(err < 1e-4, "{err:e}");
    let weak = Consistency {
        regularisation: 1e-10,
        ..Consistency::default()
    };
    let fit = identify_consistent(&ur5, &base, &data, &sigma, &prior, &weak).expect("converges");
    let err = (&fit.base - &want).amax() / want.amax();
    eprintln!(
        "UR5, consistent: π_b error {err:.1e} after {} iterations, residual {:.1e}",
        fit.iterations, fit.residual
    );
    assert!(err < 1e-8, "{err:e}");
    assert!(
        inconsistent_bodies(Ur5::REGRESSOR_PARAMETERS, &fit.parameters)
            .expect("π")
            .is_empty()
    );
    for block in fit.parameters.as_slice().chunks(10) {
        let block: [f64; 10] = block.try_into().expect("ten");
        assert!(block.iter().all(|&x| x == 0.0) || is_physically_consistent(&block));
    }
}

/// A forearm of 50 g whose inertia about its joint is 1.5e-4 kg m²,
/// measured at six states with 0.05 N·m of noise: the plain estimate of
/// link2.Izz (its inertia about the elbow) comes out negative for some
/// draws, which no body has.
fn light() -> Planar {
    Planar {
        m2: 0.05,
        c2: 0.05,
        d2: 0.0,
        ix2: 1e-5,
        iy2: 2e-5,
        iz2: 2e-5,
        ..PLANAR
    }
}

#[test]
fn a_non_physical_plain_estimate_and_the_consistent_one() {
    let arm = light();
    let base = BaseParameters::of(&arm).expect("a regressor");
    let truth = arm.inertial_parameters().expect("π");
    let izz2 = base
        .names()
        .iter()
        .position(|n| *n == "link2.Izz")
        .expect("link2.Izz");
    let sigma = Vector2::repeat(0.05);
    // The first of the fixed draws on which the plain link2.Izz < 0.
    let (data, plain) = (1..200)
        .map(|seed| {
            let data = samples(&arm, &truth, 6, 0.05, &mut Lcg(seed));
            let plain = identify(&arm, &base, &data, &sigma).expect("identifies");
            (data, plain)
        })
        .find(|(_, plain)| plain.values[izz2] < 0.0)
        .expect("a draw with a negative inertia");
    // link2.Izz is Σxx + Σyy of link 2 about the elbow, positive for every
    // real body: the projection of the prior onto the plain π_b (the
    // nearest π that has it) is no real arm.
    let prior = PLANAR.inertial_parameters().expect("π");
    let k = base.map();
    let k_pinv = k.clone().pseudo_inverse(1e-12).expect("K⁺");
    let projected = &prior + k_pinv * (&plain.values - k * &prior);
    let names = Planar::REGRESSOR_PARAMETERS;
    let bad = inconsistent_bodies(names, &projected).expect("π");
    assert!(bad.contains(&"link2".to_string()), "{bad:?}");

    let fit = identify_consistent(&arm, &base, &data, &sigma, &prior, &Consistency::default())
        .expect("converges");
    eprintln!(
        "light forearm: plain link2.Izz {:.2e} (residual {:.3}), consistent {:.2e} (residual \
         {:.3}, {} iterations)",
        plain.values[izz2], plain.residual, fit.base[izz2], fit.residual, fit.iterations
    );
    assert!(
        inconsistent_bodies(names, &fit.parameters)
            .expect("π")
            .is_empty()
    );
    assert!(fit.base[izz2] > 0.0);
    assert!(fit.residual >= plain.residual * (1.0 - 1e-9));
    assert!(
        fit.residual < 1.5 * plain.residual,
        "{} vs {}",
        fit.residual,
        plain.residual
    );
}

#[test]
fn bad_priors_settings_and_a_short_budget_are_typed_errors() {
    let base = BaseParameters::of(&PLANAR).expect("a regressor");
    let truth = PLANAR.inertial_parameters().expect("π");
    let data = samples(&PLANAR, &truth, 10, 0.01, &mut Lcg(4));
    let sigma = Vector2::repeat(0.01);
    let run = |prior: &DVector<f64>, settings: &Consistency| {
        identify_consistent(&PLANAR, &base, &data, &sigma, prior, settings)
    };
    let defaults = Consistency::default();
    let mut negative = truth.clone();
    negative[0] = -1.0;
    match run(&negative, &defaults) {
        Err(IdentifyError::Inconsistent { body, .. }) => assert_eq!(body, "link1"),
        other => panic!("{other:?}"),
    }
    let short = DVector::zeros(3);
    assert!(matches!(
        run(&short, &defaults),
        Err(IdentifyError::Lengths {
            got: 3,
            expected: 20,
            ..
        })
    ));
    let zero = Consistency {
        regularisation: 0.0,
        ..defaults.clone()
    };
    let negative_tolerance = Consistency {
        tolerance: -1.0,
        ..defaults.clone()
    };
    assert!(matches!(
        run(&truth, &negative_tolerance),
        Err(IdentifyError::Setting {
            setting: "tolerance",
            ..
        })
    ));
    assert!(matches!(
        run(&truth, &zero),
        Err(IdentifyError::Setting {
            setting: "regularisation",
            ..
        })
    ));
    // One iteration from a prior far from the data: not converged, and
    // the best iterate handed back is a real arm.
    let far = &truth * 3.0;
    match run(
        &far,
        &Consistency {
            iterations: 1,
            ..defaults
        },
    ) {
        Err(IdentifyError::NotConverged {
            iterations: 1,
            best,
            ..
        }) => {
            assert!(
                inconsistent_bodies(Planar::REGRESSOR_PARAMETERS, &best)
                    .expect("π")
                    .is_empty()
            );
        }
        other => panic!("{other:?}"),
    }
}
