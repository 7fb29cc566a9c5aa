//! Exciting trajectories: the Fourier coefficients that make the base
//! regressor stacked along one period as well conditioned as the joint
//! limits allow (Swevers et al. 1997; Park 2006), so that the noise in τ
//! spreads evenly over the base parameters.

use nalgebra::{DMatrix, DVector, SVector};

use super::base::BaseParameters;
use super::fourier::{Fourier, JointLimits};
use super::nelder_mead::minimise;
use crate::error::IdentifyError;
use crate::system::Lagrangian;

/// The settings of [`exciting_trajectory`]. The defaults are those of the
/// literature's experiments (five harmonics, a 10 s period, 100 samples
/// along it); a test or a first look wants fewer of each.
#[derive(Clone, Debug, PartialEq)]
pub struct Excitation {
    /// L, the harmonics per joint.
    pub harmonics: usize,
    /// T, the period in seconds: ω_f = 2π/T.
    pub period: f64,
    /// The times along one period at which the regressor is stacked (and
    /// whose condition number is minimised).
    pub samples: usize,
    /// Nelder–Mead steps per run.
    pub iterations: usize,
    /// Runs of Nelder–Mead, each from a fresh simplex about the best point
    /// so far (a simplex that has collapsed onto a subspace cannot leave it).
    pub restarts: usize,
    /// The seed of the first run's starting coefficients: the same seed
    /// gives the same trajectory.
    pub seed: u64,
}

impl Default for Excitation {
    fn default() -> Self {
        Excitation {
            harmonics: 5,
            period: 10.0,
            samples: 100,
            iterations: 4000,
            restarts: 3,
            seed: 1,
        }
    }
}

/// An exciting trajectory and how well it conditions the regressor.
#[derive(Clone, Debug, PartialEq)]
pub struct Excited<const N: usize> {
    /// The trajectory, within the limits at every time (not only at the
    /// samples: see [`exciting_trajectory`]).
    pub trajectory: Fourier<N>,
    /// cond(W_b) = σ_max/σ_min of the base regressor stacked at the
    /// settings' samples along `trajectory`.
    pub condition: f64,
    /// The same for the seeded starting trajectory.
    pub start_condition: f64,
    /// Whether q, q̇ and q̈ lie within the limits at ten times as many
    /// samples as the optimisation used (they do by construction; this
    /// checks it).
    pub within_limits: bool,
    /// Evaluations of the condition number spent.
    pub evaluations: usize,
}

/// The Fourier series (L harmonics per joint, period T) whose stacked base
/// regressor W_b has the smallest condition number Nelder–Mead finds,
/// within `limits` at every time.
///
/// The limits hold by construction rather than by penalty: each joint's
/// mean q0 is kept in the middle half of its range and its coefficients are
/// scaled down, whenever needed, until the analytic bounds
/// Σ_l ρ_l/(ω_f l) ≤ distance from q0 to the nearer limit, Σ_l ρ_l ≤ speed,
/// Σ_l ω_f l ρ_l ≤ acceleration hold, ρ_l = √(a_l² + b_l²): each bounds the
/// quantity at all times, not only at samples. The optimiser then searches
/// an unconstrained space (each coefficient in units of the joint's speed
/// limit), minimising ln cond(W_b). Deterministic: the start is drawn from
/// `settings.seed`.
///
/// # Errors
/// [`IdentifyError::Setting`] for no harmonics or a period that is not
/// positive and finite; [`IdentifyError::TooFewSamples`] for fewer
/// equations (samples × joints) than base parameters;
/// [`IdentifyError::NotExcited`] when no trajectory tried makes W_b of full
/// rank; [`IdentifyError::NoRegressor`] and [`IdentifyError::Lengths`] as
/// for [`BaseParameters::regressor`].
pub fn exciting_trajectory<S, const N: usize>(
    sys: &S,
    base: &BaseParameters,
    limits: &JointLimits<N>,
    settings: &Excitation,
) -> Result<Excited<N>, IdentifyError>
where
    S: Lagrangian<f64, N, N>,
{
    check(base, settings, N)?;
    let shape = Shape {
        harmonics: settings.harmonics,
        frequency: std::f64::consts::TAU / settings.period,
        limits,
    };
    let start = seeded_start(settings.seed, N, settings.harmonics);
    let mut failure = None;
    let mut objective = |p: &DVector<f64>| match (shape.decode(p))
        .and_then(|t| condition_number(sys, base, &t, settings.samples))
    {
        Ok(c) => c.ln(),
        Err(e) => {
            failure.get_or_insert(e);
            f64::INFINITY
        }
    };
    let start_value = objective(&start);
    let (mut best, mut value, mut evaluations) = (start, start_value, 1);
    for _ in 0..settings.restarts.max(1) {
        let found = minimise(&mut objective, &best, 0.5, settings.iterations, 1e-10);
        evaluations += found.evaluations;
        if found.value <= value {
            (best, value) = (found.x, found.value);
        }
    }
    if let Some(e) = failure {
        return Err(e);
    }
    if !value.is_finite() {
        return Err(IdentifyError::NotExcited {
            condition: value.exp(),
        });
    }
    let trajectory = shape.decode(&best)?;
    let within_limits = trajectory.check(limits, 10 * settings.samples).is_ok();
    Ok(Excited {
        condition: value.exp(),
        start_condition: start_value.exp(),
        within_limits,
        evaluations,
        trajectory,
    })
}

