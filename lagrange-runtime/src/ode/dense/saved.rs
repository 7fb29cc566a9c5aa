//! The saved form of a [`DenseSegment`]: its fields, with the quaternions'
//! layout as data. A segment holds its layout as `&'static` (a system's
//! `ORIENTATIONS`, shared by every segment of a run, so a segment stays
//! `Copy`); one read back is interned: each distinct layout is stored once
//! for the life of the process, so reading runs does not grow memory with
//! their number.

use super::DenseSegment;
use crate::numeric::Real;
use crate::numeric::orientation::{self, Orientation};
use crate::ode::Pair;
use std::sync::Mutex;

#[derive(Clone, serde::Serialize, serde::Deserialize)]
pub(crate) struct Saved<T: Real, const N: usize, const Q: usize> {
    t0: T,
    t1: T,
    h: T,
    r: [Pair<T, N, Q>; 8],
    used: usize,
    #[serde(default)]
    orientations: Vec<Orientation>,
}

impl<T: Real, const N: usize, const Q: usize> From<DenseSegment<T, N, Q>> for Saved<T, N, Q> {
    fn from(s: DenseSegment<T, N, Q>) -> Self {
        Saved {
            t0: s.t0,
            t1: s.t1,
            h: s.h,
            r: s.r,
            used: s.used,
            orientations: s.orientations.to_vec(),
        }
    }
}

impl<T: Real, const N: usize, const Q: usize> TryFrom<Saved<T, N, Q>> for DenseSegment<T, N, Q> {
    type Error = String;

    /// Refuses what no run writes (a layout that does not fit q and v, a
    /// coefficient count out of range), which reading would otherwise index
    /// out of bounds.
    fn try_from(s: Saved<T, N, Q>) -> Result<Self, String> {
        if !(1..=8).contains(&s.used) {
            return Err(format!(
                "a dense segment uses {} coefficients (1 to 8)",
                s.used
            ));
        }
        if !orientation::fits(&s.orientations, Q, N) {
            return Err(format!(
                "orientations {:?} do not fit a configuration of {Q} numbers with {N} velocities",
                s.orientations
            ));
        }
        Ok(DenseSegment {
            t0: s.t0,
            t1: s.t1,
            h: s.h,
            r: s.r,
            used: s.used,
            orientations: intern(s.orientations),
        })
    }
}

/// The one stored copy of `layout`.
fn intern(layout: Vec<Orientation>) -> &'static [Orientation] {
    static LAYOUTS: Mutex<Vec<&'static [Orientation]>> = Mutex::new(Vec::new());
    if layout.is_empty() {
        return &[];
    }
    let mut all = LAYOUTS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(&known) = all.iter().find(|&&l| l == layout.as_slice()) {
        return known;
    }
    let stored: &'static [Orientation] = Box::leak(layout.into_boxed_slice());
    all.push(stored);
    stored
}
