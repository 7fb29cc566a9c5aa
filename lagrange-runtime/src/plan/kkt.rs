//! The Newton system of the direct method's interior point, sparse and
//! factorised by Clarabel's QDLDL (an LDLᵀ factorisation of quasi-definite
//! matrices with an AMD ordering, from the registry), with the inertia that
//! tells whether the step is a descent direction.
//!
//! The unknowns are laid out as in `direct_qp`: (x₀, u₀, x₁, u₁, …, x_K)
//! then the multipliers of the rows (the start, each step's dynamics, a
//! final equality). The matrix is
//!
//! ```text
//! [ W + Σ + δ_w I   Jᵀ    ]        W the Lagrangian's Hessian, block diagonal by step,
//! [ J              −δ_c I ]        J the rows' Jacobian: I on x₀; I on x_{k+1}, −A_k on x_k,
//!                                    −B_k on u_k; I on x_K for a final equality
//! ```
//!
//! Its pattern is fixed by the problem's sizes, so the ordering and the
//! symbolic factorisation are done once and each iteration refills the
//! values in place. Factorised without pivoting or regularisation, the
//! pivots' signs are the matrix's inertia: the step solves the barrier
//! problem's Newton equations for a minimum (not a saddle or a maximum)
//! exactly when there are as many positive pivots as primal unknowns
//! (Wächter and Biegler 2006, §3.1). The small −δ_c makes the matrix
//! quasi-definite, so factorisable in any ordering, wherever the shifted
//! Hessian is positive definite; elsewhere a zero pivot is reported as
//! `Singular`, which the caller treats as a wrong inertia. The solve
//! refines against δ_c = 0.

use super::direct_qp::offsets;
use clarabel::algebra::CscMatrix;
use clarabel::qdldl::{QDLDLFactorisation, QDLDLSettingsBuilder};
use nalgebra::DMatrix;

/// The Newton matrix's pattern, values and factorisation.
pub(super) struct Kkt {
    layout: Layout,
    matrix: CscMatrix<f64>,
    every: Vec<usize>,
    factor: QDLDLFactorisation<f64>,
    /// The dual diagonal of the matrix factorised, to refine against zero.
    delta_c: f64,
    residual: Vec<f64>,
    correction: Vec<f64>,
}

/// The sizes: 2N state entries, P inputs, K steps, a final equality or not.
#[derive(Clone, Copy)]
pub(super) struct Layout {
    pub n2: usize,
    pub p: usize,
    pub steps: usize,
    pub final_equality: bool,
}

impl Layout {
    /// The number of primal unknowns, (K + 1) 2N + K P.
    pub fn primal(&self) -> usize {
        (self.steps + 1) * self.n2 + self.steps * self.p
    }

    /// The number of rows: the start, K steps, and the final equality.
    pub fn rows(&self) -> usize {
        (self.steps + 1 + usize::from(self.final_equality)) * self.n2
    }

    /// The width of step k's block: 2N + P, or 2N for the final state.
    pub fn block(&self, k: usize) -> usize {
        match k < self.steps {
            true => self.n2 + self.p,
            false => self.n2,
        }
    }
}

/// The upper triangle's entries column by column, rows ascending, each
/// column's diagonal last: the steps' Hessian blocks, then the rows'
/// columns (the start's, each step's, the final equality's), each its
/// Jacobian entries and its own diagonal. `Kkt::fill` writes the values in
/// this order.
fn pattern(l: Layout) -> (Vec<usize>, Vec<usize>) {
    let (n, n2) = (l.primal(), l.n2);
    let (mut colptr, mut rowval) = (vec![0], Vec::new());
    for k in 0..=l.steps {
        let (base, _) = offsets(n2, l.p, k);
        for j in 0..l.block(k) {
            rowval.extend(base..=base + j);
            colptr.push(rowval.len());
        }
    }
    let mut row = n;
    let mut close = |rowval: &mut Vec<usize>, colptr: &mut Vec<usize>| {
        rowval.push(row);
        row += 1;
        colptr.push(rowval.len());
    };
    for i in 0..n2 {
        rowval.push(i);
        close(&mut rowval, &mut colptr);
    }
    for k in 0..l.steps {
        let ((base, _), (next, _)) = (offsets(n2, l.p, k), offsets(n2, l.p, k + 1));
        for i in 0..n2 {
            rowval.extend(base..base + n2 + l.p);
            rowval.push(next + i);
            close(&mut rowval, &mut colptr);
        }
    }
    if l.final_equality {
        let (last, _) = offsets(n2, l.p, l.steps);
        for i in 0..n2 {
            rowval.push(last + i);
            close(&mut rowval, &mut colptr);
        }
    }
    (colptr, rowval)
}

