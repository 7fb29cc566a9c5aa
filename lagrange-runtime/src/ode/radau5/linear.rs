//! The linear algebra of a RADAU5 step for M = I, as in `radau5.f`: the
//! Jacobian, the factorisation of the two iteration matrices (DECOMR/DECOMC),
//! the solution for the Newton corrections (SLVRAD) and the filtered error
//! estimate (ESTRAD), on a workspace sized once per run.

// Index loops mirror the formulas of radau5.f, component by component.
#![allow(clippy::needless_range_loop)]

use super::Constants;
use crate::error::Error;
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::numeric::lu::{lu_factor, lu_solve};
use crate::ode::{Pair, SecondOrder, Stats};
use nalgebra::{DMatrix, SVector};

/// Everything a run needs, sized once.
pub(super) struct Work<T: Real> {
    pub n: usize,
    pub jac: DMatrix<T>,
    pub e1: DMatrix<T>,
    pub e2: DMatrix<T>,
    pub ip1: Vec<usize>,
    pub ip2: Vec<usize>,
    pub z: [Vec<T>; 3],
    pub f: [Vec<T>; 3],
    /// Solution of the complex system, real and imaginary parts stacked.
    pub c2: Vec<T>,
    pub cont: [Vec<T>; 3],
    pub scal: Vec<T>,
    pub tmp: Vec<T>,
}

impl<T: Real> Work<T> {
    /// The workspace for a system of dimension n = 2N.
    pub fn new(n: usize) -> Self {
        let nv = || vec![T::zero(); n];
        Self {
            n,
            jac: DMatrix::zeros(n, n),
            e1: DMatrix::zeros(n, n),
            e2: DMatrix::zeros(2 * n, 2 * n),
            ip1: vec![0; n],
            ip2: vec![0; 2 * n],
            z: [nv(), nv(), nv()],
            f: [nv(), nv(), nv()],
            c2: vec![T::zero(); 2 * n],
            cont: [nv(), nv(), nv()],
            scal: nv(),
            tmp: nv(),
        }
    }
}

pub(super) fn to_pair<T: Real, const N: usize, const Q: usize>(y: &[T]) -> Pair<T, N, Q> {
    Pair::new(
        SVector::from_fn(|i, _| y[i]),
        SVector::from_fn(|i, _| y[Q + i]),
    )
}

/// ẏ = (q̇, a) at (t, y) into `out`, counting one evaluation.
pub(super) fn rhs_into<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    t: T,
    y: &[T],
    out: &mut [T],
    evaluations: &mut usize,
) -> Result<(), Error> {
    *evaluations += 1;
    let p = to_pair::<T, N, Q>(y);
    let a = rhs.acceleration(t, &p.q, &p.v)?;
    out[..Q].copy_from_slice(rhs.rate(&p.q, &p.v).as_slice());
    out[Q..Q + N].copy_from_slice(a.as_slice());
    Ok(())
}

/// J = ∂(q̇, a)/∂(q, v) at (t, y); `f0` = (q̇, a) there.
pub(super) fn jacobian<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    t: T,
    y: &[T],
    f0: &[T],
    jac: &mut DMatrix<T>,
    stats: &mut Stats,
) -> Result<(), Error> {
    jac.fill(T::zero());
    let p = to_pair::<T, N, Q>(y);
    rate_rows(rhs, &p, jac);
    if let Some(blocks) = rhs.jacobian(t, &p.q, &p.v) {
        let (aq, av) = blocks?;
        jac.view_mut((Q, 0), (N, Q)).copy_from(&aq);
        jac.view_mut((Q, Q), (N, N)).copy_from(&av);
        return Ok(());
    }
    let eps = T::default_epsilon();
    for col in 0..Q + N {
        let mut pp = p;
        let x = if col < Q {
            &mut pp.q[col]
        } else {
            &mut pp.v[col - Q]
        };
        let delta = sqrt(eps * T::lit(1e-5).max(abs(*x)));
        *x += delta;
        stats.evaluations += 1;
        let a = rhs.acceleration(t, &pp.q, &pp.v)?;
        for i in 0..N {
            jac[(Q + i, col)] = (a[i] - f0[Q + i]) / delta;
        }
    }
    Ok(())
}

