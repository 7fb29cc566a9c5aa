//! The direct method's interior point: IPOPT's primal–dual barrier method
//! with a filter line search (Wächter and Biegler 2006), on the multiple
//! shooting problem
//!
//! ```text
//! minimise  Σ_k l_k(x_k, u_k) + l_K(x_K)
//! subject to  x₀ = x_start,  x_{k+1} = F(x_k, u_k),  (x_K = x*),   lower ≤ (x, u) ≤ upper
//! ```
//!
//! Each iteration takes the Newton step of the barrier problem (the bounds
//! as −μ Σ ln(w − l) − μ Σ ln(u − w)) with the Lagrangian's Hessian: the
//! costs' models and the dynamics' curvature −Σ ∇²(λ_{k+1}ᵀF_k), by the
//! second-order chain rule through each step's stages on forward
//! differences of the emitted ∂q̈ (`curvature`). Where that
//! Hessian is not positive definite on the constraints' null space (the
//! Newton matrix's inertia says so, `kkt`), it is shifted by δ_w I until it
//! is. The step is cut to keep every bound strictly inside (the fraction to
//! the boundary, τ = max(0.99, 1 − μ)) and shortened until the filter of
//! (constraint violation, barrier objective) pairs accepts it; μ falls
//! superlinearly as each barrier problem is solved to κ_ε μ.
//!
//! The cost is scaled, as IPOPT's gradient-based scaling does, so that its
//! gradient at the first point is at most 100: a cost of large weights
//! (a tool held to its target by 10⁵) would otherwise outweigh the
//! constraints' violation in the filter.
//!
//! Where no step is acceptable (a constraint set the iteration cannot
//! approach: a final equality out of reach) IPOPT enters its feasibility
//! restoration; here the iteration hands its point to the elastic SQP
//! (`direct`), which either finds the feasible region or reports by how
//! much the constraints are missed. It does the same after ten steps in a
//! row cut below 5 % (where IPOPT would start its watchdog): on an arm's
//! reach under a heavily weighted tool cost the Newton steps stall so,
//! and the SQP then converges.

use super::curvature::linearised;
use super::ddp::Iteration;
use super::direct_qp::offsets;
use super::interior_step::{Direction, Residuals};
use super::kkt::{Kkt, Layout};
use super::passes::{Nominal, step};
use super::problem::OptimalControl;
use crate::error::Error;
use crate::system::Driven;
use nalgebra::DVector;

/// What the iteration ended with.
pub(super) enum Outcome {
    /// The KKT conditions hold within the tolerances.
    Converged(Nominal),
    /// The budget ran out: the last point, its stationarity.
    OutOfIterations(Nominal, f64),
    /// No acceptable step: the point for the restoration, and why.
    Restore(Nominal, String),
}

/// The settings the iteration reads.
pub(super) struct Settings {
    pub(super) tolerance: f64,
    pub(super) gap_tolerance: f64,
    pub(super) max_iterations: usize,
    pub(super) verbose: bool,
}

// IPOPT's constants for the first point and the filter line search
// (Wächter and Biegler 2006, §2–3).
const MU_INIT: f64 = 0.1;
const GAMMA_THETA: f64 = 1e-5;
const GAMMA_PHI: f64 = 1e-8;
const DELTA: f64 = 1.0;
const S_THETA: f64 = 1.1;
const S_PHI: f64 = 2.3;
const ETA_PHI: f64 = 1e-4;
const GAMMA_ALPHA: f64 = 0.05;
/// A step α below this is shortened; this many shortened steps in a row
/// (IPOPT's `watchdog_shortened_iter_trigger`) hand the point to the
/// restoration: the Newton steps are not converging from there (a seven-
/// joint arm's reach under a heavily weighted tool cost, where the elastic
/// SQP then converges).
const SHORT_STEP: f64 = 0.05;
const SHORTENED_TRIGGER: usize = 10;
/// The relaxation of equal bounds, relative (IPOPT's `bound_relax_factor`,
/// which IPOPT applies to every bound; here the others are kept exactly,
/// so that a plan never crosses a limit).
const RELAX: f64 = 1e-8;
/// How far inside its bounds the first point is pushed (`bound_push`, `bound_frac`).
const PUSH: f64 = 1e-2;

/// A point of the iteration: the unknowns, the plan they make, and what
/// the line search reads.
pub(super) struct Point {
    pub(super) w: Vec<f64>,
    pub(super) nominal: Nominal,
    /// The rows' values c(w) (x₀ − x_start, x_{k+1} − F(x_k, u_k), x_K − x*).
    pub(super) c: Vec<f64>,
    /// Σ |c|.
    pub(super) theta: f64,
}

