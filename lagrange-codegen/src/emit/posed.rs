//! `impl Posed`: the world pose of every body and the position of every point
//! as one straight-line program in (q, t), the bodies' masses and inertias, and
//! the `shape(...)` items. Emitted for every description: the methods are
//! `#[inline]`, so a program that never draws a scene never compiles their
//! machine code. With `emit(kinematics)` it also overrides `frame_pose`: one
//! program per body (a hidden inherent method each, as the frame Jacobians),
//! so asking for one frame computes that frame alone.

use lagrange_symbolic::Expr as Sym;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::emitter::Emitter;
use super::output::{Signature, per_body};
use super::{Frame, constant};
use crate::ast::Scalar;
use crate::lowered::{Anchor, Poses, SolidModel};
use crate::mechanics::Model;

/// The `Posed` impl of a derived description.
pub(super) fn impl_posed(e: &Emitter, f: &Frame, model: &Model, scalar: &Scalar) -> TokenStream {
    let poses = &model.poses;
    let s = &f.s;
    let sizes = f.sizes();
    let qvec = f.qvec();
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    let p = quote!(::lagrange::__private);
    let bodies: Vec<&String> = poses.bodies.iter().map(|b| &b.name).collect();
    let points: Vec<&String> = poses.points.iter().map(|b| &b.name).collect();
    let on: Vec<TokenStream> = poses.points.iter().map(|x| option(x.body)).collect();
    let pose_body = pose_program(e, poses, scalar);
    let inertia_body = inertia_program(e, poses);
    let shape_body = shape_program(e, poses, scalar);
    let (frame_pose, frame_pose_methods) = frame_pose(e, f, model, scalar);
    quote! {
        #frame_pose_methods

        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #p::Posed<#s, #sizes> for #ident #tg #wc {
            const BODIES: &'static [&'static str] = &[#(#bodies),*];
            const POINTS: &'static [&'static str] = &[#(#points),*];
            const POINT_BODIES: &'static [::core::option::Option<usize>] = &[#(#on),*];

            #[inline]
            fn poses(&self, q: &#qvec, t: #s, bodies: &mut [#p::BodyPose<#s>], points: &mut [#p::Vector3<#s>]) {
                #pose_body
            }

            #[inline]
            fn inertias(&self, out: &mut [#p::BodyInertia<#s>]) {
                #inertia_body
            }

            #[inline]
            fn shapes(&self, out: &mut dyn FnMut(#p::Shape<#s>)) {
                #shape_body
            }

            #frame_pose
        }
    }
}

/// With the model's frames (`emit(kinematics)`), the override of
/// `Posed::frame_pose` dispatching on the body to one hidden method per body,
/// each evaluating that body's pose alone, and the inherent impl holding
/// those methods; without, nothing (the trait's default fills every pose).
fn frame_pose(
    e: &Emitter,
    f: &Frame,
    model: &Model,
    scalar: &Scalar,
) -> (TokenStream, TokenStream) {
    if model.outputs.frames.is_none() {
        return (TokenStream::new(), TokenStream::new());
    }
    let s = &f.s;
    let qvec = f.qvec();
    let p = quote!(::lagrange::__private);
    let params = quote!(q: &#qvec, t: #s);
    let ty = quote!(#p::BodyPose<#s>);
    let programs: Vec<Vec<Sym>> = model
        .poses
        .bodies
        .iter()
        .map(|b| {
            let mut all = b.origin.clone();
            all.extend(&b.centre);
            all.extend(b.rotation.iter().flatten());
            all
        })
        .collect();
    let (dispatch, methods) = per_body(
        e,
        Signature {
            name: "frame_pose",
            params: &params,
            args: quote!(q, t),
            ty: &ty,
        },
        &programs,
        |outs| {
            // Origin and centre have two components each in a planar
            // description, three otherwise; the rotation has nine.
            let k = (outs.len() - 9) / 2;
            let origin = vector3(&outs[..k], scalar);
            let centre = vector3(&outs[k..2 * k], scalar);
            let rotation = matrix3(&outs[2 * k..]);
            quote!(#p::BodyPose { origin: #origin, centre: #centre, rotation: #rotation })
        },
    );
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    let items = quote! {
        #[automatically_derived]
        #[allow(unused_variables, clippy::all)]
        impl #ig #ident #tg #wc {
            #methods
        }
    };
    let method = quote! {
        fn frame_pose(&self, body: usize, q: &#qvec, t: #s) -> ::core::option::Option<#ty> {
            #dispatch
        }
    };
    (method, items)
}

/// An index as an unsuffixed literal.
fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

fn option(i: Option<usize>) -> TokenStream {
    match i.map(index) {
        Some(i) => quote!(::core::option::Option::Some(#i)),
        None => quote!(::core::option::Option::None),
    }
}

/// Three outputs as `Vector3::new(..)`, a planar position padded with z = 0.
fn vector3(outs: &[TokenStream], scalar: &Scalar) -> TokenStream {
    let zero = constant(scalar, 0.0);
    let z = outs.get(2).cloned().unwrap_or(zero);
    let x = &outs[0];
    let y = &outs[1];
    quote!(::lagrange::__private::Vector3::new(#x, #y, #z))
}

fn matrix3(outs: &[TokenStream]) -> TokenStream {
    quote!(::lagrange::__private::Matrix3::new(#(#outs),*))
}

/// Origins, centres and rotations of the bodies, then the points, in one
/// program so that the shared sines and cosines are computed once.
fn pose_program(e: &Emitter, poses: &Poses, scalar: &Scalar) -> TokenStream {
    let mut all: Vec<Sym> = Vec::new();
    for b in &poses.bodies {
        all.extend(&b.origin);
        all.extend(&b.centre);
        all.extend(b.rotation.iter().flatten());
    }
    for x in &poses.points {
        all.extend(&x.position);
    }
    let (lets, outs) = e.program(&all);
    let mut rest = &outs[..];
    let mut sets = TokenStream::new();
    for i in (0..poses.bodies.len()).map(index) {
        let (mine, tail) = rest.split_at(15);
        rest = tail;
        let origin = vector3(&mine[..3], scalar);
        let centre = vector3(&mine[3..6], scalar);
        let rotation = matrix3(&mine[6..]);
        sets.extend(quote! {
            bodies[#i] = ::lagrange::__private::BodyPose { origin: #origin, centre: #centre, rotation: #rotation };
        });
    }
    for (i, x) in poses.points.iter().enumerate() {
        let (mine, tail) = rest.split_at(x.position.len());
        rest = tail;
        let i = index(i);
        let position = vector3(mine, scalar);
        sets.extend(quote!(points[#i] = #position;));
    }
    quote!(#lets #sets)
}

/// Each body's mass and inertia about its centre in body axes.
fn inertia_program(e: &Emitter, poses: &Poses) -> TokenStream {
    let mut all: Vec<Sym> = Vec::new();
    for b in &poses.bodies {
        all.push(b.mass);
        all.extend(b.inertia.iter().flatten());
    }
    let (lets, outs) = e.program(&all);
    let sets = outs.chunks(10).enumerate().map(|(i, c)| {
        let i = index(i);
        let mass = &c[0];
        let inertia = matrix3(&c[1..]);
        quote!(out[#i] = ::lagrange::__private::BodyInertia { mass: #mass, inertia: #inertia };)
    });
    quote!(#lets #(#sets)*)
}

fn anchor(a: Anchor) -> TokenStream {
    match a {
        Anchor::Body(i) => {
            let i = index(i);
            quote!(::lagrange::__private::Anchor::Body(#i))
        }
        Anchor::Point(i) => {
            let i = index(i);
            quote!(::lagrange::__private::Anchor::Point(#i))
        }
    }
}

/// The shapes in order, their sizes and offsets from the parameters.
fn shape_program(e: &Emitter, poses: &Poses, scalar: &Scalar) -> TokenStream {
    let mut all: Vec<Sym> = Vec::new();
    for shape in &poses.shapes {
        all.extend(&shape.at);
        all.extend(sizes(&shape.solid));
    }
    let (lets, outs) = e.program(&all);
    let mut rest = &outs[..];
    let zero = constant(scalar, 0.0);
    let p = quote!(::lagrange::__private);
    let calls = poses.shapes.iter().map(|shape| {
        let (at, tail) = rest.split_at(shape.at.len());
        let (sz, tail) = tail.split_at(sizes(&shape.solid).len());
        rest = tail;
        let at = if at.is_empty() {
            quote!(#p::Vector3::new(#zero, #zero, #zero))
        } else {
            vector3(at, scalar)
        };
        let solid = solid(&shape.solid, sz, scalar);
        let on = anchor(shape.on);
        quote!(out(#p::Shape { on: #on, at: #at, solid: #solid });)
    });
    let calls: Vec<TokenStream> = calls.collect();
    quote!(#lets #(#calls)*)
}

fn sizes(solid: &SolidModel) -> Vec<Sym> {
    match solid {
        SolidModel::Box(s) => s.to_vec(),
        SolidModel::Sphere(r) => vec![*r],
        SolidModel::Cylinder { radius, length, .. }
        | SolidModel::Capsule { radius, length, .. } => {
            vec![*radius, *length]
        }
        SolidModel::Line(_) => Vec::new(),
    }
}

fn solid(solid: &SolidModel, sz: &[TokenStream], scalar: &Scalar) -> TokenStream {
    let p = quote!(::lagrange::__private::Solid);
    match solid {
        SolidModel::Box(_) => {
            let size = vector3(sz, scalar);
            quote!(#p::Box { size: #size })
        }
        SolidModel::Sphere(_) => {
            let r = &sz[0];
            quote!(#p::Sphere { radius: #r })
        }
        SolidModel::Cylinder { axis, .. } | SolidModel::Capsule { axis, .. } => {
            let r = &sz[0];
            let l = &sz[1];
            let axis = index(*axis);
            let kind = match solid {
                SolidModel::Cylinder { .. } => quote!(Cylinder),
                _ => quote!(Capsule),
            };
            quote!(#p::#kind { radius: #r, length: #l, axis: #axis })
        }
        SolidModel::Line(to) => {
            let to = anchor(*to);
            quote!(#p::Line { to: #to })
        }
    }
}
