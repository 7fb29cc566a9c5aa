//! Cholesky factorisations on the stack.
//!
//! Written out here rather than through `nalgebra::Cholesky` for one reason: the
//! pivots L_ii² are needed to tell a *near*-singular matrix (a chart singularity of
//! the mass matrix, a redundant constraint) from a healthy one. nalgebra only
//! reports outright failure, and a pivot of 1e-30 would silently give results that
//! are pure round-off.
//!
//! Both factorisations work on the leading `n`×`n` block of a fixed-size matrix, so
//! that the holonomic rows of a constraint Jacobian, or the independent rows found
//! by pivoting, can be handled without a differently sized type.

use crate::numeric::Real;
use crate::numeric::func::sqrt;
use nalgebra::{SMatrix, SVector};

/// M = L Lᵀ for symmetric positive definite M (leading `n`×`n` block).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cholesky<T, const N: usize> {
    /// L in the lower triangle of the leading block.
    l: SMatrix<T, N, N>,
    /// 1 / L_ii: the substitutions multiply by it, so that each of their
    /// steps waits for a product, not for a division.
    recip: [T; N],
    n: usize,
}

impl<T: Real, const N: usize> Cholesky<T, N> {
    /// Factorises all of `m`. See [`leading`](Self::leading). Offered for
    /// inlining, as `leading` is, so that M is factorised where it lies
    /// rather than copied into and out of a call.
    #[inline]
    pub fn new(m: SMatrix<T, N, N>, tolerance: T) -> Result<Self, T> {
        Self::leading(m, N, tolerance)
    }

    /// Factorises the leading `n`×`n` block of `m`; only its lower triangle is read.
    ///
    /// On failure returns the pivot ratio min L_ii² / max L_ii² (or the offending
    /// non-positive pivot divided by the largest diagonal entry seen so far) so that
    /// the error can say how singular the matrix was.
    #[inline]
    pub fn leading(mut m: SMatrix<T, N, N>, n: usize, tolerance: T) -> Result<Self, T> {
        debug_assert!(n <= N);
        let mut recip = [T::one(); N];
        if n == 0 {
            return Ok(Self { l: m, recip, n });
        }
        let mut min_pivot = T::max_value().unwrap_or(T::one() / T::default_epsilon());
        let mut max_pivot = T::zero();
        let mut max_diag = T::zero();
        // Left-looking factorisation in place in the lower triangle.
        for j in 0..n {
            let mut d = m[(j, j)];
            max_diag = max_diag.max(d);
            for k in 0..j {
                d -= m[(j, k)] * m[(j, k)];
            }
            if d <= T::zero() {
                let denom = max_pivot.max(max_diag);
                return Err(if denom > T::zero() {
                    d / denom
                } else {
                    T::zero()
                });
            }
            min_pivot = min_pivot.min(d);
            max_pivot = max_pivot.max(d);
            let ljj = sqrt(d);
            m[(j, j)] = ljj;
            recip[j] = T::one() / ljj;
            for i in j + 1..n {
                let mut s = m[(i, j)];
                for k in 0..j {
                    s -= m[(i, k)] * m[(j, k)];
                }
                m[(i, j)] = s / ljj;
            }
        }
        let ratio = min_pivot / max_pivot;
        if ratio < tolerance {
            return Err(ratio);
        }
        Ok(Self { l: m, recip, n })
    }

    /// Forward substitution L y = b in place (first `n` entries).
    pub fn solve_lower(&self, b: &mut SVector<T, N>) {
        // For the whole matrix, loops of constant lengths, which the
        // compiler unrolls: no loop exit to mispredict (the two solves of a
        // 6 × 6 alone took 70 ns with run-time lengths, 33 ns so; the
        // factorisation, unrolled, ran slower and is not).
        if self.n == N {
            forward(&self.l, &self.recip, b, N);
        } else {
            forward(&self.l, &self.recip, b, self.n);
        }
    }

    /// Back substitution Lᵀ x = y in place (first `n` entries).
    pub fn solve_upper(&self, b: &mut SVector<T, N>) {
        if self.n == N {
            backward(&self.l, &self.recip, b, N);
        } else {
            backward(&self.l, &self.recip, b, self.n);
        }
    }