/// The interior point's state between iterations.
pub(super) struct Interior<'p, 'a, S, const N: usize, const P: usize>
where
    S: Driven<f64, N, P>,
{
    pub(super) problem: &'p OptimalControl<'a, S, N, P>,
    pub(super) layout: Layout,
    pub(super) lower: Vec<f64>,
    pub(super) upper: Vec<f64>,
    pub(super) kkt: Kkt,
    /// The barrier parameter.
    pub(super) mu: f64,
    /// The (θ, φ) pairs no trial may be worse than in both.
    pub(super) filter: Vec<(f64, f64)>,
    theta_max: f64,
    theta_min: f64,
    /// The last nonzero shift of the Hessian.
    pub(super) last_shift: f64,
    /// The rows' multipliers.
    pub(super) lambda: Vec<f64>,
    /// The lower and upper bounds' multipliers (zero where there is none).
    pub(super) zl: Vec<f64>,
    pub(super) zu: Vec<f64>,
    /// The factor the cost is scaled by in the iteration (IPOPT's
    /// gradient-based scaling): its gradient at the first point at most
    /// 100.
    pub(super) objective_scale: f64,
}

impl<'p, 'a, S, const N: usize, const P: usize> Interior<'p, 'a, S, N, P>
where
    S: Driven<f64, N, P>,
{
    /// The iteration's state for a problem, with equal bounds moved apart
    /// by 10⁻⁸ of themselves (so that they still leave an interior).
    pub(super) fn new(problem: &'p OptimalControl<'a, S, N, P>) -> Self {
        let layout = Layout {
            n2: 2 * N,
            p: P,
            steps: problem.steps,
            final_equality: problem.final_equality,
        };
        let (lower, upper) = bounds(problem, layout);
        let one_where = |b: &[f64]| {
            b.iter()
                .map(|b| f64::from(u8::from(b.is_finite())))
                .collect()
        };
        Self {
            problem,
            layout,
            kkt: Kkt::new(layout),
            mu: MU_INIT,
            filter: Vec::new(),
            theta_max: f64::INFINITY,
            theta_min: 0.0,
            last_shift: 0.0,
            lambda: vec![0.0; layout.rows()],
            zl: one_where(&lower),
            zu: one_where(&upper),
            objective_scale: 1.0,
            lower,
            upper,
        }
    }

    /// The iterations from a nominal, each recorded in `log`, until the log
    /// holds `max_iterations`.
    pub(super) fn run(
        &mut self,
        settings: &Settings,
        nominal: &Nominal,
        log: &mut Vec<Iteration>,
    ) -> Result<Outcome, Error> {
        let mut point = self.evaluate(self.interior(unknowns(nominal)))?;
        self.theta_max = 1e4 * point.theta.max(1.0);
        self.theta_min = 1e-4 * point.theta.max(1.0);
        let models = self.models(&point.nominal)?;
        self.scale_objective(&models);
        self.first_multipliers(&point, &models)?;
        // Consecutive iterations whose step the line search cut short.
        let mut shortened = 0;
        loop {
            let models = self.models(&point.nominal)?;
            let (derivatives, curvatures) = linearised(self.problem, &point.nominal, &self.lambda)?;
            let jac: Vec<_> = derivatives.iter().map(|d| (&d.dx, &d.du)).collect();
            let r = self.residuals(&point, &models, &jac);
            if self.error(&point, &r, 0.0) <= settings.tolerance
                && r.violation <= settings.gap_tolerance
            {
                log.push(self.record(settings, &point, r.stationarity, 0.0, 0.0));
                return Ok(Outcome::Converged(point.nominal));
            }
            if log.len() >= settings.max_iterations {
                return Ok(Outcome::OutOfIterations(point.nominal, r.stationarity));
            }
            self.lower_barrier(&point, &r, settings.tolerance);
            let hessians = self.hessians(&point, &models, &curvatures);
            let Some(shift) = self.factorise(&hessians, &jac) else {
                let why = "no shift of the Hessian gives a minimum's inertia";
                return Ok(Outcome::Restore(point.nominal, why.into()));
            };
            let d = self.direction(&point, &r, &point.c);
            let Some((next, d, alpha)) = self.search(&point, d, &r)? else {
                let why = "no step along the Newton direction is acceptable to the filter";
                return Ok(Outcome::Restore(point.nominal, why.into()));
            };
            self.accept((&point.w, &next.w), &d, alpha);
            point = next;
            log.push(self.record(settings, &point, r.stationarity, alpha, shift));
            shortened = if alpha < SHORT_STEP { shortened + 1 } else { 0 };
            if shortened == SHORTENED_TRIGGER {
                let why = "ten steps in a row shortened below 5 % by the filter";
                return Ok(Outcome::Restore(point.nominal, why.into()));
            }
        }
    }

    /// The filter line search: from the largest step that keeps the bounds
    /// strictly inside, halved until the filter accepts the trial point,
    /// with second-order corrections of the first trial (Wächter and
    /// Biegler 2006, Algorithm A). The point, the direction taken (the
    /// correction's, if one was accepted) and its step; None when α falls
    /// below its floor.
    fn search(
        &mut self,
        point: &Point,
        d: Direction,
        r: &Residuals,
    ) -> Result<Option<(Point, Direction, f64)>, Error> {
        let test = Test::new(self, point, &d, &r.gradient);
        // A step below round-off of every unknown is taken whole (IPOPT's
        // tiny step), so that the last iterations are not stopped by noise.
        let tiny = (d.dw.iter().zip(&point.w)).all(|(d, w)| d.abs() <= 1e-15 * w.abs().max(1.0));
        let first = self.to_boundary(&point.w, &d.dw);
        if tiny {
            let trial = self.evaluate(moved(&point.w, &d.dw, first))?;
            return Ok(Some((trial, d, first)));
        }
        let mut alpha = first;
        while alpha >= test.alpha_min {
            let Ok(trial) = self.evaluate(moved(&point.w, &d.dw, alpha)) else {
                alpha /= 2.0;
                continue;
            };
            if self.acceptable(&test, &trial, alpha) {
                return Ok(Some((trial, d, alpha)));
            }
            // A first trial that made the constraints worse: corrected.
            if alpha == first
                && trial.theta >= point.theta
                && let Some(found) = self.corrected(point, r, &test, (&trial, first))?
            {
                return Ok(Some(found));
            }
            alpha /= 2.0;
        }
        Ok(None)
    }

    /// Up to four second-order corrections of a rejected first trial: the
    /// step again with the rows' values c_soc ← α c_soc + c(trial), which
    /// steers it back to the constraints where their curvature took it off.
    fn corrected(
        &mut self,
        point: &Point,
        r: &Residuals,
        test: &Test,
        (trial, alpha): (&Point, f64),
    ) -> Result<Option<(Point, Direction, f64)>, Error> {
        let mut c_soc: Vec<f64> = (point.c.iter().zip(&trial.c))
            .map(|(c, t)| alpha * c + t)
            .collect();
        let mut last_theta = trial.theta;
        for _ in 0..4 {
            let d = self.direction(point, r, &c_soc);
            let alpha_soc = self.to_boundary(&point.w, &d.dw);
            let Ok(soc) = self.evaluate(moved(&point.w, &d.dw, alpha_soc)) else {
                return Ok(None);
            };
            // Judged as the first trial would have been (its α).
            if self.acceptable(test, &soc, alpha) {
                return Ok(Some((soc, d, alpha_soc)));
            }
            if soc.theta > 0.99 * last_theta {
                return Ok(None);
            }
            last_theta = soc.theta;
            for (c, t) in c_soc.iter_mut().zip(&soc.c) {
                *c = alpha_soc * *c + t;
            }
        }
        Ok(None)
    }

    /// Whether the filter accepts a trial point at step α, and so, whether
    /// it is added to the filter.
    fn acceptable(&mut self, test: &Test, trial: &Point, alpha: f64) -> bool {
        let (theta, phi, slope) = (test.theta, test.phi, test.slope);
        let phi_t = self.barrier_objective(trial);
        if !phi_t.is_finite() || trial.theta > self.theta_max {
            return false;
        }
        if (self.filter.iter()).any(|&(t, p)| trial.theta >= t && phi_t >= p) {
            return false;
        }
        let switching = slope < 0.0 && alpha * (-slope).powf(S_PHI) > DELTA * theta.powf(S_THETA);
        let armijo = phi_t <= phi + ETA_PHI * alpha * slope;
        let accepted = match switching && theta <= self.theta_min {
            true => armijo,
            false => trial.theta <= (1.0 - GAMMA_THETA) * theta || phi_t <= phi - GAMMA_PHI * theta,
        };
        if accepted && !(switching && armijo) {
            self.filter
                .push(((1.0 - GAMMA_THETA) * theta, phi - GAMMA_PHI * theta));
        }
        accepted
    }

    /// The first point: the guess pushed inside its bounds by 10⁻² of
    /// them (or of the room between them, if less).
    fn interior(&self, mut w: Vec<f64>) -> Vec<f64> {
        for (i, w) in w.iter_mut().enumerate() {
            let (l, u) = (self.lower[i], self.upper[i]);
            let room = u - l;
            if l.is_finite() {
                *w = w.max(l + (PUSH * l.abs().max(1.0)).min(PUSH * room));
            }
            if u.is_finite() {
                *w = w.min(u - (PUSH * u.abs().max(1.0)).min(PUSH * room));
            }
        }
        w
    }

    /// The plan, the rows and the violation at w.
    fn evaluate(&self, w: Vec<f64>) -> Result<Point, Error> {
        let (l, problem) = (self.layout, self.problem);
        let xs: Vec<DVector<f64>> = (0..=l.steps)
            .map(|k| DVector::from_column_slice(&w[offsets(l.n2, l.p, k).0..][..l.n2]))
            .collect();
        let us: Vec<DVector<f64>> = (0..l.steps)
            .map(|k| DVector::from_column_slice(&w[offsets(l.n2, l.p, k).1..][..l.p]))
            .collect();
        let mut c = Vec::with_capacity(l.rows());
        let mut gaps = vec![&problem.start - &xs[0]];
        c.extend(gaps[0].iter().map(|g| -g));
        for k in 0..l.steps {
            let gap = step(problem, k, &xs[k], &us[k])? - &xs[k + 1];
            c.extend(gap.iter().map(|g| -g));
            gaps.push(gap);
        }
        if l.final_equality {
            c.extend((&xs[l.steps] - &problem.goal).iter());
        }
        let cost = problem.cost(&xs, &us);
        let theta = c.iter().map(|c| c.abs()).sum();
        let nominal = Nominal { xs, us, gaps, cost };
        Ok(Point {
            w,
            nominal,
            c,
            theta,
        })
    }
}

