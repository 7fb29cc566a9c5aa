//! M = Lᵀ D L as expressions (Featherstone's LTDL, *Rigid Body Dynamics
//! Algorithms* §6.5): L unit lower triangular, D diagonal, eliminated from
//! the last coordinate up. On a kinematic tree numbered parents first,
//! M_ki = 0 unless i is an ancestor of k, and this order fills in nothing:
//! the products by those zeros vanish at construction, so the emitted
//! factorisation and its solves cost what the tree's branches cost, not n³.

use lagrange_symbolic::{Context, Expr as Sym};

/// The factors of a symmetric positive definite M.
pub(super) struct Factor {
    /// L's strictly lower entries, `lower[k][i]` for i < k.
    lower: Vec<Vec<Sym>>,
    /// 1 / D_k.
    reciprocal: Vec<Sym>,
    /// D_k, the pivots: positive exactly when M is positive definite.
    pub pivots: Vec<Sym>,
}

/// Factorises M (its lower triangle is read).
pub(super) fn factorise(ctx: &mut Context, mass: &[Vec<Sym>]) -> Factor {
    let n = mass.len();
    let mut h: Vec<Vec<Sym>> = mass.to_vec();
    let mut pivots = vec![ctx.zero(); n];
    let mut reciprocal = vec![ctx.zero(); n];
    let one = ctx.one();
    for k in (0..n).rev() {
        pivots[k] = h[k][k];
        reciprocal[k] = ctx.div(one, h[k][k]);
        // i downward, so that row k's entries left of i still hold M's
        // (updated) values when column i is eliminated.
        for i in (0..k).rev() {
            if ctx.is_zero(h[k][i]) {
                continue;
            }
            let a = ctx.mul(h[k][i], reciprocal[k]);
            let row_k: Vec<Sym> = h[k][..=i].to_vec();
            for (hij, &hkj) in h[i][..=i].iter_mut().zip(&row_k) {
                let t = ctx.mul(a, hkj);
                *hij = ctx.sub(*hij, t);
            }
            h[k][i] = a;
        }
    }
    let lower = (0..n).map(|k| h[k][..k].to_vec()).collect();
    Factor {
        lower,
        reciprocal,
        pivots,
    }
}

impl Factor {
    /// x = M⁻¹ b = L⁻¹ D⁻¹ L⁻ᵀ b.
    pub(super) fn solve(&self, ctx: &mut Context, b: &[Sym]) -> Vec<Sym> {
        let n = b.len();
        // Lᵀ z = b, from the last row up.
        let mut z = b.to_vec();
        for k in (0..n).rev() {
            for i in 0..k {
                let t = ctx.mul(self.lower[k][i], z[k]);
                z[i] = ctx.sub(z[i], t);
            }
        }
        // D y = z, then L x = y from the first row down.
        let mut x: Vec<Sym> = z
            .iter()
            .zip(&self.reciprocal)
            .map(|(&zk, &r)| ctx.mul(zk, r))
            .collect();
        for k in 0..n {
            let terms: Vec<Sym> = (0..k).map(|j| ctx.mul(self.lower[k][j], x[j])).collect();
            let s = ctx.sum(&terms);
            x[k] = ctx.sub(x[k], s);
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tree-shaped SPD matrix (coordinate 0 the root, 1–2 one branch, 3–4
    /// another): the factors reproduce M⁻¹ b, and no entry between the
    /// branches fills in.
    #[test]
    fn factors_a_tree_without_fill_in() {
        let mut ctx = Context::new();
        let parent = [None, Some(0), Some(1), Some(0), Some(3)];
        let ancestor = |mut k: usize, i: usize| loop {
            if k == i {
                return true;
            }
            match parent[k] {
                Some(p) => k = p,
                None => return false,
            }
        };
        let n = parent.len();
        let mut value = vec![vec![0.0; n]; n];
        for (k, row) in value.iter_mut().enumerate() {
            for (i, x) in row.iter_mut().enumerate() {
                if ancestor(k, i) || ancestor(i, k) {
                    *x = if k == i {
                        4.0 + k as f64
                    } else {
                        0.3 + 0.1 * (k + i) as f64
                    };
                }
            }
        }
        let mass: Vec<Vec<Sym>> = value
            .iter()
            .map(|r| r.iter().map(|&x| ctx.float(x)).collect())
            .collect();
        let factor = factorise(&mut ctx, &mass);
        assert!(ctx.is_zero(factor.lower[3][1]) && ctx.is_zero(factor.lower[4][2]));
        let b_values = [1.0, -2.0, 0.5, 3.0, -1.5];
        let b: Vec<Sym> = b_values.iter().map(|&x| ctx.float(x)).collect();
        let x = factor.solve(&mut ctx, &b);
        let x: Vec<f64> = x
            .iter()
            .map(|&e| ctx.as_f64(e).expect("a constant"))
            .collect();
        for (k, row) in value.iter().enumerate() {
            let mx: f64 = row.iter().zip(&x).map(|(m, x)| m * x).sum();
            assert!(
                (mx - b_values[k]).abs() < 1e-14,
                "row {k}: {mx} against {}",
                b_values[k]
            );
        }
        for &d in &factor.pivots {
            assert!(ctx.as_f64(d).expect("a constant") > 0.0);
        }
    }
}
