//! The derived planar chains equal the closed form collected by hand, with the
//! parameter-only terms computed once and at every call.

use lagrange::Lagrangian;
use lagrange_bench::closed_form::PlanarChain;
use nalgebra::SVector;

include!(concat!(env!("OUT_DIR"), "/planar_chains.rs"));

fn check<const N: usize>(sys: &impl Lagrangian<f64, N>) {
    let q = SVector::<f64, N>::from_fn(|i, _| 0.3 + 0.01 * i as f64);
    let v = SVector::<f64, N>::from_fn(|i, _| 0.2 - 0.01 * i as f64);
    let (hm, hr) = PlanarChain::<N>::sample().mass_matrix_and_rhs(&q, &v);
    let terms = sys.parameter_terms();
    assert!(!terms.is_empty(), "the chain has parameter-only terms");
    for (m, r) in [
        sys.mass_matrix_and_rhs(&q, &v, 0.0),
        sys.mass_matrix_and_rhs_with(&terms, &q, &v, 0.0),
    ] {
        assert!((m - hm).amax() < 1e-12 * hm.amax(), "M");
        assert!((r - hr).amax() < 1e-12 * hr.amax(), "Q − h");
    }
}

#[test]
fn derived_chains_equal_the_closed_form() {
    check::<10>(&planar10::Chain::sample());
    check::<20>(&planar20::Chain::sample());
    check::<30>(&planar30::Chain::sample());
}