/// The rows of q̇ = rate(q, v): the identity on v for ordinary coordinates;
/// a quaternion's rate is bilinear in (q, ω), so unit differences are its
/// exact derivatives.
fn rate_rows<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    p: &Pair<T, N, Q>,
    jac: &mut DMatrix<T>,
) {
    if F::ORIENTATIONS.is_empty() {
        for i in 0..N {
            jac[(i, Q + i)] = T::one();
        }
        return;
    }
    let r0 = rhs.rate(&p.q, &p.v);
    for col in 0..Q + N {
        let mut pp = *p;
        if col < Q {
            pp.q[col] += T::one();
        } else {
            pp.v[col - Q] += T::one();
        }
        let r = rhs.rate(&pp.q, &pp.v) - r0;
        for i in 0..Q {
            jac[(i, col)] = r[i];
        }
    }
}

/// Builds and factorises E1 = fac1·I − J and the real form of
/// E2 = (α + iβ)/h·I − J. False if either is singular.
pub(super) fn decompose<T: Real>(w: &mut Work<T>, fac1: T, alphn: T, betan: T) -> bool {
    let n = w.n;
    for i in 0..n {
        for j in 0..n {
            let d = if i == j { T::one() } else { T::zero() };
            let jij = w.jac[(i, j)];
            w.e1[(i, j)] = fac1 * d - jij;
            let re = alphn * d - jij;
            w.e2[(i, j)] = re;
            w.e2[(n + i, n + j)] = re;
            w.e2[(i, n + j)] = -betan * d;
            w.e2[(n + i, j)] = betan * d;
        }
    }
    lu_factor(&mut w.e1, &mut w.ip1).is_ok() && lu_factor(&mut w.e2, &mut w.ip2).is_ok()
}

/// radau5.f's SLVRAD for M = I: the Newton corrections of the transformed
/// stages, in place in z.
pub(super) fn solve_stages<T: Real>(w: &mut Work<T>, fac1: T, alphn: T, betan: T) {
    let n = w.n;
    for i in 0..n {
        let s2 = -w.f[1][i];
        let s3 = -w.f[2][i];
        w.z[0][i] -= w.f[0][i] * fac1;
        w.z[1][i] += s2 * alphn - s3 * betan;
        w.z[2][i] += s3 * alphn + s2 * betan;
    }
    lu_solve(&w.e1, &w.ip1, &mut w.z[0]);
    for i in 0..n {
        w.c2[i] = w.z[1][i];
        w.c2[n + i] = w.z[2][i];
    }
    lu_solve(&w.e2, &w.ip2, &mut w.c2);
    for i in 0..n {
        w.z[1][i] = w.c2[i];
        w.z[2][i] = w.c2[n + i];
    }
}

/// radau5.f's ESTRAD for M = I: the embedded error filtered by (γ₀/h − J)⁻¹,
/// with one more filtered evaluation at the first step and after a rejection if
/// the estimate is ≥ 1.
#[allow(clippy::too_many_arguments)]
pub(super) fn estimate<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
    rhs: &F,
    k: &Constants<T>,
    w: &mut Work<T>,
    t: T,
    h: T,
    y: &[T],
    y0: &[T],
    again: bool,
    stats: &mut Stats,
) -> Result<T, Error> {
    let n = w.n;
    let hee = k.dd.map(|d| d / h);
    // f[1] holds the combination F2 of the Fortran code; tmp the filtered error.
    for i in 0..n {
        w.f[1][i] = hee[0] * w.z[0][i] + hee[1] * w.z[1][i] + hee[2] * w.z[2][i];
        w.tmp[i] = w.f[1][i] + y0[i];
    }
    lu_solve(&w.e1, &w.ip1, &mut w.tmp);
    let norm = |e: &[T], scal: &[T]| {
        let mut s = T::zero();
        for i in 0..n {
            let r = e[i] / scal[i];
            s += r * r;
        }
        sqrt(s / T::lit(n as f64)).max(T::lit(1e-10))
    };
    let mut err = norm(&w.tmp, &w.scal);
    if err >= T::one() && again {
        for i in 0..n {
            w.tmp[i] += y[i];
        }
        let tmp = &w.tmp;
        let f0 = &mut w.f[0];
        rhs_into::<T, N, Q, F>(rhs, t, tmp, f0, &mut stats.evaluations)?;
        for i in 0..n {
            w.tmp[i] = w.f[0][i] + w.f[1][i];
        }
        lu_solve(&w.e1, &w.ip1, &mut w.tmp);
        err = norm(&w.tmp, &w.scal);
    }
    Ok(err)
}
