//! The passes of DDP over a nominal plan that need not satisfy the
//! dynamics (feasibility-driven DDP, Mastalli et al. 2020, Crocoddyl's
//! `SolverBoxFDDP`). The nominal carries its gaps, f₀ = x₀ − x̄₀ and
//! f_{k+1} = F(x̄_k, ū_k) − x̄_{k+1}, all zero for a rollout, where every
//! formula below is plain DDP's:
//!
//! - the backward pass reads the value function at the state the dynamics
//!   lead to, V_x + V_xx f, not at the nominal's next state;
//! - the forward pass from x̄₀ + α f₀ steps x_{k+1} = F(x_k, u_k) − (1 − α)
//!   f_{k+1}: each gap shrinks by 1 − α, and a full step (α = 1) closes
//!   them all;
//! - the model's predicted change of the cost along the step α adds to
//!   α Σ k·Q_u + α² Σ ½ kᵀQ_uu k the gaps' terms
//!   α (Σ ṽ·f − Σ fᵀV_xx δx) − α² (½ Σ fᵀV_xx f − Σ fᵀV_xx δx), with
//!   ṽ = V_x + V_xx f and δx the trial's states less the nominal's
//!   (Crocoddyl's model; at α = 1 it is the quadratic model's change,
//!   Σ (ṽ·f − ½ fᵀV_xx f) + Σ (k·Q_u + ½ kᵀQ_uu k)).
//!
//! With orientations every difference of states is x ⊖ x̄ and every sum
//! x ⊕ d (`OptimalControl::minus` and `plus`): a gap is the tangent vector
//! f_{k+1} = F(x̄_k, ū_k) ⊖ x̄_{k+1}, at x̄_{k+1}, and the forward pass's
//! state F(x_k, u_k) ⊕ (−(1 − α) f_{k+1}) (at α = 0 and x_k = x̄_k exactly
//! x̄_{k+1}, since x̄ exp(f) = F is F exp(−f) = x̄). The backward pass reads
//! V at x̄_{k+1} through ∂F/∂x, whose rows are in the tangent space at
//! F(x̄_k): the two differ by the gap, and the map between them, which
//! Crocoddyl's FDDP leaves out too, is left out (it is the identity once
//! the gaps are closed, where the plan converges).

use super::box_qp;
use super::cost::CostModel;
use super::expansion::{Expansion, StepJacobian};
use super::problem::{OptimalControl, split, state};
use crate::error::{Error, SettingsError};
use crate::numeric::products::{gemm, gemv};
use crate::system::Driven;
use nalgebra::{DMatrix, DVector, SVector};

/// The plan being improved: states, inputs, gaps, cost.
#[derive(Clone)]
pub(super) struct Nominal {
    pub xs: Vec<DVector<f64>>,
    pub us: Vec<DVector<f64>>,
    /// f₀ … f_K (see the module notes).
    pub gaps: Vec<DVector<f64>>,
    pub cost: f64,
}

impl Nominal {
    /// The largest |entry| of any gap: zero for a rollout.
    pub fn gap(&self) -> f64 {
        largest(&self.gaps)
    }
}

/// What a backward pass gives: per step the feed-forward change and the
/// gain, the value function's Hessians V₀ … V_K, and the model's terms of
/// the predicted change (Σ kᵀQ_u, Σ ½ kᵀQ_uu k) and the gaps' (Σ ṽ·f,
/// Σ fᵀV_xx f).
pub(super) struct Backward {
    pub feedforward: Vec<DVector<f64>>,
    pub gains: Vec<DMatrix<f64>>,
    pub hessians: Vec<DMatrix<f64>>,
    pub expected: (f64, f64),
    pub gap_terms: (f64, f64),
}

/// The largest |entry| over a sequence of vectors.
pub(super) fn largest(xs: &[DVector<f64>]) -> f64 {
    xs.iter().map(|x| x.amax()).fold(0.0, f64::max)
}

/// One step of the problem's transition on a state vector.
pub(super) fn step<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    k: usize,
    x: &DVector<f64>,
    u: &DVector<f64>,
) -> Result<DVector<f64>, Error>
where
    S: Driven<f64, N, P, Q>,
{
    let mut next = DVector::zeros(Q + N);
    step_into(problem, k, (x, u), &mut next)?;
    Ok(next)
}

