//! Periodic joint trajectories as finite Fourier series (Swevers et al.
//! 1997), and the joint limits they must keep.

use nalgebra::{DMatrix, DVector, SVector};

use super::{Sample, State};
use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// Each joint's position range and bounds on the magnitudes of its speed
/// and acceleration.
#[derive(Clone, Debug, PartialEq)]
pub struct JointLimits<const N: usize> {
    lower: SVector<f64, N>,
    upper: SVector<f64, N>,
    speed: SVector<f64, N>,
    acceleration: SVector<f64, N>,
}

impl<const N: usize> JointLimits<N> {
    /// lower ≤ q ≤ upper, |q̇| ≤ speed, |q̈| ≤ acceleration, joint by joint.
    ///
    /// # Errors
    /// [`IdentifyError::LimitRange`] for a joint whose limits are not
    /// finite with lower < upper; [`IdentifyError::LimitRate`] for a speed
    /// or acceleration bound that is not positive and finite.
    pub fn new(
        lower: SVector<f64, N>,
        upper: SVector<f64, N>,
        speed: SVector<f64, N>,
        acceleration: SVector<f64, N>,
    ) -> Result<Self, IdentifyError> {
        for joint in 0..N {
            let (lo, hi) = (lower[joint], upper[joint]);
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(IdentifyError::LimitRange {
                    joint,
                    lower: lo,
                    upper: hi,
                });
            }
            for (quantity, value) in [
                ("speed", speed[joint]),
                ("acceleration", acceleration[joint]),
            ] {
                if !(value.is_finite() && value > 0.0) {
                    return Err(IdentifyError::LimitRate {
                        joint,
                        quantity,
                        value,
                    });
                }
            }
        }
        Ok(JointLimits {
            lower,
            upper,
            speed,
            acceleration,
        })
    }

    /// The lower position limits.
    pub fn lower(&self) -> &SVector<f64, N> {
        &self.lower
    }

    /// The upper position limits.
    pub fn upper(&self) -> &SVector<f64, N> {
        &self.upper
    }

    /// The bounds on |q̇|.
    pub fn speed(&self) -> &SVector<f64, N> {
        &self.speed
    }

    /// The bounds on |q̈|.
    pub fn acceleration(&self) -> &SVector<f64, N> {
        &self.acceleration
    }
}

/// A periodic trajectory, per joint i a finite Fourier series of base
/// angular frequency ω_f and L harmonics (Swevers, Ganseman, Tükel, de
/// Schutter and Van Brussel 1997):
///
/// q_i(t) = q0_i + Σ_{l=1..L} a_il/(ω_f l) sin(ω_f l t) − b_il/(ω_f l) cos(ω_f l t),
///
/// so that q̇_i(t) = Σ a_il cos(ω_f l t) + b_il sin(ω_f l t): a_il and b_il
/// are speed amplitudes. Its period is T = 2π/ω_f and q0 is its mean.
#[derive(Clone, Debug, PartialEq)]
pub struct Fourier<const N: usize> {
    frequency: f64,
    offset: SVector<f64, N>,
    a: DMatrix<f64>,
    b: DMatrix<f64>,
}

impl<const N: usize> Fourier<N> {
    /// The series of base angular frequency `frequency` (ω_f, rad/s),
    /// means `offset` (q0) and coefficients `a`, `b` (N × L: joint i's
    /// harmonic l + 1 in row i, column l).
    ///
    /// # Errors
    /// [`IdentifyError::Setting`] for a frequency that is not positive and
    /// finite; [`IdentifyError::Lengths`] when `a` has not N rows or `b`
    /// not `a`'s shape; [`IdentifyError::NotFiniteValue`] for a NaN or an
    /// infinity in the offsets or coefficients.
    pub fn new(
        frequency: f64,
        offset: SVector<f64, N>,
        a: DMatrix<f64>,
        b: DMatrix<f64>,
    ) -> Result<Self, IdentifyError> {
        if !(frequency.is_finite() && frequency > 0.0) {
            return Err(IdentifyError::Setting {
                setting: "frequency",
                value: frequency,
                reason: "the base angular frequency must be positive and finite (2π / period)",
            });
        }
        for (what, got, expected) in [
            ("the rows of a", a.nrows(), N),
            ("the rows of b", b.nrows(), N),
            ("the columns of b", b.ncols(), a.ncols()),
        ] {
            if got != expected {
                return Err(IdentifyError::Lengths {
                    what,
                    got,
                    expected,
                });
            }
        }
        for (what, values) in [
            ("the offset q0", offset.as_slice()),
            ("a", a.as_slice()),
            ("b", b.as_slice()),
        ] {
            if let Some((index, &value)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(IdentifyError::NotFiniteValue { what, index, value });
            }
        }
        Ok(Fourier {
            frequency,
            offset,
            a,
            b,
        })
    }

