//! `impl Kinematics` (`emit(kinematics)`): each body's frame Jacobian and J̇ q̇
//! as one program per body, chosen by its index, and the centre of mass with
//! its Jacobian. Each body's program is a hidden inherent method of its own
//! (not inlined): one function holding every body's made LLVM's optimisation
//! superlinear in the bodies (the Kinova's twelve links took 47 s of CPU to
//! build in release, one function per body takes a few).

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::Pieces;
use crate::ast::System;
use crate::emit::Frame;
use crate::emit::emitter::Emitter;
use crate::mechanics::Model;

/// The per-body methods' signature: the stem of their names, their
/// parameters, the arguments the dispatch passes, their return type.
pub(in crate::emit) struct Signature<'a> {
    pub name: &'a str,
    pub params: &'a TokenStream,
    pub args: TokenStream,
    pub ty: &'a TokenStream,
}

/// A `match` on `body` with one arm per body, each calling that body's
/// method `__lagrange_<name>_<b>(&self, <args>)`, and those methods, each
/// evaluating `program(b)` into `build(outs)` of type `ty`.
pub(in crate::emit) fn per_body(
    e: &Emitter,
    signature: Signature,
    programs: &[Vec<Sym>],
    build: impl Fn(&[TokenStream]) -> TokenStream,
) -> (TokenStream, TokenStream) {
    let Signature {
        name,
        params,
        args,
        ty,
    } = signature;
    let mut arms = Vec::new();
    let mut methods = Vec::new();
    for (b, outputs) in programs.iter().enumerate() {
        let (lets, outs) = e.program(outputs);
        let method = format_ident!("__lagrange_{name}_{b}");
        let b = Literal::usize_unsuffixed(b);
        let value = build(&outs);
        arms.push(quote!(#b => ::core::option::Option::Some(self.#method(#args)),));
        methods.push(quote! {
            #[doc(hidden)]
            #[inline(never)]
            pub fn #method(&self, #params) -> #ty {
                #lets
                #value
            }
        });
    }
    let dispatch = quote! {
        match body {
            #(#arms)*
            _ => ::core::option::Option::None,
        }
    };
    (dispatch, quote!(#(#methods)*))
}

/// The `Kinematics` impl, when the model has its frames.
pub(super) fn pieces(e: &Emitter, f: &Frame, model: &Model, _: &System) -> Pieces {
    let Some(frames) = &model.outputs.frames else {
        return Pieces::default();
    };
    let s = &f.s;
    let nl = &f.n;
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    let p = quote!(::lagrange::__private);
    let vec_n = quote!(#p::SVector<#s, #nl>);
    let qvec = f.qvec();
    let sizes = f.sizes();
    let (q_t, v_t) = (
        quote!(q: &#qvec, t: #s),
        quote!(q: &#qvec, v: &#vec_n, t: #s),
    );
    let jacobian_ty = quote!(#p::SMatrix<#s, 6, #nl>);
    let bias_ty = quote!(#p::SVector<#s, 6>);
    let (jacobian, jacobian_methods) = per_body(
        e,
        Signature {
            name: "frame_jacobian",
            params: &q_t,
            args: quote!(q, t),
            ty: &jacobian_ty,
        },
        &frames.jacobians,
        |outs| quote!(#p::SMatrix::<#s, 6, #nl>::from_row_slice(&[#(#outs),*])),
    );
    let (bias, bias_methods) = per_body(
        e,
        Signature {
            name: "frame_bias",
            params: &v_t,
            args: quote!(q, v, t),
            ty: &bias_ty,
        },
        &frames.biases,
        |outs| quote!(#p::SVector::<#s, 6>::from_column_slice(&[#(#outs),*])),
    );
    let (com_lets, com) = e.program(&frames.com);
    let (jc_lets, jc) = e.program(&frames.com_jacobian);
    let items = quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #ident #tg #wc {
            #jacobian_methods
            #bias_methods
        }

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
    };
    Pieces {
        items,
        ..Pieces::default()
    }
}
