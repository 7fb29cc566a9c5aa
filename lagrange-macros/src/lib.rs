//! The `#[derive(Lagrangian)]` proc macro. All the work happens in
//! `lagrange-codegen`, an ordinary library that can be tested and benchmarked
//! without a compiler in the loop.

#![warn(missing_docs)]

use proc_macro::TokenStream;

/// Derives `lagrange::Lagrangian` from a `#[lagrange(...)]` description of the system.
/// See the `lagrange` crate documentation for the description language.
#[proc_macro_derive(Lagrangian, attributes(lagrange))]
pub fn derive_lagrangian(input: TokenStream) -> TokenStream {
    lagrange_codegen::derive(input.into()).into()
}
