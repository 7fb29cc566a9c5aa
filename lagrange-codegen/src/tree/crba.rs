//! M by composite rigid bodies (Featherstone, §6.2): each link's composite
//! inertia carried to its parent, and M_ij the projection of the force that
//! moving joint j needs onto joint i.

use lagrange_symbolic::{Context, Expr as Sym};

use super::detect::add_inertia;
use super::link::{force_to_parent, mirror_upper, origin, project, to_parent, trig};
use super::{Inertia, Link, Tree};
use crate::mat3::cross;

/// The joint-space mass matrix by composite rigid bodies: O(n²) entries, each
/// one force transform up the tree from the last.
pub fn mass_matrix(ctx: &mut Context, tree: &Tree) -> Vec<Vec<Sym>> {
    let n = tree.links.len();
    let zero = ctx.zero();
    let mut composite: Vec<Inertia> = tree
        .links
        .iter()
        .map(|l| {
            l.inertia.unwrap_or(Inertia {
                mass: zero,
                first: [zero; 3],
                rot: [[zero; 3]; 3],
            })
        })
        .collect();
    for i in (0..n).rev() {
        if let Some(p) = tree.links[i].parent {
            let moved = inertia_to_parent(ctx, &tree.links[i], &composite[i]);
            composite[p] = add_inertia(ctx, Some(composite[p]), moved);
        }
    }
    // One row per coordinate (a mimic joint's coordinate drives two links).
    let dof = ctx.coordinates().len();
    let mut m = vec![vec![zero; dof]; dof];
    for (i, link) in tree.links.iter().enumerate() {
        let mut nf = joint_force(ctx, link, &composite[i]);
        let qi = link.coordinate;
        let own = project(ctx, link, &nf);
        m[qi][qi] = ctx.add(m[qi][qi], own);
        let mut j = i;
        while let Some(p) = tree.links[j].parent {
            nf = force_to_parent(ctx, &tree.links[j], nf[0], nf[1]);
            j = p;
            let qj = tree.links[j].coordinate;
            // Joint-space entries summed over the joints each coordinate
            // drives (one each, but for a mimic joint).
            let entry = project(ctx, &tree.links[j], &nf);
            if qi == qj {
                let both = ctx.add(entry, entry);
                m[qi][qi] = ctx.add(m[qi][qi], both);
            } else {
                m[qi][qj] = ctx.add(m[qi][qj], entry);
                m[qj][qi] = m[qi][qj];
            }
        }
    }
    for &(qi, ia) in &tree.armature {
        m[qi][qi] = ctx.add(m[qi][qi], ia);
    }
    m
}

/// F = I_c S, the force that moving the joint alone needs: moment I_o e,
/// force e × h for a revolute joint about e; moment h × s, force m s for a
/// sliding one along s.
fn joint_force(ctx: &mut Context, link: &Link, ic: &Inertia) -> [[Sym; 3]; 2] {
    match link.slide {
        None => {
            let a = link.axis;
            let mut e = [ctx.zero(); 3];
            e[a] = ctx.one();
            [
                [ic.rot[0][a], ic.rot[1][a], ic.rot[2][a]],
                cross(ctx, e, ic.first),
            ]
        }
        Some(s) => [cross(ctx, ic.first, s), s.map(|x| ctx.mul(ic.mass, x))],
    }
}

/// A link's (composite) inertia in its parent's axes about the parent origin:
/// rotated by E, then moved by the offset d with the parallel-axis theorem
/// I' = E I Eᵀ + m(|d|² 1 − d dᵀ) + 2(d·h) 1 − h dᵀ − d hᵀ, h' = E h + m d.
pub(super) fn inertia_to_parent(ctx: &mut Context, link: &Link, i: &Inertia) -> Inertia {
    let cs = trig(ctx, link);
    let h = to_parent(ctx, link, cs, i.first);
    let cols: [[Sym; 3]; 3] =
        [0, 1, 2].map(|k| to_parent(ctx, link, cs, [i.rot[0][k], i.rot[1][k], i.rot[2][k]]));
    // cols[k] = E I e_k, so (E I)_{rk} = cols[k][r]; E I Eᵀ has rows E (E I)ᵀ rows.
    let ei = [0, 1, 2].map(|r| [cols[0][r], cols[1][r], cols[2][r]]);
    let mut rot = [0, 1, 2].map(|r| to_parent(ctx, link, cs, ei[r]));
    let d = origin(ctx, link);
    let first = [0, 1, 2].map(|k| {
        let md = ctx.mul(i.mass, d[k]);
        ctx.add(h[k], md)
    });
    if d.iter().any(|&x| !ctx.is_zero(x)) {
        let dd: Vec<Sym> = d.iter().map(|&x| ctx.mul(x, x)).collect();
        let dd = ctx.sum(&dd);
        let dh: Vec<Sym> = (0..3).map(|k| ctx.mul(d[k], h[k])).collect();
        let dh = ctx.sum(&dh);
        let two = ctx.int(2);
        let two_dh = ctx.mul(two, dh);
        for r in 0..3 {
            for c in r..3 {
                let ddrc = ctx.mul(d[r], d[c]);
                let diag = if r == c {
                    ctx.sub(dd, ddrc)
                } else {
                    ctx.neg(ddrc)
                };
                let mut terms = vec![rot[r][c], ctx.mul(i.mass, diag)];
                if r == c {
                    terms.push(two_dh);
                }
                let hd = ctx.mul(h[r], d[c]);
                let dh2 = ctx.mul(d[r], h[c]);
                terms.push(ctx.neg(hd));
                terms.push(ctx.neg(dh2));
                let e = ctx.sum(&terms);
                rot[r][c] = e;
                rot[c][r] = e;
            }
        }
    } else {
        mirror_upper(&mut rot);
    }
    Inertia {
        mass: i.mass,
        first,
        rot,
    }
}
