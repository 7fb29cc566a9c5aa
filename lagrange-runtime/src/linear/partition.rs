//! The split of a constrained system's coordinates and speeds into
//! independent and dependent ones, and the embeddings of the independent
//! variations into the full ones.

use super::Linearizer;
use super::dense::{condition, pivot_columns};
use super::errors::redundant;
use crate::error::{Error, LinearError};
use crate::numeric::Real;
use crate::system::Constrained;
use nalgebra::{DMatrix, DVector, SVector};

/// Independent and dependent coordinate and speed indices.
#[derive(Clone, Debug)]
pub(super) struct Partition {
    pub ci: Vec<usize>,
    pub cd: Vec<usize>,
    pub si: Vec<usize>,
    pub sd: Vec<usize>,
}

impl Linearizer {
    /// The independent/dependent split of the coordinates and speeds at G,
    /// whose N columns are the directions `coordinates` names (without
    /// orientations the coordinates; with them, the tangent directions) and
    /// whose rates `speeds` names (the velocities).
    pub(super) fn partition<S, T, const N: usize, const K: usize, const Q: usize>(
        &self,
        g: &DMatrix<f64>,
        (q, t): (&SVector<T, Q>, T),
        names: [&[&str]; 2],
    ) -> Result<Partition, Error>
    where
        S: Constrained<T, N, K, Q>,
        T: Real,
    {
        let h = holonomic::<S, T, N, K, Q>();
        self.split(g, h, names, |ratio, rows| {
            redundant::<S, T, N, K, Q>(t, q, ratio, rows)
        })
    }

    /// [`partition`](Self::partition) for constraint rows G (K × N, the
    /// first `h` holonomic) of any form; `redundant` makes the error naming
    /// dependent rows from the pivoting's ratio and their indices.
    pub(super) fn split(
        &self,
        g: &DMatrix<f64>,
        h: usize,
        [coordinates, speeds]: [&[&str]; 2],
        redundant: impl Fn(f64, Vec<usize>) -> Error,
    ) -> Result<Partition, Error> {
        let n = g.ncols();
        let k = g.nrows();
        let tol = self.tolerances.redundant;
        let phi_q = g.rows(0, h).into_owned();
        let named_c = match &self.coordinates {
            Some(names) => indices("coordinates", names, n - h, coordinates)?,
            None => Vec::new(),
        };
        let named_s = match &self.speeds {
            Some(names) => indices("speeds", names, n.saturating_sub(k), speeds)?,
            None => Vec::new(),
        };
        // Named speeds are kept independent as coordinates too where the
        // constraints allow, so that they stay rates of independent coordinates.
        let mut keep = named_c.clone();
        keep.extend(named_s.iter().filter(|i| !named_c.contains(i)));
        let complement = |named: &[usize]| (0..n).filter(|i| !named.contains(i)).collect();
        // All named: nothing to choose (the checks below still judge the
        // choice, and a singular one is the user's, not redundancy).
        let all_c = self.coordinates.is_some() && named_c.len() == n - h;
        let all_s = self.speeds.is_some() && named_s.len() == n.saturating_sub(k);
        let (mut ci, mut cd, mut ratio) = if all_c {
            (named_c.clone(), complement(&named_c), 1.0)
        } else {
            complete_coordinates(&phi_q, &named_c, &keep, n - h)
        };
        if h > 0 && !(ratio >= tol) && keep.len() > named_c.len() {
            (ci, cd, ratio) = complete_coordinates(&phi_q, &named_c, &named_c, n - h);
        }
        if h > 0 && !(ratio >= tol) && !all_c {
            let (_, null) = condition(&phi_q.transpose());
            return Err(redundant(ratio, big_entries(&null)));
        }
        check_square("coordinates", &phi_q, &cd, tol, coordinates)?;
        if let Some(&i) = named_s.iter().find(|i| cd.contains(i)) {
            return Err(LinearError::InvalidPartition {
                what: "speeds",
                reason: format!(
                    "`{}` is the rate of a dependent coordinate here; name it among the \
                     independent coordinates too",
                    speeds[i]
                ),
            }
            .into());
        }
        let (si, sd, ratio) = if all_s {
            (named_s.clone(), complement(&named_s), 1.0)
        } else {
            complete_speeds(g, h, &ci, &cd, &named_s)
        };
        if k > h && !(ratio >= tol) && !all_s {
            let (_, null) = condition(&g.rows(h, k - h).transpose());
            let rows = big_entries(&null).iter().map(|r| r + h).collect();
            return Err(redundant(ratio, rows));
        }
        check_square("speeds", g, &sd, tol, speeds)?;
        Ok(Partition { ci, cd, si, sd })
    }
}