/// One step of the problem's transition written into `next`.
fn step_into<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    k: usize,
    (x, u): (&DVector<f64>, &DVector<f64>),
    next: &mut DVector<f64>,
) -> Result<(), Error>
where
    S: Driven<f64, N, P, Q>,
{
    let (q, v) = split::<N, Q>(x);
    let u = SVector::<f64, P>::from_column_slice(u.as_slice());
    let (q1, v1) = problem.transition.step(&q, &v, &u, problem.time(k))?;
    let (q_part, v_part) = next.as_mut_slice().split_at_mut(Q);
    q_part.copy_from_slice(q1.as_slice());
    v_part.copy_from_slice(v1.as_slice());
    Ok(())
}

/// The rollout of `us` (clamped) from the start: no gaps.
pub(super) fn rollout<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    us: &[DVector<f64>],
) -> Result<Nominal, Error>
where
    S: Driven<f64, N, P, Q>,
{
    let mut xs = vec![problem.start.clone()];
    let us: Vec<DVector<f64>> = us.iter().map(|u| problem.clamp(u)).collect();
    for (k, u) in us.iter().enumerate() {
        let next = step(problem, k, &xs[k], u)?;
        xs.push(next);
    }
    let cost = problem.cost(&xs, &us);
    let gaps = vec![DVector::zeros(2 * N); xs.len()];
    Ok(Nominal { xs, us, gaps, cost })
}

/// A guess of every configuration, velocity and input.
pub(super) type Guess<'g, const N: usize, const P: usize, const Q: usize = N> = (
    &'g [SVector<f64, Q>],
    &'g [SVector<f64, N>],
    &'g [SVector<f64, P>],
);

/// The nominal of a guess of every state and input, checked: K + 1
/// configurations and velocities and K inputs, all finite (else a
/// `SettingsError::Data` of `owner`, the solver).
pub(super) fn from_guess<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    (q, v, u): Guess<N, P, Q>,
    owner: &'static str,
) -> Result<Nominal, Error>
where
    S: Driven<f64, N, P, Q>,
{
    let bad = |problem: String| -> Error { SettingsError::Data { owner, problem }.into() };
    let k = problem.steps;
    if q.len() != k + 1 || v.len() != k + 1 || u.len() != k {
        return Err(bad(format!(
            "a guess of {} configurations, {} velocities and {} inputs for {k} steps \
             (give K + 1, K + 1 and K)",
            q.len(),
            v.len(),
            u.len()
        )));
    }
    let finite = |x: &[f64]| x.iter().all(|e| e.is_finite());
    let states = (q.iter().zip(v)).all(|(q, v)| finite(q.as_slice()) && finite(v.as_slice()));
    if !states || !u.iter().all(|u| finite(u.as_slice())) {
        return Err(bad("the guessed states and inputs must be finite".into()));
    }
    let xs = q.iter().zip(v).map(|(q, v)| state(q, v)).collect();
    let us: Vec<DVector<f64>> = (u.iter())
        .map(|u| DVector::from_column_slice(u.as_slice()))
        .collect();
    guessed(problem, xs, &us)
}

/// A nominal of given states and inputs (clamped), with its gaps.
pub(super) fn guessed<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    xs: Vec<DVector<f64>>,
    us: &[DVector<f64>],
) -> Result<Nominal, Error>
where
    S: Driven<f64, N, P, Q>,
{
    let us: Vec<DVector<f64>> = us.iter().map(|u| problem.clamp(u)).collect();
    let mut gaps = vec![problem.minus(&problem.start, &xs[0])];
    for (k, u) in us.iter().enumerate() {
        gaps.push(problem.minus(&step(problem, k, &xs[k], u)?, &xs[k + 1]));
    }
    let cost = problem.cost(&xs, &us);
    Ok(Nominal { xs, us, gaps, cost })
}