    /// x = M⁻¹ b.
    pub fn solve(&self, mut b: SVector<T, N>) -> SVector<T, N> {
        self.solve_lower(&mut b);
        self.solve_upper(&mut b);
        b
    }

    /// M⁻¹ B for a matrix of right-hand sides: the same operations in the
    /// same order as [`solve`](Self::solve) on each column (so the same
    /// numbers), done a row of B at a time on Bᵀ, whose rows are contiguous,
    /// so that each step runs across the C columns at once.
    pub fn solve_columns<const C: usize>(&self, b: SMatrix<T, N, C>) -> SMatrix<T, N, C> {
        let mut bt = b.transpose();
        let rows = bt.as_mut_slice();
        // Row i of B is rows[i * C..(i + 1) * C]; `update(i, k, l)` is
        // row_i −= l · row_k.
        let update = |rows: &mut [T], i: usize, k: usize, l: T| {
            let (i_row, k_row) = if k < i {
                let (head, tail) = rows.split_at_mut(i * C);
                (&mut tail[..C], &head[k * C..(k + 1) * C])
            } else {
                let (head, tail) = rows.split_at_mut(k * C);
                (&mut head[i * C..(i + 1) * C], &tail[..C])
            };
            for (x, &y) in i_row.iter_mut().zip(k_row) {
                *x -= l * y;
            }
        };
        let scale = |rows: &mut [T], i: usize, r: T| {
            for x in &mut rows[i * C..(i + 1) * C] {
                *x *= r;
            }
        };
        for i in 0..self.n {
            for k in 0..i {
                update(rows, i, k, self.l[(i, k)]);
            }
            scale(rows, i, self.recip[i]);
        }
        for i in (0..self.n).rev() {
            for k in i + 1..self.n {
                update(rows, i, k, self.l[(k, i)]);
            }
            scale(rows, i, self.recip[i]);
        }
        bt.transpose()
    }
}

/// L y = b in place over the first `n` entries.
#[inline(always)]
fn forward<T: Real, const N: usize>(
    l: &SMatrix<T, N, N>,
    recip: &[T; N],
    b: &mut SVector<T, N>,
    n: usize,
) {
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[(i, k)] * b[k];
        }
        b[i] = s * recip[i];
    }
}

/// Lᵀ x = y in place over the first `n` entries.
#[inline(always)]
fn backward<T: Real, const N: usize>(
    l: &SMatrix<T, N, N>,
    recip: &[T; N],
    b: &mut SVector<T, N>,
    n: usize,
) {
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[(k, i)] * b[k];
        }
        b[i] = s * recip[i];
    }
}

/// P S Pᵀ = L Lᵀ with diagonal pivoting, for symmetric positive *semi*definite S
/// (leading `n`×`n` block), stopping at the numerical rank.
///
/// Pivoting on the largest remaining diagonal entry puts an independent set of rows
/// first; the factorisation stops when the largest remaining pivot falls below
/// `tolerance` times the first (largest) one, and the rows left over are the ones
/// that depend (numerically) on the others. For S = G M⁻¹ Gᵀ these are redundant
/// constraints.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PivotedCholesky<T, const K: usize> {
    /// L (n × rank, lower trapezoidal) in the permuted order, columns 0..rank.
    l: SMatrix<T, K, K>,
    /// Row `i` of the permuted matrix is row `perm[i]` of S.
    perm: [usize; K],
    n: usize,
    rank: usize,
    /// Smallest pivot over largest: of the accepted pivots if full rank, of the
    /// first rejected one otherwise (≤ 0 for a zero or negative pivot).
    ratio: T,
}

