//! `impl Lagrangian`, the `EQUATIONS` texts and the programs over the hoisted
//! parameter terms.

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::Frame;
use super::constrained::impl_constrained;
use super::driven::impl_driven;
use super::emitter::{CHUNK_OPS, Emitter};
use super::method::{check_parameters, visit_form};
use super::output::{Pieces, outputs};
use super::posed::impl_posed;
use super::reduced::impl_reduced;
use crate::ast::System;
use crate::doc;
use crate::mechanics::{ForwardRoute, Model};

/// Every impl of a derived description: `Lagrangian`, the inherent `EQUATIONS`
/// and optional outputs, the hoisted programs, and the constrained and driven
/// forms it has.
pub fn impl_lagrangian(system: &System, model: &Model) -> TokenStream {
    let e = Emitter::new(model, &system.scalar);
    let f = Frame::new(system, model.dof(), model.configuration_len());
    let docs = Docs::new(system, model);
    let Pieces {
        lagrangian: output_methods,
        mut inherent,
        hoisted: output_hoisted,
        items: output_items,
    } = outputs(&e, &f, model, system);
    let lagrangian = lagrangian_trait(&e, &f, system, model, output_methods);
    inherent.extend(urdf_consts(system));
    let equations = equations_impl(&f, &docs, inherent);
    let urdf_file = system.urdf.as_ref().map(|u| {
        let path = &u.path;
        // Read by the compiler, so that the crate rebuilds when the file changes.
        quote!(
            const _: &[u8] = include_bytes!(#path);
        )
    });
    let hoisted = hoisted_impl(&e, &f, model, output_hoisted);
    let constrained = impl_constrained(&e, &f, model);
    let reduced = impl_reduced(&e, &f, model);
    let driven = impl_driven(&e, &f, model);
    let posed = impl_posed(&e, &f, model, &system.scalar);
    let contacts = super::contacts::impl_contacts(&e, &f, model);
    let docs_macro = &docs.name;
    let docs_text = &docs.equations;
    quote! {
        macro_rules! #docs_macro {
            () => {
                #docs_text
            };
        }

        #urdf_file
        #lagrangian
        #equations
        #hoisted
        #constrained
        #reduced
        #driven
        #posed
        #contacts
        #output_items
    }
}

/// The `EQUATIONS` texts. The text is emitted once, in a macro both the rustdoc
/// and `EQUATIONS` expand (a summary replaces it in the rustdoc beyond the cap).
struct Docs {
    equations: String,
    latex: String,
    name: syn::Ident,
    impl_doc: TokenStream,
}

