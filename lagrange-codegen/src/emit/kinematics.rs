//! `impl Kinematics` (`emit(kinematics)`): each body's frame Jacobian and J̇ q̇
//! as one program per body, chosen by its index, and the centre of mass with
//! its Jacobian.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::Frame;
use super::emitter::Emitter;
use crate::mechanics::Model;

/// A `match` on `body` with one arm per body, each evaluating `program(b)`
/// into `build(outs)`.
fn per_body(
    e: &Emitter,
    programs: &[Vec<Sym>],
    build: impl Fn(&[TokenStream]) -> TokenStream,
) -> TokenStream {
    let arms = programs.iter().enumerate().map(|(b, outputs)| {
        let (lets, outs) = e.program(outputs);
        let (b, value) = (Literal::usize_unsuffixed(b), build(&outs));
        quote!(#b => { #lets ::core::option::Option::Some(#value) })
    });
    quote! {
        match body {
            #(#arms)*
            _ => ::core::option::Option::None,
        }
    }
}

/// The `Kinematics` impl, when the model has its frames.
pub(super) fn impl_kinematics(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let Some(frames) = &model.frames else {
        return TokenStream::new();
    };
    let (s, nl) = (&f.s, &f.n);
    let (ident, ig, tg, wc) = (f.ident, &f.impl_generics, &f.ty_generics, &f.where_clause);
    let p = quote!(::lagrange::__private);
    let vec_n = quote!(#p::SVector<#s, #nl>);
    let (qvec, sizes) = (f.qvec(), f.sizes());
    let jacobian = per_body(
        e,
        &frames.jacobians,
        |outs| quote!(#p::SMatrix::<#s, 6, #nl>::from_row_slice(&[#(#outs),*])),
    );
    let bias = per_body(
        e,
        &frames.biases,
        |outs| quote!(#p::SVector::<#s, 6>::from_column_slice(&[#(#outs),*])),
    );
    let (com_lets, com) = e.program(&frames.com);
    let (jc_lets, jc) = e.program(&frames.com_jacobian);
    quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #p::Kinematics<#s, #sizes> for #ident #tg #wc {
            fn frame_jacobian(&self, body: usize, q: &#qvec, t: #s) -> ::core::option::Option<#p::SMatrix<#s, 6, #nl>> {
                #jacobian
            }

            fn frame_bias(&self, body: usize, q: &#qvec, v: &#vec_n, t: #s) -> ::core::option::Option<#p::SVector<#s, 6>> {
                #bias
            }

            fn center_of_mass(&self, q: &#qvec, t: #s) -> #p::Vector3<#s> {
                #com_lets
                #p::Vector3::new(#(#com),*)
            }

            fn center_of_mass_jacobian(&self, q: &#qvec, t: #s) -> #p::SMatrix<#s, 3, #nl> {
                #jc_lets
                #p::SMatrix::<#s, 3, #nl>::from_row_slice(&[#(#jc),*])
            }
        }
    }
}
