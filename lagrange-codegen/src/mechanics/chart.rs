//! Free orientations: the equations in the chart that moves with the body,
//! taken at its centre.
//!
//! A free orientation's rotation is lowered as R₀·exp(θ), R₀ the quaternion's
//! matrix (a constant to every derivative) and θ three ordinary coordinates
//! (see [`OrientationSymbols`](crate::lower::OrientationSymbols)). Everything
//! is derived in θ like any coordinate; here, last, θ = 0 is substituted in
//! every output, where θ̇ is the angular velocity in body axes and θ̈ its rate:
//! M, h and Q are then the equations in ω (Euler's for a lone body), read
//! from the quaternion, with no chart and no singular set.

use lagrange_symbolic::{Context, Expr as Sym};

use super::Derived;
use crate::lowered::{OrientationModel, Poses};
use crate::mat3::Mat3;

/// Free orientations: every output at the centre of the moving chart, θ = 0
/// (see `chart`). What takes no orientation yet (constraints, inputs and the
/// optional outputs but the articulated q̈ and the inverse dynamics) is
/// refused before the derivation.
pub(super) fn at_centre(ctx: &mut Context, d: &mut Derived) {
    if d.orientations.is_empty() {
        return;
    }
    let at = centre(ctx, &d.orientations);
    let norms = unit_norms(ctx, &d.orientations);
    let mut c = AtCentre {
        ctx,
        at: &at,
        norms: &norms,
    };
    let m = &mut d.motion;
    c.rows(&mut m.mass);
    for v in [&mut m.bias, &mut m.bias_other, &mut m.rhs, &mut m.forces] {
        c.all(v);
    }
    c.all(&mut d.forces.generalized);
    if let Some(a) = &mut d.forces.articulated {
        c.all(&mut a.accelerations);
        c.all(&mut a.pivots);
    }
    if let Some([jq, jv]) = &mut d.jacobians {
        c.rows(jq);
        c.rows(jv);
    }
    if let Some(i) = &mut d.inverse {
        c.all(&mut i.torques);
        c.all(&mut i.gravity);
    }
    for e in [&mut d.kinetic, &mut d.integral, &mut d.forces.potential] {
        *e = c.one(*e);
    }
    d.forces.gravity_potential = c.one(d.forces.gravity_potential);
    for (mass, position) in &mut d.particles {
        *mass = c.one(*mass);
        c.all(position);
    }
    c.poses(&mut d.poses);
}

/// θ ↦ 0 for every orientation.
pub(super) fn centre(ctx: &mut Context, orientations: &[OrientationModel]) -> Vec<(Sym, Sym)> {
    let zero = ctx.zero();
    orientations
        .iter()
        .flat_map(|o| o.theta.map(|x| (x, zero)))
        .collect()
}

/// Each quaternion's w and 1 − x² − y² − z², the unit norm's w².
pub(super) fn unit_norms(ctx: &mut Context, orientations: &[OrientationModel]) -> Vec<(Sym, Sym)> {
    orientations
        .iter()
        .map(|o| {
            let [w, x, y, z] = o.quaternion;
            let squares: Vec<Sym> = [x, y, z].iter().map(|&c| ctx.powi(c, 2)).collect();
            let sum = ctx.sum(&squares);
            let one = ctx.one();
            (w, ctx.sub(one, sum))
        })
        .collect()
}

/// Expressions up to this DAG size are also tried reduced by the unit norm
/// (expanding a larger one costs more than it is likely to save).
const REDUCE_UP_TO: usize = 3000;

/// Substitutes the chart's centre (`at`) into expressions, simplified again
/// (the zeros let products vanish and sums collect), and keeps the cheaper
/// of that and its reduction by each quaternion's unit norm (where R₀ᵀR₀ = I
/// hides: a point's kinetic energy |R₀ u|² = |u|²).
pub(super) struct AtCentre<'a> {
    pub ctx: &'a mut Context,
    pub at: &'a [(Sym, Sym)],
    pub norms: &'a [(Sym, Sym)],
}

impl AtCentre<'_> {
    pub fn one(&mut self, e: Sym) -> Sym {
        let s = self.ctx.substitute(e, self.at);
        let s = self.ctx.collect(s);
        let mut best = s;
        for &(w, square) in self.norms {
            if !self.ctx.depends_on(best, w) || self.ctx.node_count(best) > REDUCE_UP_TO {
                continue;
            }
            let reduced = self.ctx.reduce_square(best, w, square);
            if super::generic::cost(self.ctx, &[reduced]) < super::generic::cost(self.ctx, &[best])
            {
                best = reduced;
            }
        }
        best
    }

    pub fn all(&mut self, v: &mut [Sym]) {
        for e in v {
            *e = self.one(*e);
        }
    }

    pub fn rows(&mut self, m: &mut [Vec<Sym>]) {
        for row in m {
            self.all(row);
        }
    }

    pub fn mat3(&mut self, m: &mut Mat3) {
        for row in m {
            self.all(row);
        }
    }

    /// The bodies' frames and the points' positions the scene draws.
    pub fn poses(&mut self, poses: &mut Poses) {
        for b in &mut poses.bodies {
            self.all(&mut b.origin);
            self.all(&mut b.centre);
            self.mat3(&mut b.rotation);
        }
        for p in &mut poses.points {
            self.all(&mut p.position);
        }
    }
}
