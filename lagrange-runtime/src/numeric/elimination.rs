//! The inverse of a small square matrix by Gauss–Jordan elimination with
//! complete pivoting, for the reduced form's stacked velocity rows A = [U; G].
//!
//! The rows mix units (a forward speed in m/s, a turning rate in rad/s, rolling
//! constraints), so each row is first scaled to a largest entry of 1; complete
//! pivoting then reveals the rank: when the largest entry left falls below the
//! tolerance times the first pivot, the rows not yet used are combinations of
//! the used ones, and the elimination's record of row operations says which.
//! N is small (the degrees of freedom), so the N³ cost is a few hundred flops.

// Index loops mirror the elimination they implement.
#![allow(clippy::needless_range_loop)]

use crate::numeric::Real;
use crate::numeric::func::abs;
use core::ops::Range;
use nalgebra::{SMatrix, SVector};

/// The rows of a matrix found linearly dependent.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Dependent {
    /// The rows in the dependency (indices into the matrix), ascending.
    pub rows: Vec<usize>,
    /// The largest entry left when elimination stopped over the first pivot
    /// (0 for an exact dependency).
    pub ratio: f64,
}

/// A⁻¹, or the dependent rows when a pivot falls below `tolerance` times the
/// first (all rows scaled to a largest entry of 1). A zero row is dependent on
/// its own.
pub(crate) fn invert<T: Real, const N: usize>(
    a: &SMatrix<T, N, N>,
    tolerance: T,
) -> Result<SMatrix<T, N, N>, Dependent> {
    let mut e = Elimination::new(a, 0..N)?;
    e.run(0..N, tolerance)?;
    // ops · D · A is the permutation with m[(i, column_of[i])] = 1, so row
    // column_of[i] of A⁻¹ is row i of ops · D.
    let mut inverse = SMatrix::<T, N, N>::zeros();
    for i in 0..N {
        for j in 0..N {
            inverse[(e.column_of[i], j)] = e.ops[(i, j)] * e.scale[j];
        }
    }
    Ok(inverse)
}

/// Rows `rows` of a matrix eliminated with complete pivoting, as
/// constraints G x = r on N unknowns: each row fixes one pivot unknown in
/// terms of the unknowns left free (coordinate partitioning).
pub(crate) struct Partition<T: Real, const N: usize> {
    elimination: Elimination<T, N>,
    rows: Range<usize>,
}

impl<T: Real, const N: usize> Partition<T, N> {
    /// Eliminates rows `rows` of `a`, or names the dependent ones among them.
    pub(crate) fn new(
        a: &SMatrix<T, N, N>,
        rows: Range<usize>,
        tolerance: T,
    ) -> Result<Self, Dependent> {
        let mut elimination = Elimination::new(a, rows.clone())?;
        elimination.run(rows.clone(), tolerance)?;
        Ok(Self { elimination, rows })
    }

    /// Whether each unknown is left free by the rows.
    pub(crate) fn free(&self) -> [bool; N] {
        let mut free = [true; N];
        for i in self.rows.clone() {
            free[self.elimination.column_of[i]] = false;
        }
        free
    }

    /// Overwrites the pivot unknowns of x so that the rows hold with the
    /// right-hand sides r (indexed by row; only the eliminated rows are read),
    /// keeping the free unknowns of x.
    pub(crate) fn complete(&self, x: &mut SVector<T, N>, r: &SVector<T, N>) {
        let e = &self.elimination;
        for i in self.rows.clone() {
            // Row i of the eliminated system: x_p + Σ_free m[i][j] x_j = (ops D r)_i.
            let mut value = T::zero();
            for k in self.rows.clone() {
                value += e.ops[(i, k)] * e.scale[k] * r[k];
            }
            // The other pivot columns of row i are exactly zero after
            // Gauss–Jordan (each was cleared by subtracting itself times 1).
            let p = e.column_of[i];
            for j in (0..N).filter(|&j| j != p) {
                value -= e.m[(i, j)] * x[j];
            }
            x[p] = value;
        }
    }

    /// A basis of the null space of the rows: column c is the c-th free unknown
    /// set to 1, the others to 0, and the pivot unknowns completed.
    pub(crate) fn basis<const K: usize>(&self) -> SMatrix<T, N, K> {
        let e = &self.elimination;
        let mut w = SMatrix::<T, N, K>::zeros();
        let free = self.free();
        for (c, j) in (0..N).filter(|&j| free[j]).take(K).enumerate() {
            w[(j, c)] = T::one();
            for i in self.rows.clone() {
                w[(e.column_of[i], c)] = -e.m[(i, j)];
            }
        }
        w
    }
}

