//! Inputs kept within bounds: an actuator's effort limits on whatever
//! source drives the run ([`Simulation::input_limits`]), and where the run
//! held them there ([`ControlRun::saturations`]).
//!
//! [`Simulation::input_limits`]: crate::Simulation::input_limits
//! [`ControlRun::saturations`]: crate::ControlRun::saturations

use super::InputSource;
use crate::error::{Error, SettingsError};
use crate::numeric::Real;
use nalgebra::SVector;

/// A source whose inputs are clamped into [lower, upper], each input on
/// its own: a motor that cannot give more than its rated torque whatever
/// its controller asks. Built by
/// [`Simulation::input_limits`](crate::Simulation::input_limits).
#[derive(Clone, Debug)]
pub struct Saturated<C, const P: usize> {
    source: C,
    lower: [f64; P],
    upper: [f64; P],
    /// Each input's joint (its index in v) and no-load speed, where the
    /// torque–speed line narrows the bounds.
    speeds: Option<([usize; P], [f64; P])>,
}

impl<C, const P: usize> Saturated<C, P> {
    /// `source` with its inputs clamped into [lower, upper].
    pub fn new(source: C, lower: [f64; P], upper: [f64; P]) -> Self {
        Self {
            source,
            lower,
            upper,
            speeds: None,
        }
    }

    /// The same, each input k's bounds also narrowed by its motor's
    /// torque–speed line: driving the joint at `joints[k]` (its index in
    /// v) at speed w in the bound's own direction leaves that bound times
    /// max(0, 1 − |w|/`no_load[k]`), the full bound against the motion.
    pub fn with_speeds(mut self, joints: [usize; P], no_load: [f64; P]) -> Self {
        self.speeds = Some((joints, no_load));
        self
    }
}

/// Input k's bounds (lower, upper) at the velocities v: the effort limits,
/// each narrowed by the torque–speed line where `speeds` gives one (see
/// [`Saturated::with_speeds`]). One function for the clamp and for the
/// report of where it held, so that the two agree to the bit.
pub(crate) fn bounds_at<T: Real, const N: usize, const P: usize>(
    (lower, upper): ([f64; P], [f64; P]),
    speeds: Option<([usize; P], [f64; P])>,
    k: usize,
    v: &SVector<T, N>,
) -> (T, T) {
    let (lo, hi) = (T::lit(lower[k]), T::lit(upper[k]));
    let Some((joints, no_load)) = speeds else {
        return (lo, hi);
    };
    // An index past v is refused before the run (`check_speeds`).
    let Some(&w) = v.as_slice().get(joints[k]) else {
        return (lo, hi);
    };
    let left = T::one() - w.abs() / T::lit(no_load[k]);
    let share = left.max(T::zero()).min(T::one());
    // A bound pushing along the motion is narrowed; one against it is not.
    let narrowed = |bound: T| match (bound * w) > T::zero() {
        true => bound * share,
        false => bound,
    };
    (narrowed(lo), narrowed(hi))
}

impl<T, C, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for Saturated<C, P>
where
    T: Real,
    C: InputSource<T, N, P, Q>,
{
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        self.limit(t, q, v, self.source.input(t, q, v))
    }

    fn limit(
        &self,
        _: T,
        _: &SVector<T, Q>,
        v: &SVector<T, N>,
        mut u: SVector<T, P>,
    ) -> SVector<T, P> {
        for (k, x) in u.iter_mut().enumerate() {
            let (lo, hi) = bounds_at((self.lower, self.upper), self.speeds, k, v);
            // A NaN stays NaN: the run refuses it, naming the input.
            *x = x.max(lo).min(hi);
        }
        u
    }

    fn next_break(&self, start: T, after: T) -> Option<T> {
        self.source.next_break(start, after)
    }

    fn held(&self) -> bool {
        self.source.held()
    }

    fn breaks_within(&self, start: T, end: T) -> Option<f64> {
        self.source.breaks_within(start, end)
    }

    /// Each bound not NaN, lower ≤ upper (an infinite bound is none), and
    /// the source's own settings.
    fn check(&self) -> Result<(), Error> {
        for k in 0..P {
            let (lo, hi) = (self.lower[k], self.upper[k]);
            if lo.is_nan() || hi.is_nan() || lo > hi {
                return Err(SettingsError::Value {
                    owner: "input limits",
                    setting: "lower",
                    value: lo,
                    requirement: format!("a number at most the upper bound {hi} (input {k})"),
                }
                .into());
            }
        }
        if let Some((joints, no_load)) = self.speeds {
            check_speeds::<N, P>(joints, no_load)?;
        }
        self.source.check()
    }

    fn bounds(&self) -> Option<([f64; P], [f64; P])> {
        Some((self.lower, self.upper))
    }

    fn speed_limits(&self) -> Option<([usize; P], [f64; P])> {
        self.speeds
    }
}

/// Each no-load speed positive (∞ for none) and each joint an index into
/// the N velocities.
fn check_speeds<const N: usize, const P: usize>(
    joints: [usize; P],
    no_load: [f64; P],
) -> Result<(), Error> {
    for k in 0..P {
        let w = no_load[k];
        if w.is_nan() || w <= 0.0 {
            return Err(SettingsError::Value {
                owner: "speed limits",
                setting: "no_load",
                value: w,
                requirement: format!("positive (input {k}; ∞ for none)"),
            }
            .into());
        }
        if joints[k] >= N {
            return Err(SettingsError::Value {
                owner: "speed limits",
                setting: "joints",
                value: joints[k] as f64,
                requirement: format!("an index into the {N} velocities (input {k})"),
            }
            .into());
        }
    }
    Ok(())
}

/// A stretch of a controlled run during which an input was held at one of
/// its limits ([`ControlRun::saturations`](crate::ControlRun::saturations)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Saturation<T> {
    /// Which input (its index in [`Driven::INPUTS`](crate::Driven::INPUTS)).
    pub input: usize,
    /// The first recorded point at which it was at the limit.
    pub from: T,
    /// The first recorded point after `from` at which it was not (the
    /// run's end if it stayed there).
    pub to: T,
    /// At the upper limit (`true`) or the lower one.
    pub upper: bool,
}

/// The stretches of `inputs` (at `times`, with the velocities `v`) held
/// at a bound of `bounds`, narrowed by `speeds` as the clamp narrowed them.
pub(crate) fn stretches<T: Real, const N: usize, const P: usize>(
    (times, v): (&[T], &[SVector<T, N>]),
    inputs: &[SVector<T, P>],
    bounds: ([f64; P], [f64; P]),
    speeds: Option<([usize; P], [f64; P])>,
) -> Vec<Saturation<T>> {
    let mut out: Vec<Saturation<T>> = Vec::new();
    for k in 0..P {
        let mut open: Option<Saturation<T>> = None;
        for ((&t, u), v) in times.iter().zip(inputs).zip(v) {
            let (lower, upper) = bounds_at(bounds, speeds, k, v);
            let side = if u[k] == upper {
                Some(true)
            } else if u[k] == lower {
                Some(false)
            } else {
                None
            };
            match (&mut open, side) {
                (Some(s), Some(up)) if s.upper == up => s.to = t,
                (_, side) => {
                    if let Some(mut s) = open.take() {
                        s.to = t;
                        out.push(s);
                    }
                    open = side.map(|up| Saturation {
                        input: k,
                        from: t,
                        to: t,
                        upper: up,
                    });
                }
            }
        }
        out.extend(open);
    }
    out.sort_by(|a, b| {
        a.from
            .partial_cmp(&b.from)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    out
}
