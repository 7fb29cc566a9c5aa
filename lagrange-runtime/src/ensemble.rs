//! Ensembles: many independent runs (initial conditions, parameter sets) on
//! all cores, with a progress bar on long work (feature `parallel`).
//!
//! Each run is a pure function of its index and its input, and the results
//! come back in input order, so an ensemble gives the same results whatever
//! the number of threads: a seed for a random draw is the run's index, not a
//! shared generator.
//!
//! Sweeps larger than one machine are split into shards: machine k of K runs
//! [`shard(len, k, K)`](shard) of the inputs (contiguous index ranges whose
//! sizes differ by at most one), writes its results with their indices, and
//! any batch system (a job array, `xargs -P`, a cluster scheduler) runs the
//! shards; concatenating the outputs in shard order gives exactly the
//! single-machine result.
//!
//! ```
//! use lagrange_runtime::ensemble::Ensemble;
//! // The squares of 0..1000 on all cores, in order.
//! let inputs: Vec<f64> = (0..1000).map(f64::from).collect();
//! let out = Ensemble::new().progress(false).run(&inputs, |_, x| x * x);
//! assert_eq!(out[999], 998_001.0);
//! ```

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use rayon::prelude::*;
use std::ops::Range;
use std::time::Duration;

/// How an ensemble is run: on rayon's global pool (all cores) or a pool of a
/// given size, with or without a progress bar.
#[derive(Clone, Debug)]
pub struct Ensemble {
    progress: bool,
    threads: Option<usize>,
    label: String,
}

impl Default for Ensemble {
    fn default() -> Self {
        Self::new()
    }
}

impl Ensemble {
    /// All cores, a progress bar on a terminal.
    pub fn new() -> Self {
        Self {
            progress: true,
            threads: None,
            label: "runs".into(),
        }
    }

    /// Whether to draw a progress bar on stderr (default on; it is hidden
    /// anyway when stderr is not a terminal, e.g. in CI or a pipe).
    pub fn progress(mut self, on: bool) -> Self {
        self.progress = on;
        self
    }

    /// The word after the count on the progress bar ("runs").
    pub fn label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }

    /// Runs on a pool of `n` threads instead of all cores (the results are
    /// the same; only the wall time changes). `n` = 0 is taken as 1.
    pub fn threads(mut self, n: usize) -> Self {
        self.threads = Some(n.max(1));
        self
    }

    /// `run(i, &inputs[i])` for every input, in parallel; the results in input
    /// order.
    ///
    /// # Panics
    /// If a pool of the requested size cannot be created (the operating
    /// system refused the threads) or a run panics.
    pub fn run<P, R, F>(&self, inputs: &[P], run: F) -> Vec<R>
    where
        P: Sync,
        R: Send,
        F: Fn(usize, &P) -> R + Sync + Send,
    {
        let bar = self.bar(inputs.len());
        let work = || {
            inputs
                .par_iter()
                .enumerate()
                .map(|(i, p)| {
                    let r = run(i, p);
                    bar.inc(1);
                    r
                })
                .collect::<Vec<R>>()
        };
        let out = match self.threads {
            None => work(),
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .expect("the operating system refused the ensemble's threads")
                .install(work),
        };
        bar.finish_and_clear();
        out
    }

    fn bar(&self, len: usize) -> ProgressBar {
        let bar = ProgressBar::with_draw_target(
            Some(len as u64),
            if self.progress {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            },
        );
        let template = format!("{{bar:40}} {{pos}}/{{len}} {} ({{left}})", self.label);
        let workers = self.threads.unwrap_or_else(rayon::current_num_threads) as u64;
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style.with_key(
                "left",
                move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let text = time_left(state.pos(), state.len(), state.elapsed(), workers);
                    let _ = w.write_str(&text);
                },
            ));
        }
        bar
    }
}

/// The time left, from the mean rate since the start: elapsed / done per run.
/// Until every worker has finished a run, the runs that finished first are
/// only the first wave, and a per-run time read from them overestimates the
/// total by up to the number of workers (17 s shown for a 3 s job), so the
/// bar says it is still estimating.
fn time_left(done: u64, len: Option<u64>, elapsed: Duration, workers: u64) -> String {
    let Some(len) = len else {
        return "estimating the time left".into();
    };
    if done < workers.max(1).min(len) || done == 0 {
        return "estimating the time left".into();
    }
    let left = elapsed.as_secs_f64() / done as f64 * len.saturating_sub(done) as f64;
    if left < 60.0 {
        format!("{left:.0} s left")
    } else {
        format!("{:.0} min {:.0} s left", (left / 60.0).floor(), left % 60.0)
    }
}

/// The indices of shard `k` of `count` over `len` inputs: contiguous ranges
/// that cover 0..len in order, sizes differing by at most one (the first
/// `len % count` shards have one more). `count` 0 is taken as 1, and a `k`
/// past the last shard gets an empty range.
pub fn shard(len: usize, k: usize, count: usize) -> Range<usize> {
    let count = count.max(1);
    if k >= count {
        return len..len;
    }
    let base = len / count;
    let extra = len % count;
    let start = k * base + k.min(extra);
    let size = base + usize::from(k < extra);
    start..start + size
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_left_waits_for_the_first_wave_then_uses_the_mean_rate() {
        let s = Duration::from_secs;
        // One run done of 100 on four workers: the first wave is not over.
        assert_eq!(time_left(1, Some(100), s(1), 4), "estimating the time left");
        assert_eq!(time_left(0, Some(100), s(0), 1), "estimating the time left");
        // 50 of 100 in 10 s: 10 s more at the same rate.
        assert_eq!(time_left(50, Some(100), s(10), 2), "10 s left");
        assert_eq!(time_left(10, Some(100), s(20), 2), "3 min 0 s left");
        assert_eq!(time_left(3, Some(3), s(3), 8), "0 s left");
    }

    #[test]
    fn shards_cover_the_inputs_in_order() {
        for len in [0, 1, 7, 100, 101] {
            for count in [1, 2, 3, 8] {
                let ranges: Vec<Range<usize>> = (0..count).map(|k| shard(len, k, count)).collect();
                let all: Vec<usize> = ranges.iter().flat_map(|r| r.clone()).collect();
                assert_eq!(
                    all,
                    (0..len).collect::<Vec<_>>(),
                    "len {len}, count {count}"
                );
                let sizes: Vec<usize> = ranges.iter().map(|r| r.len()).collect();
                let lo = sizes.iter().min().unwrap();
                let hi = sizes.iter().max().unwrap();
                assert!(hi - lo <= 1);
            }
        }
        assert_eq!(shard(10, 5, 3), 10..10);
    }

    #[test]
    fn results_are_in_order_and_independent_of_the_thread_count() {
        let inputs: Vec<u64> = (0..500).collect();
        // A run whose result depends on its index and input only.
        let f = |i: usize, x: &u64| {
            let mut h = *x ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            for _ in 0..100 {
                h = h
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
            }
            h
        };
        let one = Ensemble::new().progress(false).threads(1).run(&inputs, f);
        let many = Ensemble::new().progress(false).threads(4).run(&inputs, f);
        assert_eq!(one, many);
        assert_eq!(one[17], f(17, &17));
    }
}
