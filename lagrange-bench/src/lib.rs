//! Benchmarks: see `benches/`; peers in `peer/` and, hand-written in Rust,
//! [`recursive`] and [`closed_form`].

pub mod closed_form;
pub mod recursive;
