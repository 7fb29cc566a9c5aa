//! ∂τ/∂q and ∂τ/∂q̇ of recursive Newton–Euler in closed form (Carpentier and
//! Mansard, *Analytical derivatives of rigid body dynamics algorithms*, RSS
//! 2018), at the accelerations' symbols.
//!
//! Differentiating the link-axes recursion (`rnea`) coordinate by coordinate
//! carries every derivative through every later link's transform: O(n²)
//! transforms. Here every quantity is taken in world axes at the world origin,
//! where turning joint k moves its whole subtree by the motion S_k: the
//! derivative of a world quantity is then a cross product with S_k, and each
//! pair of joints costs a few dot products with composite quantities gathered
//! once per joint (the composite inertia Y^c, the composite of
//! B = v ×* Y − Y v× + (Y v) ×̄ and the composite force F^c).
//!
//! The same composites give M (M_ij = S_iᵀ Y^c S_j) and τ at q̈ = 0 (S_iᵀ F^c),
//! which the program of q̈ and its derivatives takes where that is cheaper
//! than the link-axes recursions.
//!
//! A spherical joint (a free orientation's three chart links) is one joint of
//! three columns, differentiated along q ⊕ δ at fixed ω, which is the tangent
//! space's derivative the rest of the library uses. A coordinate that drives
//! several joints (a mimic joint) sums their rows and columns: the chain rule.

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{add3, elementary};
use super::{Inertia, Link, Tree};
use crate::mat3::{Mat3, cross, dot, mat_mul, mat_vec, skew};

/// A spatial motion (ω, v at the world origin) or force (moment about the
/// world origin, force), world axes.
type Pair = [[Sym; 3]; 2];

/// B = v ×* Y − Y v× + (Y v) ×̄ in its sixteen numbers: B m = Ẏ m + m ×* h,
/// Ẏ = v ×* Y − Y v× (an inertia of no mass) and h = Y v; the composite of a
/// subtree is the sums of both.
#[derive(Clone, Copy)]
struct Coriolis {
    rate: WorldInertia,
    momentum: Pair,
}

/// A rigid body's spatial inertia in world axes about the world origin: mass,
/// first moment m c and the rotational inertia about the origin.
#[derive(Clone, Copy)]
struct WorldInertia {
    mass: Sym,
    first: [Sym; 3],
    rot: Mat3,
}

/// One joint of the recursion: a revolute or sliding link, or a spherical
/// joint's three chart links together.
struct Joint {
    parent: Option<usize>,
    /// (coordinate, world motion subspace column).
    columns: Vec<(usize, Pair)>,
    inertia: WorldInertia,
}

/// Per joint, what the forward pass leaves for the backward one.
struct Kinematic {
    /// The force the joint's own bodies need, Y a + v ×* Y v.
    force: Pair,
    /// B = v ×* Y − Y v× + (Y v) ×̄.
    coriolis: Coriolis,
    /// Per column: ∂v/∂q-like v_parent × S, the acceleration column
    /// a_parent × S + v_parent × (v_parent × S), and ∂a/∂q̇ = v × S + v_parent × S.
    dv_dq: Vec<Pair>,
    da_dq: Vec<Pair>,
    da_dv: Vec<Pair>,
}

/// ∂τ/∂q and ∂τ/∂q̇ for τ = RNEA(q, q̇, q̈; gravity as a base acceleration),
/// and M and τ at q̈ = 0 read off the same composites; N × N row-major, in
/// coordinate order.
pub struct Derivatives {
    /// ∂τ/∂q (∂τ/∂δ along a spherical joint's tangent).
    pub position: Vec<Vec<Sym>>,
    /// ∂τ/∂q̇.
    pub velocity: Vec<Vec<Sym>>,
    /// M, with M_ij = S_iᵀ Y^c_j S_j where i's joint is j's or its ancestor
    /// (Y^c_j S_j is what the derivatives' rows already take), and the
    /// rotors' inertias on the diagonal.
    pub mass: Vec<Vec<Sym>>,
    /// τ at q̈ = 0, h − Q_gravity: S_iᵀ F^c_i with the accelerations zero.
    pub bias: Vec<Sym>,
}

