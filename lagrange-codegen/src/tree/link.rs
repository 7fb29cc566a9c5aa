//! Algebra in link coordinates: the joint rotation E = rot_axis(q) and its
//! transpose, cross products, and 3×3 blocks, written so that products by the
//! zeros and ones of a unit joint axis vanish at construction.

use lagrange_symbolic::{Context, Expr as Sym};

use super::Link;
use crate::mat3::{Mat3, cross, mat_vec, transpose};

/// Copies the upper triangle below the diagonal, so a symmetric matrix holds
/// one node per pair.
pub(super) fn mirror_upper(m: &mut Mat3) {
    for (r, c) in [(0, 1), (0, 2), (1, 2)] {
        m[c][r] = m[r][c];
    }
}

/// cos and sin of a link's joint angle (1 and 0 at a chart's centre).
pub(super) fn trig(ctx: &mut Context, link: &Link) -> (Sym, Sym) {
    if link.chart.is_some() {
        return (ctx.one(), ctx.zero());
    }
    let q = ctx.coordinates()[link.coordinate];
    (ctx.cos(q), ctx.sin(q))
}

/// E x, E = rot_axis(q) (link axes to parent axes).
pub(super) fn rotate(ctx: &mut Context, axis: usize, (c, s): (Sym, Sym), x: [Sym; 3]) -> [Sym; 3] {
    let i = (axis + 1) % 3;
    let j = (axis + 2) % 3;
    let mut out = x;
    let ci = ctx.mul(c, x[i]);
    let sj = ctx.mul(s, x[j]);
    out[i] = ctx.sub(ci, sj);
    let si = ctx.mul(s, x[i]);
    let cj = ctx.mul(c, x[j]);
    out[j] = ctx.add(si, cj);
    out
}

/// E x with E = P rot_axis(q): a vector in link axes in the parent's axes
/// (E = 1 for a sliding joint).
pub(super) fn to_parent(ctx: &mut Context, link: &Link, cs: (Sym, Sym), x: [Sym; 3]) -> [Sym; 3] {
    if link.slide.is_some() {
        return x;
    }
    let turned = rotate(ctx, link.axis, cs, x);
    match &link.placement {
        None => turned,
        Some(p) => mat_vec(ctx, p, turned),
    }
}

/// Eᵀ x = rot_axis(q)ᵀ Pᵀ x: a vector in the parent's axes in link axes.
pub(super) fn to_link(ctx: &mut Context, link: &Link, cs: (Sym, Sym), x: [Sym; 3]) -> [Sym; 3] {
    if link.slide.is_some() {
        return x;
    }
    let placed = match &link.placement {
        None => x,
        Some(p) => mat_vec(ctx, &transpose(p), x),
    };
    rotate_back(ctx, link.axis, cs, placed)
}

/// The link's origin in the parent's axes: the offset, moved by q along the
/// direction of a sliding joint.
pub(super) fn origin(ctx: &mut Context, link: &Link) -> [Sym; 3] {
    let Some(dir) = link.slide else {
        return link.offset;
    };
    let q = ctx.coordinates()[link.coordinate];
    [0, 1, 2].map(|k| {
        let moved = ctx.mul(dir[k], q);
        ctx.add(link.offset[k], moved)
    })
}

/// The joint's rate S q̇ added to the link's velocity (w, v) carried in from
/// the parent, and the velocity-product acceleration c = (w, v) ×m S q̇:
/// S = (e_axis, 0) for a revolute joint, (0, slide) for a sliding one. For an
/// axis of a spherical joint c reads `entering`, the velocity carried into
/// the joint's first link (see [`Link::chart`]); otherwise it is (w, v).
pub(super) fn joint_velocity(
    ctx: &mut Context,
    link: &Link,
    [w, v]: [[Sym; 3]; 2],
    entering: [[Sym; 3]; 2],
    rate: Sym,
) -> ([[Sym; 3]; 2], [[Sym; 3]; 2]) {
    let Some(dir) = link.slide else {
        let mut turned = w;
        turned[link.axis] = ctx.add(w[link.axis], rate);
        let [we, ve] = if link.chart.is_some() {
            entering
        } else {
            [w, v]
        };
        let wq = cross_axis(ctx, we, link.axis, rate);
        let vq = cross_axis(ctx, ve, link.axis, rate);
        return ([turned, v], [wq, vq]);
    };
    let u = dir.map(|x| ctx.mul(x, rate));
    let zero = ctx.zero();
    ([w, add3(ctx, v, u)], [[zero; 3], cross(ctx, w, u)])
}

