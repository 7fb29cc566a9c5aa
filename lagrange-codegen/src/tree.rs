//! The recursive route: when the bodies form a kinematic tree of revolute joints,
//! M by composite rigid bodies (CRBA) and h − Q_gravity by recursive
//! Newton–Euler (RNEA), built as expressions so the engine's CSE emits them as
//! straight-line code (Featherstone, *Rigid Body Dynamics Algorithms*, ch. 5–6).
//!
//! Differentiating ξ(q) of every body costs O(n³) operations in 3-D (Jacobians of
//! products of rotations, then M = Σ Jᵀ m J); the recursions cost O(n²) for M and
//! O(n) for h, in link coordinates where joint axes are unit vectors and offsets
//! are constant, so most products are by 0 or 1 and vanish at construction.
//!
//! A tree is detected from the description, not declared: a body's rotation is
//! its parent's factors followed by elementary rotations about coordinates
//! (`rot_z(q1) * rot_y(q2)` under `rot_z(q1)`), and its reference point is a
//! point fixed in the parent (`at = [j.x, j.y, j.z]` with `point(j, on = parent)`)
//! or a fixed point for a root. Each elementary factor is one joint; a body with
//! several new factors (`euler_zxz(ψ, θ, φ)` about a fixed point) hangs on
//! massless links that meet at its reference point. Anything else — a rotation
//! written as a matrix, a translating coordinate, a point mass that is neither
//! fixed in a body nor in space, a coordinate in two joints, time in a position
//! — leaves the system to the generic route.

use lagrange_symbolic::{Context, Expr as Sym, SymbolKind};

use crate::lowered::Skeleton;
use crate::mat3::{Mat3, transpose};

/// Mass, first moment h = m c and rotational inertia about the link origin, in
/// link axes: the spatial inertia in its ten numbers.
#[derive(Clone, Copy)]
struct Inertia {
    mass: Sym,
    first: [Sym; 3],
    rot: Mat3,
}

/// One revolute joint and the link it moves: the link frame is the parent's
/// rotated by rot_axis(q) about the parent point `offset`.
struct Link {
    parent: Option<usize>,
    axis: usize,
    coordinate: usize,
    offset: [Sym; 3],
    inertia: Option<Inertia>,
}

/// A detected kinematic tree; links are ordered parents first.
pub struct Tree {
    links: Vec<Link>,
    gravity: Option<[Sym; 3]>,
}

/// What the tree's bodies carry, as `derive` hands them over.
pub struct Masses<'a> {
    pub point_masses: &'a [Sym],
    pub point_positions: &'a [Vec<Sym>],
    pub inertias: &'a [Mat3],
    pub gravity: Option<&'a [Sym]>,
}

impl Tree {
    /// Number of joints.
    pub fn len(&self) -> usize {
        self.links.len()
    }

    /// Whether the tree has no joints (never returned by [`detect`]).
    pub fn is_empty(&self) -> bool {
        self.links.is_empty()
    }
}

/// Whether `e` depends on parameters only (fixed in space and time).
fn fixed(ctx: &Context, e: Sym) -> bool {
    ctx.free_symbols(e)
        .iter()
        .all(|&s| matches!(ctx.symbol_kind(s), SymbolKind::Parameter(_)))
}

