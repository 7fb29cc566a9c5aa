//! The contacts lowered: each one's gap φ(q, t) as a holonomic expression
//! and, for a contact on a plane, its contact point's slip along the plane's
//! two tangents as expressions linear in the velocities. They are written in
//! the description's own language (`p.x`, `dot(p.x)`, `B.omega_x`) at the
//! contact's tokens and lowered like the user's constraints, so a name that
//! does not resolve is reported there.

use proc_macro2::{Literal, Span};
use syn::{Expr, Ident, parse_quote_spanned};

use super::constraint;
use crate::ast::{Contact, ContactGeometry, System};
use crate::lower::{Lowerer, Mode, NoInputs};
use crate::lowered::{ConstraintModel, ContactModel};
use quote::format_ident;

/// Every contact of the description, lowered (those with errors left out;
/// the errors are in the context).
pub(super) fn contacts(lw: &mut Lowerer, system: &System) -> Vec<ContactModel> {
    let mut out = Vec::new();
    for c in &system.contacts {
        if atlas_twin(system).is_some() {
            lw.cx.error_at(c.name.span(), through_atlas(&c.name));
            continue;
        }
        let Some((gap, slips)) = written(lw, system, c) else {
            continue;
        };
        let approach = match &c.geometry {
            ContactGeometry::Spheres {
                on,
                radius,
                against,
                against_radius,
            } => {
                let written =
                    spheres_approach(on, radius.as_ref(), against, against_radius.as_ref());
                let place = format!("contact `{}`", c.name);
                let lowered = lw.lowering_as(place, |lw| {
                    lw.without_inputs(NoInputs::NONHOLONOMIC, |lw| {
                        constraint(lw, &c.name, &written, Mode::State)
                    })
                });
                let Some(lowered) = lowered else { continue };
                Some(lowered.value)
            }
            _ => None,
        };
        let place = format!("contact `{}`", c.name);
        let gap = lw.lowering_as(place.clone(), |lw| {
            lw.without_inputs(NoInputs::HOLONOMIC, |lw| {
                constraint(lw, &c.name, &gap, Mode::Configuration)
            })
        });
        let slips: Option<Vec<_>> = (slips.iter())
            .map(|s| {
                lw.lowering_as(place.clone(), |lw| {
                    lw.without_inputs(NoInputs::NONHOLONOMIC, |lw| {
                        constraint(lw, &c.name, s, Mode::State)
                    })
                })
            })
            .collect();
        let (Some(gap), Some(slips)) = (gap, slips) else {
            continue;
        };
        if moves(lw, gap.value, &slips) {
            lw.cx.error_at(
                c.name.span(),
                format!(
                    "contact `{}`: its gap or slip depends on the time itself (a point \
                     moved by a prescribed motion); contacts on a rheonomic description \
                     are not supported yet",
                    c.name
                ),
            );
            continue;
        }
        out.push(ContactModel {
            name: c.name.to_string(),
            restitution: c.restitution,
            friction: c.friction,
            gap,
            slips,
            approach,
            dry: false,
        });
    }
    out.extend(joint_frictions(lw, system));
    unique_names(lw, system);
    out
}

/// The contacts' names, each a law's name in reports, must differ: a
/// second use is refused at its token (a joint's friction at the joint's
/// coordinate).
fn unique_names(lw: &Lowerer, system: &System) {
    let items = system
        .contacts
        .iter()
        .map(|c| (c.name.to_string(), &c.name, None));
    let frictions = (system.joints.iter())
        .filter(|j| j.friction.is_some())
        .map(|j| (j.friction_name(), &j.coordinate, Some(&j.coordinate)));
    let mut seen = std::collections::BTreeSet::new();
    for (name, token, joint) in items.chain(frictions) {
        if seen.insert(name.clone()) {
            continue;
        }
        let message = match joint {
            Some(q) => format!(
                "joint `{q}`'s friction is the contact `{name}`, a name a contact already has; \
                 rename that contact"
            ),
            None => format!("a second contact named `{name}`: give each contact its own name"),
        };
        lw.cx.error_at(token.span(), message);
    }
}