/// Sᵀ f: the joint's share of a spatial force (moment, force), or the joint
/// component of a spatial motion.
pub(super) fn project(ctx: &mut Context, link: &Link, f: &[[Sym; 3]; 2]) -> Sym {
    let Some(dir) = link.slide else {
        return f[0][link.axis];
    };
    let terms: Vec<Sym> = (0..3).map(|k| ctx.mul(f[1][k], dir[k])).collect();
    ctx.sum(&terms)
}

/// a + S q̈.
pub(super) fn add_motion(ctx: &mut Context, link: &Link, a: &mut [[Sym; 3]; 2], qdd: Sym) {
    match link.slide {
        None => a[0][link.axis] = ctx.add(a[0][link.axis], qdd),
        Some(dir) => {
            for k in 0..3 {
                let m = ctx.mul(dir[k], qdd);
                a[1][k] = ctx.add(a[1][k], m);
            }
        }
    }
}

/// The rotation about `axis` by a constant `angle`, as a matrix.
pub(super) fn elementary(ctx: &mut Context, axis: usize, angle: Sym) -> Mat3 {
    let zero = ctx.zero();
    let one = ctx.one();
    let (c, s) = crate::mat3::cos_sin(ctx, angle);
    let i = (axis + 1) % 3;
    let j = (axis + 2) % 3;
    let mut m = [[zero; 3]; 3];
    m[axis][axis] = one;
    m[i][i] = c;
    m[j][j] = c;
    m[i][j] = ctx.neg(s);
    m[j][i] = s;
    m
}

/// Eᵀ x (parent axes to link axes) for E = rot_axis(q).
pub(super) fn rotate_back(
    ctx: &mut Context,
    axis: usize,
    (c, s): (Sym, Sym),
    x: [Sym; 3],
) -> [Sym; 3] {
    let ms = ctx.neg(s);
    rotate(ctx, axis, (c, ms), x)
}

pub(super) fn add3(ctx: &mut Context, a: [Sym; 3], b: [Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| ctx.add(a[i], b[i]))
}

/// x × e_axis q̇ without forming the zero products.
pub(super) fn cross_axis(ctx: &mut Context, x: [Sym; 3], axis: usize, rate: Sym) -> [Sym; 3] {
    let i = (axis + 1) % 3;
    let j = (axis + 2) % 3;
    let zero = ctx.zero();
    let mut out = [zero; 3];
    out[i] = ctx.mul(x[j], rate);
    let xi = ctx.mul(x[i], rate);
    out[j] = ctx.neg(xi);
    out
}

/// A force (moment about the origin, force) carried from a link to its parent.
pub(super) fn force_to_parent(
    ctx: &mut Context,
    link: &Link,
    n: [Sym; 3],
    f: [Sym; 3],
) -> [[Sym; 3]; 2] {
    let cs = trig(ctx, link);
    let f = to_parent(ctx, link, cs, f);
    let n = to_parent(ctx, link, cs, n);
    let d = origin(ctx, link);
    let moment = cross(ctx, d, f);
    [add3(ctx, n, moment), f]
}

pub(super) fn mat_add(ctx: &mut Context, x: &Mat3, y: &Mat3, sign: i64) -> Mat3 {
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            if sign < 0 {
                ctx.sub(x[i][j], y[i][j])
            } else {
                ctx.add(x[i][j], y[i][j])
            }
        })
    })
}
