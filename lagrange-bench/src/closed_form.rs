//! The planar n-link pendulum (absolute angles from the downward vertical)
//! collected by hand: M_ij = M̄ l_i l_j cos(θ_i − θ_j) with M̄ the mass from
//! link max(i, j) to the tip, h_i = Σ_j M̄ l_i l_j sin(θ_i − θ_j) θ̇_j²,
//! Q_i = −g l_i sin θ_i M̄_i — what a careful engineer writes for this one
//! system, the peer of the derived `n_link_source` chain.

use nalgebra::{SMatrix, SVector};

/// Masses, lengths and gravity of an N-link planar chain.
pub struct PlanarChain<const N: usize> {
    pub m: [f64; N],
    pub l: [f64; N],
    pub g: f64,
}

impl<const N: usize> PlanarChain<N> {
    /// The benchmark's chain: m_k = 1 + 0.1 k, l_k = 1 − 0.02 k, g = 9.81.
    pub fn sample() -> Self {
        PlanarChain {
            m: std::array::from_fn(|k| 1.0 + 0.1 * k as f64),
            l: std::array::from_fn(|k| 1.0 - 0.02 * k as f64),
            g: 9.81,
        }
    }

    /// M and Q − h; sines and cosines once per coordinate, the tip masses once
    /// per call, each pair (i, j) once for M and both h_i and h_j.
    pub fn mass_matrix_and_rhs(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        let sc: [(f64, f64); N] = std::array::from_fn(|i| q[i].sin_cos());
        let mut tip = [0.0; N];
        let mut acc = 0.0;
        for k in (0..N).rev() {
            acc += self.m[k];
            tip[k] = acc;
        }
        let mut m = SMatrix::<f64, N, N>::zeros();
        let mut h = [0.0; N];
        let v2: [f64; N] = std::array::from_fn(|i| v[i] * v[i]);
        // Each pair once: k = M̄ l_i l_j, cos and sin of θ_i − θ_j from the
        // sines and cosines; sin(θ_j − θ_i) = −sin(θ_i − θ_j).
        for i in 0..N {
            let (si, ci) = sc[i];
            m[(i, i)] = tip[i] * self.l[i] * self.l[i];
            for j in i + 1..N {
                let (sj, cj) = sc[j];
                let k = tip[j] * self.l[i] * self.l[j];
                let e = k * (ci * cj + si * sj);
                m[(i, j)] = e;
                m[(j, i)] = e;
                let ks = k * (si * cj - ci * sj);
                h[i] += ks * v2[j];
                h[j] -= ks * v2[i];
            }
        }
        let rhs = SVector::<f64, N>::from_fn(|i, _| -self.g * self.l[i] * sc[i].0 * tip[i] - h[i]);
        (m, rhs)
    }
}