/// Why the matrix could not be factorised.
pub(super) struct Singular;

impl Kkt {
    /// The pattern of a problem's Newton matrix, ordered and analysed.
    pub fn new(layout: Layout) -> Self {
        let (colptr, rowval) = pattern(layout);
        let size = layout.primal() + layout.rows();
        let nnz = rowval.len();
        let matrix = CscMatrix::new(size, size, colptr, rowval, vec![1.0; nnz]);
        let settings = QDLDLSettingsBuilder::default()
            .logical(true)
            .regularize_enable(false)
            .build()
            .expect("the settings are complete");
        let factor = QDLDLFactorisation::new(&matrix, Some(settings))
            .expect("the pattern is upper triangular with every diagonal");
        Self {
            layout,
            matrix,
            every: (0..nnz).collect(),
            factor,
            delta_c: 0.0,
            residual: vec![0.0; size],
            correction: vec![0.0; size],
        }
    }

    /// Refills the values from the Hessian blocks (step by step, the final
    /// state's last), the steps' ∂F/∂x and ∂F/∂u, and the shifts, then
    /// factorises. Returns the number of positive pivots.
    pub fn factorise(
        &mut self,
        hessians: &[DMatrix<f64>],
        jacobians: &[(&DMatrix<f64>, &DMatrix<f64>)],
        (delta_w, delta_c): (f64, f64),
    ) -> Result<usize, Singular> {
        self.fill(hessians, jacobians, (delta_w, delta_c));
        self.delta_c = delta_c;
        self.factor.update_values(&self.every, &self.matrix.nzval);
        match self.factor.refactor() {
            Ok(()) => Ok(self.factor.positive_inertia()),
            Err(_) => Err(Singular),
        }
    }

    /// The values in `pattern`'s order: each Hessian block's upper
    /// triangle (δ_w on its diagonal), then each row's Jacobian entries and
    /// −δ_c.
    fn fill(
        &mut self,
        hessians: &[DMatrix<f64>],
        jacobians: &[(&DMatrix<f64>, &DMatrix<f64>)],
        (delta_w, delta_c): (f64, f64),
    ) {
        let (l, values) = (self.layout, &mut self.matrix.nzval);
        let mut p = 0;
        let mut put = |value: f64| {
            values[p] = value;
            p += 1;
        };
        // A row's own +1 on the state it sets, then its −δ_c.
        let close = |put: &mut dyn FnMut(f64)| {
            put(1.0);
            put(-delta_c);
        };
        for h in hessians {
            for j in 0..h.ncols() {
                (0..j).for_each(|i| put(h[(i, j)]));
                put(h[(j, j)] + delta_w);
            }
        }
        for _ in 0..l.n2 {
            close(&mut put);
        }
        for (a, b) in jacobians {
            for i in 0..l.n2 {
                (0..l.n2).for_each(|j| put(-a[(i, j)]));
                (0..l.p).for_each(|j| put(-b[(i, j)]));
                close(&mut put);
            }
        }
        if l.final_equality {
            for _ in 0..l.n2 {
                close(&mut put);
            }
        }
        debug_assert_eq!(p, values.len(), "the values follow the pattern");
    }

    /// The number of primal unknowns: the positive pivots a minimum has.
    pub fn primal(&self) -> usize {
        self.layout.primal()
    }

    /// Solves in place, refined against the matrix with no dual shift (δ_c
    /// only steadies the pivots) until the residual is below 10⁻¹⁰ of the
    /// right-hand side, at most twice.
    pub fn solve(&mut self, rhs: &mut [f64]) {
        let b = rhs.to_vec();
        // IPOPT's `residual_ratio_max`.
        let floor = 1e-10 * b.iter().fold(1.0f64, |m, b| m.max(b.abs()));
        self.factor.solve(rhs);
        for _ in 0..2 {
            self.residual.copy_from_slice(&b);
            self.subtract_product(rhs);
            if self.residual.iter().all(|r| r.abs() <= floor) {
                return;
            }
            self.correction.copy_from_slice(&self.residual);
            self.factor.solve(&mut self.correction);
            for (x, d) in rhs.iter_mut().zip(&self.correction) {
                *x += d;
            }
        }
    }

