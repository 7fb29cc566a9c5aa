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

use super::force::InputModel;
use super::{Derived, Frames};
use crate::constraint::{ConstraintSet, Reduction};
use crate::lowered::{OrientationModel, Poses};
use crate::mat3::Mat3;

/// The constrained forms derived in θ, to be taken at the centre.
pub(super) struct Forms<'a> {
    pub constraints: Option<&'a mut ConstraintSet>,
    pub reduced: Option<&'a mut Reduction>,
}

/// Free orientations: every output at the centre of the moving chart, θ = 0,
/// the inputs' forces, both constrained forms' rows and the Coriolis matrix
/// included (derived in θ before: the rates γ and c = −(Ȧ q̇ + ḃ) need the
/// rows' θ-derivatives, and the Christoffel symbols of M(θ) at θ = 0 give C
/// with h = C ω and Ṁ − 2C skew along the motion), and ∂T/∂θ for
/// Hamilton's form.
pub(super) fn at_centre(
    ctx: &mut Context,
    d: &mut Derived,
    forms: Forms<'_>,
    frames: Option<&mut Frames>,
    coriolis: Option<&mut Vec<Vec<Sym>>>,
) {
    let variables = &d.variables;
    if variables.orientations.is_empty() {
        return;
    }
    let at = centre(ctx, &variables.orientations);
    let norms = unit_norms(ctx, &variables.orientations);
    let mut c = AtCentre {
        ctx,
        at: &at,
        norms: &norms,
    };
    let m = &mut d.motion;
    c.rows(&mut m.mass);
    let other = &mut m.derivation.other_bias;
    for v in [&mut m.bias, other, &mut m.rhs, &mut m.forces] {
        c.all(v);
    }
    c.all(&mut d.forces.generalized);
    // The articulated-body recursions are built at the centre already and
    // are not reduced by the unit norm: the quaternion reaches q̈ only
    // through gravity in the root's axes (linear in R₀), so there is
    // nothing to reduce, and the reduction's full expansion of q̈ through
    // the nested 1/D of every link costs seconds (9 of Solo 12's 10 s).
    if let Some(a) = &mut d.forces.articulated {
        c.unreduced(&mut a.accelerations);
        c.unreduced(&mut a.pivots);
    }
    substituted_only(&mut c, d, frames);
    if let Some(cm) = coriolis {
        c.rows(cm);
    }
    if let Some(g) = &mut d.chart_gradient {
        c.all(g);
    }
    if let Some(i) = &mut d.inverse {
        c.all(&mut i.torques);
        c.all(&mut i.gravity);
    }
    let energies = &mut d.energies;
    for e in [
        &mut energies.kinetic,
        &mut energies.integral,
        &mut energies.potential,
    ] {
        *e = c.one(*e);
    }
    d.forces.gravity_potential = c.one(d.forces.gravity_potential);
    for (mass, position) in &mut d.masses.particles {
        *mass = c.one(*mass);
        c.all(position);
    }
    c.poses(&mut d.poses);
    if let Some(inputs) = &mut d.forces.inputs {
        let v = &d.variables;
        c.inputs(inputs, v.coordinates.len(), v.orientations.len());
    }
    c.forms(forms);
}

/// The derivatives (the right-hand side's Jacobians, the frames', Y's
/// columns, Y_E and Y_p) are substituted only: R(θ) → 1 makes most of their
/// terms vanish at construction, and collecting a few hundred of them costs
/// seconds of build time for no fewer operations.
fn substituted_only(c: &mut AtCentre, d: &mut Derived, frames: Option<&mut Frames>) {
    if let Some(j) = &mut d.jacobians {
        for row in j.position.iter_mut().chain(j.velocity.iter_mut()) {
            c.substituted(row);
        }
    }
    if let Some(f) = frames {
        for row in f.jacobians.iter_mut().chain(f.biases.iter_mut()) {
            c.substituted(row);
        }
        c.substituted(&mut f.com);
        c.substituted(&mut f.com_jacobian);
    }
    if let Some(r) = &mut d.regressor {
        for row in &mut r.rows {
            c.substituted(row);
        }
        c.substituted(&mut r.energy);
        for row in &mut r.momentum {
            c.substituted(row);
        }
    }
}

/// The kinetic-energy gradient at fixed ω from its value at fixed θ̇ (both
/// at θ = 0): ω = (1 − ½[θ]×) θ̇ + O(θ²), so at fixed θ̇ a turn δθ also
/// changes ω by −½ δθ × ω, and ∂T/∂θ|θ̇ = ∂T/∂θ|ω + ½ π × ω with π = ∂T/∂ω.
/// What Hamilton's form with orientations needs is ∂T/∂θ|ω, the derivative
/// along body-axis turns (X T, Hamel's equations π̇ = π × ω + X T + Q).
pub(super) fn at_fixed_omega(
    ctx: &mut Context,
    mut gradient: Vec<Sym>,
    p: &[Sym],
    (first, orientations): (usize, usize),
) -> Vec<Sym> {
    let v = ctx.velocities();
    let half = ctx.rational(1, 2);
    for k in 0..orientations {
        let o = first + 3 * k;
        for j in 0..3 {
            let a = o + (j + 1) % 3;
            let b = o + (j + 2) % 3;
            // (π × ω)_j = π_a ω_b − π_b ω_a.
            let ab = ctx.mul(p[a], v[b]);
            let ba = ctx.mul(p[b], v[a]);
            let cross = ctx.sub(ab, ba);
            let correction = ctx.mul(half, cross);
            let e = ctx.sub(gradient[o + j], correction);
            gradient[o + j] = ctx.collect(e);
        }
    }
    gradient
}

