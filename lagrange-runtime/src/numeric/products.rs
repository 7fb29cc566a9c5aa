//! Products of small dynamically sized matrices without allocating, for the
//! inner loops that run them thousands of times a solve (the backward pass
//! of DDP: 14 × 7 × 14 products for a seven-joint arm). nalgebra sends a
//! `DMatrix` product to `matrixmultiply`, which packs and allocates per
//! call, and its `gemm_tr` takes one dot product (a horizontal sum) per
//! entry and checks every index. Here A B adds scaled columns of A (vector
//! registers, no horizontal sums); a caller wanting Aᵀ B copies Aᵀ out
//! first.
//!
//! Up to 16 rows, a kernel is compiled for each row count: a column of A is
//! then an array of known length, held whole in vector registers with no
//! index checked inside the loop (in isolation, 2.1–2.7× the general kernel
//! on a seven-joint arm's backward-pass shapes, 1.7–3.5× on a six-joint
//! arm's). More rows go through the general
//! kernel, four rows to a register, 32 at a time.

use crate::numeric::func::mul_add;
use nalgebra::{DMatrix, DVector};

/// c ← α a b + β c (c is not read when β = 0), as c_j = Σ_l b_lj a_l: each
/// step a scaled column of a added to a column of c, which the compiler
/// runs in vector registers (no horizontal sums).
///
/// # Panics
/// If the shapes do not agree (a programming error of the caller).
pub(crate) fn gemm(
    c: &mut DMatrix<f64>,
    alpha: f64,
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    beta: f64,
) {
    let (m, k) = a.shape();
    assert!(
        b.nrows() == k && c.nrows() == m && c.ncols() == b.ncols(),
        "gemm: {}×{} ← {m}×{k} {}×{}",
        c.nrows(),
        c.ncols(),
        b.nrows(),
        b.ncols()
    );
    product(
        c.as_mut_slice(),
        alpha,
        (a.as_slice(), m),
        (b.as_slice(), k),
        beta,
    );
}

/// y ← α a x + β y (y is not read when β = 0).
///
/// # Panics
/// If the shapes do not agree.
pub(crate) fn gemv(
    y: &mut DVector<f64>,
    alpha: f64,
    a: &DMatrix<f64>,
    x: &DVector<f64>,
    beta: f64,
) {
    let (m, k) = a.shape();
    assert!(
        x.len() == k && y.len() == m,
        "gemv: {} ← {m}×{k} {}",
        y.len(),
        x.len()
    );
    product(
        y.as_mut_slice(),
        alpha,
        (a.as_slice(), m),
        (x.as_slice(), k),
        beta,
    );
}

/// c ← α a b + β c in column-major slices: a has m rows, b k; c's columns
/// are as many as b's (c is not read when β = 0). Sent to the kernel of m
/// rows where there is one.
pub(crate) fn product(
    c: &mut [f64],
    alpha: f64,
    (a, m): (&[f64], usize),
    (b, k): (&[f64], usize),
    beta: f64,
) {
    assert!(
        a.len() == m * k && c.len().is_multiple_of(m) && b.len() * m == k * c.len(),
        "product: {} numbers as {m} rows of a, {} numbers with {k} rows of b, {} of c",
        a.len(),
        b.len(),
        c.len()
    );
    if m == 0 || c.is_empty() {
        return;
    }
    if k == 0 {
        // An empty sum: c ← β c.
        let zeros = [0.0; 16];
        c.chunks_mut(16)
            .for_each(|c| write(c, alpha, &zeros[..c.len()], beta));
        return;
    }
    macro_rules! fixed {
        ($($rows:literal)*) => {
            match m {
                $($rows => fixed_rows::<$rows>(c, alpha, a, (b, k), beta),)*
                _ => general(c, alpha, (a, m), (b, k), beta),
            }
        };
    }
    fixed!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16)
}