/// Gauss–Jordan elimination in progress on the row-scaled matrix D A.
struct Elimination<T: Real, const N: usize> {
    m: SMatrix<T, N, N>,
    /// The row operations so far: ops · (D A) = m.
    ops: SMatrix<T, N, N>,
    /// D.
    scale: [T; N],
    /// The pivot column of each row, `usize::MAX` while it has none.
    column_of: [usize; N],
}

impl<T: Real, const N: usize> Elimination<T, N> {
    /// Scales the rows in `rows` to a largest entry of 1; a zero row among
    /// them is dependent on its own.
    fn new(a: &SMatrix<T, N, N>, rows: Range<usize>) -> Result<Self, Dependent> {
        let mut m = *a;
        let mut scale = [T::one(); N];
        for i in rows {
            let largest = m.row(i).iter().fold(T::zero(), |x, &y| x.max(abs(y)));
            if largest == T::zero() {
                return Err(Dependent {
                    rows: vec![i],
                    ratio: 0.0,
                });
            }
            scale[i] = T::one() / largest;
            m.row_mut(i).scale_mut(scale[i]);
        }
        Ok(Self {
            m,
            ops: SMatrix::identity(),
            scale,
            column_of: [usize::MAX; N],
        })
    }

    /// One pivot per row of `rows`, the largest entry left each time.
    fn run(&mut self, rows: Range<usize>, tolerance: T) -> Result<(), Dependent> {
        let mut first = T::zero();
        for step in 0..rows.len() {
            let (p, c, size) = largest_entry(&self.m, &self.column_of, rows.clone());
            if step == 0 {
                first = size;
            }
            // A NaN size fails too: it is not above the threshold.
            let above = size > tolerance * first;
            if !above {
                return Err(dependency(
                    &self.ops,
                    &self.column_of,
                    rows,
                    (size / first).to_f64(),
                ));
            }
            self.column_of[p] = c;
            self.pivot(p, c, rows.clone());
        }
        Ok(())
    }

    /// Scales row p to a unit pivot and clears column c from the other rows.
    fn pivot(&mut self, p: usize, c: usize, rows: Range<usize>) {
        let m = &mut self.m;
        let ops = &mut self.ops;
        let inv = T::one() / m[(p, c)];
        m.row_mut(p).scale_mut(inv);
        ops.row_mut(p).scale_mut(inv);
        for r in rows {
            let f = m[(r, c)];
            if r == p || f == T::zero() {
                continue;
            }
            for j in 0..N {
                let mp = m[(p, j)];
                let op = ops[(p, j)];
                m[(r, j)] -= f * mp;
                ops[(r, j)] -= f * op;
            }
        }
    }
}

/// The largest |m[(i, j)]| over the rows and columns not yet used as pivots:
/// (row, column, size). A NaN entry is taken as the largest, so that it fails
/// the tolerance test instead of being skipped.
fn largest_entry<T: Real, const N: usize>(
    m: &SMatrix<T, N, N>,
    column_of: &[usize; N],
    rows: Range<usize>,
) -> (usize, usize, T) {
    let used_column = |c: usize| column_of.contains(&c);
    let mut best = (usize::MAX, usize::MAX, T::zero());
    for i in rows.filter(|&i| column_of[i] == usize::MAX) {
        for j in (0..N).filter(|&j| !used_column(j)) {
            let x = abs(m[(i, j)]);
            // `x != x` holds for NaN alone.
            #[allow(clippy::eq_op)]
            if best.0 == usize::MAX || x > best.2 || x != x {
                best = (i, j, x);
            }
        }
    }
    best
}

