//! The quadratic program of one step of the direct method, assembled
//! sparse and solved by Clarabel (an interior-point solver for convex
//! conic problems, pure Rust, from the registry).
//!
//! The unknowns are the changes of every state and input, laid out by step
//! as (δx₀, δu₀, δx₁, δu₁, …, δx_K), so that the cost's Hessian is block
//! diagonal with one (2N + P)-square block per step and the constraints'
//! matrix is banded:
//!
//! ```text
//! minimise    Σ_k ½ [δx_k; δu_k]ᵀ [l_xx l_uxᵀ; l_ux l_uu] [δx_k; δu_k] + l_x·δx_k + l_u·δu_k  + (final)
//! subject to  δx₀ = f₀,   δx_{k+1} − A_k δx_k − B_k δu_k = f_{k+1}   (the dynamics, linearised)
//!             δx_K = x* − x̄_K                                        (a final equality)
//!             lower − ū_k ≤ δu_k ≤ upper − ū_k,  the same for x₁ … x_K with state limits
//! ```
//!
//! with f the nominal's gaps. The final equality and the state limits are
//! elastic (Fletcher's Sℓ₁QP): each may be missed by a slack s ≥ 0 that
//! costs ν s, ν the merit function's penalty, so that a program whose
//! linearised constraints cannot all hold (a guess far from the goal, a goal
//! out of reach) still gives the step that best reduces the merit
//! function's violation, and the SQP reports the constraints it could not
//! meet rather than stopping on an infeasible program. The dynamics and the
//! input bounds can always be met and stay hard.
//!
//! Clarabel's form is A z + s = b with s in a product of cones: the
//! equalities in the zero cone, then the inequalities (A z ≤ b) in the
//! nonnegative cone; infinite bounds give no row.

use super::cost::CostModel;
use crate::linear::StepDerivatives;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::DVector;

/// What the program is built from, at the nominal plan.
pub(super) struct Linearised<'d, const N: usize> {
    /// The running costs' models at (x̄_k, ū_k), then the final one.
    pub models: &'d [CostModel],
    /// Each step's ∂F/∂x and ∂F/∂u.
    pub derivatives: &'d [StepDerivatives<N>],
    /// f₀ … f_K.
    pub gaps: &'d [DVector<f64>],
    /// x* − x̄_K when the last state is held at the goal.
    pub final_equality: Option<DVector<f64>>,
    /// Per step (ū_k), the input bounds less ū_k.
    pub input_room: Vec<(DVector<f64>, DVector<f64>)>,
    /// Per state x₁ … x_K, the state limits less x̄_k.
    pub state_room: Vec<(DVector<f64>, DVector<f64>)>,
    /// Added to the Hessian's diagonal (a proximal term that damps the step).
    pub damping: f64,
    /// The cost ν of a unit of slack on the elastic constraints.
    pub elastic: f64,
}

/// The step and the multipliers of the equalities.
pub(super) struct Step {
    /// (δx₀, δu₀, …, δx_K) in the layout above.
    pub delta: Vec<f64>,
    /// The largest |multiplier| of the start's and the dynamics' rows: the
    /// merit function's penalty must exceed it (an elastic row's is at most
    /// its price, the penalty itself).
    pub largest_multiplier: f64,
    /// Σ slacks: what the step leaves of the elastic constraints' violation,
    /// to first order.
    pub slack: f64,
    /// The largest entry of the Lagrangian's gradient at the current plan
    /// with the program's multipliers, ∇J + Aᵀz over the states and inputs:
    /// the KKT conditions' stationarity, zero at an optimum.
    pub kkt: f64,
}

/// Why the program has no step.
pub(super) struct Unsolved(pub SolverStatus);

/// A sparse matrix built from (row, column, value) entries.
struct Triplets {
    rows: usize,
    cols: usize,
    entries: Vec<(usize, usize, f64)>,
}

impl Triplets {
    fn new(cols: usize) -> Self {
        Self {
            rows: 0,
            cols,
            entries: Vec::new(),
        }
    }