/// The product for a of M rows: the columns of c J at a time (independent
/// chains of additions, which the processor overlaps), four where a column
/// takes at most two registers, else two.
fn fixed_rows<const M: usize>(
    c: &mut [f64],
    alpha: f64,
    a: &[f64],
    (b, k): (&[f64], usize),
    beta: f64,
) {
    const { assert!(M > 0) };
    let (a, _) = a.as_chunks::<M>();
    let (c, _) = c.as_chunks_mut::<M>();
    let group = if M <= 8 { 4 } else { 2 };
    let mut outs = c.chunks_exact_mut(group);
    let mut xs = b.chunks_exact(group * k);
    for (out, x) in (&mut outs).zip(&mut xs) {
        if M <= 8 {
            fixed_columns::<M, 4>(out, alpha, a, (x, k), beta);
        } else {
            fixed_columns::<M, 2>(out, alpha, a, (x, k), beta);
        }
    }
    let rest = outs.into_remainder().chunks_exact_mut(1);
    for (out, x) in rest.zip(xs.remainder().chunks_exact(k)) {
        fixed_columns::<M, 1>(out, alpha, a, (x, k), beta);
    }
}

/// J columns of c ← α a x_j + β c_j, a's columns M-arrays, x_j the J
/// columns in `x` (k each): the J sums of M rows stay in registers across
/// a's columns, each term one fused multiply–add where the build has FMA.
#[inline(always)]
fn fixed_columns<const M: usize, const J: usize>(
    c: &mut [[f64; M]],
    alpha: f64,
    a: &[[f64; M]],
    (x, k): (&[f64], usize),
    beta: f64,
) {
    let mut acc = [[0.0; M]; J];
    let xs: [&[f64]; J] = std::array::from_fn(|j| &x[j * k..(j + 1) * k]);
    for (l, column) in a.iter().enumerate().take(k) {
        for (sum, x) in acc.iter_mut().zip(&xs) {
            let xl = x[l];
            for i in 0..M {
                sum[i] = mul_add(xl, column[i], sum[i]);
            }
        }
    }
    for (out, sums) in c.iter_mut().zip(&acc) {
        write(out, alpha, sums, beta);
    }
}

/// The product for a of any number of rows (see `columns`).
fn general(c: &mut [f64], alpha: f64, (a, m): (&[f64], usize), (b, k): (&[f64], usize), beta: f64) {
    let n = c.len() / m;
    // Several columns of c at once where the rows are few: their sums are
    // independent chains of additions, which the processor overlaps.
    let group = match m / 4 {
        0..=2 => 4,
        3..=4 => 2,
        _ => 1,
    };
    let mut j = 0;
    while j + group <= n {
        let (out, x) = (&mut c[j * m..(j + group) * m], &b[j * k..(j + group) * k]);
        match group {
            4 => columns::<4>(out, alpha, (a, m), (x, k), beta),
            2 => columns::<2>(out, alpha, (a, m), (x, k), beta),
            _ => columns::<1>(out, alpha, (a, m), (x, k), beta),
        }
        j += group;
    }
    for j in j..n {
        let (out, x) = (&mut c[j * m..(j + 1) * m], &b[j * k..(j + 1) * k]);
        columns::<1>(out, alpha, (a, m), (x, k), beta);
    }
}

/// J columns of c (m rows each, in `out`) ← α a x_j + β c_j, x_j the J
/// columns in `x` (k each). The rows go four to a vector register: up to 32
/// of them by a kernel that knows their count (its sums stay in registers
/// across the columns of a), more 32 at a time; the rows beyond a multiple
/// of four as the last four rows' block (fewer than four rows one by one).
fn columns<const J: usize>(
    out: &mut [f64],
    alpha: f64,
    (a, m): (&[f64], usize),
    (x, k): (&[f64], usize),
    beta: f64,
) {
    let blocked = 4 * (m / 4);
    let mut rows = |first: usize, sums: &[[f64; 4]], count: usize, j: usize| {
        let flat = sums.as_flattened();
        let skip = flat.len() - count;
        write(
            &mut out[j * m + first..j * m + first + count],
            alpha,
            &flat[skip..],
            beta,
        );
    };
    let mut block = |first: usize, blocks: usize| {
        // The sums of `blocks` four-row blocks from row `first`, written.
        macro_rules! run {
            ($b:literal) => {{
                let s = sums::<$b, J>(&a[first..], m, x, k);
                (0..J).for_each(|j| rows(first, &s[j], 4 * $b, j));
            }};
        }
        match blocks {
            1 => run!(1),
            2 => run!(2),
            3 => run!(3),
            4 => run!(4),
            5 => run!(5),
            6 => run!(6),
            7 => run!(7),
            _ => run!(8),
        }
    };
    let mut first = 0;
    while first < blocked {
        let blocks = ((blocked - first) / 4).min(8);
        block(first, blocks);
        first += 4 * blocks;
    }
    let tail = m - blocked;
    if tail > 0 && m >= 4 {
        // The last four rows as one block, overlapping the blocks above;
        // only the rows they left are written.
        let s = sums::<1, J>(&a[m - 4..], m, x, k);
        (0..J).for_each(|j| rows(blocked, &s[j], tail, j));
    } else if tail > 0 {
        for j in 0..J {
            for row in 0..m {
                let xs = &x[j * k..(j + 1) * k];
                let total: f64 = xs
                    .iter()
                    .enumerate()
                    .map(|(l, &xl)| xl * a[l * m + row])
                    .sum();
                rows(row, &[[0.0, 0.0, 0.0, total]], 1, j);
            }
        }
    }
}

