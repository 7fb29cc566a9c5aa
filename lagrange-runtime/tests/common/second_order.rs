//! Plain second-order reference problems q̈ = f(t, q, q̇) from Hairer's test
//! set, for the integrators on their own.
// The Arenstorf constants are quoted with the digits Hairer publishes.
#![allow(clippy::excessive_precision)]

use lagrange_runtime::{Error, SecondOrder};
use nalgebra::{Matrix1, Vector1, Vector2};

/// Van der Pol in Hairer's scaling, ε q̈ = (1 − q²) q̇ − q; with its analytic
/// Jacobian when `analytic` (otherwise the integrator differences).
pub struct VanDerPol {
    pub eps: f64,
    pub analytic: bool,
}

impl SecondOrder<f64, 1> for VanDerPol {
    fn acceleration(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
    ) -> Result<Vector1<f64>, Error> {
        Ok(Vector1::new(((1.0 - q[0] * q[0]) * v[0] - q[0]) / self.eps))
    }
    fn jacobian(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        v: &Vector1<f64>,
    ) -> Option<Result<(Matrix1<f64>, Matrix1<f64>), Error>> {
        self.analytic.then(|| {
            Ok((
                Matrix1::new((-2.0 * q[0] * v[0] - 1.0) / self.eps),
                Matrix1::new((1.0 - q[0] * q[0]) / self.eps),
            ))
        })
    }
}

/// The restricted three-body problem (Arenstorf orbit), Hairer–Nørsett–Wanner I, §II.0.
pub struct Arenstorf;

impl Arenstorf {
    /// The mass ratio μ.
    pub const MU: f64 = 0.012277471;
    /// The period of the orbit.
    pub const T_ORBIT: f64 = 17.065_216_560_157_962_558_891_720_624_9;
    /// The initial ẏ of the periodic orbit from (0.994, 0).
    pub const V0: f64 = -2.001_585_106_379_082_522_405_378_622_24;
}

impl SecondOrder<f64, 2> for Arenstorf {
    fn acceleration(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
    ) -> Result<Vector2<f64>, Error> {
        let mu = Self::MU;
        let mu1 = 1.0 - mu;
        let (x, y) = (q[0], q[1]);
        let d1 = ((x + mu).powi(2) + y * y).powf(1.5);
        let d2 = ((x - mu1).powi(2) + y * y).powf(1.5);
        Ok(Vector2::new(
            x + 2.0 * v[1] - mu1 * (x + mu) / d1 - mu * (x - mu1) / d2,
            y - 2.0 * v[0] - mu1 * y / d1 - mu * y / d2,
        ))
    }
}