/// The independent coordinates: the `named` ones in their order, then as many
/// more as `count` needs, in coordinate order; the dependent ones are the
/// columns of Φ_q outside `keep` (the named coordinates and speeds) chosen by
/// QR with column pivoting, so the user names only the coordinates of
/// interest. Returns (independent, dependent sorted, the pivoting's ratio).
pub(super) fn complete_coordinates(
    phi_q: &DMatrix<f64>,
    named: &[usize],
    keep: &[usize],
    count: usize,
) -> (Vec<usize>, Vec<usize>, f64) {
    let n = phi_q.ncols();
    let free: Vec<usize> = (0..n).filter(|i| !keep.contains(i)).collect();
    let (picked, ratio) = pivot_columns(&phi_q.select_columns(free.iter()), n - count);
    let mut cd: Vec<usize> = picked.iter().map(|&j| free[j]).collect();
    cd.sort_unstable();
    let mut ci = named.to_vec();
    ci.extend((0..n).filter(|i| !cd.contains(i) && !named.contains(i)));
    (ci, cd, ratio)
}

/// The independent speeds: the `named` ones, then the rest chosen as
/// [`Linearizer`] describes (the rates of the dependent coordinates are
/// dependent, and pivoting on the nonholonomic rows restricted to the
/// holonomic motions picks the other dependent speeds among the unnamed
/// independent coordinates). Returns (independent, dependent sorted, the
/// pivoting's ratio).
fn complete_speeds(
    g: &DMatrix<f64>,
    h: usize,
    ci: &[usize],
    cd: &[usize],
    named: &[usize],
) -> (Vec<usize>, Vec<usize>, f64) {
    let k = g.nrows();
    let phi_q = g.rows(0, h);
    let nh = g.rows(h, k - h);
    // The nonholonomic rows on the holonomic motions, A_i − A_d Φ_{q_d}⁻¹ Φ_{q_i}.
    let e = if h > 0 {
        let (phi_d, phi_i) = (
            phi_q.select_columns(cd.iter()),
            phi_q.select_columns(ci.iter()),
        );
        let x = phi_d
            .lu()
            .solve(&phi_i)
            .unwrap_or_else(|| DMatrix::from_element(phi_i.nrows(), phi_i.ncols(), f64::NAN));
        nh.select_columns(ci.iter()) - nh.select_columns(cd.iter()) * x
    } else {
        nh.select_columns(ci.iter())
    };
    let free: Vec<usize> = (0..ci.len()).filter(|&j| !named.contains(&ci[j])).collect();
    let (chosen, ratio) = pivot_columns(&e.select_columns(free.iter()), k - h);
    let mut sd = cd.to_vec();
    sd.extend(chosen.iter().map(|&j| ci[free[j]]));
    sd.sort_unstable();
    let mut si = named.to_vec();
    si.extend(ci.iter().filter(|i| !sd.contains(i) && !named.contains(i)));
    (si, sd, ratio)
}

