//! A step's curvature against central differences of its exact first
//! derivatives: ∇²(yᵀF) column j ≈ ([∂F/∂x ∂F/∂u]ᵀ y at z + ε e_j − at
//! z − ε e_j) / 2ε, by RK4 and by semi-implicit Euler, on a nonlinear
//! velocity-dependent system with two inputs and on the pendulum; and the
//! derivatives the same sweep gives against the step's own.

use super::*;
use crate::linear::test_systems::{Pendulum, SPHERICAL_STATES, Spherical};
use nalgebra::{DVector, Vector1};

const METHODS: [StepMethod; 2] = [StepMethod::Rk4, StepMethod::SemiImplicitEuler];

/// ∇²(yᵀF) by central differences of ∂F/∂(x, u), ε = 1e-5.
fn differences<S, const N: usize, const P: usize>(
    tr: &Transition<S>,
    (q, v, u): (SVector<f64, N>, SVector<f64, N>, SVector<f64, P>),
    y: &[f64],
) -> DMatrix<f64>
where
    S: Driven<f64, N, P>,
{
    let eps = 1e-5;
    let y = DVector::from_column_slice(y);
    let gradient = |z: &DVector<f64>| {
        let q = SVector::<f64, N>::from_column_slice(&z.as_slice()[..N]);
        let v = SVector::<f64, N>::from_column_slice(&z.as_slice()[N..2 * N]);
        let u = SVector::<f64, P>::from_column_slice(&z.as_slice()[2 * N..]);
        let d = tr.derivatives(&q, &v, &u, 0.3).unwrap();
        let mut g = d.dx.tr_mul(&y).as_slice().to_vec();
        g.extend(d.du.tr_mul(&y).iter());
        DVector::from_vec(g)
    };
    let z = DVector::from_iterator(2 * N + P, q.iter().chain(v.iter()).chain(u.iter()).copied());
    let mut h = DMatrix::zeros(2 * N + P, 2 * N + P);
    for j in 0..2 * N + P {
        let (mut plus, mut minus) = (z.clone(), z.clone());
        plus[j] += eps;
        minus[j] -= eps;
        h.set_column(j, &((gradient(&plus) - gradient(&minus)) / (2.0 * eps)));
    }
    h
}

#[test]
fn a_steps_curvature_matches_differences_of_its_derivatives() {
    let sys = Spherical { l: 0.9 };
    let states = &SPHERICAL_STATES[..2];
    let y = [0.8, -1.3, 0.4, 2.1];
    for method in METHODS {
        let tr = Transition::new(&sys, 0.05).unwrap().method(method);
        for &(q, v, u) in states {
            let (d, exact) = tr.curvature((&q, &v, &u), 0.3, &y).unwrap();
            let plain = tr.derivatives(&q, &v, &u, 0.3).unwrap();
            assert!((&d.dx - &plain.dx).amax() < 1e-15 && (&d.du - &plain.du).amax() < 1e-15);
            assert!((d.q - plain.q).amax() < 1e-15 && (d.v - plain.v).amax() < 1e-15);
            let reference = differences(&tr, (q, v, u), &y);
            let error = (&exact - &reference).amax() / reference.amax();
            // These test systems emit no derivatives: their stages' are
            // central differences, so the curvature's step is ∛ε and its
            // truncation error ~10⁻⁵; a wrong term would be O(1).
            assert!(
                error < 5e-5,
                "{method:?} at {q:?}: relative error {error:e}"
            );
            assert!((&exact - exact.transpose()).amax() == 0.0);
        }
    }
    let tr = Transition::new(&Pendulum, 0.02).unwrap();
    let (q, v, u) = (Vector1::new(2.0), Vector1::new(-0.5), Vector1::new(1.0));
    let (_, exact) = tr.curvature((&q, &v, &u), 0.3, &[1.5, -0.7]).unwrap();
    let reference = differences(&tr, (q, v, u), &[1.5, -0.7]);
    assert!((&exact - &reference).amax() < 5e-5 * reference.amax());
    // No multipliers, no curvature.
    let (_, zero) = tr.curvature((&q, &v, &u), 0.3, &[0.0, 0.0]).unwrap();
    assert_eq!(zero.amax(), 0.0);
}