/// Σ_l x_jl a[l stride ..][..4 B] for the J columns x_j (k entries each)
/// of `x`, in B four-row blocks per column, held in registers across l;
/// each term one fused multiply–add where the build targets FMA.
fn sums<const B: usize, const J: usize>(
    a: &[f64],
    stride: usize,
    x: &[f64],
    k: usize,
) -> [[[f64; 4]; B]; J] {
    let mut acc = [[[0.0; 4]; B]; J];
    for l in 0..k {
        let (column, _) = a[l * stride..l * stride + 4 * B].as_chunks::<4>();
        for (j, blocks) in acc.iter_mut().enumerate() {
            let xl = x[j * k + l];
            for (sum, rows) in blocks.iter_mut().zip(column) {
                for i in 0..4 {
                    sum[i] = mul_add(xl, rows[i], sum[i]);
                }
            }
        }
    }
    acc
}

/// out ← α sums + β out (out not read when β = 0).
fn write(out: &mut [f64], alpha: f64, sums: &[f64], beta: f64) {
    // One loop per case: no branch inside the loop (β = 1 is the usual
    // accumulation).
    let pairs = out.iter_mut().zip(sums);
    if beta == 0.0 {
        pairs.for_each(|(o, s)| *o = alpha * s);
    } else if beta == 1.0 {
        pairs.for_each(|(o, s)| *o += alpha * s);
    } else {
        pairs.for_each(|(o, s)| *o = beta * *o + alpha * s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against nalgebra's own products, on shapes with and without a tail
    /// of fewer than four rows, every row count of a fixed kernel and past
    /// them, past the 32 rows of the general kernel's blocks, β
    /// zero, one and neither.
    #[test]
    fn products_agree_with_nalgebras() {
        let listed = [
            (12, 12, 6),
            (7, 3, 5),
            (4, 4, 4),
            (1, 2, 3),
            (14, 14, 14),
            (9, 37, 3),
            (5, 64, 2),
            (8, 5, 9),
            (0, 7, 3),
            (0, 20, 2),
        ];
        // Every row count of a fixed kernel and two past them, with column
        // counts that leave a remainder of each group (four and two).
        let rows = (1..=18).flat_map(|m| [(7, m, 14), (3, m, 5), (1, m, 2)]);
        for (k, m, n) in listed.into_iter().chain(rows) {
            let a = DMatrix::from_fn(m, k, |i, j| {
                ((i * 7 + j * 3) % 11) as f64 - 5.0 + 0.1 * i as f64
            });
            let b = DMatrix::from_fn(k, n, |i, j| ((i * 5 + j * 2) % 13) as f64 * 0.3 - 1.0);
            let c0 = DMatrix::from_fn(m, n, |i, j| (i + 2 * j) as f64 * 0.25);
            let close =
                |x: &DMatrix<f64>, y: &DMatrix<f64>| (x - y).amax() <= 1e-12 * (1.0 + y.amax());
            let mut c = c0.clone();
            gemm(&mut c, 1.5, &a, &b, -0.5);
            assert!(close(&c, &(&a * &b * 1.5 - &c0 * 0.5)), "{k} {m} {n}");
            let mut fresh = DMatrix::from_element(m, n, f64::NAN);
            gemm(&mut fresh, 1.0, &a, &b, 0.0);
            assert!(close(&fresh, &(&a * &b)));
            let mut y = c0.column(0).into_owned();
            gemv(&mut y, -1.0, &a, &b.column(1).into_owned(), 1.0);
            let expected = c0.column(0) - &a * b.column(1);
            assert!((&y - &expected).amax() <= 1e-12 * (1.0 + expected.amax()));
        }
    }
}