    /// ω_f, rad/s.
    pub fn frequency(&self) -> f64 {
        self.frequency
    }

    /// T = 2π/ω_f.
    pub fn period(&self) -> f64 {
        std::f64::consts::TAU / self.frequency
    }

    /// L, the harmonics per joint.
    pub fn harmonics(&self) -> usize {
        self.a.ncols()
    }

    /// q0, each joint's mean position.
    pub fn offset(&self) -> &SVector<f64, N> {
        &self.offset
    }

    /// The sine coefficients a (N × L).
    pub fn a(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// The cosine coefficients b (N × L).
    pub fn b(&self) -> &DMatrix<f64> {
        &self.b
    }

    /// (q, q̇, q̈) at time t, each from its own closed form.
    pub fn state(&self, t: f64) -> (SVector<f64, N>, SVector<f64, N>, SVector<f64, N>) {
        let mut q = self.offset;
        let mut v = SVector::zeros();
        let mut acc = SVector::zeros();
        for l in 0..self.harmonics() {
            let w = self.frequency * (l + 1) as f64;
            let (s, c) = (w * t).sin_cos();
            for i in 0..N {
                let (a, b) = (self.a[(i, l)], self.b[(i, l)]);
                q[i] += (a * s - b * c) / w;
                v[i] += a * c + b * s;
                acc[i] += w * (b * c - a * s);
            }
        }
        (q, v, acc)
    }

    /// q(t).
    pub fn position(&self, t: f64) -> SVector<f64, N> {
        self.state(t).0
    }

    /// q̇(t).
    pub fn velocity(&self, t: f64) -> SVector<f64, N> {
        self.state(t).1
    }

    /// q̈(t).
    pub fn acceleration(&self, t: f64) -> SVector<f64, N> {
        self.state(t).2
    }

    /// The times k T / count, k = 0 … count − 1: one period, evenly.
    pub fn times(&self, count: usize) -> Vec<f64> {
        let period = self.period();
        (0..count)
            .map(|k| period * k as f64 / count as f64)
            .collect()
    }

    /// The states at [`times`](Self::times)`(count)`.
    pub fn states(&self, count: usize) -> Vec<State<N, N>> {
        self.times(count)
            .into_iter()
            .map(|t| self.state(t))
            .collect()
    }

    /// Samples along one period at [`times`](Self::times)`(count)` with
    /// τ = Y(q, q̇, q̈) π: what a system whose parameters are `pi` needs to
    /// move so, without noise. For simulated measurements (a model whose π
    /// differs from `sys`'s own: a payload added, a link made heavier).
    ///
    /// # Errors
    /// [`IdentifyError::NoRegressor`] unless the system was derived with
    /// `emit(regressor)`; [`IdentifyError::Lengths`] when π is not as long
    /// as the system's.
    pub fn samples<S>(
        &self,
        sys: &S,
        pi: &DVector<f64>,
        count: usize,
    ) -> Result<Vec<Sample<N, N>>, IdentifyError>
    where
        S: Lagrangian<f64, N, N>,
    {
        self.states(count)
            .into_iter()
            .map(|(q, v, a)| {
                let y = super::regressor_at(sys, &q, &v, &a)?;
                if y.ncols() != pi.len() {
                    return Err(IdentifyError::Lengths {
                        what: "π",
                        got: pi.len(),
                        expected: y.ncols(),
                    });
                }
                let tau = SVector::from_iterator((y * pi).iter().copied());
                Ok(Sample { q, v, a, tau })
            })
            .collect()
    }

    /// Checks q, q̇ and q̈ against `limits` at [`times`](Self::times)`(count)`.
    ///
    /// # Errors
    /// [`IdentifyError::OutsideLimits`] for the first joint and time found
    /// outside, with the quantity, its value and the limit passed.
    pub fn check(&self, limits: &JointLimits<N>, count: usize) -> Result<(), IdentifyError> {
        for t in self.times(count) {
            let (q, v, a) = self.state(t);
            for joint in 0..N {
                let outside = |quantity, value: f64, limit: f64| IdentifyError::OutsideLimits {
                    joint,
                    quantity,
                    time: t,
                    value,
                    limit,
                };
                if q[joint] < limits.lower[joint] {
                    return Err(outside("position", q[joint], limits.lower[joint]));
                }
                if q[joint] > limits.upper[joint] {
                    return Err(outside("position", q[joint], limits.upper[joint]));
                }
                if v[joint].abs() > limits.speed[joint] {
                    return Err(outside("speed", v[joint], limits.speed[joint]));
                }
                if a[joint].abs() > limits.acceleration[joint] {
                    return Err(outside(
                        "acceleration",
                        a[joint],
                        limits.acceleration[joint],
                    ));
                }
            }
        }
        Ok(())
    }
}