/// What the line search judges trials against: the point's violation
/// θ, barrier objective φ, φ's slope along the step, and the floor of α.
struct Test {
    theta: f64,
    phi: f64,
    slope: f64,
    alpha_min: f64,
}

impl Test {
    fn new<S, const N: usize, const P: usize>(
        interior: &Interior<S, N, P>,
        point: &Point,
        d: &Direction,
        gradient: &[f64],
    ) -> Self
    where
        S: Driven<f64, N, P>,
    {
        let (theta, phi) = (point.theta, interior.barrier_objective(point));
        let slope = interior.slope(point, gradient, &d.dw);
        let alpha_min = GAMMA_ALPHA
            * match slope < 0.0 {
                false => GAMMA_THETA,
                true if theta <= interior.theta_min => GAMMA_THETA
                    .min(GAMMA_PHI * theta / -slope)
                    .min(DELTA * theta.powf(S_THETA) / (-slope).powf(S_PHI)),
                true => GAMMA_THETA.min(GAMMA_PHI * theta / -slope),
            };
        Self {
            theta,
            phi,
            slope,
            alpha_min,
        }
    }
}

/// w + α δw.
fn moved(w: &[f64], dw: &[f64], alpha: f64) -> Vec<f64> {
    w.iter().zip(dw).map(|(w, d)| w + alpha * d).collect()
}

