//! The constraints' reactions (`emit(reactions)`, with the multiplier form):
//! the inherent `REACTION_POINTS`, `reactions` and `generalized_reactions`.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Pieces;
use crate::ast::{Extra, System};
use crate::constraint::ConstraintSet;
use crate::emit::emitter::Emitter;
use crate::emit::{Frame, constant};
use crate::mechanics::Model;

pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, system: &System) -> Pieces {
    let wanted = system.extras.iter().any(|(_, x)| *x == Extra::Reactions);
    let Some(c) = model.constraints.multipliers.as_ref().filter(|_| wanted) else {
        return Pieces::default();
    };
    let mut inherent = reactions(e, f, model, system, c);
    inherent.extend(generalized_reactions(f, c));
    Pieces {
        inherent,
        ..Pieces::default()
    }
}

/// `REACTION_POINTS` and `reactions`: R = Σ_α ν_α ∂f_α/∂ξ per point.
fn reactions(
    e: &Emitter,
    f: &Frame,
    model: &Model,
    system: &System,
    c: &ConstraintSet,
) -> TokenStream {
    let s = &f.s;
    let nl = &f.n;
    let vec_n = f.vec(nl);
    let qvec = f.qvec();
    let k = c.names.len();
    let kl = Literal::usize_unsuffixed(k);
    let p = c.reactions.len();
    let pl = Literal::usize_unsuffixed(p);
    let dim = c.reactions.first().map_or(3, |(_, r)| r.len());
    let dl = Literal::usize_unsuffixed(dim);
    let vec_k = f.vec(&kl);
    let vec_d = f.vec(&dl);
    let coeffs: Vec<Sym> = c
        .reactions
        .iter()
        .flat_map(|(_, r)| r.iter().flatten().copied())
        .collect();
    let (lets, outs) = e.program(&coeffs);
    let zero = constant(&system.scalar, 0.0);
    let mut it = outs.iter();
    let mut idx = 0;
    let vectors: Vec<TokenStream> = c
        .reactions
        .iter()
        .map(|(_, r)| {
            let comps: Vec<TokenStream> = r
                .iter()
                .map(|row| {
                    let terms: Vec<TokenStream> = row
                        .iter()
                        .enumerate()
                        .filter_map(|(j, &coef)| {
                            let o = it.next();
                            idx += 1;
                            let o = o?;
                            if model.ctx.is_zero(coef) {
                                return None;
                            }
                            let j = Literal::usize_unsuffixed(j);
                            Some(quote!(#o * nu[#j]))
                        })
                        .collect();
                    if terms.is_empty() {
                        zero.clone()
                    } else {
                        quote!(#(#terms)+*)
                    }
                })
                .collect();
            quote!(<#vec_d>::from([#(#comps),*]))
        })
        .collect();
    let names: Vec<&String> = c.reactions.iter().map(|(n, _)| n).collect();
    quote! {
        /// Points and bodies that constraints act on, in the order of [`Self::reactions`].
        pub const REACTION_POINTS: [&'static str; #pl] = [#(#names),*];

        /// Cartesian constraint reactions R = Σ_α ν_α ∂f_α/∂ξ on each of
        /// [`Self::REACTION_POINTS`], from the multipliers ν the constrained
        /// dynamics compute. A constraint written in generalized coordinates
        /// only acts on no point and adds nothing here: its reaction is a
        /// generalized force, given by [`Self::generalized_reactions`].
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        pub fn reactions(&self, q: &#qvec, v: &#vec_n, t: #s, nu: &#vec_k) -> [#vec_d; #pl] {
            #lets
            [#(#vectors),*]
        }
    }
}

/// `generalized_reactions`: G_αᵀ ν_α per constraint, from the emitted G.
fn generalized_reactions(f: &Frame, c: &ConstraintSet) -> TokenStream {
    let kl = Literal::usize_unsuffixed(c.names.len());
    let s = &f.s;
    let vec_n = f.vec(&f.n);
    let vec_k = f.vec(&kl);
    let qvec = f.qvec();
    let sizes = f.sizes_after(&kl);
    quote! {
        /// Each constraint's generalized reaction G_αᵀ ν_α, in the order of
        /// `CONSTRAINTS`: the force (per velocity, an orientation's entries
        /// a torque in body axes) that constraint α adds to M q̈ + h = Q +
        /// Gᵀν. Defined for every constraint, on points or on coordinates;
        /// the sum over α is the whole constraint force Gᵀν.
        #[allow(clippy::all)]
        pub fn generalized_reactions(&self, q: &#qvec, t: #s, nu: &#vec_k) -> [#vec_n; #kl] {
            let (g, _) = <Self as ::lagrange::__private::Constrained<#s, #sizes>>::constraint_jacobian(self, q, t);
            ::core::array::from_fn(|a| g.row(a).transpose() * nu[a])
        }
    }
}
