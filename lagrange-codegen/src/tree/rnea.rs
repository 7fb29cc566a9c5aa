//! h − Q_gravity (or h alone) by recursive Newton–Euler (Featherstone, §5.3):
//! velocities and accelerations outward, forces inward.

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{
    add_motion, add3, cross, force_to_parent, joint_velocity, mat_vec, origin, project, to_link,
    trig,
};
use super::{Inertia, Tree};

/// Recursive Newton–Euler at q̈ = 0: τ = h(q, q̇) − Q_gravity(q) with gravity, h
/// alone without. Velocities and bias accelerations go out from the root in link
/// axes, the link forces I a + v ×* I v come back, and τ_i is the joint-axis
/// component of the moment.
pub fn inverse_dynamics(ctx: &mut Context, tree: &Tree, with_gravity: bool) -> Vec<Sym> {
    recursive_newton_euler(ctx, tree, with_gravity, false)
}

/// τ = M q̈ + h (− Q_gravity `with_gravity`) at the accelerations' symbols, by
/// the same passes with S q̈ added to each link's acceleration.
pub fn inverse_dynamics_at_accelerations(
    ctx: &mut Context,
    tree: &Tree,
    with_gravity: bool,
) -> Vec<Sym> {
    recursive_newton_euler(ctx, tree, with_gravity, true)
}

fn recursive_newton_euler(
    ctx: &mut Context,
    tree: &Tree,
    with_gravity: bool,
    accelerated: bool,
) -> Vec<Sym> {
    let n = tree.links.len();
    let zero = ctx.zero();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    // (ω, v, α, a) of each link at its origin, in its axes.
    let mut motion: Vec<[[Sym; 3]; 4]> = Vec::with_capacity(n);
    let ground = {
        let mut a = [zero; 3];
        if let (true, Some(g)) = (with_gravity, tree.gravity) {
            a = g.map(|x| ctx.neg(x));
        }
        [[zero; 3], [zero; 3], [zero; 3], a]
    };
    let mut entering: Vec<[[Sym; 3]; 2]> = Vec::with_capacity(n);
    for link in &tree.links {
        let [w, v, al, a] = link.parent.map_or(ground, |p| motion[p]);
        let cs = trig(ctx, link);
        let rate = qd[link.coordinate];
        let d = origin(ctx, link);
        let wd = cross(ctx, w, d);
        let v_at = add3(ctx, v, wd);
        let ad = cross(ctx, al, d);
        let a_at = add3(ctx, a, ad);
        let w_in = to_link(ctx, link, cs, w);
        let v_in = to_link(ctx, link, cs, v_at);
        let al_in = to_link(ctx, link, cs, al);
        let a_in = to_link(ctx, link, cs, a_at);
        entering.push([w_in, v_in]);
        let first = link.chart.map_or([w_in, v_in], |k| entering[k]);
        let ([w, v], [cw, cv]) = joint_velocity(ctx, link, [w_in, v_in], first, rate);
        let mut acc = [add3(ctx, al_in, cw), add3(ctx, a_in, cv)];
        if accelerated {
            add_motion(ctx, link, &mut acc, qdd[link.coordinate]);
        }
        motion.push([w, v, acc[0], acc[1]]);
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
    let mut tau = vec![zero; ctx.coordinates().len()];
    for k in (0..n).rev() {
        let link = &tree.links[k];
        let [nk, fk] = forces[k];
        // A coordinate that drives several joints (a mimic joint) takes the
        // sum of their shares: the chain rule through q̇_joint = S q̇.
        let share = project(ctx, link, &[nk, fk]);
        tau[link.coordinate] = ctx.add(tau[link.coordinate], share);
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
pub(super) fn body_force(
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