impl<T: Real, const K: usize> PivotedCholesky<T, K> {
    /// Factorises the leading `n`×`n` block of the symmetric `s` (fully stored).
    pub fn new(mut a: SMatrix<T, K, K>, n: usize, tolerance: T) -> Self {
        debug_assert!(n <= K);
        let mut perm = [0; K];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let mut rank = n;
        let mut ratio = T::one();
        let mut first = T::zero();
        for j in 0..n {
            let mut p = j;
            for i in j + 1..n {
                if a[(i, i)] > a[(p, p)] {
                    p = i;
                }
            }
            let d = a[(p, p)];
            if j == 0 {
                first = d;
            }
            let r = if first > T::zero() {
                d / first
            } else {
                T::zero()
            };
            // A NaN pivot is unordered and counts as rejected too.
            let positive = d.partial_cmp(&T::zero()) == Some(std::cmp::Ordering::Greater);
            if !positive || r < tolerance {
                rank = j;
                ratio = r;
                break;
            }
            ratio = ratio.min(r);
            if p != j {
                a.swap_rows(j, p);
                a.swap_columns(j, p);
                perm.swap(j, p);
            }
            let ljj = sqrt(d);
            a[(j, j)] = ljj;
            for i in j + 1..n {
                a[(i, j)] /= ljj;
            }
            // The trailing block is kept fully symmetric so that row and column
            // swaps of later steps stay valid.
            for k in j + 1..n {
                for i in k..n {
                    let x = a[(i, k)] - a[(i, j)] * a[(k, j)];
                    a[(i, k)] = x;
                    a[(k, i)] = x;
                }
            }
        }
        Self {
            l: a,
            perm,
            n,
            rank,
            ratio,
        }
    }

    /// Whether all `n` rows are independent.
    pub fn is_full_rank(&self) -> bool {
        self.rank == self.n
    }

    /// See the field: the pivot ratio that decided the rank.
    pub fn ratio(&self) -> T {
        self.ratio
    }

    /// The rows (indices into S) that depend on the others.
    pub fn dependent_rows(&self) -> &[usize] {
        &self.perm[self.rank..self.n]
    }

    /// The solution of S x = b of minimum norm (the unique one at full rank).
    ///
    /// Rank deficient: with L = L_r (n × r, full column rank) the solutions of
    /// L L_rᵀ x = b of minimum norm lie in range(L_r), x = L_r y. The independent
    /// rows fix w = L_rᵀ x = L₁₁⁻¹ b₁ (the dependent rows of b are consistent for
    /// truly redundant constraints and are not used), and then C y = w with
    /// C = L_rᵀ L_r (r × r, positive definite, with the nonzero eigenvalues of S).
    /// `None` only if C is not numerically positive definite, which the pivot
    /// threshold rules out in practice.
    pub fn solve_min_norm(&self, b: &SVector<T, K>) -> Option<SVector<T, K>> {
        let n = self.n;
        let r = self.rank;
        let mut w = SVector::<T, K>::zeros();
        for i in 0..n {
            w[i] = b[self.perm[i]];
        }
        // Forward substitution with the top r×r block: w = L₁₁⁻¹ b₁.
        for i in 0..r {
            let mut s = w[i];
            for k in 0..i {
                s -= self.l[(i, k)] * w[k];
            }
            w[i] = s / self.l[(i, i)];
        }
        let y = if r == n {
            // Full rank: x = L⁻ᵀ w.
            for i in (0..n).rev() {
                let mut s = w[i];
                for k in i + 1..n {
                    s -= self.l[(k, i)] * w[k];
                }
                w[i] = s / self.l[(i, i)];
            }
            w
        } else {
            let mut c = SMatrix::<T, K, K>::zeros();
            for a in 0..r {
                for b in 0..=a {
                    let mut s = T::zero();
                    for i in a..n {
                        s += self.l[(i, a)] * self.l[(i, b)];
                    }
                    c[(a, b)] = s;
                }
            }
            for x in w.iter_mut().skip(r) {
                *x = T::zero();
            }
            let y = Cholesky::leading(c, r, T::zero()).ok()?.solve(w);
            let mut x = SVector::<T, K>::zeros();
            for i in 0..n {
                for k in 0..r.min(i + 1) {
                    x[i] += self.l[(i, k)] * y[k];
                }
            }
            x
        };
        // Undo the permutation.
        let mut x = SVector::<T, K>::zeros();
        for i in 0..n {
            x[self.perm[i]] = y[i];
        }
        Some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

    /// Solves M x = b through the factorisation; on failure the pivot ratio.
    fn cholesky_solve<T: Real, const N: usize>(
        m: SMatrix<T, N, N>,
        b: SVector<T, N>,
        tolerance: T,
    ) -> Result<SVector<T, N>, T> {
        Ok(Cholesky::new(m, tolerance)?.solve(b))
    }

    #[test]
    fn cholesky_solves_spd_system() {
        let a = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let x = Vector3::new(1.0, -2.0, 0.5);
        let b = a * x;
        let got = cholesky_solve(a, b, 1e-12).unwrap();
        assert!((got - x).norm() < 1e-14, "{got}");
    }

    #[test]
    fn cholesky_reports_pivot_ratio() {
        let s = 1e-8_f64; // sin θ near the pole
        let m = Matrix2::new(1.0, 0.0, 0.0, s * s);
        let ratio = cholesky_solve(m, Vector2::new(1.0, 0.0), 1e-12).unwrap_err();
        assert!((ratio - 1e-16).abs() < 1e-30);
        // A tolerance below the ratio accepts the same matrix.
        assert!(cholesky_solve(m, Vector2::new(1.0, 0.0), 1e-20).is_ok());
        // Indefinite: the second pivot is negative.
        let m = Matrix2::new(1.0, 2.0, 2.0, 1.0);
        let ratio = cholesky_solve(m, Vector2::new(1.0, 0.0), 1e-12).unwrap_err();
        assert!(ratio < 0.0);
    }

    #[test]
    fn leading_block_ignores_the_rest() {
        // The trailing row/column is garbage (NaN) and must not be read.
        let a = Matrix3::new(
            4.0,
            1.0,
            f64::NAN,
            1.0,
            3.0,
            f64::NAN,
            f64::NAN,
            f64::NAN,
            0.0,
        );
        let c = Cholesky::leading(a, 2, 1e-12).unwrap();
        let x = c.solve(Vector3::new(5.0, 4.0, 7.0));
        assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15);
        assert_eq!(x[2], 7.0);
    }