/// The derivatives of recursive Newton–Euler and M and h from the same
/// world-axes composites.
pub fn inverse_dynamics_derivatives(ctx: &mut Context, tree: &Tree) -> Derivatives {
    let joints = joints(ctx, tree);
    let kinematics = forward(ctx, tree, &joints);
    let mut d = backward(ctx, &joints, &kinematics);
    for &(q, ia) in &tree.armature {
        d.mass[q][q] = ctx.add(d.mass[q][q], ia);
    }
    let zero = ctx.zero();
    let at_rest: Vec<(Sym, Sym)> = ctx.accelerations().into_iter().map(|a| (a, zero)).collect();
    d.bias = ctx.substitute_all(&d.bias, &at_rest);
    d
}

/// The joints in parent-first order with their world columns and inertias.
fn joints(ctx: &mut Context, tree: &Tree) -> Vec<Joint> {
    let zero = ctx.zero();
    let one = ctx.one();
    let identity = [[one, zero, zero], [zero, one, zero], [zero, zero, one]];
    let ground = (identity, [zero; 3]);
    let mut poses: Vec<(Mat3, [Sym; 3])> = Vec::with_capacity(tree.links.len());
    let mut joint_of: Vec<usize> = Vec::with_capacity(tree.links.len());
    let mut joints: Vec<Joint> = Vec::new();
    for (l, link) in tree.links.iter().enumerate() {
        let (rp, pp) = link.parent.map_or(ground, |p| poses[p]);
        let (pose, column) = world_link(ctx, link, rp, pp);
        poses.push(pose);
        let coordinate = link.coordinate;
        // A chart's later axes join its first link's joint.
        let joined = link.chart.filter(|&k| k != l).map(|k| joint_of[k]);
        let j = match joined {
            Some(j) => {
                joints[j].columns.push((coordinate, column));
                j
            }
            None => {
                joints.push(Joint {
                    parent: link.parent.map(|p| joint_of[p]),
                    columns: vec![(coordinate, column)],
                    inertia: massless(ctx),
                });
                joints.len() - 1
            }
        };
        joint_of.push(j);
        if let Some(i) = &link.inertia {
            let w = world_inertia(ctx, i, pose);
            joints[j].inertia = add_inertia(ctx, &joints[j].inertia, &w);
        }
    }
    joints
}

/// A link's world pose (rotation, origin) and its joint's world column S.
fn world_link(ctx: &mut Context, link: &Link, rp: Mat3, pp: [Sym; 3]) -> ((Mat3, [Sym; 3]), Pair) {
    let zero = ctx.zero();
    let at = mat_vec(ctx, &rp, link.offset);
    let origin = add3(ctx, pp, at);
    if let Some(dir) = link.slide {
        let u = mat_vec(ctx, &rp, dir);
        let q = ctx.coordinates()[link.coordinate];
        let moved = u.map(|x| ctx.mul(x, q));
        let origin = add3(ctx, origin, moved);
        return ((rp, origin), [[zero; 3], u]);
    }
    let placed = match &link.placement {
        None => rp,
        Some(p) => mat_mul(ctx, &rp, p),
    };
    // The axis is the placed frame's: rot_axis(q) leaves it where it is.
    let u = [0, 1, 2].map(|r| placed[r][link.axis]);
    let rotation = if link.chart.is_some() {
        placed
    } else {
        let q = ctx.coordinates()[link.coordinate];
        let turn = elementary(ctx, link.axis, q);
        mat_mul(ctx, &placed, &turn)
    };
    let moment = cross(ctx, origin, u);
    ((rotation, origin), [u, moment])
}