/// The kinematic tree the description spans, if it is one.
pub fn detect(ctx: &mut Context, skeleton: &Skeleton, masses: &Masses) -> Option<Tree> {
    let coordinates = ctx.coordinates();
    let n = coordinates.len();
    let bodies = &skeleton.bodies;
    if bodies.is_empty() || n == 0 {
        return None;
    }
    // Each body's joints as (axis, coordinate index).
    let mut joints: Vec<Vec<(usize, usize)>> = Vec::new();
    for b in bodies {
        let factors = b.factors.as_ref()?;
        let js = factors
            .iter()
            .map(|&(axis, angle)| Some((axis, coordinates.iter().position(|&q| q == angle)?)))
            .collect::<Option<Vec<_>>>()?;
        joints.push(js);
    }
    // Parents: the body whose joints are the longest proper prefix.
    let mut order: Vec<usize> = (0..bodies.len()).collect();
    order.sort_by_key(|&b| joints[b].len());
    let mut links: Vec<Link> = Vec::new();
    let mut last_link: Vec<Option<usize>> = vec![None; bodies.len()];
    let mut used = vec![false; n];
    let zero = ctx.zero();
    for &b in &order {
        let mine = &joints[b];
        let parent = (0..bodies.len())
            .filter(|&p| p != b && joints[p].len() < mine.len() && mine.starts_with(&joints[p]))
            .max_by_key(|&p| joints[p].len());
        let prefix = parent.map_or(0, |p| joints[p].len());
        if prefix == mine.len() {
            return None;
        }
        if parent
            .is_some_and(|p| (0..bodies.len()).any(|o| o != p && o != b && joints[o] == joints[p]))
        {
            return None; // two bodies with one rotation: which one carries b is unclear
        }
        let reference = &bodies[b].reference;
        let offset: [Sym; 3] = match parent {
            None => {
                if reference.len() != 3 || !reference.iter().all(|&x| fixed(ctx, x)) {
                    return None;
                }
                [reference[0], reference[1], reference[2]]
            }
            Some(p) => {
                let (_, _, local) = skeleton
                    .anchors
                    .iter()
                    .find(|(at, body, _)| *body == p && at == reference)?;
                if local.len() != 3 || !local.iter().all(|&x| fixed(ctx, x)) {
                    return None;
                }
                [local[0], local[1], local[2]]
            }
        };
        let mut up = parent.map(|p| last_link[p].expect("parents come first"));
        for (k, &(axis, coordinate)) in mine[prefix..].iter().enumerate() {
            if std::mem::replace(&mut used[coordinate], true) {
                return None;
            }
            links.push(Link {
                parent: up,
                axis,
                coordinate,
                offset: if k == 0 { offset } else { [zero; 3] },
                inertia: None,
            });
            up = Some(links.len() - 1);
        }
        last_link[b] = up;
    }
    if used.iter().any(|u| !u) {
        return None;
    }
    // Masses: point masses fixed in bodies (body centres included) and the bodies'
    // rotational inertia; a point mass fixed in space moves with nothing.
    for (i, at) in skeleton.masses.iter().enumerate() {
        match at {
            Some((b, local)) if local.len() == 3 && local.iter().all(|&x| fixed(ctx, x)) => {
                let link = last_link[*b]?;
                let add =
                    point_inertia(ctx, masses.point_masses[i], [local[0], local[1], local[2]]);
                links[link].inertia = Some(add_inertia(ctx, links[link].inertia, add));
            }
            None if masses.point_positions[i].iter().all(|&x| fixed(ctx, x)) => {}
            _ => return None,
        }
    }
    for (b, tensor) in masses.inertias.iter().enumerate() {
        let link = last_link[b]?;
        let spin = Inertia {
            mass: zero,
            first: [zero; 3],
            rot: *tensor,
        };
        links[link].inertia = Some(add_inertia(ctx, links[link].inertia, spin));
    }
    let gravity = match masses.gravity {
        None => None,
        Some(g) if g.len() == 3 && g.iter().all(|&x| fixed(ctx, x)) => Some([g[0], g[1], g[2]]),
        Some(_) => return None,
    };
    Some(Tree { links, gravity })
}

/// A point mass μ at r: (μ, μ r, μ(|r|² 1 − r rᵀ)).
fn point_inertia(ctx: &mut Context, mass: Sym, r: [Sym; 3]) -> Inertia {
    let first = r.map(|x| ctx.mul(mass, x));
    let squares: Vec<Sym> = r.iter().map(|&x| ctx.mul(x, x)).collect();
    let norm = ctx.sum(&squares);
    let rot = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let outer = ctx.mul(r[i], r[j]);
            let e = if i == j {
                ctx.sub(norm, outer)
            } else {
                ctx.neg(outer)
            };
            ctx.mul(mass, e)
        })
    });
    Inertia { mass, first, rot }
}