/// C_q (N × n_i), C_v (N × n_s) and C_vq (N × n_i): δq = C_q δq_i and
/// δq̇ = C_v δq̇_s + C_vq δq_i on the linearised constraints.
pub(super) fn embeddings(
    part: &Partition,
    g: &DMatrix<f64>,
    dvel: &DMatrix<f64>,
    h: usize,
) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let n = g.ncols();
    let ni = part.ci.len();
    let ns = part.si.len();
    let mut cq = DMatrix::zeros(n, ni);
    for (k, &i) in part.ci.iter().enumerate() {
        cq[(i, k)] = 1.0;
    }
    if h > 0 {
        let phi_q = g.rows(0, h);
        let lu = phi_q.select_columns(part.cd.iter()).lu();
        let x = lu
            .solve(&-phi_q.select_columns(part.ci.iter()))
            .unwrap_or_else(|| DMatrix::from_element(h, ni, f64::NAN));
        for (k, &i) in part.cd.iter().enumerate() {
            cq.row_mut(i).copy_from(&x.row(k));
        }
    }
    let mut cv = DMatrix::zeros(n, ns);
    let mut cvq = DMatrix::zeros(n, ni);
    for (k, &i) in part.si.iter().enumerate() {
        cv[(i, k)] = 1.0;
    }
    if !part.sd.is_empty() {
        let lu = g.select_columns(part.sd.iter()).lu();
        let nan = |r, c| DMatrix::from_element(r, c, f64::NAN);
        let kd = part.sd.len();
        let xs = lu
            .solve(&-g.select_columns(part.si.iter()))
            .unwrap_or_else(|| nan(kd, ns));
        let xq = lu.solve(&-(dvel * &cq)).unwrap_or_else(|| nan(kd, ni));
        for (k, &i) in part.sd.iter().enumerate() {
            cv.row_mut(i).copy_from(&xs.row(k));
            cvq.row_mut(i).copy_from(&xq.row(k));
        }
    }
    (cq, cv, cvq)
}

/// Indices in `known` of the given names, checked: known, distinct, at most
/// `count` of them.
pub(super) fn indices(
    what: &'static str,
    names: &[String],
    count: usize,
    known: &[&str],
) -> Result<Vec<usize>, Error> {
    let bad = |reason: String| Error::from(LinearError::InvalidPartition { what, reason });
    if names.len() > count {
        return Err(bad(format!(
            "at most {count} (the degrees of freedom left by the constraints), got {} \
             ({names:?}); name only the ones of interest and the rest are chosen",
            names.len()
        )));
    }
    let mut out = Vec::with_capacity(count);
    for name in names {
        let i = known.iter().position(|c| c == name).ok_or_else(|| {
            bad(format!(
                "no coordinate `{name}`; the names of the {what} are {known:?}"
            ))
        })?;
        if out.contains(&i) {
            return Err(bad(format!("`{name}` named twice")));
        }
        out.push(i);
    }
    Ok(out)
}

/// Checks that the columns `dependent` of `full` form a square matrix whose
/// smallest singular value is at least `tol` times the largest singular value of
/// `full` (relative to the whole Jacobian, so that a 1 × 1 block is judged too).
/// `known` names the columns.
fn check_square(
    what: &'static str,
    full: &DMatrix<f64>,
    dependent: &[usize],
    tol: f64,
    known: &[&str],
) -> Result<(), Error> {
    let m = full.select_columns(dependent.iter());
    let ratio = if m.is_empty() {
        1.0
    } else {
        let big = full.clone().singular_values().max();
        let small = m.clone().singular_values().min();
        if big > 0.0 { small / big } else { 0.0 }
    };
    if m.nrows() == m.ncols() && ratio >= tol {
        return Ok(());
    }
    Err(LinearError::SingularPartition {
        what,
        dependent: dependent.iter().map(|&i| known[i].to_string()).collect(),
        ratio,
    }
    .into())
}

pub(super) fn big_entries(x: &DVector<f64>) -> Vec<usize> {
    let big = x.amax();
    (0..x.len()).filter(|&i| x[i].abs() > 0.1 * big).collect()
}

pub(super) fn holonomic<S, T, const N: usize, const K: usize, const Q: usize>() -> usize
where
    S: Constrained<T, N, K, Q>,
    T: Real,
{
    S::HOLONOMIC.min(K)
}