/// The rows in the dependencies found: each unused row i now reads
/// Σ_j ops[(i, j)] (D A)_j ≈ 0, so the rows j with a nonzero coefficient are
/// the ones it depends on.
fn dependency<T: Real, const N: usize>(
    ops: &SMatrix<T, N, N>,
    column_of: &[usize; N],
    eliminated: Range<usize>,
    ratio: f64,
) -> Dependent {
    let mut rows = Vec::new();
    for i in eliminated.filter(|&i| column_of[i] == usize::MAX) {
        let largest = ops.row(i).iter().fold(T::zero(), |x, &y| x.max(abs(y)));
        for j in 0..N {
            if abs(ops[(i, j)]) > T::default_epsilon() * largest && !rows.contains(&j) {
                rows.push(j);
            }
        }
    }
    rows.sort_unstable();
    Dependent {
        rows,
        ratio: if ratio.is_finite() { ratio } else { 0.0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    #[test]
    fn inverse_of_a_rotation_with_mixed_row_scales() {
        let th: f64 = 1.3;
        let (s, c) = th.sin_cos();
        // A knife edge's rows: forward speed, turning rate, sideways constraint.
        let a = Matrix3::new(c, s, 0.0, 0.0, 0.0, 1e3, -s, c, 0.0);
        let inv = invert(&a, 1e-12).unwrap();
        assert!((inv * a - Matrix3::identity()).amax() < 1e-15);
    }

    #[test]
    fn names_the_rows_of_a_dependency() {
        // Row 2 = 2 row 0 − row 1 (scaled rows: the dependency survives scaling).
        let a = Matrix3::new(1.0, 2.0, 3.0, 0.0, 1.0, 4.0, 2.0, 3.0, 2.0);
        let d = invert(&a, 1e-12).unwrap_err();
        assert_eq!(d.rows, vec![0, 1, 2]);
        assert!(d.ratio < 1e-14, "{}", d.ratio);
        // A zero row depends on nothing else.
        let z = Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
        assert_eq!(invert(&z, 1e-12).unwrap_err().rows, vec![1]);
        // A row independent of the dependent pair is not named.
        let b = Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 2.0, 2.0);
        assert_eq!(invert(&b, 1e-12).unwrap_err().rows, vec![1, 2]);
    }

    #[test]
    fn nearly_dependent_rows_are_still_inverted_above_the_tolerance() {
        let e: f64 = 1e-9;
        let a = Matrix3::new(1.0, 0.0, 0.0, -1.0, e, 0.0, 0.0, 0.0, 1.0);
        let inv = invert(&a, 1e-12).unwrap();
        assert!((a * inv - Matrix3::identity()).amax() < 1e-7);
        assert!((inv[(1, 0)] - 1.0 / e).abs() < 1e-6 / e);
        assert!(invert(&a, 1e-8).is_err());
    }

    #[test]
    fn partition_of_a_knife_edge_row() {
        // Rows 0, 1 are speeds (ignored); row 2 is the constraint −ẋ + 0 ẏ
        // heading north: ẋ is fixed by it, ẏ and θ̇ are free.
        let a = Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0, 6e-17, 0.0);
        let p = Partition::new(&a, 2..3, 1e-12).unwrap();
        assert_eq!(p.free(), [false, true, true]);
        let z = Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
        assert_eq!(Partition::new(&z, 2..3, 1e-12).err().unwrap().rows, vec![2]);
    }

    #[test]
    fn partition_completes_and_spans_the_null_space() {
        // Two constraint rows (1, 2) on four unknowns, row 0 ignored.
        let a = nalgebra::Matrix4::new(
            9.0, 9.0, 9.0, 9.0, //
            1.0, 2.0, 0.5, -1.0, //
            0.0, 3.0, 1.0, 2.0, //
            0.0, 0.0, 0.0, 0.0,
        );
        let p = Partition::new(&a, 1..3, 1e-12).unwrap();
        let g = a.fixed_rows::<2>(1);
        let w: nalgebra::SMatrix<f64, 4, 2> = p.basis();
        assert!((g * w).amax() < 1e-15);
        assert!(w.rank(1e-12) == 2);
        let r = nalgebra::Vector4::new(0.0, 0.7, -1.1, 0.0);
        let mut x = nalgebra::Vector4::new(0.3, 0.2, -0.4, 0.9);
        let keep = x;
        p.complete(&mut x, &r);
        assert!((g * x - r.fixed_rows::<2>(1)).amax() < 1e-15);
        for j in (0..4).filter(|&j| p.free()[j]) {
            assert_eq!(x[j], keep[j]);
        }
    }

    #[test]
    fn a_nan_entry_is_a_dependency_not_an_inverse() {
        let a = Matrix3::new(1.0, 0.0, 0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0, 1.0);
        assert!(invert(&a, 1e-12).is_err());
    }
}