/// Copies the upper triangle below the diagonal, so a symmetric matrix holds
/// one node per pair.
fn mirror_upper(m: &mut Mat3) {
    for (r, c) in [(0, 1), (0, 2), (1, 2)] {
        m[c][r] = m[r][c];
    }
}

fn add_inertia(ctx: &mut Context, a: Option<Inertia>, b: Inertia) -> Inertia {
    let Some(a) = a else { return b };
    Inertia {
        mass: ctx.add(a.mass, b.mass),
        first: [0, 1, 2].map(|i| ctx.add(a.first[i], b.first[i])),
        rot: [0, 1, 2].map(|i| [0, 1, 2].map(|j| ctx.add(a.rot[i][j], b.rot[i][j]))),
    }
}

/// cos and sin of a link's joint angle.
fn trig(ctx: &mut Context, link: &Link) -> (Sym, Sym) {
    let q = ctx.coordinates()[link.coordinate];
    (ctx.cos(q), ctx.sin(q))
}

/// E x, E = rot_axis(q) (link axes to parent axes).
fn rotate(ctx: &mut Context, axis: usize, (c, s): (Sym, Sym), x: [Sym; 3]) -> [Sym; 3] {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut out = x;
    let (ci, sj) = (ctx.mul(c, x[i]), ctx.mul(s, x[j]));
    out[i] = ctx.sub(ci, sj);
    let (si, cj) = (ctx.mul(s, x[i]), ctx.mul(c, x[j]));
    out[j] = ctx.add(si, cj);
    out
}

/// Eᵀ x (parent axes to link axes).
fn rotate_back(ctx: &mut Context, axis: usize, (c, s): (Sym, Sym), x: [Sym; 3]) -> [Sym; 3] {
    let ms = ctx.neg(s);
    rotate(ctx, axis, (c, ms), x)
}

fn cross(ctx: &mut Context, a: [Sym; 3], b: [Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let p = ctx.mul(a[j], b[k]);
        let m = ctx.mul(a[k], b[j]);
        ctx.sub(p, m)
    })
}

fn add3(ctx: &mut Context, a: [Sym; 3], b: [Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| ctx.add(a[i], b[i]))
}

fn mat_vec(ctx: &mut Context, m: &Mat3, v: [Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| {
        let terms: Vec<Sym> = (0..3).map(|k| ctx.mul(m[i][k], v[k])).collect();
        ctx.sum(&terms)
    })
}

/// x × e_axis q̇ without forming the zero products.
fn cross_axis(ctx: &mut Context, x: [Sym; 3], axis: usize, rate: Sym) -> [Sym; 3] {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let zero = ctx.zero();
    let mut out = [zero; 3];
    out[i] = ctx.mul(x[j], rate);
    let xi = ctx.mul(x[i], rate);
    out[j] = ctx.neg(xi);
    out
}

/// A force (moment about the origin, force) carried from a link to its parent.
fn force_to_parent(ctx: &mut Context, link: &Link, n: [Sym; 3], f: [Sym; 3]) -> [[Sym; 3]; 2] {
    let cs = trig(ctx, link);
    let f = rotate(ctx, link.axis, cs, f);
    let n = rotate(ctx, link.axis, cs, n);
    let moment = cross(ctx, link.offset, f);
    [add3(ctx, n, moment), f]
}

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
    let mut m = vec![vec![zero; n]; n];
    for (i, link) in tree.links.iter().enumerate() {
        let a = link.axis;
        let ic = composite[i];
        let mut e = [zero; 3];
        e[a] = ctx.one();
        // F = I_c S: moment I_o e_a, force e_a × h.
        let mut nf = [
            [ic.rot[0][a], ic.rot[1][a], ic.rot[2][a]],
            cross(ctx, e, ic.first),
        ];
        let qi = link.coordinate;
        m[qi][qi] = ic.rot[a][a];
        let mut j = i;
        while let Some(p) = tree.links[j].parent {
            nf = force_to_parent(ctx, &tree.links[j], nf[0], nf[1]);
            j = p;
            let qj = tree.links[j].coordinate;
            let entry = nf[0][tree.links[j].axis];
            m[qi][qj] = entry;
            m[qj][qi] = entry;
        }
    }
    m
}

