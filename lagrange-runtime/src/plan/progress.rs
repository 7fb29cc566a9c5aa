//! The progress bar of a long solve, behind the feature `progress`: the
//! iterations against the budget, with the cost and the largest gap. Drawn
//! on standard error only when asked for ([`Ddp::progress`](super::Ddp)),
//! cleared when the solve returns; without the feature, nothing.

use super::ddp::Iteration;

/// The bar, if one is drawn; cleared when dropped.
pub(super) struct Ticker {
    #[cfg(feature = "progress")]
    bar: Option<indicatif::ProgressBar>,
}

impl Ticker {
    /// A bar over `budget` iterations when `show`.
    #[cfg_attr(not(feature = "progress"), allow(unused_variables))]
    pub fn new(show: bool, budget: usize) -> Self {
        #[cfg(feature = "progress")]
        {
            let bar = show.then(|| {
                let bar = indicatif::ProgressBar::new(budget as u64);
                let template = "{bar:40} {pos}/{len} iterations {msg}";
                if let Ok(style) = indicatif::ProgressStyle::with_template(template) {
                    bar.set_style(style);
                }
                bar
            });
            Self { bar }
        }
        #[cfg(not(feature = "progress"))]
        Self {}
    }

    /// One iteration done.
    #[cfg_attr(not(feature = "progress"), allow(unused_variables))]
    pub fn tick(&self, it: &Iteration) {
        #[cfg(feature = "progress")]
        if let Some(bar) = &self.bar {
            bar.inc(1);
            bar.set_message(format!("cost {:.6e}  gap {:.1e}", it.cost, it.gap));
        }
    }
}

#[cfg(feature = "progress")]
impl Drop for Ticker {
    fn drop(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
