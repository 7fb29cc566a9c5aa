//! h − Q_gravity (or h alone) by recursive Newton–Euler: angular velocities
//! and accelerations and the classical accelerations of the link origins
//! outward, forces inward (Luh, Walker and Paul's form of Featherstone's §5.3:
//! no linear velocities, and a body's force is Newton–Euler about its origin,
//! cheaper than I a + v ×* I v).

use lagrange_symbolic::{Context, Expr as Sym};

use super::link::{add_motion, add3, cross_axis, force_to_parent, origin, project, to_link, trig};
use super::{Inertia, Tree};
use crate::mat3::{cross, mat_vec};

/// Recursive Newton–Euler at q̈ = 0: τ = h(q, q̇) − Q_gravity(q) with gravity, h
/// alone without. Angular velocities and accelerations go out from the root
/// in link axes, the link forces come back, and τ_i is the joint's share of
/// the force at its link (the joint-axis component of the moment).
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
    let motion = accelerations(ctx, tree, with_gravity, accelerated);
    let mut forces: Vec<[[Sym; 3]; 2]> = tree
        .links
        .iter()
        .zip(&motion)
        .map(|(link, &[w, al, a])| match &link.inertia {
            None => [[zero; 3], [zero; 3]],
            Some(i) => body_force(ctx, i, w, al, a),
        })
        .collect();
    let mut tau = vec![zero; ctx.coordinates().len()];
    if accelerated {
        // A rotor's reflected inertia turns with its coordinate alone.
        let qdd = ctx.accelerations();
        for &(qi, ia) in &tree.armature {
            tau[qi] = ctx.mul(ia, qdd[qi]);
        }
    }
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

/// Each link's (ω, α, a) in its axes, a the classical acceleration of its
/// origin, outward from the ground (accelerating at −g `with_gravity`), with
/// S q̈ added `accelerated`. The classical form needs no linear velocity:
/// a' = a + α × d + ω × (ω × d) at the child's origin d, and Newton–Euler at
/// the origin reads ω, α and a alone.
pub(super) fn accelerations(
    ctx: &mut Context,
    tree: &Tree,
    with_gravity: bool,
    accelerated: bool,
) -> Vec<[[Sym; 3]; 3]> {
    let zero = ctx.zero();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let mut a = [zero; 3];
    if let (true, Some(g)) = (with_gravity, tree.gravity) {
        a = g.map(|x| ctx.neg(x));
    }
    let ground = [[zero; 3], [zero; 3], a];
    let mut motion: Vec<[[Sym; 3]; 3]> = Vec::with_capacity(tree.links.len());
    // ω carried into each link: a spherical joint's axes turn about the
    // first one's (see `Link::chart`).
    let mut entering: Vec<[Sym; 3]> = Vec::with_capacity(tree.links.len());
    for link in &tree.links {
        let [w, al, a] = link.parent.map_or(ground, |p| motion[p]);
        let cs = trig(ctx, link);
        let rate = qd[link.coordinate];
        let d = origin(ctx, link);
        let wd = cross(ctx, w, d);
        let wwd = cross(ctx, w, wd);
        let ad = cross(ctx, al, d);
        let a_at = [0, 1, 2].map(|k| ctx.sum(&[a[k], ad[k], wwd[k]]));
        let w_in = to_link(ctx, link, cs, w);
        let al_in = to_link(ctx, link, cs, al);
        let mut a_in = to_link(ctx, link, cs, a_at);
        entering.push(w_in);
        let mut acc = [al_in, a_in];
        let w = match link.slide {
            None => {
                let first = link.chart.map_or(w_in, |k| entering[k]);
                let turn = cross_axis(ctx, first, link.axis, rate);
                acc[0] = add3(ctx, al_in, turn);
                let mut turned = w_in;
                turned[link.axis] = ctx.add(w_in[link.axis], rate);
                turned
            }
            Some(dir) => {
                // Coriolis: 2 ω × s q̇ along a sliding joint.
                let u = dir.map(|x| ctx.mul(x, rate));
                let wu = cross(ctx, w_in, u);
                let two = ctx.int(2);
                a_in = [0, 1, 2].map(|k| {
                    let c = ctx.mul(two, wu[k]);
                    ctx.add(a_in[k], c)
                });
                acc[1] = a_in;
                w_in
            }
        };
        if accelerated {
            add_motion(ctx, link, &mut acc, qdd[link.coordinate]);
        }
        motion.push([w, acc[0], acc[1]]);
    }
    motion
}

/// The force a rigid body (m, h = m c, I_o) needs at its origin: Newton–Euler
/// about the origin with its classical acceleration a,
/// moment I_o α + ω × I_o ω + h × a, force m a + α × h + ω × (ω × h).
pub(super) fn body_force(
    ctx: &mut Context,
    i: &Inertia,
    w: [Sym; 3],
    al: [Sym; 3],
    a: [Sym; 3],
) -> [[Sym; 3]; 2] {
    let iw = mat_vec(ctx, &i.rot, w);
    let ia = mat_vec(ctx, &i.rot, al);
    let wiw = cross(ctx, w, iw);
    let ha = cross(ctx, i.first, a);
    let moment = [0, 1, 2].map(|k| ctx.sum(&[ia[k], wiw[k], ha[k]]));
    let ma = a.map(|x| ctx.mul(i.mass, x));
    let ah = cross(ctx, al, i.first);
    let wh = cross(ctx, w, i.first);
    let wwh = cross(ctx, w, wh);
    let force = [0, 1, 2].map(|k| ctx.sum(&[ma[k], ah[k], wwh[k]]));
    [moment, force]
}
