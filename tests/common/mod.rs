//! Helpers shared by the root crate's integration tests, one module per kind
//! (`numeric`: random states and finite differences). The catalog systems
//! themselves are shared through `examples/catalog`.
#![allow(dead_code)] // each test binary uses a different subset

pub mod numeric;
