//! q̈ by the articulated-body algorithm (Featherstone, Table 7.1).

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{
    add_motion, add3, force_to_parent, joint_velocity, mat_add, mirror_upper, origin, project,
    to_link, trig,
};
use super::spatial::{Spatial, rigid_spatial, spatial_apply, spatial_to_parent};
use super::{Link, Tree};
use crate::mat3::{Mat3, cross, mat_vec};

/// The accelerations by the articulated-body algorithm and its pivots.
pub struct ForwardDynamics {
    /// q̈_i, in coordinate order.
    pub accelerations: Vec<Sym>,
    /// D_i = Sᵢᵀ I_iᴬ Sᵢ (+ the joint's armature), the pivots of M's LᵀDL factorisation in tree order: a
    /// tiny ratio of the smallest to the largest says M is nearly singular.
    pub pivots: Vec<Sym>,
}

/// A spatial motion or force as (angular, linear) parts.
type Pair = [[Sym; 3]; 2];

/// q̈ by the articulated-body algorithm (Featherstone, Table 7.1) with the
/// generalized forces `tau` (in coordinate order) and gravity: O(n) operations,
/// no mass matrix and no factorisation. The three passes are the algorithm's.
pub fn forward_dynamics(ctx: &mut Context, tree: &Tree, tau: &[Sym]) -> ForwardDynamics {
    let mut links = velocities(ctx, tree);
    let joints = articulated_inertias(ctx, tree, tau, &mut links);
    let accelerations = accelerations(ctx, tree, &links.bias_acc, &joints);
    ForwardDynamics {
        accelerations,
        pivots: joints.pivots,
    }
}

/// What pass 1 leaves per link: the velocity-product accelerations c, the
/// (then articulated) inertias and the (then articulated) bias forces.
struct Links {
    bias_acc: Vec<Pair>,
    inertia: Vec<Spatial>,
    bias: Vec<Pair>,
}

/// What pass 2 leaves per joint: U = Iᴬ S, D = Sᵀ U and u = τ − Sᵀ pᴬ.
struct Joints {
    columns: Vec<Pair>,
    pivots: Vec<Sym>,
    residual: Vec<Sym>,
}

/// Pass 1, outward: velocities, velocity-product accelerations c and the bias
/// forces p = v ×* I v.
fn velocities(ctx: &mut Context, tree: &Tree) -> Links {
    let n = tree.links.len();
    let zero = ctx.zero();
    let qd = ctx.velocities();
    let mut vel: Vec<Pair> = Vec::with_capacity(n);
    let mut bias_acc: Vec<Pair> = Vec::with_capacity(n);
    let mut inertia: Vec<Spatial> = Vec::with_capacity(n);
    let mut bias: Vec<Pair> = Vec::with_capacity(n);
    let mut entering: Vec<Pair> = Vec::with_capacity(n);
    for link in &tree.links {
        let [w, v] = link.parent.map_or([[zero; 3]; 2], |p| vel[p]);
        let cs = trig(ctx, link);
        let rate = qd[link.coordinate];
        let d = origin(ctx, link);
        let wd = cross(ctx, w, d);
        let v_at = add3(ctx, v, wd);
        let w_in = to_link(ctx, link, cs, w);
        let v_in = to_link(ctx, link, cs, v_at);
        entering.push([w_in, v_in]);
        let first = link.chart.map_or([w_in, v_in], |k| entering[k]);
        let ([w, v], c) = joint_velocity(ctx, link, [w_in, v_in], first, rate);
        vel.push([w, v]);
        bias_acc.push(c);
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
    Links {
        bias_acc,
        inertia,
        bias,
    }
}

/// U = Iᴬ S: for S = (e_axis, 0) the moment column A e and the force column
/// Bᵀ e (row `axis` of B); for S = (0, s), B s and C s.
fn column(ctx: &mut Context, link: &Link, s: &Spatial) -> Pair {
    match link.slide {
        None => {
            let axis = link.axis;
            [[s.a[0][axis], s.a[1][axis], s.a[2][axis]], s.b[axis]]
        }
        Some(dir) => [mat_vec(ctx, &s.b, dir), mat_vec(ctx, &s.c, dir)],
    }
}

/// Pass 2, inward: articulated inertias and bias forces, each carried to the
/// parent, and the joint terms U, D, u.
fn articulated_inertias(ctx: &mut Context, tree: &Tree, tau: &[Sym], links: &mut Links) -> Joints {
    let n = tree.links.len();
    let zero = ctx.zero();
    let Links {
        bias_acc,
        inertia,
        bias,
    } = links;
    let mut columns: Vec<Pair> = vec![[[zero; 3]; 2]; n];
    let mut pivots = vec![zero; n];
    let mut residual = vec![zero; n];
    for i in (0..n).rev() {
        let link = &tree.links[i];
        let s = inertia[i];
        let [u_n, u_f] = column(ctx, link, &s);
        let d = project(ctx, link, &[u_n, u_f]);
        // D = Sᵀ Iᴬ S + Ia: the rotor's inertia is the joint's own.
        let d = (tree.armature.iter())
            .filter(|(q, _)| *q == link.coordinate)
            .fold(d, |d, &(_, ia)| ctx.add(d, ia));
        let p_joint = project(ctx, link, &bias[i]);
        let u = ctx.sub(tau[link.coordinate], p_joint);
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
    Joints {
        columns,
        pivots,
        residual,
    }
}

/// Pass 3, outward: a' = X a_parent + c, q̈ = (u − Uᵀ a')/D, a = a' + S q̈.
fn accelerations(ctx: &mut Context, tree: &Tree, bias_acc: &[Pair], joints: &Joints) -> Vec<Sym> {
    let n = tree.links.len();
    let zero = ctx.zero();
    let Joints {
        columns,
        pivots,
        residual,
    } = joints;
    let ground = {
        let a = tree.gravity.map_or([zero; 3], |g| g.map(|x| ctx.neg(x)));
        [[zero; 3], a]
    };
    let mut acc: Vec<Pair> = Vec::with_capacity(n);
    let mut qdd = vec![zero; n];
    for (i, link) in tree.links.iter().enumerate() {
        let [al, a] = link.parent.map_or(ground, |p| acc[p]);
        let cs = trig(ctx, link);
        let d = origin(ctx, link);
        let ad = cross(ctx, al, d);
        let a_at = add3(ctx, a, ad);
        let al = to_link(ctx, link, cs, al);
        let a = to_link(ctx, link, cs, a_at);
        let al = add3(ctx, al, bias_acc[i][0]);
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
        let mut pair = [al, a];
        add_motion(ctx, link, &mut pair, q);
        acc.push(pair);
    }
    qdd
}