impl Docs {
    fn new(system: &System, model: &Model) -> Self {
        let doc::Texts {
            mut equations,
            latex,
        } = doc::texts(model);
        if let Some(line) = crate::atlas::describe(system) {
            equations.push_str(&format!("\n{line}\n"));
        }
        let name = format_ident!("__lagrange_equations_{}", system.ident);
        let impl_doc = match doc::rustdoc(&equations, &system.ident.to_string()) {
            Some(summary) => quote!(#[doc = #summary]),
            None => quote! {
                #[doc = "Equations of motion derived by `#[derive(Lagrangian)]`.\n\n```text"]
                #[doc = #name!()]
                #[doc = "```"]
            },
        };
        Docs {
            equations,
            latex,
            name,
            impl_doc,
        }
    }
}

/// `impl Lagrangian`: M, h, Q, the energies and the methods over the hoisted
/// terms, with the optional outputs' methods (`outputs`).
fn lagrangian_trait(
    e: &Emitter,
    f: &Frame,
    system: &System,
    model: &Model,
    outputs: TokenStream,
) -> TokenStream {
    let s = &f.s;
    let nl = &f.n;
    let n = model.dof();
    let (m_lets, m_outs) = e.program(&e.upper());
    let m_fill = e.symmetric_matrix(&m_outs, n);
    let bias = e.vector_body(&model.motion.bias, s, nl);
    let forces = e.vector_body(&model.motion.forces, s, nl);
    let energies = energy_methods(e, f, model);
    let names = configuration_names(model);
    let rheonomic = model.motion.rheonomic;
    let has_constraints = !(system.holonomic.is_empty() && system.nonholonomic.is_empty());
    let cyclic = cyclic_const(model, nl);
    let route = route_const(model);
    let forward = forward_route_const(model);
    let atlas = atlas_const(system);
    let contacts = contacts_const(system);
    let check_parameters = check_parameters(e, model);
    let visit_form = visit_form(f, model);
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let vec_t = f.vec(nl);
    let mat_t = f.mat(nl, nl);
    let qvec_t = f.qvec();
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    let sizes = f.sizes();
    let nq = &f.nq;
    let orientations = orientation_consts(model);
    let limits = position_limits(system, &names);
    quote! {
        /// The system as `#[derive(Lagrangian)]` derived it; the equations are
        /// on the type's inherent impl (`EQUATIONS`).
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig ::lagrange::__private::Lagrangian<#s, #sizes> for #ident #tg #wc {
            const COORDINATES: [&'static str; #nq] = [#(#names),*];
            #orientations
            const RHEONOMIC: bool = #rheonomic;
            const CONSTRAINED: bool = #has_constraints;
            #cyclic
            #route #forward #atlas #contacts

            #[inline]
            fn mass_matrix(&self, q: &#qvec_t, t: #s) -> #mat_t {
                #m_lets
                <#mat_t>::from(#m_fill)
            }

            #[inline]
            fn bias(&self, q: &#qvec_t, v: &#vec_t, t: #s) -> #vec_t {
                #bias
            }

            #[inline]
            fn generalized_forces(&self, q: &#qvec_t, v: &#vec_t, t: #s) -> #vec_t {
                #forces
            }

            #[inline]
            fn mass_matrix_and_rhs(&self, q: &#qvec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) {
                self.__lagrange_mass_matrix_and_rhs(&self.__lagrange_parameter_terms(), q, v, t)
            }

            fn parameter_terms(&self) -> ::std::vec::Vec<#s> {
                self.__lagrange_parameter_terms().to_vec()
            }

            #[inline]
            fn mass_matrix_and_rhs_with(&self, terms: &[#s], q: &#qvec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) {
                match <&[#s; #h_len]>::try_from(terms) {
                    ::core::result::Result::Ok(p) => self.__lagrange_mass_matrix_and_rhs(p, q, v, t),
                    ::core::result::Result::Err(_) => self.mass_matrix_and_rhs(q, v, t),
                }
            }

            #energies

            #outputs
            #check_parameters
            #visit_form #limits
        }
    }
}

/// `position_limits` of a robot read from URDF: each coordinate with a finite
/// limit, by its index in q (`names`, q's entries); nothing otherwise (the
/// trait's default has none).
fn position_limits(system: &System, names: &[String]) -> TokenStream {
    let Some(u) = &system.urdf else {
        return TokenStream::new();
    };
    let limits: Vec<TokenStream> = u
        .coordinates
        .iter()
        .zip(&u.limits)
        .filter(|(_, (lo, hi))| lo.is_finite() || hi.is_finite())
        .filter_map(|(name, &(lo, hi))| {
            let at = Literal::usize_unsuffixed(names.iter().position(|n| n == name)?);
            let bound = |x: f64| match x {
                f64::INFINITY => quote!(f64::INFINITY),
                f64::NEG_INFINITY => quote!(f64::NEG_INFINITY),
                _ => {
                    let x = Literal::f64_suffixed(x);
                    quote!(#x)
                }
            };
            let lo = bound(lo);
            let hi = bound(hi);
            Some(quote! {
                ::lagrange::__private::JointLimit { joint: #name, coordinate: #at, lower: #lo, upper: #hi }
            })
        })
        .collect();
    if limits.is_empty() {
        return TokenStream::new();
    }
    quote! {
        #[allow(clippy::approx_constant)]
        fn position_limits(&self) -> &'static [::lagrange::__private::JointLimit] {
            &[#(#limits),*]
        }
    }
}

/// The names of q's entries: the coordinates', then each orientation's
/// quaternion components `name.w`, `name.x`, `name.y`, `name.z`.
fn configuration_names(model: &Model) -> Vec<String> {
    let mut names = model.variables.coordinates.clone();
    for o in &model.variables.orientations {
        names.extend(["w", "x", "y", "z"].map(|c| format!("{}.{c}", o.name)));
    }
    names
}

/// `VELOCITIES` and `ORIENTATIONS` of a description with free orientations
/// (nothing without: the trait's defaults are right).
fn orientation_consts(model: &Model) -> TokenStream {
    if model.variables.orientations.is_empty() {
        return TokenStream::new();
    }
    let mut velocities = model.variables.coordinates.clone();
    for o in &model.variables.orientations {
        velocities.extend(["wx", "wy", "wz"].map(|c| format!("{}.{c}", o.name)));
    }
    let n = Literal::usize_unsuffixed(velocities.len());
    let first = model.variables.coordinates.len();
    let layout = (0..model.variables.orientations.len()).map(|k| {
        let (q, v) = (
            Literal::usize_unsuffixed(first + 4 * k),
            Literal::usize_unsuffixed(first + 3 * k),
        );
        quote!(::lagrange::__private::Orientation { q: #q, v: #v })
    });
    quote! {
        const VELOCITIES: [&'static str; #n] = [#(#velocities),*];
        const ORIENTATIONS: &'static [::lagrange::__private::Orientation] = &[#(#layout),*];
    }
}

/// `CYCLIC`, where some coordinate is; the trait's default (none) otherwise, so
/// that most expansions do not carry a line of `false`s.
fn cyclic_const(model: &Model, nl: &Literal) -> TokenStream {
    if !model.variables.cyclic.iter().any(|&c| c) {
        return TokenStream::new();
    }
    let cyclic = &model.variables.cyclic;
    quote!(const CYCLIC: [bool; #nl] = [#(#cyclic),*];)
}

/// `ATLAS = true` with `emit(atlas)` (else the default, false): a run that
/// meets a singular M then says to run through the atlas.
fn atlas_const(system: &System) -> Option<TokenStream> {
    (system.extras.iter())
        .any(|(_, e)| *e == crate::ast::Extra::Atlas)
        .then(|| {
            quote!(
                const ATLAS: bool = true;
            )
        })
}

/// `CONTACTS`, the names of the `contact` and `stop` items and of the
/// joints' dry friction (else the default, none): every run but `run_contacts` refuses a system that has
/// some, as it would ignore them.
fn contacts_const(system: &System) -> Option<TokenStream> {
    let names = system.contact_names();
    if names.is_empty() {
        return None;
    }
    Some(quote!(
        const CONTACTS: &'static [&'static str] = &[#(#names),*];
    ))
}

/// `ROUTE`: recursive, or generic with the reason.
fn route_const(model: &Model) -> TokenStream {
    match &model.motion.derivation.reason {
        None => quote!(
            const ROUTE: ::lagrange::__private::Route = ::lagrange::__private::Route::Recursive;
        ),
        Some(reason) => quote! {
            const ROUTE: ::lagrange::__private::Route =
                ::lagrange::__private::Route::Generic { reason: #reason };
        },
    }
}

/// `FORWARD_ROUTE`, where `emit(articulated)` chose a route for q̈.
fn forward_route_const(model: &Model) -> TokenStream {
    let Some(c) = &model.outputs.forward_route else {
        return TokenStream::new();
    };
    let f = c.factored_mass;
    let route = match (c.route, c.articulated_body) {
        (ForwardRoute::ArticulatedBody, Some(a)) => {
            quote!(ArticulatedBody { articulated_body: #a, factored_mass: #f })
        }
        (_, Some(a)) => quote!(FactoredMass {
            articulated_body: ::core::option::Option::Some(#a),
            factored_mass: #f
        }),
        (_, None) => quote!(FactoredMass {
            articulated_body: ::core::option::Option::None,
            factored_mass: #f
        }),
    };
    quote! {
        const FORWARD_ROUTE: ::lagrange::__private::ForwardRoute =
            ::lagrange::__private::ForwardRoute::#route;
    }
}

/// `kinetic_energy`, `potential_energy` and `integral`.
fn energy_methods(e: &Emitter, f: &Frame, model: &Model) -> TokenStream {
    let s = &f.s;
    let vec_t = f.vec(&f.n);
    let qvec_t = f.qvec();
    let (k_lets, k_out) = e.program(&[model.energies.kinetic]);
    let (p_lets, p_out) = e.program(&[model.energies.potential]);
    let (i_lets, i_out) = e.program(&[model.energies.integral]);
    let k_out = &k_out[0];
    let p_out = &p_out[0];
    let i_out = &i_out[0];
    quote! {
        #[inline]
        fn kinetic_energy(&self, q: &#qvec_t, v: &#vec_t, t: #s) -> #s {
            #k_lets
            #k_out
        }

        #[inline]
        fn potential_energy(&self, q: &#qvec_t, t: #s) -> #s {
            #p_lets
            #p_out
        }

        #[inline]
        fn integral(&self, q: &#qvec_t, v: &#vec_t, t: #s) -> #s {
            #i_lets
            #i_out
        }
    }
}

/// `ROBOT` and `JOINT_LIMITS` of a description read from URDF.
fn urdf_consts(system: &System) -> TokenStream {
    let Some(u) = &system.urdf else {
        return TokenStream::new();
    };
    let bound = |x: f64| {
        if x == f64::INFINITY {
            quote!(f64::INFINITY)
        } else if x == f64::NEG_INFINITY {
            quote!(f64::NEG_INFINITY)
        } else {
            let lit = Literal::f64_suffixed(x);
            quote!(#lit)
        }
    };
    let limits = u.limits.iter().map(|&(lo, hi)| {
        let lo = bound(lo);
        let hi = bound(hi);
        quote!((#lo, #hi))
    });
    let efforts = u.efforts.iter().map(|&e| bound(e));
    let velocities = u.velocities.iter().map(|&e| bound(e));
    let robot = &u.robot;
    let n = Literal::usize_unsuffixed(u.limits.len());
    let snapped = u.snapped.iter().map(|(at, written, exact)| {
        let (w, e) = (
            Literal::f64_suffixed(*written),
            Literal::f64_suffixed(*exact),
        );
        quote!((#at, #w, #e))
    });
    let repaired = u.repaired.iter().map(|(link, written, used)| {
        let (w, r) = (
            written.map(Literal::f64_suffixed),
            used.map(Literal::f64_suffixed),
        );
        quote!((#link, [#(#w),*], [#(#r),*]))
    });
    quote! {
        /// The robot's name in its URDF file.
        pub const ROBOT: &'static str = #robot;
        /// Each coordinate's position limits (lower, upper) from the URDF
        /// file, in coordinate order; ±∞ for a continuous joint or one without
        /// limits. Runs watch them (`Error::JointLimit`) unless told
        /// `.joint_limits(LimitPolicy::Ignore)`; pair them with events to
        /// bounce at a limit.
        #[allow(clippy::approx_constant)] // as the file writes them: 3.14159 is not π
        pub const JOINT_LIMITS: [(f64, f64); #n] = [#(#limits),*];
        /// Each coordinate's effort limit from the URDF file (`<limit
        /// effort>`, N or N·m), in coordinate order; ∞ where the file gives
        /// none (a free base's coordinates). Map them to the inputs that
        /// drive the joints and pass them to `Simulation::input_limits`.
        pub const JOINT_EFFORTS: [f64; #n] = [#(#efforts),*];
        /// Each coordinate's velocity limit from the URDF file (`<limit
        /// velocity>`, m/s or rad/s), in coordinate order; ∞ where the file
        /// gives none. Map them to the inputs that drive the joints and pass
        /// them to `Simulation::speed_limits` as the motors' no-load speeds.
        #[allow(clippy::approx_constant)] // as the file writes them: 3.1415 is not π
        pub const JOINT_VELOCITIES: [f64; #n] = [#(#velocities),*];
        /// The angles made exact multiples of π/2, (where, as the file
        /// writes it, as used): those within 1e-9 rad of one (π/2 written to
        /// nine or more decimals), or within `urdf(.., snap = tol)`'s
        /// tolerance. Empty with `snap = 0`, which keeps the file's numbers.
        #[allow(clippy::approx_constant)]
        pub const URDF_SNAPPED: &'static [(&'static str, f64, f64)] = &[#(#snapped),*];
        /// The inertias `urdf(.., inertia = repair)` made physical: (link,
        /// [ixx, iyy, izz, ixy, ixz, iyz] as the file writes them, as used).
        /// Empty without `inertia = repair` or where every inertia is physical.
        pub const URDF_REPAIRED: &'static [(&'static str, [f64; 6], [f64; 6])] =
            &[#(#repaired),*];
    }
}

/// The inherent impl with `EQUATIONS`, `EQUATIONS_LATEX` and the optional outputs.
fn equations_impl(f: &Frame, docs: &Docs, extras: TokenStream) -> TokenStream {
    let docs_macro = &docs.name;
    let latex = &docs.latex;
    let impl_doc = &docs.impl_doc;
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        #impl_doc
        #[automatically_derived]
        impl #ig #ident #tg #wc {
            /// The derived equations of motion as text: M, h, Q, the energies
            /// and the constraint rows, as one listing with shared
            /// intermediates named.
            pub const EQUATIONS: &'static str = #docs_macro!();
            /// The same equations as LaTeX: the lines of an `aligned` block
            /// (`M_{0 1} &= …`, `h_{0}`, `Q_{0}`, `T`, `V`, and `\Phi`, `G`, `g`,
            /// `\gamma`, `A`, `b`, `c` per constraint or speed row), ready for
            /// `$$ … $$` in a document or a notebook.
            pub const EQUATIONS_LATEX: &'static str = #latex;
            #extras
        }
    }
}

/// M and Q − h over the hoisted parameter terms `p`: the `let`s, M's fill, Q − h
/// and the piece functions of a chunked program.
struct Joint {
    lets: TokenStream,
    fill: TokenStream,
    rhs: Vec<TokenStream>,
    pieces: TokenStream,
}

fn joint_program(e: &Emitter, f: &Frame, model: &Model) -> Joint {
    let s = &f.s;
    let nl = &f.n;
    let n = model.dof();
    let joint = model.hoisted_upper_and_rhs();
    let upper_len = joint.len() - n;
    // A large program runs as pieces, each its own function, passing values
    // through the array `s`.
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let vec_t = f.vec(nl);
    let qvec_t = f.qvec();
    let params = quote!(p: &[#s; #h_len], q: &#qvec_t, v: &#vec_t, t: #s);
    let (lets, outs, pieces) = e.program_in_pieces(
        &joint,
        ("__lagrange_mass_matrix_and_rhs", CHUNK_OPS),
        (&params, &quote!(p, q, v, t)),
    );
    Joint {
        lets,
        fill: e.symmetric_matrix(&outs[..upper_len], n),
        rhs: outs[upper_len..].to_vec(),
        pieces,
    }
}

/// The inherent impl of the parameter-only terms and the programs over them.
fn hoisted_impl(e: &Emitter, f: &Frame, model: &Model, outputs: TokenStream) -> TokenStream {
    let s = &f.s;
    let nl = &f.n;
    let vec_t = f.vec(nl);
    let mat_t = f.mat(nl, nl);
    let qvec_t = f.qvec();
    let h_len = Literal::usize_unsuffixed(model.hoisted.terms.len());
    let (t_lets, t_outs) = e.program(&model.hoisted.terms);
    let Joint {
        lets: j_lets,
        fill: j_fill,
        rhs: j_rhs,
        pieces: j_pieces,
    } = joint_program(e, f, model);
    let ident = f.ident;
    let ig = &f.impl_generics;
    let tg = &f.ty_generics;
    let wc = &f.where_clause;
    quote! {
        /// The parameter-only terms and the programs over them.
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, unused_assignments, clippy::all)]
        impl #ig #ident #tg #wc {
            #[doc(hidden)]
            #[inline(never)]
            pub fn __lagrange_parameter_terms(&self) -> [#s; #h_len] {
                #t_lets
                [#(#t_outs),*]
            }

            // Not `#[inline]`: two trait methods call it, and one copy of a
            // large straight-line program is what keeps model crates quick to
            // build (the call costs nothing beside the body).
            #[doc(hidden)]
            pub fn __lagrange_mass_matrix_and_rhs(&self, p: &[#s; #h_len], q: &#qvec_t, v: &#vec_t, t: #s) -> (#mat_t, #vec_t) {
                #j_lets
                (<#mat_t>::from(#j_fill), <#vec_t>::from([#(#j_rhs),*]))
            }

            #j_pieces

            #outputs
        }
    }
}
