//! `impl Atlas` for a description with `emit(atlas)`: its Euler rotations
//! and its free twin (a private type that derefs to the user's struct, so
//! the twin's generated code reads the same fields), and `impl DrivenAtlas`:
//! the twin's forces of the user's inputs.

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::{Frame, impl_lagrangian};
use crate::ast::System;
use crate::atlas::EulerTriple;
use crate::mechanics::Model;

/// The twin's type, its `Lagrangian` impl and the user's `Atlas` impl.
pub fn impl_atlas(
    system: &System,
    model: &Model,
    twin: &System,
    twin_model: &Model,
    triples: &[EulerTriple],
) -> TokenStream {
    let f = Frame::new(system, model.dof(), model.configuration_len());
    let s = &f.s;
    let n = &f.n;
    let ident = f.ident;
    let (impl_generics, ty_generics, where_clause) =
        (&f.impl_generics, &f.ty_generics, &f.where_clause);
    let nf = Literal::usize_unsuffixed(twin_model.configuration_len());
    let (twin_impl_generics, twin_ty_generics, twin_where) = twin.generics.split_for_impl();
    let twin_ident = &twin.ident;
    let p = Literal::usize_unsuffixed(twin_model.inputs.as_ref().map_or(0, |i| i.names.len()));
    let twin_lagrangian = impl_lagrangian(twin, twin_model);
    let rotations = triples.iter().map(|t| {
        let (body, [c0, c1, c2], [a0, a1, a2]) = (&t.body, t.coordinates, t.axes);
        quote!(::lagrange::__private::EulerRotation {
            body: #body,
            coordinates: [#c0, #c1, #c2],
            axes: [#a0, #a1, #a2],
        })
    });
    quote! {
        struct #twin_ident #twin_impl_generics (&'__twin #ident #ty_generics) #twin_where;

        impl #twin_impl_generics ::core::ops::Deref for #twin_ident #twin_ty_generics #twin_where {
            type Target = #ident #ty_generics;
            fn deref(&self) -> &Self::Target {
                self.0
            }
        }

        #twin_lagrangian

        impl #impl_generics ::lagrange::__private::Atlas<#s, #n, #nf> for #ident #ty_generics #where_clause {
            const EULER: &'static [::lagrange::__private::EulerRotation] = &[#(#rotations),*];
            fn visit_free<V: ::lagrange::__private::FreeVisitor<#s, #n, #nf>>(&self, visitor: V) -> V::Output {
                visitor.visit(&#twin_ident(self))
            }
        }

        impl #impl_generics ::lagrange::__private::DrivenAtlas<#s, #n, #p, #nf> for #ident #ty_generics #where_clause {
            #[inline]
            fn free_input_forces(
                &self,
                q: &::lagrange::__private::SVector<#s, #nf>,
                v: &::lagrange::__private::SVector<#s, #n>,
                u: &::lagrange::__private::SVector<#s, #p>,
                t: #s,
            ) -> ::lagrange::__private::SVector<#s, #n> {
                ::lagrange::__private::Driven::<#s, #n, #p, #nf>::input_forces(&#twin_ident(self), q, v, u, t)
            }
        }
    }
}
