//! Benchmarks: see `benches/`; peers in `peer/` and, hand-written in Rust,
//! [`recursive`].

pub mod recursive;
