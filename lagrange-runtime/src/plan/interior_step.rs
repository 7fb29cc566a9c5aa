//! The interior point's Newton step: the KKT residuals, the barrier
//! parameter's fall, the Lagrangian's Hessian, the inertia correction,
//! the direction, and the multipliers' update after the line search
//! (`interior` has the iteration and the filter).

use super::cost::CostModel;
use super::ddp::Iteration;
use super::direct_qp::offsets;
use super::interior::{Interior, Point, Settings};
use crate::error::Error;
use crate::system::Driven;
use nalgebra::DMatrix;

// IPOPT's constants for the barrier's fall and the inertia correction.
const KAPPA_EPSILON: f64 = 10.0;
const KAPPA_MU: f64 = 0.2;
const THETA_MU: f64 = 1.5;
const KAPPA_SIGMA: f64 = 1e10;
const S_MAX: f64 = 100.0;
/// IPOPT's `nlp_scaling_max_gradient`.
const MAX_GRADIENT: f64 = 100.0;
/// The multipliers' diagonal: it keeps every dual pivot nonzero whatever
/// the ordering; the solve refines it away.
const DUAL_SHIFT: f64 = 1e-9;

/// A step's direction in the unknowns and in the rows' multipliers.
pub(super) struct Direction {
    pub dw: Vec<f64>,
    pub dl: Vec<f64>,
}

/// ∂F_k/∂x and ∂F_k/∂u of every step.
pub(super) type Jacobians<'d> = [(&'d DMatrix<f64>, &'d DMatrix<f64>)];

/// The KKT conditions' residuals at a point.
pub(super) struct Residuals {
    /// ∇f, the cost's gradient.
    pub gradient: Vec<f64>,
    /// ∇f + Jᵀλ − z_L + z_U, the Lagrangian's gradient.
    pub dual: Vec<f64>,
    /// ‖dual‖∞.
    pub stationarity: f64,
    /// ‖c‖∞.
    pub violation: f64,
    /// IPOPT's scales of the dual residual and the complementarity.
    scales: (f64, f64),
}