fn massless(ctx: &mut Context) -> WorldInertia {
    let zero = ctx.zero();
    WorldInertia {
        mass: zero,
        first: [zero; 3],
        rot: [[zero; 3]; 3],
    }
}

/// A link's inertia (about its origin, link axes) in world axes about the
/// world origin: first moment m p + h with h = R h_link, rotational inertia
/// R I Rᵀ + m (|p|² 1 − p pᵀ) + 2 (p·h) 1 − h pᵀ − p hᵀ (the parallel-axis
/// terms −m [p]×² − [p]×[h]× − [h]×[p]×, by [a]×[b]× = b aᵀ − (a·b) 1).
fn world_inertia(ctx: &mut Context, i: &Inertia, (r, p): (Mat3, [Sym; 3])) -> WorldInertia {
    let h = mat_vec(ctx, &r, i.first);
    let mp = p.map(|x| ctx.mul(i.mass, x));
    let first = add3(ctx, mp, h);
    let ri = mat_mul(ctx, &r, &i.rot);
    let p_mp = dot(ctx, &p, &mp);
    let p_h = dot(ctx, &p, &h);
    let two = ctx.int(2);
    let twice = ctx.mul(two, p_h);
    let diagonal = ctx.add(p_mp, twice);
    let rot = symmetric(ctx, diagonal, |ctx, a, b| {
        let turned = dot(ctx, &ri[a], &r[b]);
        let outer = ctx.mul(mp[a], p[b]);
        let hp = ctx.mul(h[a], p[b]);
        let ph = ctx.mul(p[a], h[b]);
        let e = ctx.sum(&[outer, hp, ph]);
        ctx.sub(turned, e)
    });
    WorldInertia {
        mass: i.mass,
        first,
        rot,
    }
}

/// Ẏ = v ×* Y − Y v× of a body moving with v = (ω, v_O), an inertia of no
/// mass: first moment m v_O + ω × h and rotational inertia
/// [ω]× I − I [ω]× − [v_O]×[h]× − [h]×[v_O]× (each product and its
/// transpose: C + Cᵀ with C = [ω]× I, and 2 (v_O·h) 1 − h v_Oᵀ − v_O hᵀ).
fn rate(ctx: &mut Context, y: &WorldInertia, [w, v]: Pair) -> WorldInertia {
    let mv = v.map(|x| ctx.mul(y.mass, x));
    let wh = cross(ctx, w, y.first);
    let first = add3(ctx, mv, wh);
    let wx = skew(ctx, w);
    let c = mat_mul(ctx, &wx, &y.rot);
    let vh = dot(ctx, &v, &y.first);
    let two = ctx.int(2);
    let diagonal = ctx.mul(two, vh);
    let rot = symmetric(ctx, diagonal, |ctx, a, b| {
        let hv = ctx.mul(y.first[a], v[b]);
        let vh = ctx.mul(v[a], y.first[b]);
        let outer = ctx.add(hv, vh);
        let e = ctx.add(c[a][b], c[b][a]);
        ctx.sub(e, outer)
    });
    WorldInertia {
        mass: ctx.zero(),
        first,
        rot,
    }
}

/// The symmetric matrix with entries `entry(a, b)` for a ≤ b, `diagonal`
/// added on the diagonal.
fn symmetric(
    ctx: &mut Context,
    diagonal: Sym,
    mut entry: impl FnMut(&mut Context, usize, usize) -> Sym,
) -> Mat3 {
    let mut m = [[diagonal; 3]; 3];
    for (a, b) in [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)] {
        let mut e = entry(ctx, a, b);
        if a == b {
            e = ctx.add(e, diagonal);
        }
        m[a][b] = e;
        m[b][a] = e;
    }
    m
}

fn add_inertia(ctx: &mut Context, a: &WorldInertia, b: &WorldInertia) -> WorldInertia {
    WorldInertia {
        mass: ctx.add(a.mass, b.mass),
        first: add3(ctx, a.first, b.first),
        rot: [0, 1, 2].map(|r| [0, 1, 2].map(|c| ctx.add(a.rot[r][c], b.rot[r][c]))),
    }
}