/// Each joint's dry friction as a contact: no gap (a zero one, so that its
/// normal row is zero) and one slip, the coordinate's velocity.
fn joint_frictions(lw: &mut Lowerer, system: &System) -> Vec<ContactModel> {
    let mut out = Vec::new();
    for j in &system.joints {
        let Some(fc) = j.friction else { continue };
        // An unknown coordinate is `check`'s error.
        let Some(i) = system.coordinates.iter().position(|c| *c == j.coordinate) else {
            continue;
        };
        if atlas_twin(system).is_some() {
            let message = through_atlas(&format_ident!("{}", j.friction_name()));
            lw.cx.error_at(j.coordinate.span(), message);
            continue;
        }
        let name = j.friction_name();
        let zero = lw.ctx.zero();
        let rate = lw.ctx.velocities()[i];
        let row = |value| ConstraintModel {
            name: name.clone(),
            value,
            cartesian: Vec::new(),
        };
        out.push(ContactModel {
            name: name.clone(),
            restitution: 0.0,
            friction: fc,
            gap: row(zero),
            slips: vec![row(rate)],
            approach: None,
            dry: true,
        });
    }
    out
}

/// A contact's gap and slips written in the description's language, or
/// `None` (the error recorded) for a stop on something not a coordinate.
fn written(lw: &Lowerer, system: &System, c: &Contact) -> Option<(Expr, Vec<Expr>)> {
    match &c.geometry {
        ContactGeometry::Plane {
            on,
            radius,
            normal,
            offset,
        } => {
            let turns = radius.is_some() && system.bodies.iter().any(|b| b.name == *on);
            Some(plane(on, radius.as_ref(), *normal, offset.as_ref(), turns))
        }
        ContactGeometry::Spheres {
            on,
            radius,
            against,
            against_radius,
        } => {
            let gap = spheres_gap(on, radius.as_ref(), against, against_radius.as_ref());
            if c.friction == 0.0 {
                return Some((gap, Vec::new()));
            }
            let body = |b: &Ident| system.bodies.iter().any(|x| x.name == *b);
            let radii = [
                radius.as_ref().filter(|_| body(on)),
                against_radius.as_ref().filter(|_| body(against)),
            ];
            let slips = spheres_slips([on, against], radii);
            Some((gap, slips.into()))
        }
        ContactGeometry::Stop {
            coordinate,
            lower,
            bound,
        } => {
            if !system.coordinates.contains(coordinate) {
                lw.cx.error_at(
                    coordinate.span(),
                    format!(
                        "stop `{}`: `{coordinate}` is not a coordinate; a stop bounds one of \
                         `coordinates(...)`",
                        c.name
                    ),
                );
                return None;
            }
            let gap: Expr = if *lower {
                parse_quote_spanned!(coordinate.span()=> #coordinate - (#bound))
            } else {
                parse_quote_spanned!(coordinate.span()=> (#bound) - #coordinate)
            };
            Some((gap, Vec::new()))
        }
    }
}

/// Whether the gap reads the time, or a slip has a part without velocities
/// (the runtime's contact rows are those of a scleronomic contact).
fn moves(
    lw: &mut Lowerer,
    gap: lagrange_symbolic::Expr,
    slips: &[crate::lowered::ConstraintModel],
) -> bool {
    let ctx = &mut lw.ctx;
    let t = ctx.time();
    let zero = ctx.zero();
    let rate = ctx.diff(gap, t);
    let rate = ctx.collect(rate);
    let at_rest: Vec<_> = ctx.velocities().into_iter().map(|v| (v, zero)).collect();
    rate != zero
        || slips.iter().any(|s| {
            let b = ctx.substitute(s.value, &at_rest);
            ctx.collect(b) != zero
        })
}

/// The gap n·x − offset − radius of a point (or sphere centre) `on` and its
/// slips t_k·ẋ − r (n × t_k)·ω, the ω term for a sphere on a body.
fn plane(
    on: &Ident,
    radius: Option<&Expr>,
    n: [f64; 3],
    offset: Option<&Expr>,
    turns: bool,
) -> (Expr, Vec<Expr>) {
    let span = on.span();
    let zero: Expr = parse_quote_spanned!(span=> 0.0);
    let offset = offset.unwrap_or(&zero);
    let radius = radius.unwrap_or(&zero);
    let position = ["x", "y", "z"].map(|c| field(on, c, span));
    let gap = combination(n, &position, span);
    let gap: Expr = parse_quote_spanned!(span=> #gap - (#offset) - (#radius));
    let rates: [Expr; 3] = position.map(|p| parse_quote_spanned!(span=> dot(#p)));
    let omega = ["omega_x", "omega_y", "omega_z"].map(|c| field(on, c, span));
    let slips = tangents(n)
        .into_iter()
        .map(|t| {
            let along = combination(t, &rates, span);
            if turns {
                let lever = combination(cross(n, t), &omega, span);
                parse_quote_spanned!(span=> #along - (#radius) * (#lever))
            } else {
                along
            }
        })
        .collect();
    (gap, slips)
}

/// The gap |a − b| − r_a − r_b of two spheres around `on` and `against`
/// (without friction they have no slips: the tangential motion is free).
fn spheres_gap(on: &Ident, radius: Option<&Expr>, against: &Ident, other: Option<&Expr>) -> Expr {
    let span = on.span();
    let zero: Expr = parse_quote_spanned!(span=> 0.0);
    let (radius, other) = (radius.unwrap_or(&zero), other.unwrap_or(&zero));
    let squares: [Expr; 3] = ["x", "y", "z"].map(|c| {
        let (a, b) = (field(on, c, span), field(against, c, span));
        parse_quote_spanned!(span=> (#a - #b) * (#a - #b))
    });
    let [x, y, z] = &squares;
    parse_quote_spanned!(span=> sqrt(#x + #y + #z) - (#radius) - (#other))
}

/// The slips of two spheres along two unit tangents of their contact: with
/// Δ = a − b and n = Δ/|Δ|, the contact points' relative velocity
/// Δ̇ − r_a ω_a × n − r_b ω_b × n along t₁ and t₂ = n × t₁, that is
/// t₁·Δ̇ − (r_a ω_a + r_b ω_b)·t₂ and t₂·Δ̇ + (r_a ω_a + r_b ω_b)·t₁ (the ω
/// terms for a sphere on a body: `radii` gives its radius, `None` for a
/// point). No tangent field covers the sphere of directions without a
/// zero, so t₁ comes from one of two charts, ẑ × n while n is within 45° of
/// the xy-plane (Δx² + Δy² > Δz²), else x̂ × n, each normalised far from
/// its singular direction; the cone is isotropic, so the switch between
/// them changes no force.
fn spheres_slips(spheres: [&Ident; 2], radii: [Option<&Expr>; 2]) -> [Expr; 2] {
    let span = spheres[0].span();
    let d: [Expr; 3] = ["x", "y", "z"].map(|c| {
        let (a, b) = (field(spheres[0], c, span), field(spheres[1], c, span));
        parse_quote_spanned!(span=> (#a - #b))
    });
    let rate: [Expr; 3] = ["x", "y", "z"].map(|c| {
        let (a, b) = (field(spheres[0], c, span), field(spheres[1], c, span));
        parse_quote_spanned!(span=> (dot(#a) - dot(#b)))
    });
    // r_a ω_a + r_b ω_b, component by component (0 for two points).
    let spin: [Expr; 3] = ["omega_x", "omega_y", "omega_z"].map(|c| {
        let terms: Vec<Expr> = (spheres.iter().zip(radii))
            .filter_map(|(s, r)| r.map(|r| (field(s, c, span), r)))
            .map(|(w, r)| parse_quote_spanned!(span=> (#r) * #w))
            .collect();
        (terms.into_iter())
            .reduce(|a, b| parse_quote_spanned!(span=> (#a + #b)))
            .unwrap_or_else(|| parse_quote_spanned!(span=> 0.0))
    });
    let [dx, dy, dz] = &d;
    let dist: Expr = parse_quote_spanned!(span=> sqrt(#dx * #dx + #dy * #dy + #dz * #dz));
    // ẑ × n chart: t₁ = (−Δy, Δx, 0)/ρ, t₂ = (−Δz Δx, −Δz Δy, ρ²)/(|Δ| ρ).
    let rho: Expr = parse_quote_spanned!(span=> sqrt(#dx * #dx + #dy * #dy));
    let zeta: [[Expr; 3]; 2] = [
        [
            parse_quote_spanned!(span=> -#dy / #rho),
            parse_quote_spanned!(span=> #dx / #rho),
            parse_quote_spanned!(span=> 0.0),
        ],
        [
            parse_quote_spanned!(span=> -#dz * #dx / (#dist * #rho)),
            parse_quote_spanned!(span=> -#dz * #dy / (#dist * #rho)),
            parse_quote_spanned!(span=> #rho / #dist),
        ],
    ];
    // x̂ × n chart: t₁ = (0, −Δz, Δy)/σ, t₂ = (σ², −Δx Δy, −Δx Δz)/(|Δ| σ).
    let sigma: Expr = parse_quote_spanned!(span=> sqrt(#dy * #dy + #dz * #dz));
    let xi: [[Expr; 3]; 2] = [
        [
            parse_quote_spanned!(span=> 0.0),
            parse_quote_spanned!(span=> -#dz / #sigma),
            parse_quote_spanned!(span=> #dy / #sigma),
        ],
        [
            parse_quote_spanned!(span=> #sigma / #dist),
            parse_quote_spanned!(span=> -#dx * #dy / (#dist * #sigma)),
            parse_quote_spanned!(span=> -#dx * #dz / (#dist * #sigma)),
        ],
    ];
    let slips = |[t1, t2]: &[[Expr; 3]; 2]| -> [Expr; 2] {
        let dot3 = |a: &[Expr; 3], b: &[Expr; 3]| -> Expr {
            let [a0, a1, a2] = a;
            let [b0, b1, b2] = b;
            // Parenthesised: an interpolated `Expr` keeps no parentheses of
            // its own, and a sum times a factor would re-parse as a sum.
            parse_quote_spanned!(span=> ((#a0) * (#b0) + (#a1) * (#b1) + (#a2) * (#b2)))
        };
        let (along1, along2) = (dot3(t1, &rate), dot3(t2, &rate));
        let (turn1, turn2) = (dot3(&spin, t2), dot3(&spin, t1));
        [
            parse_quote_spanned!(span=> #along1 - #turn1),
            parse_quote_spanned!(span=> #along2 + #turn2),
        ]
    };
    let (near_xy, near_z) = (slips(&zeta), slips(&xi));
    let test: Expr = parse_quote_spanned!(span=> #dx * #dx + #dy * #dy > #dz * #dz);
    [0, 1].map(|k| {
        let (a, b) = (&near_xy[k], &near_z[k]);
        parse_quote_spanned!(span=> if #test { #a } else { #b })
    })
}

/// The touch event's function for two spheres: while they approach (or
/// pass their closest point without meeting), the gap; once past the
/// closest point of straight paths that came within the sum of the radii
/// R, the miss distance b = √(|Δx|² − (Δx·Δv)²/|Δv|²) less R, below zero.
/// It is continuous (at the closest point b = |Δx|), falls through zero at
/// the touch as the gap does, and stays below zero while a pass-through
/// lasts, so a touch shorter than an integrator's step still shows as a
/// sign change at the step's end, where the gap alone would be positive
/// again.
fn spheres_approach(
    on: &Ident,
    radius: Option<&Expr>,
    against: &Ident,
    other: Option<&Expr>,
) -> Expr {
    let span = on.span();
    let zero: Expr = parse_quote_spanned!(span=> 0.0);
    let (radius, other) = (radius.unwrap_or(&zero), other.unwrap_or(&zero));
    let [dx, dy, dz]: [Expr; 3] = ["x", "y", "z"].map(|c| {
        let (a, b) = (field(on, c, span), field(against, c, span));
        parse_quote_spanned!(span=> (#a - #b))
    });
    let [ux, uy, uz]: [Expr; 3] = ["x", "y", "z"].map(|c| {
        let (a, b) = (field(on, c, span), field(against, c, span));
        parse_quote_spanned!(span=> (dot(#a) - dot(#b)))
    });
    let distance2: Expr = parse_quote_spanned!(span=> #dx * #dx + #dy * #dy + #dz * #dz);
    let along: Expr = parse_quote_spanned!(span=> #dx * #ux + #dy * #uy + #dz * #uz);
    let speed2: Expr = parse_quote_spanned!(span=> #ux * #ux + #uy * #uy + #uz * #uz);
    let reach: Expr = parse_quote_spanned!(span=> ((#radius) + (#other)));
    let gap: Expr = parse_quote_spanned!(span=> sqrt(#distance2) - #reach);
    let miss2: Expr = parse_quote_spanned!(span=> #distance2 - (#along) * (#along) / (#speed2));
    parse_quote_spanned!(span=>
        if #along > 0 && #miss2 < #reach * #reach {
            sqrt(max(#miss2, 0)) - #reach
        } else {
            #gap
        }
    )
}

/// `base.member`.
fn field(base: &Ident, member: &str, span: Span) -> Expr {
    let member = Ident::new(member, span);
    parse_quote_spanned!(span=> #base.#member)
}

/// Σ c_i e_i, leaving out the zero coefficients (so that a planar
/// description's out-of-plane rows come out as exact zeros).
fn combination(c: [f64; 3], e: &[Expr; 3], span: Span) -> Expr {
    let terms: Vec<Expr> = c
        .iter()
        .zip(e)
        .filter(|(ci, _)| **ci != 0.0)
        .map(|(ci, ei)| {
            let l = Literal::f64_unsuffixed(*ci);
            parse_quote_spanned!(span=> #l * #ei)
        })
        .collect();
    match terms.split_first() {
        None => parse_quote_spanned!(span=> 0.0),
        Some((first, rest)) => rest.iter().fold(
            first.clone(),
            |acc, t| parse_quote_spanned!(span=> #acc + #t),
        ),
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Two unit tangents of the plane with unit normal n, (t₁, t₂ = n × t₁):
/// t₁ from the world axis least along n, so n = z gives x and y.
pub(crate) fn tangents(n: [f64; 3]) -> [[f64; 3]; 2] {
    let axis = (0..3)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let mut t = [0.0; 3];
    t[axis] = 1.0;
    let along = n[axis];
    let t = [
        t[0] - along * n[0],
        t[1] - along * n[1],
        t[2] - along * n[2],
    ];
    let size = t.iter().map(|x| x * x).sum::<f64>().sqrt();
    let t1 = t.map(|x| x / size);
    [t1, cross(n, t1)]
}

/// The first of the atlas's twin orientations (`__euler_<k>`): `emit(atlas)`
/// turns the description's Euler angles into free orientations before the
/// contacts are read, and its charts do not carry contacts yet.
fn atlas_twin(system: &System) -> Option<&Ident> {
    (system.orientations.iter()).find(|o| o.to_string().starts_with("__euler_"))
}

/// Why a contact is refused with `emit(atlas)`.
fn through_atlas(contact: &Ident) -> String {
    format!(
        "contact `{contact}`: contacts do not run through the atlas yet (its charts switch \
         between Euler angles at events of their own); drop `atlas` from `emit(...)`, and \
         the contacts run in the Euler angles as written"
    )
}

#[cfg(test)]
mod tests {
    use super::tangents;

    #[test]
    fn the_tangents_of_the_floor_are_x_and_y() {
        assert_eq!(
            tangents([0.0, 0.0, 1.0]),
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        );
    }

    #[test]
    fn tangents_are_orthonormal_and_normal_to_n() {
        let s = 0.5f64.sqrt();
        for n in [[s, 0.0, s], [0.0, -1.0, 0.0], [0.6, 0.0, 0.8]] {
            let [a, b] = tangents(n);
            let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            for (u, v, want) in [
                (a, a, 1.0),
                (b, b, 1.0),
                (a, b, 0.0),
                (a, n, 0.0),
                (b, n, 0.0),
            ] {
                assert!((dot(u, v) - want).abs() < 1e-15, "{n:?}");
            }
        }
    }
}
