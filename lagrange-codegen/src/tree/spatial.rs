//! Spatial inertias as three 3×3 blocks, for the articulated-body algorithm,
//! whose articulated inertias are general symmetric 6×6 matrices.

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{add3, mat_add, mirror_upper, origin, to_parent, trig};
use super::{Inertia, Link};
use crate::mat3::{Mat3, mat_mul, mat_vec, skew, transpose};

/// A spatial inertia as three 3×3 blocks acting on (ω, v): moment A ω + B v,
/// force Bᵀ ω + C v. A rigid body has A = I_o, B = [h]×, C = m 1; an articulated
/// body is any symmetric 6×6 of this shape.
#[derive(Clone, Copy)]
pub(super) struct Spatial {
    pub a: Mat3,
    pub b: Mat3,
    pub c: Mat3,
}

pub(super) fn rigid_spatial(ctx: &mut Context, i: Option<&Inertia>) -> Spatial {
    let zero = ctx.zero();
    let Some(i) = i else {
        return Spatial {
            a: [[zero; 3]; 3],
            b: [[zero; 3]; 3],
            c: [[zero; 3]; 3],
        };
    };
    let h = i.first;
    let mut b = [[zero; 3]; 3];
    for (r, row) in b.iter_mut().enumerate() {
        let j = (r + 1) % 3;
        let k = (r + 2) % 3;
        row[k] = h[j];
        row[j] = ctx.neg(h[k]);
    }
    let mut c = [[zero; 3]; 3];
    for (r, row) in c.iter_mut().enumerate() {
        row[r] = i.mass;
    }
    Spatial { a: i.rot, b, c }
}

/// (moment, force) = I (ω, v).
pub(super) fn spatial_apply(
    ctx: &mut Context,
    s: &Spatial,
    w: [Sym; 3],
    v: [Sym; 3],
) -> [[Sym; 3]; 2] {
    let aw = mat_vec(ctx, &s.a, w);
    let bv = mat_vec(ctx, &s.b, v);
    let bt = transpose(&s.b);
    let btw = mat_vec(ctx, &bt, w);
    let cv = mat_vec(ctx, &s.c, v);
    [add3(ctx, aw, bv), add3(ctx, btw, cv)]
}

/// E M Eᵀ; `symmetric` mirrors the upper triangle so equal entries are one node.
pub(super) fn conjugate(
    ctx: &mut Context,
    link: &Link,
    cs: (Sym, Sym),
    m: &Mat3,
    symmetric: bool,
) -> Mat3 {
    let cols: [[Sym; 3]; 3] =
        [0, 1, 2].map(|k| to_parent(ctx, link, cs, [m[0][k], m[1][k], m[2][k]]));
    let rows = [0, 1, 2].map(|r| [cols[0][r], cols[1][r], cols[2][r]]);
    let mut out = [0, 1, 2].map(|r| to_parent(ctx, link, cs, rows[r]));
    if symmetric {
        mirror_upper(&mut out);
    }
    out
}

/// Xᵀ I X for the motion transform X from the parent to the link: the blocks
/// rotated by E, then moved from the link origin d to the parent origin,
/// A' − B'[d]× + [d]×B'ᵀ − [d]×C'[d]×, B' + [d]×C', C'.
pub(super) fn spatial_to_parent(ctx: &mut Context, link: &Link, s: &Spatial) -> Spatial {
    let cs = trig(ctx, link);
    let a = conjugate(ctx, link, cs, &s.a, true);
    let b = conjugate(ctx, link, cs, &s.b, false);
    let c = conjugate(ctx, link, cs, &s.c, true);
    let offset = origin(ctx, link);
    if offset.iter().all(|&x| ctx.is_zero(x)) {
        return Spatial { a, b, c };
    }
    let d = skew(ctx, offset);
    let bd = mat_mul(ctx, &b, &d);
    let db = mat_mul(ctx, &d, &transpose(&b));
    let dc = mat_mul(ctx, &d, &c);
    let dcd = mat_mul(ctx, &dc, &d);
    let mut ap = [[a[0][0]; 3]; 3];
    for r in 0..3 {
        for k in r..3 {
            let e = ctx.sum(&[a[r][k], db[r][k]]);
            let e = ctx.sub(e, bd[r][k]);
            let e = ctx.sub(e, dcd[r][k]);
            ap[r][k] = e;
            ap[k][r] = e;
        }
    }
    Spatial {
        a: ap,
        b: mat_add(ctx, &b, &dc, 1),
        c,
    }
}