/// Y m = (I ω + h × v, m v − h × ω).
fn apply(ctx: &mut Context, y: &WorldInertia, [w, v]: Pair) -> Pair {
    let iw = mat_vec(ctx, &y.rot, w);
    let hv = cross(ctx, y.first, v);
    let mv = v.map(|x| ctx.mul(y.mass, x));
    let hw = cross(ctx, y.first, w);
    let force = [0, 1, 2].map(|k| ctx.sub(mv[k], hw[k]));
    [add3(ctx, iw, hv), force]
}

/// a × b of two motions.
fn cross_motion(ctx: &mut Context, [w, v]: Pair, [x, u]: Pair) -> Pair {
    let ang = cross(ctx, w, x);
    let wu = cross(ctx, w, u);
    let vx = cross(ctx, v, x);
    [ang, add3(ctx, wu, vx)]
}

/// m ×* f of a motion and a force.
fn cross_force(ctx: &mut Context, [w, v]: Pair, [n, f]: Pair) -> Pair {
    let wn = cross(ctx, w, n);
    let vf = cross(ctx, v, f);
    [add3(ctx, wn, vf), cross(ctx, w, f)]
}

fn add_pair(ctx: &mut Context, a: Pair, b: Pair) -> Pair {
    [add3(ctx, a[0], b[0]), add3(ctx, a[1], b[1])]
}

fn scale(ctx: &mut Context, a: Pair, s: Sym) -> Pair {
    a.map(|p| p.map(|x| ctx.mul(x, s)))
}

fn flat(a: Pair) -> [Sym; 6] {
    [a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2]]
}

/// Forward pass: world velocities and accelerations (the ground accelerating
/// at −g), each joint's force, B and its columns' motion derivatives.
fn forward(ctx: &mut Context, tree: &Tree, joints: &[Joint]) -> Vec<Kinematic> {
    let zero = ctx.zero();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let lift = tree.gravity.map_or([zero; 3], |g| g.map(|x| ctx.neg(x)));
    let ground: (Pair, Pair) = ([[zero; 3]; 2], [[zero; 3], lift]);
    let mut motion: Vec<(Pair, Pair)> = Vec::with_capacity(joints.len());
    let mut out = Vec::with_capacity(joints.len());
    for joint in joints {
        let (vp, ap) = joint.parent.map_or(ground, |p| motion[p]);
        let mut v = vp;
        for &(c, s) in &joint.columns {
            let sv = scale(ctx, s, qd[c]);
            v = add_pair(ctx, v, sv);
        }
        let mut a = ap;
        let mut dj = Vec::with_capacity(joint.columns.len());
        for &(c, s) in &joint.columns {
            let d = cross_motion(ctx, v, s);
            let sa = scale(ctx, s, qdd[c]);
            let dq = scale(ctx, d, qd[c]);
            a = add_pair(ctx, a, sa);
            a = add_pair(ctx, a, dq);
            dj.push(d);
        }
        motion.push((v, a));
        let y = &joint.inertia;
        let h = apply(ctx, y, v);
        let ya = apply(ctx, y, a);
        let vh = cross_force(ctx, v, h);
        let force = add_pair(ctx, ya, vh);
        let coriolis = Coriolis {
            rate: rate(ctx, y, v),
            momentum: h,
        };
        let mut dv_dq = Vec::new();
        let mut da_dq = Vec::new();
        let mut da_dv = Vec::new();
        for (&(_, s), d) in joint.columns.iter().zip(dj) {
            let vs = cross_motion(ctx, vp, s);
            let as_ = cross_motion(ctx, ap, s);
            let vvs = cross_motion(ctx, vp, vs);
            da_dq.push(add_pair(ctx, as_, vvs));
            da_dv.push(add_pair(ctx, d, vs));
            dv_dq.push(vs);
        }
        out.push(Kinematic {
            force,
            coriolis,
            dv_dq,
            da_dq,
            da_dv,
        });
    }
    out
}