    fn push(&mut self, row: usize, col: usize, value: f64) {
        if value != 0.0 {
            self.entries.push((row, col, value));
        }
    }

    /// Compressed sparse columns, entries at the same place summed.
    fn csc(mut self) -> CscMatrix<f64> {
        self.entries.sort_by_key(|&(r, c, _)| (c, r));
        let mut colptr = vec![0; self.cols + 1];
        let (mut rowval, mut nzval): (Vec<usize>, Vec<f64>) = (Vec::new(), Vec::new());
        let mut last = None;
        for (r, c, v) in self.entries {
            if last == Some((r, c)) {
                *nzval.last_mut().expect("a previous entry") += v;
                continue;
            }
            last = Some((r, c));
            rowval.push(r);
            nzval.push(v);
            colptr[c + 1] = rowval.len();
        }
        for c in 0..self.cols {
            colptr[c + 1] = colptr[c + 1].max(colptr[c]);
        }
        CscMatrix::new(self.rows, self.cols, colptr, rowval, nzval)
    }
}

/// Offsets of δx_k and δu_k in the layout.
pub(super) fn offsets(n2: usize, p: usize, k: usize) -> (usize, usize) {
    (k * (n2 + p), k * (n2 + p) + n2)
}

/// Builds and solves the program.
pub(super) fn solve<const N: usize>(
    lin: &Linearised<N>,
    p: usize,
    steps: usize,
) -> Result<Step, Unsolved> {
    let n2 = 2 * N;
    let unknowns = steps * (n2 + p) + n2;
    let mut a = Triplets::new(unknowns);
    let mut b = Vec::new();
    equalities(lin, p, steps, &mut a, &mut b);
    let equal = b.len();
    inequalities(lin, p, &mut a, &mut b);
    let slacks = a.cols - unknowns;
    // The slacks' own rows: −s ≤ 0.
    for i in 0..slacks {
        a.push(a.rows, unknowns + i, -1.0);
        b.push(0.0);
        a.rows += 1;
    }
    let (hessian, mut gradient) = objective(lin, p, unknowns + slacks);
    gradient[unknowns..].fill(lin.elastic);
    let cones = [
        SupportedConeT::ZeroConeT(equal),
        SupportedConeT::NonnegativeConeT(b.len() - equal),
    ];
    let cones = if b.len() > equal {
        &cones[..]
    } else {
        &cones[..1]
    };
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .build()
        .expect("the settings are valid");
    let a = a.csc();
    let mut solver = DefaultSolver::new(&hessian, &gradient, &a, &b, cones, settings)
        .map_err(|_| Unsolved(SolverStatus::Unsolved))?;
    solver.solve();
    let solution = &solver.solution;
    match solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(Step {
            kkt: stationarity(&a, &gradient, &solution.z, unknowns),
            delta: solution.x[..unknowns].to_vec(),
            slack: solution.x[unknowns..].iter().map(|s| s.max(0.0)).sum(),
            // The hard rows' alone (the start's and the dynamics'): an
            // elastic row's multiplier is its slack's price ν whenever its
            // slack is in use.
            largest_multiplier: solution.z[..2 * N * (steps + 1)]
                .iter()
                .fold(0.0, |m: f64, z| m.max(z.abs())),
        }),
        status => Err(Unsolved(status)),
    }
}

/// max_j |g_j + (Aᵀz)_j| over the first `unknowns` columns (the states and
/// inputs; the slacks' columns are the elastic constraints' own).
fn stationarity(a: &CscMatrix<f64>, g: &[f64], z: &[f64], unknowns: usize) -> f64 {
    (0..unknowns)
        .map(|j| {
            let column = a.colptr[j]..a.colptr[j + 1];
            let atz: f64 = column.map(|i| a.nzval[i] * z[a.rowval[i]]).sum();
            (g[j] + atz).abs()
        })
        .fold(0.0, f64::max)
}

