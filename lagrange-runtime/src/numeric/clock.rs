//! Wall-clock time for the statistics, where the platform has a clock.
//!
//! `std::time::Instant::now` panics on `wasm32-unknown-unknown`, which has no
//! clock; the integrators must run there all the same, so the time they report
//! is optional: zero on such targets.

use std::time::Duration;

/// Measures the wall time of a run, or nothing where there is no clock.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stopwatch {
    #[cfg(not(all(target_family = "wasm", target_os = "unknown")))]
    started: std::time::Instant,
}

impl Stopwatch {
    /// Starts measuring.
    pub(crate) fn start() -> Self {
        Self {
            #[cfg(not(all(target_family = "wasm", target_os = "unknown")))]
            started: std::time::Instant::now(),
        }
    }

    /// The time since [`start`](Self::start); zero without a clock.
    pub(crate) fn elapsed(&self) -> Duration {
        #[cfg(not(all(target_family = "wasm", target_os = "unknown")))]
        {
            self.started.elapsed()
        }
        #[cfg(all(target_family = "wasm", target_os = "unknown"))]
        {
            Duration::ZERO
        }
    }
}