/// B m = Ẏ m + m ×* h.
fn coriolis_apply(ctx: &mut Context, b: &Coriolis, m: Pair) -> Pair {
    let ym = apply(ctx, &b.rate, m);
    let mh = cross_force(ctx, m, b.momentum);
    add_pair(ctx, ym, mh)
}

/// Bᵀ x = Ẏ x + (n × a + l × b, l × a) for x = (a, b) and h = (n, l): Ẏ is
/// symmetric, and the transpose of m ↦ m ×* h is that map.
fn coriolis_transpose_apply(ctx: &mut Context, b: &Coriolis, x: Pair) -> Pair {
    let yx = apply(ctx, &b.rate, x);
    let [n, l] = b.momentum;
    let na = cross(ctx, n, x[0]);
    let lb = cross(ctx, l, x[1]);
    let la = cross(ctx, l, x[0]);
    let turned = [add3(ctx, na, lb), la];
    add_pair(ctx, yx, turned)
}

fn dot6(ctx: &mut Context, a: Pair, b: Pair) -> Sym {
    dot(ctx, &flat(a), &flat(b))
}

/// Composite quantities of a subtree, gathered leaves first.
#[derive(Clone, Copy)]
struct Composite {
    inertia: WorldInertia,
    coriolis: Coriolis,
    force: Pair,
}

/// What a column leaves for its ancestors' rows and columns.
struct Column {
    coordinate: usize,
    s: Pair,
    /// Y^c S and B^cᵀ S, for the rows of this column below an ancestor.
    ys: Pair,
    bts: Pair,
    /// ∂F/∂q and ∂F/∂q̇ of the subtree, for the ancestors' rows.
    df_dq: Pair,
    df_dv: Pair,
}

/// Backward pass: composites, then each joint's columns against its
/// subtree's (τ and M at the accelerations' symbols; `inverse_dynamics_derivatives`
/// adds the rotors and sets q̈ = 0 in τ).
fn backward(ctx: &mut Context, joints: &[Joint], kin: &[Kinematic]) -> Derivatives {
    let n = ctx.coordinates().len();
    let zero = ctx.zero();
    let mut dq = vec![vec![zero; n]; n];
    let mut dv = vec![vec![zero; n]; n];
    let mut mass = vec![vec![zero; n]; n];
    let mut tau = vec![zero; n];
    let mut composite: Vec<Composite> = joints
        .iter()
        .zip(kin)
        .map(|(j, k)| Composite {
            inertia: j.inertia,
            coriolis: k.coriolis,
            force: k.force,
        })
        .collect();
    // The columns of each joint's subtree, its own first.
    let mut below: Vec<Vec<Column>> = (0..joints.len()).map(|_| Vec::new()).collect();
    for j in (0..joints.len()).rev() {
        let c = composite[j];
        let k = &kin[j];
        let descendants = std::mem::take(&mut below[j]);
        let mut own = Vec::with_capacity(joints[j].columns.len());
        for (i, &(coordinate, s)) in joints[j].columns.iter().enumerate() {
            let matrices = (&mut dq[..], &mut dv[..]);
            descendant_rows(ctx, matrices, &descendants, (k, i), (coordinate, s));
            own.push(column(ctx, &c, (k, i), (coordinate, s)));
        }
        // This joint's rows against its own columns and its subtree's; M's
        // entries below this joint are symmetric, τ its columns' S ᵀ F^c.
        for r in &own {
            for (index, e) in own.iter().chain(&descendants).enumerate() {
                let x = dot6(ctx, r.s, e.df_dq);
                accumulate(ctx, &mut dq, r.coordinate, e.coordinate, x);
                let x = dot6(ctx, r.s, e.df_dv);
                accumulate(ctx, &mut dv, r.coordinate, e.coordinate, x);
                let x = dot6(ctx, r.s, e.ys);
                accumulate(ctx, &mut mass, r.coordinate, e.coordinate, x);
                if index >= own.len() {
                    accumulate(ctx, &mut mass, e.coordinate, r.coordinate, x);
                }
            }
            let x = dot6(ctx, r.s, c.force);
            tau[r.coordinate] = ctx.add(tau[r.coordinate], x);
        }
        // Turning this joint turns the subtree's force: S ×* F^c, for the
        // ancestors' rows (its own rows see none of it: Sᵀ (S ×* F) = 0 for
        // one column, and a spherical joint's derivative at fixed ω leaves it
        // out).
        for col in &mut own {
            let turn = cross_force(ctx, col.s, c.force);
            col.df_dq = add_pair(ctx, col.df_dq, turn);
        }
        if let Some(p) = joints[j].parent {
            composite[p] = merge(ctx, &composite[p], &c);
            below[p].extend(own);
            below[p].extend(descendants);
        }
    }
    Derivatives {
        position: dq,
        velocity: dv,
        mass,
        bias: tau,
    }
}