/// A link's (composite) inertia in its parent's axes about the parent origin:
/// rotated by E, then moved by the offset d with the parallel-axis theorem
/// I' = E I Eᵀ + m(|d|² 1 − d dᵀ) + 2(d·h) 1 − h dᵀ − d hᵀ, h' = E h + m d.
fn inertia_to_parent(ctx: &mut Context, link: &Link, i: &Inertia) -> Inertia {
    let cs = trig(ctx, link);
    let a = link.axis;
    let h = rotate(ctx, a, cs, i.first);
    let cols: [[Sym; 3]; 3] =
        [0, 1, 2].map(|k| rotate(ctx, a, cs, [i.rot[0][k], i.rot[1][k], i.rot[2][k]]));
    // cols[k] = E I e_k, so (E I)_{rk} = cols[k][r]; E I Eᵀ has rows E (E I)ᵀ rows.
    let ei = [0, 1, 2].map(|r| [cols[0][r], cols[1][r], cols[2][r]]);
    let mut rot = [0, 1, 2].map(|r| rotate(ctx, a, cs, ei[r]));
    let d = link.offset;
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

/// Recursive Newton–Euler at q̈ = 0: τ = h(q, q̇) − Q_gravity(q) with gravity, h
/// alone without. Velocities and bias accelerations go out from the root in link
/// axes, the link forces I a + v ×* I v come back, and τ_i is the joint-axis
/// component of the moment.
pub fn inverse_dynamics(ctx: &mut Context, tree: &Tree, with_gravity: bool) -> Vec<Sym> {
    let n = tree.links.len();
    let zero = ctx.zero();
    let qd = ctx.velocities();
    // (ω, v, α, a) of each link at its origin, in its axes.
    let mut motion: Vec<[[Sym; 3]; 4]> = Vec::with_capacity(n);
    let ground = {
        let mut a = [zero; 3];
        if let (true, Some(g)) = (with_gravity, tree.gravity) {
            a = g.map(|x| ctx.neg(x));
        }
        [[zero; 3], [zero; 3], [zero; 3], a]
    };
    for link in &tree.links {
        let [w, v, al, a] = link.parent.map_or(ground, |p| motion[p]);
        let cs = trig(ctx, link);
        let rate = qd[link.coordinate];
        let wd = cross(ctx, w, link.offset);
        let v_at = add3(ctx, v, wd);
        let ad = cross(ctx, al, link.offset);
        let a_at = add3(ctx, a, ad);
        let w_in = rotate_back(ctx, link.axis, cs, w);
        let v = rotate_back(ctx, link.axis, cs, v_at);
        let al_in = rotate_back(ctx, link.axis, cs, al);
        let a_in = rotate_back(ctx, link.axis, cs, a_at);
        let mut w = w_in;
        w[link.axis] = ctx.add(w[link.axis], rate);
        let wq = cross_axis(ctx, w_in, link.axis, rate);
        let al = add3(ctx, al_in, wq);
        let vq = cross_axis(ctx, v, link.axis, rate);
        let a = add3(ctx, a_in, vq);
        motion.push([w, v, al, a]);
    }
    let mut forces: Vec<[[Sym; 3]; 2]> = tree
        .links
        .iter()
        .zip(&motion)
        .map(|(link, &[w, v, al, a])| match &link.inertia {
            None => [[zero; 3], [zero; 3]],
            Some(i) => body_force(ctx, i, w, v, al, a),
        })
        .collect();
    let mut tau = vec![zero; n];
    for k in (0..n).rev() {
        let link = &tree.links[k];
        let [nk, fk] = forces[k];
        tau[link.coordinate] = nk[link.axis];
        if let Some(p) = link.parent {
            let [np, fp] = force_to_parent(ctx, link, nk, fk);
            forces[p] = [add3(ctx, forces[p][0], np), add3(ctx, forces[p][1], fp)];
        }
    }
    tau
}

/// I a + v ×* I v for the spatial inertia (m, h, I_o): with momentum
/// p = m v + ω × h and L = I_o ω + h × v,
/// moment I_o α + h × a + ω × L + v × p, force m a + α × h + ω × p.
fn body_force(
    ctx: &mut Context,
    i: &Inertia,
    w: [Sym; 3],
    v: [Sym; 3],
    al: [Sym; 3],
    a: [Sym; 3],
) -> [[Sym; 3]; 2] {
    let mv = v.map(|x| ctx.mul(i.mass, x));
    let wh = cross(ctx, w, i.first);
    let p = add3(ctx, mv, wh);
    let iw = mat_vec(ctx, &i.rot, w);
    let hv = cross(ctx, i.first, v);
    let l = add3(ctx, iw, hv);
    let ia = mat_vec(ctx, &i.rot, al);
    let ha = cross(ctx, i.first, a);
    let wl = cross(ctx, w, l);
    let vp = cross(ctx, v, p);
    let moment = [0, 1, 2].map(|k| ctx.sum(&[ia[k], ha[k], wl[k], vp[k]]));
    let ma = a.map(|x| ctx.mul(i.mass, x));
    let ah = cross(ctx, al, i.first);
    let wp = cross(ctx, w, p);
    let force = [0, 1, 2].map(|k| ctx.sum(&[ma[k], ah[k], wp[k]]));
    [moment, force]
}

/// A spatial inertia as three 3×3 blocks acting on (ω, v): moment A ω + B v,
/// force Bᵀ ω + C v. A rigid body has A = I_o, B = [h]×, C = m 1; an articulated
/// body is any symmetric 6×6 of this shape.
#[derive(Clone, Copy)]
struct Spatial {
    a: Mat3,
    b: Mat3,
    c: Mat3,
}

/// The accelerations by the articulated-body algorithm and its pivots.
pub struct ForwardDynamics {
    /// q̈_i, in coordinate order.
    pub accelerations: Vec<Sym>,
    /// D_i = Sᵢᵀ I_iᴬ Sᵢ, the pivots of M's LᵀDL factorisation in tree order: a
    /// tiny ratio of the smallest to the largest says M is nearly singular.
    pub pivots: Vec<Sym>,
}

fn rigid_spatial(ctx: &mut Context, i: Option<&Inertia>) -> Spatial {
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
        let (j, k) = ((r + 1) % 3, (r + 2) % 3);
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
fn spatial_apply(ctx: &mut Context, s: &Spatial, w: [Sym; 3], v: [Sym; 3]) -> [[Sym; 3]; 2] {
    let aw = mat_vec(ctx, &s.a, w);
    let bv = mat_vec(ctx, &s.b, v);
    let bt = transpose(&s.b);
    let btw = mat_vec(ctx, &bt, w);
    let cv = mat_vec(ctx, &s.c, v);
    [add3(ctx, aw, bv), add3(ctx, btw, cv)]
}

/// E M Eᵀ; `symmetric` mirrors the upper triangle so equal entries are one node.
fn conjugate(ctx: &mut Context, axis: usize, cs: (Sym, Sym), m: &Mat3, symmetric: bool) -> Mat3 {
    let cols: [[Sym; 3]; 3] = [0, 1, 2].map(|k| rotate(ctx, axis, cs, [m[0][k], m[1][k], m[2][k]]));
    let rows = [0, 1, 2].map(|r| [cols[0][r], cols[1][r], cols[2][r]]);
    let mut out = [0, 1, 2].map(|r| rotate(ctx, axis, cs, rows[r]));
    if symmetric {
        mirror_upper(&mut out);
    }
    out
}

/// [d]×, with [d]× x = d × x.
fn skew(ctx: &mut Context, d: [Sym; 3]) -> Mat3 {
    let zero = ctx.zero();
    let mut m = [[zero; 3]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        let (j, k) = ((r + 1) % 3, (r + 2) % 3);
        row[k] = d[j];
        row[j] = ctx.neg(d[k]);
    }
    m
}

fn mat_mul(ctx: &mut Context, x: &Mat3, y: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let terms: Vec<Sym> = (0..3).map(|k| ctx.mul(x[i][k], y[k][j])).collect();
            ctx.sum(&terms)
        })
    })
}