/// The Hessian's upper triangle (block diagonal, damped) and the gradient.
fn objective<const N: usize>(
    lin: &Linearised<N>,
    p: usize,
    unknowns: usize,
) -> (CscMatrix<f64>, Vec<f64>) {
    let n2 = 2 * N;
    let steps = lin.input_room.len();
    let mut h = Triplets::new(unknowns);
    h.rows = unknowns;
    let mut g = vec![0.0; unknowns];
    for (k, m) in lin.models.iter().enumerate() {
        let (x, u) = offsets(n2, p, k);
        let inputs = if k < steps { p } else { 0 };
        for i in 0..n2 {
            g[x + i] = m.lx[i];
            for j in i..n2 {
                h.push(x + i, x + j, m.lxx[(i, j)]);
            }
        }
        for i in 0..inputs {
            g[u + i] = m.lu[i];
            for j in 0..n2 {
                h.push(x + j, u + i, m.lux[(i, j)]);
            }
            for j in i..inputs {
                h.push(u + i, u + j, m.luu[(i, j)]);
            }
        }
    }
    for i in 0..unknowns {
        h.push(i, i, lin.damping);
    }
    (h.csc(), g)
}

/// The start, the linearised dynamics and the final equality, in the zero
/// cone.
fn equalities<const N: usize>(
    lin: &Linearised<N>,
    p: usize,
    steps: usize,
    a: &mut Triplets,
    b: &mut Vec<f64>,
) {
    let n2 = 2 * N;
    let identity_at = |a: &mut Triplets, b: &mut Vec<f64>, k: usize, rhs: &DVector<f64>| {
        let (x, _) = offsets(n2, p, k);
        for i in 0..n2 {
            a.push(a.rows + i, x + i, 1.0);
            b.push(rhs[i]);
        }
    };
    identity_at(a, b, 0, &lin.gaps[0]);
    a.rows += n2;
    for k in 0..steps {
        let (x, u) = offsets(n2, p, k);
        let d = &lin.derivatives[k];
        for i in 0..n2 {
            for j in 0..n2 {
                a.push(a.rows + i, x + j, -d.dx[(i, j)]);
            }
            for j in 0..p {
                a.push(a.rows + i, u + j, -d.du[(i, j)]);
            }
        }
        identity_at(a, b, k + 1, &lin.gaps[k + 1]);
        a.rows += n2;
    }
    if let Some(rest) = &lin.final_equality {
        // δx_K − s⁺ + s⁻ = x* − x̄_K.
        identity_at(a, b, steps, rest);
        for i in 0..n2 {
            a.push(a.rows + i, a.cols, -1.0);
            a.push(a.rows + i, a.cols + 1, 1.0);
            a.cols += 2;
        }
        a.rows += n2;
    }
}

/// The input bounds (hard) and the state limits (elastic: δx − s ≤ room),
/// A z ≤ b in the nonnegative cone; an infinite bound gives no row.
fn inequalities<const N: usize>(lin: &Linearised<N>, p: usize, a: &mut Triplets, b: &mut Vec<f64>) {
    let n2 = 2 * N;
    let boxed = |a: &mut Triplets,
                 b: &mut Vec<f64>,
                 at: usize,
                 room: &(DVector<f64>, DVector<f64>),
                 elastic: bool| {
        for i in 0..room.0.len() {
            for (sign, bound) in [(1.0, room.1[i]), (-1.0, -room.0[i])] {
                if bound.is_finite() {
                    a.push(a.rows, at + i, sign);
                    if elastic {
                        a.push(a.rows, a.cols, -1.0);
                        a.cols += 1;
                    }
                    b.push(bound);
                    a.rows += 1;
                }
            }
        }
    };
    for (k, room) in lin.input_room.iter().enumerate() {
        boxed(a, b, offsets(n2, p, k).1, room, false);
    }
    for (k, room) in lin.state_room.iter().enumerate() {
        boxed(a, b, offsets(n2, p, k + 1).0, room, true);
    }
}