/// The forward pass with step α: from x̄₀ + α f₀, each input clamped at
/// ū + α k + K (x − x̄), each state the step's less (1 − α) of its gap
/// (x̄₀ ⊕ α f₀, x ⊖ x̄ and F ⊕ (−(1 − α) f) on the group). Written over
/// `trial`, a plan of the same length (the line search's trials and the
/// plan it replaces take turns in one pair of buffers: no allocation per
/// step where no gap is open). On an error `trial` holds a partial pass.
pub(super) fn forward<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    (nominal, backward): (&Nominal, &Backward),
    alpha: f64,
    trial: &mut Nominal,
) -> Result<(), Error>
where
    S: Driven<f64, N, P, Q>,
{
    // Each gap left is (1 − α) of the nominal's, exactly: x̄ ⊕ α f and
    // (x̄ ⊕ f) ⊖ (x̄ ⊕ α f) = (1 − α) f on the group as in the plane, and
    // taken so, not measured, a full step leaves no round-off behind.
    trial.xs[0] = problem.plus(&nominal.xs[0], &(&nominal.gaps[0] * alpha));
    trial.gaps[0] = &nominal.gaps[0] * (1.0 - alpha);
    let (mut input, mut deviation) = (DVector::zeros(P), DVector::zeros(2 * N));
    for k in 0..problem.steps {
        let (done, next) = trial.xs.split_at_mut(k + 1);
        let (x, next) = (&done[k], &mut next[0]);
        problem.minus_into(x, &nominal.xs[k], &mut deviation);
        // ū + α k + K (x − x̄), in place.
        input.copy_from(&nominal.us[k]);
        input.axpy(alpha, &backward.feedforward[k], 1.0);
        gemv(&mut input, 1.0, &backward.gains[k], &deviation, 1.0);
        let u = &mut trial.us[k];
        problem.clamp_into(&input, u);
        step_into(problem, k, (x, u), next)?;
        let (gap, left) = (&nominal.gaps[k + 1], &mut trial.gaps[k + 1]);
        // A closed gap (every step of a rollout) leaves the step's state as it is.
        if gap.amax() == 0.0 {
            left.fill(0.0);
        } else {
            left.copy_from(gap);
            *left *= 1.0 - alpha;
            *next = problem.plus(next, &-&*left);
        }
    }
    trial.cost = problem.cost(&trial.xs, &trial.us);
    Ok(())
}

/// The decrease of the cost the model predicts for the step α that gave
/// `trial` (see the module notes; −(α Σ k·Q_u + α² Σ ½ kᵀQ_uu k) without
/// gaps).
pub(super) fn predicted_decrease<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: &Nominal,
    backward: &Backward,
    trial: &Nominal,
    alpha: f64,
) -> f64
where
    S: Driven<f64, N, P, Q>,
{
    let (d1, d2) = backward.expected;
    let (dg, dq) = backward.gap_terms;
    let dv: f64 = (nominal.gaps.iter().zip(&backward.hessians))
        .zip(trial.xs.iter().zip(&nominal.xs))
        .filter(|((f, _), _)| f.amax() > 0.0)
        .map(|((f, v), (x, x0))| f.dot(&(v * problem.minus(x, x0))))
        .sum();
    let change = alpha * (d1 + dg - dv) + alpha * alpha * (d2 - 0.5 * dq + dv);
    -change
}

/// ∂F/∂x and ∂F/∂u at every step of the plan, as the backward pass reads
/// them: a semi-implicit Euler step in the plane by its stage's q̈
/// derivatives (see `expansion`), any other dense. Written into `into`,
/// whose matrices of the last iteration are reused where they fit.
pub(super) fn jacobians<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: &Nominal,
    into: &mut Vec<StepJacobian>,
) -> Result<(), Error>
where
    S: Driven<f64, N, P, Q>,
{
    let transition = &problem.transition;
    into.truncate(problem.steps);
    for k in 0..problem.steps {
        let (q, v) = split::<N, Q>(&nominal.xs[k]);
        let u = SVector::from_column_slice(nominal.us[k].as_slice());
        let t = problem.time(k);
        match transition.euler_stage(&q, &v, &u, t)? {
            Some(d) if k < into.len() => into[k].set_euler(transition.h(), &d),
            Some(d) => into.push(StepJacobian::euler(transition.h(), &d)),
            None => {
                let d = transition.derivatives(&q, &v, &u, t)?;
                let dense = StepJacobian::dense(d.dx, d.du);
                match k < into.len() {
                    true => into[k] = dense,
                    false => into.push(dense),
                }
            }
        }
    }
    Ok(())
}

/// ∂F/∂x and ∂F/∂u at every step of the plan, dense.
#[cfg(feature = "direct")]
pub(super) fn linearise<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: &Nominal,
) -> Result<Vec<crate::linear::StepDerivatives<N, Q>>, Error>
where
    S: Driven<f64, N, P, Q>,
{
    (0..problem.steps)
        .map(|k| {
            let (q, v) = split::<N, Q>(&nominal.xs[k]);
            let u = SVector::from_column_slice(nominal.us[k].as_slice());
            problem.transition.derivatives(&q, &v, &u, problem.time(k))
        })
        .collect()
}