fn mat_add(ctx: &mut Context, x: &Mat3, y: &Mat3, sign: i64) -> Mat3 {
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

/// Xᵀ I X for the motion transform X from the parent to the link: the blocks
/// rotated by E, then moved from the link origin d to the parent origin,
/// A' − B'[d]× + [d]×B'ᵀ − [d]×C'[d]×, B' + [d]×C', C'.
fn spatial_to_parent(ctx: &mut Context, link: &Link, s: &Spatial) -> Spatial {
    let cs = trig(ctx, link);
    let axis = link.axis;
    let a = conjugate(ctx, axis, cs, &s.a, true);
    let b = conjugate(ctx, axis, cs, &s.b, false);
    let c = conjugate(ctx, axis, cs, &s.c, true);
    if link.offset.iter().all(|&x| ctx.is_zero(x)) {
        return Spatial { a, b, c };
    }
    let d = skew(ctx, link.offset);
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

/// q̈ by the articulated-body algorithm (Featherstone, Table 7.1) with the
/// generalized forces `tau` (in coordinate order) and gravity: O(n) operations,
/// no mass matrix and no factorisation.
pub fn forward_dynamics(ctx: &mut Context, tree: &Tree, tau: &[Sym]) -> ForwardDynamics {
    let n = tree.links.len();
    let zero = ctx.zero();
    let qd = ctx.velocities();
    // Pass 1, outward: velocities, velocity-product accelerations c and the
    // bias forces p = v ×* I v.
    let mut vel: Vec<[[Sym; 3]; 2]> = Vec::with_capacity(n);
    let mut bias_acc: Vec<[[Sym; 3]; 2]> = Vec::with_capacity(n);
    let mut inertia: Vec<Spatial> = Vec::with_capacity(n);
    let mut bias: Vec<[[Sym; 3]; 2]> = Vec::with_capacity(n);
    for link in &tree.links {
        let [w, v] = link.parent.map_or([[zero; 3]; 2], |p| vel[p]);
        let cs = trig(ctx, link);
        let rate = qd[link.coordinate];
        let wd = cross(ctx, w, link.offset);
        let v_at = add3(ctx, v, wd);
        let w_in = rotate_back(ctx, link.axis, cs, w);
        let v = rotate_back(ctx, link.axis, cs, v_at);
        let mut w = w_in;
        w[link.axis] = ctx.add(w[link.axis], rate);
        let wq = cross_axis(ctx, w_in, link.axis, rate);
        let vq = cross_axis(ctx, v, link.axis, rate);
        vel.push([w, v]);
        bias_acc.push([wq, vq]);
        let spatial = rigid_spatial(ctx, link.inertia.as_ref());
        let p = match &link.inertia {
            None => [[zero; 3]; 2],
            Some(_) => {
                let [l, p] = spatial_apply(ctx, &spatial, w, v);
                let wl = cross(ctx, w, l);
                let vp = cross(ctx, v, p);
                [add3(ctx, wl, vp), cross(ctx, w, p)]
            }
        };
        inertia.push(spatial);
        bias.push(p);
    }
    // Pass 2, inward: articulated inertias, U = Iᴬ S, D = Sᵀ U, u = τ − Sᵀ pᴬ.
    let mut columns: Vec<[[Sym; 3]; 2]> = vec![[[zero; 3]; 2]; n];
    let mut pivots = vec![zero; n];
    let mut residual = vec![zero; n];
    for i in (0..n).rev() {
        let link = &tree.links[i];
        let axis = link.axis;
        let s = inertia[i];
        let u_n = [s.a[0][axis], s.a[1][axis], s.a[2][axis]];
        let u_f = s.b[axis];
        let d = s.a[axis][axis];
        let u = ctx.sub(tau[link.coordinate], bias[i][0][axis]);
        columns[i] = [u_n, u_f];
        pivots[i] = d;
        residual[i] = u;
        let Some(p) = link.parent else { continue };
        // Iᵃ = Iᴬ − U Uᵀ/D, pᵃ = pᴬ + Iᵃ c + U u/D, carried to the parent.
        let inv = ctx.powi(d, -1);
        let scaled_n = u_n.map(|x| ctx.mul(x, inv));
        let scaled_f = u_f.map(|x| ctx.mul(x, inv));
        let outer = |ctx: &mut Context, x: [Sym; 3], y: [Sym; 3]| -> Mat3 {
            [0, 1, 2].map(|r| [0, 1, 2].map(|c| ctx.mul(x[r], y[c])))
        };
        let ua = outer(ctx, scaled_n, u_n);
        let ub = outer(ctx, scaled_n, u_f);
        let uc = outer(ctx, scaled_f, u_f);
        let mut art = Spatial {
            a: mat_add(ctx, &s.a, &ua, -1),
            b: mat_add(ctx, &s.b, &ub, -1),
            c: mat_add(ctx, &s.c, &uc, -1),
        };
        mirror_upper(&mut art.a);
        mirror_upper(&mut art.c);
        let [cw, cv] = bias_acc[i];
        let [ic_n, ic_f] = spatial_apply(ctx, &art, cw, cv);
        let uu = ctx.mul(u, inv);
        let un = u_n.map(|x| ctx.mul(x, uu));
        let uf = u_f.map(|x| ctx.mul(x, uu));
        let pn = [0, 1, 2].map(|k| ctx.sum(&[bias[i][0][k], ic_n[k], un[k]]));
        let pf = [0, 1, 2].map(|k| ctx.sum(&[bias[i][1][k], ic_f[k], uf[k]]));
        let moved = spatial_to_parent(ctx, link, &art);
        inertia[p] = Spatial {
            a: mat_add(ctx, &inertia[p].a, &moved.a, 1),
            b: mat_add(ctx, &inertia[p].b, &moved.b, 1),
            c: mat_add(ctx, &inertia[p].c, &moved.c, 1),
        };
        let [fn_, ff] = force_to_parent(ctx, link, pn, pf);
        bias[p] = [add3(ctx, bias[p][0], fn_), add3(ctx, bias[p][1], ff)];
    }
    // Pass 3, outward: a' = X a_parent + c, q̈ = (u − Uᵀ a')/D, a = a' + S q̈.
    let ground = {
        let a = tree.gravity.map_or([zero; 3], |g| g.map(|x| ctx.neg(x)));
        [[zero; 3], a]
    };
    let mut acc: Vec<[[Sym; 3]; 2]> = Vec::with_capacity(n);
    let mut qdd = vec![zero; n];
    for (i, link) in tree.links.iter().enumerate() {
        let [al, a] = link.parent.map_or(ground, |p| acc[p]);
        let cs = trig(ctx, link);
        let ad = cross(ctx, al, link.offset);
        let a_at = add3(ctx, a, ad);
        let al = rotate_back(ctx, link.axis, cs, al);
        let a = rotate_back(ctx, link.axis, cs, a_at);
        let mut al = add3(ctx, al, bias_acc[i][0]);
        let a = add3(ctx, a, bias_acc[i][1]);
        let [u_n, u_f] = columns[i];
        let mut terms = vec![residual[i]];
        for k in 0..3 {
            let x = ctx.mul(u_n[k], al[k]);
            terms.push(ctx.neg(x));
            let y = ctx.mul(u_f[k], a[k]);
            terms.push(ctx.neg(y));
        }
        let num = ctx.sum(&terms);
        let q = ctx.div(num, pivots[i]);
        qdd[link.coordinate] = q;
        al[link.axis] = ctx.add(al[link.axis], q);
        acc.push([al, a]);
    }
    ForwardDynamics {
        accelerations: qdd,
        pivots,
    }
}