/// Column `i` of joint `k` (`coordinate`, S) with the composites of its
/// subtree: Y^c S, B^cᵀ S, ∂F/∂q = B^c (v_parent × S) + Y^c ∂a/∂q and
/// ∂F/∂q̇ = B^c S + Y^c ∂a/∂q̇.
fn column(
    ctx: &mut Context,
    c: &Composite,
    (k, i): (&Kinematic, usize),
    (coordinate, s): (usize, Pair),
) -> Column {
    let ys = apply(ctx, &c.inertia, s);
    let bts = coriolis_transpose_apply(ctx, &c.coriolis, s);
    let bq = coriolis_apply(ctx, &c.coriolis, k.dv_dq[i]);
    let yq = apply(ctx, &c.inertia, k.da_dq[i]);
    let bs = coriolis_apply(ctx, &c.coriolis, s);
    let yv = apply(ctx, &c.inertia, k.da_dv[i]);
    Column {
        coordinate,
        s,
        ys,
        bts,
        df_dq: add_pair(ctx, bq, yq),
        df_dv: add_pair(ctx, bs, yv),
    }
}

/// The rows of the descendants' columns against column `i` of joint `k`:
/// (Y^c S)_d · ∂a/∂q + (B^cᵀ S)_d · (v_parent × S), and likewise in q̇.
fn descendant_rows(
    ctx: &mut Context,
    (dq, dv): (&mut [Vec<Sym>], &mut [Vec<Sym>]),
    descendants: &[Column],
    (k, i): (&Kinematic, usize),
    (coordinate, s): (usize, Pair),
) {
    for d in descendants {
        let a = dot6(ctx, d.ys, k.da_dq[i]);
        let b = dot6(ctx, d.bts, k.dv_dq[i]);
        let e = ctx.add(a, b);
        accumulate(ctx, dq, d.coordinate, coordinate, e);
        let a = dot6(ctx, d.ys, k.da_dv[i]);
        let b = dot6(ctx, d.bts, s);
        let e = ctx.add(a, b);
        accumulate(ctx, dv, d.coordinate, coordinate, e);
    }
}

/// The composites of a parent and one of its subtrees together.
fn merge(ctx: &mut Context, up: &Composite, c: &Composite) -> Composite {
    Composite {
        inertia: add_inertia(ctx, &up.inertia, &c.inertia),
        coriolis: Coriolis {
            rate: add_inertia(ctx, &up.coriolis.rate, &c.coriolis.rate),
            momentum: add_pair(ctx, up.coriolis.momentum, c.coriolis.momentum),
        },
        force: add_pair(ctx, up.force, c.force),
    }
}

fn accumulate(ctx: &mut Context, m: &mut [Vec<Sym>], r: usize, c: usize, x: Sym) {
    m[r][c] = ctx.add(m[r][c], x);
}