/// The backward pass with regularisation μ, warm-starting each box QP from
/// the last pass's feed-forward; `Ok(None)` if some Q_uu is not positive
/// definite on its free inputs.
pub(super) fn backward_pass<S, const N: usize, const P: usize, const Q: usize>(
    problem: &OptimalControl<S, N, P, Q>,
    nominal: &Nominal,
    jacobians: &[StepJacobian],
    mu: f64,
    last: Option<&Backward>,
) -> Result<Option<Backward>, Error>
where
    S: Driven<f64, N, P, Q>,
{
    let steps = problem.steps;
    let n2 = 2 * N;
    let terminal = problem.final_model(&nominal.xs[steps])?;
    let (mut vx, mut vxx) = (terminal.lx, terminal.lxx);
    let mut gap_terms = (0.0, 0.0);
    shift(&mut vx, &vxx, &nominal.gaps[steps], &mut gap_terms);
    let mut hessians = vec![DMatrix::zeros(0, 0); steps + 1];
    hessians[steps] = vxx.clone();
    let mut feedforward = vec![DVector::zeros(P); steps];
    let mut gains = vec![DMatrix::zeros(P, n2); steps];
    let mut expected = (0.0, 0.0);
    let mut s = Expansion::new(n2, P);
    let (mut lower, mut upper) = (DVector::zeros(P), DVector::zeros(P));
    let mut l = CostModel::zero(n2, P);
    for k in (0..steps).rev() {
        problem.running_model_into(k, &nominal.xs[k], &nominal.us[k], &mut l)?;
        s.expand(&l, &jacobians[k], (&vx, &vxx), mu);
        let start = last.map(|b| &b.feedforward[k]);
        lower.copy_from(&problem.lower);
        lower -= &nominal.us[k];
        upper.copy_from(&problem.upper);
        upper -= &nominal.us[k];
        let Some(qp) = box_qp::solve_step::<P>(&s.reg_uu, &s.qu, &lower, &upper, start) else {
            return Ok(None);
        };
        feedback(&qp, &s.reg_ux, &mut gains[k]);
        let kff = qp.x;
        s.value(&gains[k], &kff, (&mut vx, &mut vxx));
        // k·Q_u and ½ kᵀQ_uu k, the latter from Q_uu k + Q_u as `value` left it.
        let along = kff.dot(&s.qu);
        expected.0 += along;
        expected.1 += 0.5 * (kff.dot(&s.step_change) - along);
        shift(&mut vx, &vxx, &nominal.gaps[k], &mut gap_terms);
        hessians[k] = vxx.clone();
        feedforward[k] = kff;
    }
    Ok(Some(Backward {
        feedforward,
        gains,
        hessians,
        expected,
        gap_terms,
    }))
}

/// K = −Q̃_uu⁻¹ Q̃_ux on the free inputs of the step's box QP, zero on the
/// clamped ones: the inverse of the free block times Q̃_ux's rows.
fn feedback(qp: &box_qp::StepSolution, reg_ux: &DMatrix<f64>, gain: &mut DMatrix<f64>) {
    let Some(inverse) = &qp.inverse else {
        return;
    };
    if qp.free.len() == gain.nrows() {
        gemm(gain, -1.0, inverse, reg_ux, 0.0);
        return;
    }
    let n2 = reg_ux.ncols();
    let rows = DMatrix::from_fn(qp.free.len(), n2, |i, j| reg_ux[(qp.free[i], j)]);
    let mut free_gain = DMatrix::zeros(qp.free.len(), n2);
    gemm(&mut free_gain, -1.0, inverse, &rows, 0.0);
    (qp.free.iter().enumerate()).for_each(|(i, &r)| gain.set_row(r, &free_gain.row(i)));
}

/// V_x at the state the dynamics lead to, V_x + V_xx f, and the gap's
/// terms of the predicted change, ṽ·f and fᵀV_xx f (nothing for f = 0).
fn shift(vx: &mut DVector<f64>, vxx: &DMatrix<f64>, gap: &DVector<f64>, terms: &mut (f64, f64)) {
    if gap.amax() == 0.0 {
        return;
    }
    let vf = vxx * gap;
    *vx += &vf;
    terms.0 += vx.dot(gap);
    terms.1 += gap.dot(&vf);
}