/// The settings' own checks, and enough equations for the base parameters.
fn check(base: &BaseParameters, settings: &Excitation, joints: usize) -> Result<(), IdentifyError> {
    if settings.harmonics == 0 {
        return Err(IdentifyError::Setting {
            setting: "harmonics",
            value: 0.0,
            reason: "a trajectory needs at least one harmonic per joint",
        });
    }
    if !(settings.period.is_finite() && settings.period > 0.0) {
        return Err(IdentifyError::Setting {
            setting: "period",
            value: settings.period,
            reason: "the period must be positive and finite, in seconds",
        });
    }
    let parameters = base.len();
    if settings.samples * joints < parameters {
        return Err(IdentifyError::TooFewSamples {
            samples: settings.samples,
            joints,
            equations: settings.samples * joints,
            parameters,
            needed: parameters.div_ceil(joints.max(1)),
        });
    }
    Ok(())
}

/// cond(W_b) = σ_max/σ_min of the base regressor stacked along
/// `trajectory` at [`Fourier::times`]`(count)`, +∞ for a rank-deficient
/// W_b: the figure [`exciting_trajectory`] minimises, for comparing a
/// trajectory of one's own.
///
/// # Errors
/// [`IdentifyError::NoRegressor`] and [`IdentifyError::Lengths`] as for
/// [`BaseParameters::regressor`].
pub fn condition_number<S, const N: usize>(
    sys: &S,
    base: &BaseParameters,
    trajectory: &Fourier<N>,
    count: usize,
) -> Result<f64, IdentifyError>
where
    S: Lagrangian<f64, N, N>,
{
    let mut w = DMatrix::zeros(count * N, base.len());
    for (k, (q, v, a)) in trajectory.states(count).iter().enumerate() {
        let yb = base.regressor(sys, q, v, a)?;
        w.view_mut((k * N, 0), (N, base.len())).copy_from(&yb);
    }
    let sv = w.singular_values();
    let (largest, smallest) = (sv.max(), sv.min());
    Ok(if smallest > 0.0 {
        largest / smallest
    } else {
        f64::INFINITY
    })
}

/// How an unconstrained vector p becomes a trajectory within the limits:
/// per joint p's entries are the offset's and then L sine and L cosine
/// coefficients.
struct Shape<'a, const N: usize> {
    harmonics: usize,
    frequency: f64,
    limits: &'a JointLimits<N>,
}

impl<const N: usize> Shape<'_, N> {
    fn decode(&self, p: &DVector<f64>) -> Result<Fourier<N>, IdentifyError> {
        let l = self.harmonics;
        let mut offset = SVector::<f64, N>::zeros();
        let mut a = DMatrix::zeros(N, l);
        let mut b = DMatrix::zeros(N, l);
        for i in 0..N {
            let chunk = &p.as_slice()[i * (2 * l + 1)..(i + 1) * (2 * l + 1)];
            let (lower, upper) = (self.limits.lower()[i], self.limits.upper()[i]);
            let (centre, half) = (0.5 * (lower + upper), 0.5 * (upper - lower));
            offset[i] = centre + 0.5 * half * chunk[0].tanh();
            let room = half - (offset[i] - centre).abs();
            let speed = self.limits.speed()[i];
            let (mut sq, mut sv, mut sa) = (0.0, 0.0, 0.0);
            for h in 0..l {
                let rho = speed * chunk[1 + h].hypot(chunk[1 + l + h]);
                let w = self.frequency * (h + 1) as f64;
                (sq, sv, sa) = (sq + rho / w, sv + rho, sa + rho * w);
            }
            let mut scale: f64 = 1.0;
            for (bound, sum) in [(room, sq), (speed, sv), (self.limits.acceleration()[i], sa)] {
                if sum > 0.0 {
                    scale = scale.min(bound / sum);
                }
            }
            // A margin of round-off: the bounds are met with equality when
            // a limit is active, and the series' evaluation rounds.
            scale *= 1.0 - 1e-12;
            for h in 0..l {
                a[(i, h)] = scale * speed * chunk[1 + h];
                b[(i, h)] = scale * speed * chunk[1 + l + h];
            }
        }
        Fourier::new(self.frequency, offset, a, b)
    }
}

/// Offsets 0 (the middle of each range) and coefficients drawn evenly from
/// [−1, 1] by SplitMix64 from `seed`, in [`Shape`]'s layout.
fn seeded_start(seed: u64, joints: usize, harmonics: usize) -> DVector<f64> {
    let mut state = seed;
    DVector::from_fn(joints * (2 * harmonics + 1), |k, _| {
        if k % (2 * harmonics + 1) == 0 {
            return 0.0;
        }
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    })
}