/// The unknowns of a nominal in the layout (x₀, u₀, …, x_K).
fn unknowns(nominal: &Nominal) -> Vec<f64> {
    let mut w = Vec::new();
    for (k, x) in nominal.xs.iter().enumerate() {
        w.extend(x.iter());
        if let Some(u) = nominal.us.get(k) {
            w.extend(u.iter());
        }
    }
    w
}

/// Each unknown's bounds, relaxed (±∞ where it has none): the inputs', and
/// the state limits on x₁ … x_K.
fn bounds<S, const N: usize, const P: usize>(
    problem: &OptimalControl<S, N, P>,
    l: Layout,
) -> (Vec<f64>, Vec<f64>)
where
    S: Driven<f64, N, P>,
{
    let inf = f64::INFINITY;
    let (mut lower, mut upper) = (vec![-inf; l.primal()], vec![inf; l.primal()]);
    for k in 0..=l.steps {
        let (x, u) = offsets(l.n2, l.p, k);
        if let (Some((lo, hi)), true) = (&problem.state_limits, k > 0) {
            lower[x..x + l.n2].copy_from_slice(lo.as_slice());
            upper[x..x + l.n2].copy_from_slice(hi.as_slice());
        }
        if k < l.steps {
            lower[u..u + l.p].copy_from_slice(problem.lower.as_slice());
            upper[u..u + l.p].copy_from_slice(problem.upper.as_slice());
        }
    }
    for (l, u) in lower.iter_mut().zip(upper.iter_mut()) {
        if l == u {
            (*l, *u) = (*l - RELAX * l.abs().max(1.0), *u + RELAX * u.abs().max(1.0));
        }
    }
    (lower, upper)
}