    #[test]
    fn pivoted_full_rank_matches_plain_solve() {
        let a = Matrix3::new(1.0, 0.3, 0.1, 0.3, 5.0, 0.2, 0.1, 0.2, 2.0);
        let x = Vector3::new(1.0, -2.0, 0.5);
        let f = PivotedCholesky::new(a, 3, 1e-12);
        assert!(f.is_full_rank() && f.dependent_rows().is_empty());
        // Pivoting picks row 1 (diagonal 5) first.
        assert_eq!(f.perm[0], 1);
        let got = f.solve_min_norm(&(a * x)).unwrap();
        assert!((got - x).norm() < 1e-14, "{got}");
    }

    #[test]
    fn pivoted_finds_dependent_row_and_min_norm_solution() {
        // Rows 0 and 2 of G are equal: S = G Gᵀ has rank 2 and row 2 depends on 0.
        let g = Matrix3::<f64>::new(1.0, 2.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 0.0);
        let s = g * g.transpose();
        let f = PivotedCholesky::new(s, 3, 1e-12);
        assert!(!f.is_full_rank());
        assert!(f.ratio() < 1e-12, "{}", f.ratio());
        assert_eq!(f.dependent_rows(), &[2]);
        // A consistent right-hand side: the minimum-norm solution has equal
        // components on the duplicated rows and reproduces b.
        let b = s * Vector3::new(0.3, -1.0, 0.7);
        let x = f.solve_min_norm(&b).unwrap();
        assert!((s * x - b).norm() < 1e-13, "{}", s * x - b);
        assert!((x[0] - x[2]).abs() < 1e-13, "{x}");
        assert!((x[0] - 0.5).abs() < 1e-13, "{x}");
        // The leading-block form ignores rows beyond n.
        let f = PivotedCholesky::new(s, 2, 1e-12);
        assert!(f.is_full_rank());
    }

    #[test]
    fn zero_matrix_has_rank_zero() {
        let f = PivotedCholesky::new(Matrix2::<f64>::zeros(), 2, 1e-12);
        assert_eq!(f.dependent_rows(), &[0, 1]);
        assert_eq!(f.ratio(), 0.0);
        assert_eq!(
            f.solve_min_norm(&Vector2::new(0.0, 0.0)).unwrap(),
            Vector2::zeros()
        );
    }
}