/// C_θ + ½ M W, W the block-diagonal [ω]× at each orientation's ω (zero
/// elsewhere): the Christoffel factorisation taken in the chart that moves
/// with the body (C_θ) satisfies Ṁ_θ − 2C_θ skew, where at θ = 0 Ṁ_θ =
/// Ṁ + ½(W M − M W) with Ṁ the rate of M along the motion (θ enters
/// through ω = (1 − ½[θ]×) θ̇). Adding ½ M W keeps C v = h (W v = 0, as
/// ω × ω = 0) and makes Ṁ − 2C skew: Ṁ − 2C = S − ½(W M + M W).
pub(super) fn along_the_motion(
    ctx: &mut Context,
    mut c: Vec<Vec<Sym>>,
    mass: &[Vec<Sym>],
    first: usize,
    orientations: usize,
) -> Vec<Vec<Sym>> {
    let v = ctx.velocities();
    let half = ctx.rational(1, 2);
    for k in 0..orientations {
        let o = first + 3 * k;
        let [x, y, z] = [v[o], v[o + 1], v[o + 2]];
        let nx = ctx.neg(x);
        let ny = ctx.neg(y);
        let nz = ctx.neg(z);
        let zero = ctx.zero();
        let skew = [[zero, nz, y], [z, zero, nx], [ny, x, zero]];
        for (row, m) in c.iter_mut().zip(mass) {
            for j in 0..3 {
                let terms: Vec<Sym> = (0..3).map(|l| ctx.mul(m[o + l], skew[l][j])).collect();
                let mw = ctx.sum(&terms);
                let mw = ctx.mul(half, mw);
                let e = ctx.add(row[o + j], mw);
                row[o + j] = ctx.collect(e);
            }
        }
    }
    c
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
    /// Both constrained forms' rows and rates at the centre.
    fn forms(&mut self, forms: Forms<'_>) {
        if let Some(set) = forms.constraints {
            self.all(&mut set.phi);
            self.rows(&mut set.jacobian);
            self.all(&mut set.velocity_term);
            self.all(&mut set.gamma);
            for (_, coefficients) in &mut set.reactions {
                self.rows(coefficients);
            }
        }
        if let Some(r) = forms.reduced {
            self.all(&mut r.speeds);
            self.rows(&mut r.matrix);
            self.all(&mut r.free);
            self.all(&mut r.rates);
            self.all(&mut r.positions);
        }
    }

    pub fn one(&mut self, e: Sym) -> Sym {
        // What the recursions built at the centre already (a spherical
        // joint's links) has no θ: collecting it would only expand it.
        let centred = !self
            .at
            .iter()
            .any(|&(theta, _)| self.ctx.depends_on(e, theta));
        let mut best = if centred {
            e
        } else {
            let s = self.ctx.substitute(e, self.at);
            self.ctx.collect(s)
        };
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

    /// θ = 0 substituted, nothing expanded.
    pub fn substituted(&mut self, v: &mut [Sym]) {
        for e in v {
            *e = self.ctx.substitute(*e, self.at);
        }
    }

    /// At the centre (substituted and collected where θ appears), not
    /// tried reduced by the unit norm.
    pub fn unreduced(&mut self, v: &mut [Sym]) {
        for e in v {
            if self
                .at
                .iter()
                .any(|&(theta, _)| self.ctx.depends_on(*e, theta))
            {
                let s = self.ctx.substitute(*e, self.at);
                *e = self.ctx.collect(s);
            }
        }
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

    /// The inputs' forces and Jacobians, the orientations' θ starting at
    /// velocity `first`. ΔQ in θ is J_r(θ)ᵀ τ = τ + ½ θ × τ (τ the body-axis
    /// torques, J_r = I − ½[θ]× the right Jacobian to the first order), so
    /// at θ = 0 its θ-derivative is ∂τ/∂δ − ½[τ]×: the term is added back, so
    /// that ∂ΔQ/∂q is along q ⊕ δ, as the runtime reads it.
    pub fn inputs(&mut self, inputs: &mut InputModel, first: usize, count: usize) {
        self.all(&mut inputs.forces);
        self.rows(&mut inputs.jacobian_u);
        self.rows(&mut inputs.jacobian_q);
        self.rows(&mut inputs.jacobian_v);
        let half = self.ctx.rational(1, 2);
        for k in 0..count {
            let o = first + 3 * k;
            let tau = [0, 1, 2].map(|i| inputs.forces[o + i]);
            for i in 0..3 {
                for j in 0..3 {
                    if i == j {
                        continue;
                    }
                    // [τ]×[i][j] = −ε_ijl τ_l, l the third axis.
                    let l = 3 - i - j;
                    let sign = if (i + 1) % 3 == j { -1 } else { 1 };
                    let entry = self.ctx.mul(half, tau[l]);
                    let entry = if sign < 0 { self.ctx.neg(entry) } else { entry };
                    let sum = self.ctx.add(inputs.jacobian_q[o + i][o + j], entry);
                    inputs.jacobian_q[o + i][o + j] = self.ctx.collect(sum);
                }
            }
        }
    }
}
