//! The derived spatial chains against Pinocchio 4.1 (CRBA and
//! nonLinearEffects at the same state, printed by `peer/pinocchio/run.sh`):
//! two derivations that share nothing agree to round-off.

use lagrange::Lagrangian;
use nalgebra::SVector;

include!(concat!(env!("OUT_DIR"), "/spatial_chains.rs"));

fn state<const N: usize>() -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|i, _| 0.3 + 0.01 * i as f64),
        SVector::from_fn(|i, _| 0.2 - 0.01 * i as f64),
    )
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn mass_matrix_and_rhs_match_pinocchio() {
    // (n, M[0][0], (Q − h)[0]) from Pinocchio.
    let (q, v) = state::<6>();
    let (m, f) = n6::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    assert!(close(m[(0, 0)], 74.0315975272448), "{}", m[(0, 0)]);
    assert!(close(f[0], 4.42521592570079), "{}", f[0]);
    let (q, v) = state::<14>();
    let (m, f) = n14::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    assert!(close(m[(0, 0)], 482.975828915347), "{}", m[(0, 0)]);
    assert!(close(f[0], 210.052527264394), "{}", f[0]);
    let (q, v) = state::<30>();
    let (m, f) = n30::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    assert!(close(m[(0, 0)], 1069.00074347317), "{}", m[(0, 0)]);
    assert!(close(f[0], 697.322883981117), "{}", f[0]);
    // Past six joints the recursive route is taken alone, and says so.
    assert_eq!(
        <n14::SpatialChain as Lagrangian<f64, 14>>::ROUTE,
        lagrange::Route::Recursive
    );
    assert!(n30::SpatialChain::EQUATIONS.contains("route: recursive"));
}

/// The hand-written recursive Newton–Euler chain equals the derived one.
#[test]
fn recursive_newton_euler_matches_the_derivation() {
    use lagrange_bench::recursive::SerialChain;
    use nalgebra::DVector;
    fn check<const N: usize>(f: SVector<f64, N>, mm: nalgebra::SMatrix<f64, N, N>) {
        let chain = SerialChain::benchmark(N);
        let (q, v) = state::<N>();
        let (rm, rf) = chain.mass_matrix_and_rhs(
            &DVector::from_column_slice(q.as_slice()),
            &DVector::from_column_slice(v.as_slice()),
        );
        let scale = mm.amax();
        for i in 0..N {
            for j in 0..N {
                assert!(
                    (rm[(i, j)] - mm[(i, j)]).abs() < 1e-12 * scale,
                    "M[{i}][{j}]"
                );
            }
            assert!((rf[i] - f[i]).abs() < 1e-12 * f.amax().max(1.0), "rhs[{i}]");
        }
    }
    let (q, v) = state::<6>();
    let (m, f) = n6::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    check::<6>(f, m);
    let (q, v) = state::<14>();
    let (m, f) = n14::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    check::<14>(f, m);
    let (q, v) = state::<30>();
    let (m, f) = n30::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    check::<30>(f, m);
}

/// The articulated-body algorithm gives the accelerations of M⁻¹(Q − h) by
/// Cholesky, and a run with it the same trajectory.
#[test]
fn articulated_body_matches_cholesky() {
    fn check<const N: usize>(chol: SVector<f64, N>, aba: SVector<f64, N>) {
        let scale = chol.amax().max(1.0);
        for i in 0..N {
            assert!(
                (chol[i] - aba[i]).abs() < 1e-11 * scale,
                "q̈[{i}]: {} vs {}",
                chol[i],
                aba[i]
            );
        }
    }
    let (q, v) = state::<6>();
    check(
        lagrange::accelerations(&n6::SpatialChain::benchmark(), &q, &v, 0.0).unwrap(),
        lagrange::accelerations(&a6::SpatialChain::benchmark(), &q, &v, 0.0).unwrap(),
    );
    let (q, v) = state::<14>();
    check(
        lagrange::accelerations(&n14::SpatialChain::benchmark(), &q, &v, 0.0).unwrap(),
        lagrange::accelerations(&a14::SpatialChain::benchmark(), &q, &v, 0.0).unwrap(),
    );
    let (q, v) = state::<30>();
    check(
        lagrange::accelerations(&n30::SpatialChain::benchmark(), &q, &v, 0.0).unwrap(),
        lagrange::accelerations(&a30::SpatialChain::benchmark(), &q, &v, 0.0).unwrap(),
    );
    // One second of the 14-link arm falling from the same state, both ways.
    let (q, v) = state::<14>();
    let (full, articulated) = (
        n14::SpatialChain::benchmark(),
        a14::SpatialChain::benchmark(),
    );
    let a = lagrange::Simulation::new(&full)
        .integrator(lagrange::Dopri5::tol(1e-10))
        .run(q, v, 0.0..1.0)
        .unwrap();
    let b = lagrange::Simulation::new(&articulated)
        .integrator(lagrange::Dopri5::tol(1e-10))
        .run(q, v, 0.0..1.0)
        .unwrap();
    let ((qa, _), (qb, _)) = (a.final_state(), b.final_state());
    assert!((qa - qb).amax() < 1e-7, "{}", (qa - qb).amax());
}

/// The chain with its poses written out (explicit matrices of `define`s, ξ(q)
/// as sums) is read back onto the recursive route and equals the chain
/// written with factors; Pinocchio's numbers hold for it too.
#[test]
fn written_out_chain_takes_the_recursive_route() {
    fn same<const N: usize>(
        (wm, wf): (nalgebra::SMatrix<f64, N, N>, SVector<f64, N>),
        (m, f): (nalgebra::SMatrix<f64, N, N>, SVector<f64, N>),
    ) {
        let scale = m.amax();
        assert!((wm - m).amax() <= 1e-12 * scale, "M: {}", (wm - m).amax());
        assert!(
            (wf - f).amax() <= 1e-12 * scale,
            "Q − h: {}",
            (wf - f).amax()
        );
    }
    let (q, v) = state::<12>();
    let written = w12::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    same(
        written,
        n12::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0),
    );
    assert_eq!(
        <w12::SpatialChain as Lagrangian<f64, 12>>::ROUTE,
        lagrange::Route::Recursive
    );
    let (q, v) = state::<6>();
    let (m, f) = w6::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0);
    assert!(close(m[(0, 0)], 74.0315975272448), "{}", m[(0, 0)]);
    assert!(close(f[0], 4.42521592570079), "{}", f[0]);
    same(
        (m, f),
        n6::SpatialChain::benchmark().mass_matrix_and_rhs(&q, &v, 0.0),
    );
}
