//! M = Lᵀ D L as expressions (Featherstone's LTDL, *Rigid Body Dynamics
//! Algorithms* §6.5): L unit lower triangular, D diagonal, eliminated from
//! the last coordinate up. On a kinematic tree M_ki = 0 unless one of i, k
//! is the other's ancestor, and eliminating children before their parents
//! fills in nothing: the products by those zeros vanish at construction, so
//! the emitted factorisation and its solves cost what the tree's branches
//! cost, not n³. The coordinates are not always numbered parents first (a
//! floating base's orientation comes last), so the order is read off M's
//! zeros: each step eliminates the coordinate that fills in least.

use lagrange_symbolic::{Context, Expr as Sym};

/// The factors of a symmetric positive definite M, P M Pᵀ = Lᵀ D L.
pub(super) struct Factor {
    /// The coordinate at each position of the permuted M.
    order: Vec<usize>,
    /// L's strictly lower entries, `lower[k][i]` for i < k (zero above).
    lower: Vec<Vec<Sym>>,
    /// 1 / D_k.
    reciprocal: Vec<Sym>,
    /// D_k, the pivots: positive exactly when M is positive definite.
    pub pivots: Vec<Sym>,
}

/// Factorises M. Each entry of L and D is built as one sum,
/// M_pi − Σ_{k>p} L_kp D_k L_ki (a running update would copy a growing sum
/// at every step, and the engine's sums are flat).
pub(super) fn factorise(ctx: &mut Context, mass: &[Vec<Sym>]) -> Factor {
    let n = mass.len();
    let order = elimination_order(ctx, mass);
    let m = |p: usize, r: usize| mass[order[p]][order[r]];
    let zero = ctx.zero();
    let one = ctx.one();
    let mut lower = vec![vec![zero; n]; n];
    // L_kp D_k, for the sums.
    let mut weighted = vec![vec![zero; n]; n];
    let mut pivots = vec![zero; n];
    let mut reciprocal = vec![zero; n];
    for p in (0..n).rev() {
        let below: Vec<usize> = ((p + 1)..n)
            .filter(|&k| !ctx.is_zero(lower[k][p]))
            .collect();
        let mut terms = vec![m(p, p)];
        for &k in &below {
            let t = ctx.mul(weighted[k][p], lower[k][p]);
            terms.push(ctx.neg(t));
        }
        pivots[p] = ctx.sum(&terms);
        reciprocal[p] = ctx.div(one, pivots[p]);
        for i in (0..p).rev() {
            let mut terms = vec![m(p, i)];
            for &k in &below {
                let t = ctx.mul(weighted[k][p], lower[k][i]);
                terms.push(ctx.neg(t));
            }
            let entry = ctx.sum(&terms);
            if ctx.is_zero(entry) {
                continue;
            }
            lower[p][i] = ctx.mul(entry, reciprocal[p]);
            weighted[p][i] = entry;
        }
    }
    Factor {
        order,
        lower,
        reciprocal,
        pivots,
    }
}

impl Factor {
    /// x = M⁻¹ b = Pᵀ L⁻¹ D⁻¹ L⁻ᵀ P b, each entry one sum.
    pub(super) fn solve(&self, ctx: &mut Context, b: &[Sym]) -> Vec<Sym> {
        let n = b.len();
        // Lᵀ z = P b, from the last row up: z_i = b_i − Σ_{k>i} L_ki z_k.
        let mut z: Vec<Sym> = self.order.iter().map(|&c| b[c]).collect();
        for i in (0..n).rev() {
            let mut terms = vec![z[i]];
            for (row, &zk) in self.lower[i + 1..].iter().zip(&z[i + 1..]) {
                if !ctx.is_zero(row[i]) {
                    let t = ctx.mul(row[i], zk);
                    terms.push(ctx.neg(t));
                }
            }
            z[i] = ctx.sum(&terms);
        }
        // D y = z, then L x = y from the first row down.
        let mut x: Vec<Sym> = z
            .iter()
            .zip(&self.reciprocal)
            .map(|(&zk, &r)| ctx.mul(zk, r))
            .collect();
        for k in 0..n {
            let mut terms = vec![x[k]];
            for (&l, &xj) in self.lower[k][..k].iter().zip(&x[..k]) {
                if !ctx.is_zero(l) {
                    let t = ctx.mul(l, xj);
                    terms.push(ctx.neg(t));
                }
            }
            x[k] = ctx.sum(&terms);
        }
        let mut out = x.clone();
        for (p, &c) in self.order.iter().enumerate() {
            out[c] = x[p];
        }
        out
    }
}

/// The coordinates by position, the last eliminated first: each step takes
/// the coordinate whose elimination joins the fewest pairs of its remaining
/// neighbours (M's nonzeros) that were not joined, then the one with the
/// fewest neighbours, then the highest-numbered (so that a tree numbered
/// parents first keeps its order).
fn elimination_order(ctx: &Context, mass: &[Vec<Sym>]) -> Vec<usize> {
    let n = mass.len();
    let mut joined: Vec<Vec<bool>> = (0..n)
        .map(|i| (0..n).map(|j| i != j && !ctx.is_zero(mass[i][j])).collect())
        .collect();
    let mut left: Vec<usize> = (0..n).collect();
    let mut order = vec![0; n];
    for position in (0..n).rev() {
        let neighbours = |v: usize, joined: &[Vec<bool>]| -> Vec<usize> {
            left.iter().copied().filter(|&u| joined[v][u]).collect()
        };
        let cost = |v: usize| {
            let near = neighbours(v, &joined);
            let fill = near
                .iter()
                .enumerate()
                .flat_map(|(k, &a)| near[k + 1..].iter().map(move |&b| (a, b)))
                .filter(|&(a, b)| !joined[a][b])
                .count();
            (fill, near.len(), std::cmp::Reverse(v))
        };
        let Some(&v) = left.iter().min_by_key(|&&v| cost(v)) else {
            break;
        };
        for &a in &neighbours(v, &joined) {
            for &b in &neighbours(v, &joined) {
                if a != b {
                    joined[a][b] = true;
                }
            }
        }
        left.retain(|&u| u != v);
        order[position] = v;
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tree-shaped SPD matrix (coordinate 4 the root, 0–1 one branch, 2–3
    /// another): the factors reproduce M⁻¹ b, and no entry between the
    /// branches fills in.
    #[test]
    fn factors_a_tree_without_fill_in() {
        let mut ctx = Context::new();
        // Numbered children first, as a floating base's orientation is.
        let parent = [Some(4), Some(0), Some(4), Some(2), None];
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
        let filled = (0..n).flat_map(|k| (0..k).map(move |i| (k, i)));
        let fill = filled
            .filter(|&(k, i)| !ctx.is_zero(factor.lower[k][i]))
            .filter(|&(k, i)| {
                !(ancestor(factor.order[k], factor.order[i])
                    || ancestor(factor.order[i], factor.order[k]))
            })
            .count();
        assert_eq!(fill, 0, "fill-in between the branches");
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