    /// residual −= K₀ x, K₀ the symmetric matrix from its upper triangle
    /// (each column's diagonal its last entry) with the dual shift taken
    /// out: K₀ x = K x + δ_c x on the rows' unknowns.
    fn subtract_product(&mut self, x: &[f64]) {
        let m = &self.matrix;
        let r = &mut self.residual;
        for j in 0..m.n {
            let (first, diagonal) = (m.colptr[j], m.colptr[j + 1] - 1);
            let (rows, values) = (&m.rowval[first..diagonal], &m.nzval[first..diagonal]);
            let mut column = 0.0;
            for (&i, &a) in rows.iter().zip(values) {
                r[i] -= a * x[j];
                column += a * x[i];
            }
            r[j] -= column + m.nzval[diagonal] * x[j];
        }
        let primal = self.layout.primal();
        for (r, x) in r[primal..].iter_mut().zip(&x[primal..]) {
            *r -= self.delta_c * x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::samples::uniform;
    use nalgebra::SymmetricEigen;

    /// A small problem's Newton matrix, dense, from the same blocks.
    fn dense(
        l: Layout,
        hessians: &[DMatrix<f64>],
        jac: &[(DMatrix<f64>, DMatrix<f64>)],
    ) -> DMatrix<f64> {
        let (n, m) = (l.primal(), l.rows());
        let mut k = DMatrix::zeros(n + m, n + m);
        for (s, h) in hessians.iter().enumerate() {
            let (x, _) = offsets(l.n2, l.p, s);
            k.view_mut((x, x), h.shape()).copy_from(h);
        }
        let mut set = |r: usize, c: usize, v: f64| {
            k[(n + r, c)] = v;
            k[(c, n + r)] = v;
        };
        for i in 0..l.n2 {
            set(i, i, 1.0);
        }
        for (s, (a, b)) in jac.iter().enumerate() {
            let (x, u) = offsets(l.n2, l.p, s);
            let (next, _) = offsets(l.n2, l.p, s + 1);
            for i in 0..l.n2 {
                let r = (s + 1) * l.n2 + i;
                (0..l.n2).for_each(|j| set(r, x + j, -a[(i, j)]));
                (0..l.p).for_each(|j| set(r, u + j, -b[(i, j)]));
                set(r, next + i, 1.0);
            }
        }
        let (last, _) = offsets(l.n2, l.p, l.steps);
        for i in 0..l.n2 {
            set((l.steps + 1) * l.n2 + i, last + i, 1.0);
        }
        k
    }

    /// The solve against a dense one, and the positive pivots against the
    /// dense matrix's positive eigenvalues, for a convex Hessian and for
    /// one made indefinite on the constraints' null space.
    #[test]
    fn the_sparse_solve_and_inertia_match_the_dense_matrix() {
        let l = Layout {
            n2: 2,
            p: 1,
            steps: 3,
            final_equality: true,
        };
        let mut sample = uniform(7);
        let mut random = |r: usize, c: usize| DMatrix::from_fn(r, c, |_, _| sample());
        let jac: Vec<_> = (0..l.steps).map(|_| (random(2, 2), random(2, 1))).collect();
        let refs: Vec<_> = jac.iter().map(|(a, b)| (a, b)).collect();
        for shift in [2.0, -2.0] {
            let hessians: Vec<DMatrix<f64>> = (0..=l.steps)
                .map(|k| {
                    let r = random(l.block(k), l.block(k));
                    &r * r.transpose() * 0.1 + DMatrix::identity(l.block(k), l.block(k)) * shift
                })
                .collect();
            let mut kkt = Kkt::new(l);
            let positive = kkt.factorise(&hessians, &refs, (0.0, 1e-9)).ok().unwrap();
            let k = dense(l, &hessians, &jac);
            let eigen = SymmetricEigen::new(k.clone()).eigenvalues;
            let expected = eigen.iter().filter(|e| **e > 0.0).count();
            assert_eq!(positive, expected, "shift {shift}: {eigen}");
            assert_eq!(positive == l.primal(), shift > 0.0);
            let b = random(l.primal() + l.rows(), 1);
            let mut x = b.as_slice().to_vec();
            kkt.solve(&mut x);
            let residual = &k * DMatrix::from_vec(x.len(), 1, x) - b;
            assert!(
                residual.amax() < 1e-9,
                "shift {shift}: residual {}",
                residual.amax()
            );
        }
    }
}
