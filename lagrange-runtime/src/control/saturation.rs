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
}

impl<C, const P: usize> Saturated<C, P> {
    /// `source` with its inputs clamped into [lower, upper].
    pub fn new(source: C, lower: [f64; P], upper: [f64; P]) -> Self {
        Self {
            source,
            lower,
            upper,
        }
    }
}

impl<T, C, const N: usize, const P: usize, const Q: usize> InputSource<T, N, P, Q>
    for Saturated<C, P>
where
    T: Real,
    C: InputSource<T, N, P, Q>,
{
    fn input(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> SVector<T, P> {
        let mut u = self.source.input(t, q, v);
        for (k, x) in u.iter_mut().enumerate() {
            // A NaN stays NaN: the run refuses it, naming the input.
            *x = x.max(T::lit(self.lower[k])).min(T::lit(self.upper[k]));
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
        self.source.check()
    }

    fn bounds(&self) -> Option<([f64; P], [f64; P])> {
        Some((self.lower, self.upper))
    }
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

/// The stretches of `inputs` (at `times`) held at a bound of `bounds`.
pub(crate) fn stretches<T: Real, const P: usize>(
    times: &[T],
    inputs: &[SVector<T, P>],
    (lower, upper): ([f64; P], [f64; P]),
) -> Vec<Saturation<T>> {
    let mut out: Vec<Saturation<T>> = Vec::new();
    for k in 0..P {
        let mut open: Option<Saturation<T>> = None;
        for (&t, u) in times.iter().zip(inputs) {
            let side = if u[k] == T::lit(upper[k]) {
                Some(true)
            } else if u[k] == T::lit(lower[k]) {
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