impl<S, const N: usize, const P: usize> Interior<'_, '_, S, N, P>
where
    S: Driven<f64, N, P>,
{
    /// The cost's models at every step, the final state's last.
    pub(super) fn models(&self, nominal: &super::passes::Nominal) -> Result<Vec<CostModel>, Error> {
        let problem = self.problem;
        let mut models = Vec::with_capacity(problem.steps + 1);
        for k in 0..problem.steps {
            models.push(problem.running_model(k, &nominal.xs[k], &nominal.us[k])?);
        }
        models.push(problem.final_model(&nominal.xs[problem.steps])?);
        Ok(models)
    }

    /// The cost's scale: 1, or less where its gradient at the first point
    /// is above 100 (IPOPT's gradient-based scaling), so that the filter
    /// weighs a cost of large weights against the constraints' violation
    /// as it would a cost of moderate ones. The plan is the same; the log
    /// reports the cost unscaled.
    pub(super) fn scale_objective(&mut self, models: &[CostModel]) {
        let largest = (models.iter())
            .flat_map(|m| m.lx.iter().chain(m.lu.iter()))
            .fold(0.0f64, |g, x| g.max(x.abs()));
        self.objective_scale = (MAX_GRADIENT / largest).min(1.0);
    }

    /// The rows' first multipliers: the least-squares fit of ∇f − z_L + z_U
    /// + Jᵀλ = 0, from [I Jᵀ; J 0] (IPOPT's), or zero if any is beyond 10³.
    pub(super) fn first_multipliers(
        &mut self,
        point: &Point,
        models: &[CostModel],
    ) -> Result<(), Error> {
        let l = self.layout;
        let (derivatives, _) =
            super::curvature::linearised(self.problem, &point.nominal, &self.lambda)?;
        let jac: Vec<_> = derivatives.iter().map(|d| (&d.dx, &d.du)).collect();
        let r = self.residuals(point, models, &jac);
        let identities: Vec<_> = (0..=l.steps)
            .map(|k| DMatrix::identity(l.block(k), l.block(k)))
            .collect();
        if self
            .kkt
            .factorise(&identities, &jac, (0.0, DUAL_SHIFT))
            .is_err()
        {
            return Ok(());
        }
        // λ is zero here, so the Lagrangian's gradient is ∇f − z_L + z_U.
        let mut rhs: Vec<f64> = r.dual.iter().map(|d| -d).collect();
        rhs.resize(l.primal() + l.rows(), 0.0);
        self.kkt.solve(&mut rhs);
        let lambda = &rhs[l.primal()..];
        if largest(lambda) <= 1e3 {
            self.lambda.copy_from_slice(lambda);
        }
        Ok(())
    }

    /// ∇f, the Lagrangian's gradient and their norms at `point`.
    pub(super) fn residuals(
        &self,
        point: &Point,
        models: &[CostModel],
        jac: &Jacobians,
    ) -> Residuals {
        let l = self.layout;
        let mut gradient = vec![0.0; l.primal()];
        for (k, m) in models.iter().enumerate() {
            let (x, u) = offsets(l.n2, l.p, k);
            gradient[x..x + l.n2].copy_from_slice(m.lx.as_slice());
            if k < l.steps {
                gradient[u..u + l.p].copy_from_slice(m.lu.as_slice());
            }
        }
        gradient.iter_mut().for_each(|g| *g *= self.objective_scale);
        let mut dual = gradient.clone();
        self.add_transposed(jac, &mut dual);
        for (i, d) in dual.iter_mut().enumerate() {
            *d += self.zu[i] - self.zl[i];
        }
        let norm1 = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
        let (n, m) = (l.primal() as f64, l.rows() as f64);
        let z = norm1(&self.zl) + norm1(&self.zu);
        let s_d = (S_MAX.max((norm1(&self.lambda) + z) / (m + n))) / S_MAX;
        let s_c = (S_MAX.max(z / n)) / S_MAX;
        Residuals {
            stationarity: largest(&dual),
            violation: largest(&point.c),
            gradient,
            dual,
            scales: (s_d, s_c),
        }
    }

    /// out += Jᵀλ.
    fn add_transposed(&self, jac: &Jacobians, out: &mut [f64]) {
        let (l, lambda) = (self.layout, &self.lambda);
        for i in 0..l.n2 {
            out[i] += lambda[i];
        }
        for (k, (a, b)) in jac.iter().enumerate() {
            let y = &lambda[(k + 1) * l.n2..][..l.n2];
            let (x, u) = offsets(l.n2, l.p, k);
            let (next, _) = offsets(l.n2, l.p, k + 1);
            for i in 0..l.n2 {
                out[next + i] += y[i];
            }
            for j in 0..l.n2 {
                out[x + j] -= (0..l.n2).map(|i| a[(i, j)] * y[i]).sum::<f64>();
            }
            for j in 0..l.p {
                out[u + j] -= (0..l.n2).map(|i| b[(i, j)] * y[i]).sum::<f64>();
            }
        }
        if l.final_equality {
            let (last, _) = offsets(l.n2, l.p, l.steps);
            let y = &lambda[(l.steps + 1) * l.n2..];
            for i in 0..l.n2 {
                out[last + i] += y[i];
            }
        }
    }

    /// IPOPT's optimality error at barrier parameter μ (0 for the problem
    /// itself): the scaled dual residual, the violation, the scaled
    /// complementarity less μ.
    pub(super) fn error(&self, point: &Point, r: &Residuals, mu: f64) -> f64 {
        let mut complementarity = 0.0f64;
        for (i, w) in point.w.iter().enumerate() {
            if self.lower[i].is_finite() {
                complementarity =
                    complementarity.max(((w - self.lower[i]) * self.zl[i] - mu).abs());
            }
            if self.upper[i].is_finite() {
                complementarity =
                    complementarity.max(((self.upper[i] - w) * self.zu[i] - mu).abs());
            }
        }
        let (s_d, s_c) = r.scales;
        (r.stationarity / s_d)
            .max(r.violation)
            .max(complementarity / s_c)
    }

    /// μ lowered (and the filter cleared) while the barrier problem is
    /// solved to κ_ε μ, not below a tenth of the tolerance.
    pub(super) fn lower_barrier(&mut self, point: &Point, r: &Residuals, tolerance: f64) {
        let floor = tolerance / 10.0;
        while self.mu > floor && self.error(point, r, self.mu) <= KAPPA_EPSILON * self.mu {
            self.mu = floor.max((KAPPA_MU * self.mu).min(self.mu.powf(THETA_MU)));
            self.filter.clear();
        }
    }

    /// Each step's block of the barrier problem's Hessian: the cost's model,
    /// less the dynamics' curvature ∇²(λ_{k+1}ᵀF_k) (`curvatures`), plus Σ = z_L/(w − l) +
    /// z_U/(u − w) on the diagonal.
    pub(super) fn hessians(
        &self,
        point: &Point,
        models: &[CostModel],
        curvatures: &[DMatrix<f64>],
    ) -> Vec<DMatrix<f64>> {
        let l = self.layout;
        let mut blocks = Vec::with_capacity(l.steps + 1);
        for (k, m) in models.iter().enumerate() {
            let width = l.block(k);
            let mut h = DMatrix::zeros(width, width);
            h.view_mut((0, 0), (l.n2, l.n2)).copy_from(&m.lxx);
            if k < l.steps {
                h.view_mut((l.n2, l.n2), (l.p, l.p)).copy_from(&m.luu);
                h.view_mut((l.n2, 0), (l.p, l.n2)).copy_from(&m.lux);
                h.view_mut((0, l.n2), (l.n2, l.p))
                    .copy_from(&m.lux.transpose());
            }
            h *= self.objective_scale;
            if k < l.steps {
                h -= &curvatures[k];
            }
            let (x, _) = offsets(l.n2, l.p, k);
            for j in 0..width {
                let (i, w) = (x + j, point.w[x + j]);
                h[(j, j)] += self.zl[i] / (w - self.lower[i]) + self.zu[i] / (self.upper[i] - w);
            }
            blocks.push(h);
        }
        blocks
    }

    /// Factorises the Newton matrix, the Hessian shifted by the least δ_w
    /// (0, else from a tenth of the last shift up by eightfold steps, or from
    /// 10⁻⁴ up a hundredfold) that gives as many positive pivots as primal
    /// unknowns. None if no shift up to 10⁴⁰ does.
    pub(super) fn factorise(&mut self, hessians: &[DMatrix<f64>], jac: &Jacobians) -> Option<f64> {
        let n = self.kkt.primal();
        let fits = |kkt: &mut super::kkt::Kkt, shift: f64| matches!(kkt.factorise(hessians, jac, (shift, DUAL_SHIFT)), Ok(p) if p == n);
        if fits(&mut self.kkt, 0.0) {
            return Some(0.0);
        }
        let (mut shift, growth) = match self.last_shift == 0.0 {
            true => (1e-4, 100.0),
            false => ((self.last_shift / 3.0).max(1e-20), 8.0),
        };
        while shift <= 1e40 {
            if fits(&mut self.kkt, shift) {
                self.last_shift = shift;
                return Some(shift);
            }
            shift *= growth;
        }
        None
    }

    /// The Newton direction (δw, δλ) of the barrier problem for rows
    /// `c` (the point's own, or a second-order correction's), from the
    /// factorised matrix.
    pub(super) fn direction(&mut self, point: &Point, r: &Residuals, c: &[f64]) -> Direction {
        let n = self.layout.primal();
        let mut rhs = Vec::with_capacity(n + self.layout.rows());
        for i in 0..n {
            // ∇φ_μ + Jᵀλ = (∇f + Jᵀλ − z_L + z_U) + z_L − z_U − μ/(w − l) + μ/(u − w).
            let w = point.w[i];
            let barrier = self.mu / (self.upper[i] - w) - self.mu / (w - self.lower[i]);
            rhs.push(-(r.dual[i] + self.zl[i] - self.zu[i] + barrier));
        }
        rhs.extend(c.iter().map(|c| -c));
        self.kkt.solve(&mut rhs);
        let dl = rhs.split_off(n);
        Direction { dw: rhs, dl }
    }

    /// The barrier objective's derivative along δw, ∇φ_μ·δw.
    pub(super) fn slope(&self, point: &Point, gradient: &[f64], dw: &[f64]) -> f64 {
        (0..dw.len())
            .map(|i| {
                let w = point.w[i];
                let barrier = self.mu / (self.upper[i] - w) - self.mu / (w - self.lower[i]);
                (gradient[i] + barrier) * dw[i]
            })
            .sum()
    }

    /// The barrier objective f − μ Σ ln(w − l) − μ Σ ln(u − w).
    pub(super) fn barrier_objective(&self, point: &Point) -> f64 {
        let mut logs = 0.0;
        for (i, w) in point.w.iter().enumerate() {
            if self.lower[i].is_finite() {
                logs += (w - self.lower[i]).ln();
            }
            if self.upper[i].is_finite() {
                logs += (self.upper[i] - w).ln();
            }
        }
        self.objective_scale * point.nominal.cost - self.mu * logs
    }

    /// The largest α ≤ 1 that keeps w + α δw beyond (1 − τ) of its room to
    /// every bound, τ = max(0.99, 1 − μ).
    pub(super) fn to_boundary(&self, w: &[f64], dw: &[f64]) -> f64 {
        let tau = 0.99f64.max(1.0 - self.mu);
        let mut alpha = 1.0f64;
        for i in 0..w.len() {
            if self.lower[i].is_finite() && dw[i] < 0.0 {
                alpha = alpha.min(-tau * (w[i] - self.lower[i]) / dw[i]);
            }
            if self.upper[i].is_finite() && dw[i] > 0.0 {
                alpha = alpha.min(tau * (self.upper[i] - w[i]) / dw[i]);
            }
        }
        alpha
    }

    /// After a step α from w: λ moves by α δλ, the bounds' multipliers by
    /// their own fraction to the boundary along their Newton direction,
    /// then kept within κ_Σ of μ/(w − l) either way.
    pub(super) fn accept(&mut self, (w, next): (&[f64], &[f64]), d: &Direction, alpha: f64) {
        let (dw, dl) = (&d.dw, &d.dl);
        for (l, d) in self.lambda.iter_mut().zip(dl) {
            *l += alpha * d;
        }
        let tau = 0.99f64.max(1.0 - self.mu);
        let mu = self.mu;
        let n = w.len();
        let mut dzl = vec![0.0; n];
        let mut dzu = vec![0.0; n];
        let mut alpha_z = 1.0f64;
        for i in 0..n {
            if self.lower[i].is_finite() {
                let s = w[i] - self.lower[i];
                dzl[i] = (mu - self.zl[i] * s - self.zl[i] * dw[i]) / s;
                if dzl[i] < 0.0 {
                    alpha_z = alpha_z.min(-tau * self.zl[i] / dzl[i]);
                }
            }
            if self.upper[i].is_finite() {
                let s = self.upper[i] - w[i];
                dzu[i] = (mu - self.zu[i] * s + self.zu[i] * dw[i]) / s;
                if dzu[i] < 0.0 {
                    alpha_z = alpha_z.min(-tau * self.zu[i] / dzu[i]);
                }
            }
        }
        for i in 0..n {
            if self.lower[i].is_finite() {
                let s = next[i] - self.lower[i];
                let z = self.zl[i] + alpha_z * dzl[i];
                self.zl[i] = z.clamp(mu / (KAPPA_SIGMA * s), KAPPA_SIGMA * mu / s);
            }
            if self.upper[i].is_finite() {
                let s = self.upper[i] - next[i];
                let z = self.zu[i] + alpha_z * dzu[i];
                self.zu[i] = z.clamp(mu / (KAPPA_SIGMA * s), KAPPA_SIGMA * mu / s);
            }
        }
    }

    /// An iteration's record, printed when verbose.
    pub(super) fn record(
        &self,
        settings: &Settings,
        point: &Point,
        stationarity: f64,
        alpha: f64,
        shift: f64,
    ) -> Iteration {
        let (cost, gap) = (point.nominal.cost, largest(&point.c));
        // The Lagrangian's gradient of the cost as given, not as scaled.
        let stationarity = stationarity / self.objective_scale;
        if settings.verbose {
            eprintln!(
                "direct: cost {cost:.9e}  KKT {stationarity:.2e}  α {alpha:.3}  μ {:.1e}  \
                 δ_w {shift:.1e}  violation {gap:.2e}",
                self.mu
            );
        }
        Iteration {
            cost,
            stationarity,
            step: alpha,
            regularization: shift,
            expected: f64::NAN,
            gap,
        }
    }
}

/// The largest |entry|.
pub(super) fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}
