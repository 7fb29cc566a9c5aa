//! The optional outputs, one module each: what each adds to the derived code,
//! read from its own part of the model ([`crate::mechanics::Outputs`], and
//! the multiplier form's reactions). A new output is a module here and a line
//! in [`OUTPUTS`].

mod articulated;
mod batched;
mod coriolis;
mod hamilton;
mod inverse;
mod jacobians;
mod kinematics;
mod reactions;
mod regressor;
mod solved;

pub(super) use kinematics::{Signature, per_body};

use proc_macro2::TokenStream;

use super::Frame;
use super::emitter::Emitter;
use crate::ast::System;
use crate::mechanics::Model;

/// What an output adds, by where it goes; empty for an output the model
/// does not have.
#[derive(Default)]
pub(super) struct Pieces {
    /// Methods of `impl Lagrangian` (overriding the trait's defaults).
    pub lagrangian: TokenStream,
    /// Inherent methods and constants beside `EQUATIONS`.
    pub inherent: TokenStream,
    /// Hidden inherent methods over the hoisted parameter terms `p`, and
    /// the pieces of a large program (this impl allows generated code's lints).
    pub hoisted: TokenStream,
    /// Items of their own: impls of further traits.
    pub items: TokenStream,
}

impl Pieces {
    fn extend(&mut self, other: Pieces) {
        self.lagrangian.extend(other.lagrangian);
        self.inherent.extend(other.inherent);
        self.hoisted.extend(other.hoisted);
        self.items.extend(other.items);
    }
}

/// One output's emitter: its pieces, from its part of `model`.
type Output = fn(&Emitter, &Frame, &Model, &System) -> Pieces;

/// Every optional output, in the order their pieces are emitted.
const OUTPUTS: [Output; 10] = [
    hamilton::pieces,
    jacobians::pieces,
    solved::pieces,
    inverse::pieces,
    articulated::pieces,
    reactions::pieces,
    coriolis::pieces,
    kinematics::pieces,
    batched::pieces,
    regressor::pieces,
];

/// The pieces of every output the model has.
pub(super) fn outputs(e: &Emitter, f: &Frame, model: &Model, system: &System) -> Pieces {
    let mut all = Pieces::default();
    for output in OUTPUTS {
        all.extend(output(e, f, model, system));
    }
    all
}
