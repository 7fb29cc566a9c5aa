//! Base parameters in closed form: the classical regrouping of the links'
//! inertial numbers (Khalil and Bennis 1995; Gautier and Khalil 1990), done
//! on the tree's expressions, so that each regrouped parameter is a linear
//! combination of π with coefficients in the description's own symbols
//! (ZZ1 + m2 l1², not ZZ1 + 0.25 m2).
//!
//! A revolute joint turns its link about one axis a. What of the link is
//! symmetric about that axis — its mass, its first moment along a, and an
//! inertia I_cc (1 − e_a e_aᵀ) for one of the other axes c — moves with the
//! parent whatever the joint's angle, so it acts exactly as a body fixed in
//! the parent: it is taken off the link (leaving I_bb − I_cc on the third
//! axis b, and nothing of m, h_a, I_cc) and added to the parent, moved to
//! the parent's origin and axes at the joint's zero. (A sliding joint's
//! rule, its link's rotational inertia acting as the parent's, is not
//! applied yet; the numerical reduction reports what it would regroup.)
//! Working from the
//! leaves to the root carries each link's symmetric part as far as it goes;
//! what reaches the ground is lost (no motion shows it).
//!
//! A rotor on a joint whose axis is fixed in space (a revolute joint at
//! the root) shows only as q̈ on its own row, as its link's axial inertia
//! does: the caller adds its armature to that inertia
//! (`root_axial_inertia`), ZZ1R = ZZ1 + … + Ia1.
//!
//! The rules leave parameters that a particular geometry still cannot show
//! (a first link's inertia about axes it never turns about, a planar chain's
//! products of inertia): those are found numerically by the caller, from
//! the link regressor at random states.

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{add3, origin, to_parent};
use super::spatial::conjugate;
use super::{Link, Tree};
use crate::mat3::{Mat3, parallel_axis};

/// Each link's ten numbers (m, h, I_o in its axes, π's order) after the
/// regrouping, None for a link that holds nothing before or after.
pub fn regrouped(ctx: &mut Context, tree: &Tree) -> Vec<Option<[Sym; 10]>> {
    let mut numbers: Vec<Option<[Sym; 10]>> = (tree.links.iter())
        .map(|l| l.inertia.map(|i| super::regressor::ten(&i)))
        .collect();
    for (j, link) in tree.links.iter().enumerate().rev() {
        let Some(own) = numbers[j] else { continue };
        // The axes of a spherical joint turn together: none of them alone
        // leaves anything of the link symmetric. A sliding joint's rule
        // (its link's rotational inertia acts as the parent's) is not
        // checked against τ by any test yet, so it is not applied: what it
        // would regroup is then reported as dependent, not printed wrong.
        if link.chart.is_some() || link.slide.is_some() {
            continue;
        }
        let moved = symmetric_part(ctx, link, &own);
        numbers[j] = Some([0, 1, 2, 3, 4, 5, 6, 7, 8, 9].map(|c| ctx.sub(own[c], moved[c])));
        let Some(p) = link.parent else { continue };
        let carried = to_parent_at_zero(ctx, link, &moved);
        numbers[p] = Some(match numbers[p] {
            None => carried,
            Some(before) => [0, 1, 2, 3, 4, 5, 6, 7, 8, 9].map(|c| ctx.add(before[c], carried[c])),
        });
    }
    numbers
}

/// Where a rotor's inertia on `coordinate` regroups, when its joint turns a
/// link about an axis fixed in space (a revolute joint at the root): the
/// link and the index of its axial inertia I_aa among its ten numbers. That
/// inertia's column is then q̈ on the joint's row alone, an armature's.
pub fn root_axial_inertia(tree: &Tree, coordinate: usize) -> Option<(usize, usize)> {
    let j = tree.links.iter().position(|l| l.coordinate == coordinate)?;
    let link = &tree.links[j];
    let revolute = link.slide.is_none() && link.chart.is_none();
    (link.parent.is_none() && revolute).then(|| (j, diagonal(link.axis)))
}

/// What of the link acts as a body fixed in its parent, in the link's
/// numbers, for a revolute joint about a: m, h_a and I_cc (1 − e_a e_aᵀ),
/// b and c the axes after a (about z: M, MZ and YY, leaving XX − YY, as the
/// textbooks write it).
fn symmetric_part(ctx: &mut Context, link: &Link, n: &[Sym; 10]) -> [Sym; 10] {
    let zero = ctx.zero();
    let mut part = [zero; 10];
    let a = link.axis;
    let b = (a + 1) % 3;
    let c = (a + 2) % 3;
    part[0] = n[0];
    part[1 + a] = n[1 + a];
    part[diagonal(b)] = n[diagonal(c)];
    part[diagonal(c)] = n[diagonal(c)];
    part
}

/// The index of I_kk among the ten numbers (Ixx, Iyy, Izz at 4, 6, 9).
fn diagonal(k: usize) -> usize {
    [4, 6, 9][k]
}

/// A body's ten numbers in the link's axes about its origin, carried to the
/// parent's origin and axes at the joint's zero: m, m d + E h and
/// E I Eᵀ + m(|d|² 1 − d dᵀ) + 2 (d·g) 1 − g dᵀ − d gᵀ with g = E h (the
/// parallel-axis theorem for a body whose centre is not at its origin).
fn to_parent_at_zero(ctx: &mut Context, link: &Link, n: &[Sym; 10]) -> [Sym; 10] {
    let at_zero = (ctx.one(), ctx.zero());
    let d = origin(ctx, link);
    let g = to_parent(ctx, link, at_zero, [n[1], n[2], n[3]]);
    let md = d.map(|x| ctx.mul(n[0], x));
    let h = add3(ctx, md, g);
    let turned = conjugate(ctx, link, at_zero, &inertia(n), true);
    let shift = parallel_axis(ctx, n[0], d);
    let dg: Vec<Sym> = (0..3).map(|k| ctx.mul(d[k], g[k])).collect();
    let dg = ctx.sum(&dg);
    let two_dg = ctx.add(dg, dg);
    let mut i: Mat3 = turned;
    for r in 0..3 {
        for k in r..3 {
            let gd = ctx.mul(g[r], d[k]);
            let dgt = ctx.mul(d[r], g[k]);
            let mut terms = vec![turned[r][k], shift[r][k]];
            if r == k {
                terms.push(two_dg);
            }
            let e = ctx.sum(&terms);
            let both = ctx.add(gd, dgt);
            i[r][k] = ctx.sub(e, both);
            i[k][r] = i[r][k];
        }
    }
    [
        n[0], h[0], h[1], h[2], i[0][0], i[0][1], i[1][1], i[0][2], i[1][2], i[2][2],
    ]
}

/// I_o of the ten numbers as a matrix.
fn inertia(n: &[Sym; 10]) -> Mat3 {
    [[n[4], n[5], n[7]], [n[5], n[6], n[8]], [n[7], n[8], n[9]]]
}
