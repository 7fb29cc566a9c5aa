//! Closed forms the tests check against.

/// Arithmetic–geometric mean.
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    // Quadratic convergence: 10 iterations reach round-off from any start the
    // tests use; iterating "until equal" can cycle in the last ulp.
    for _ in 0..10 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// Period of a pendulum of length l released from rest at amplitude θ₀:
/// 4 √(l/g) K(sin(θ₀/2)), K(k) = π / (2 AGM(1, √(1−k²))). The complementary
/// modulus √(1−k²) = cos(θ₀/2) is computed directly: near θ₀ = π, 1 − k² cancels.
pub fn pendulum_period(l: f64, g: f64, theta0: f64) -> f64 {
    let k_complete = std::f64::consts::PI / (2.0 * agm(1.0, (0.5 * theta0).cos()));
    4.0 * (l / g).sqrt() * k_complete
}
