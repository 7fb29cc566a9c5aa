//! A link's `<inertia>` that is no rigid body's: refused with the link, file
//! and line (the default), made the nearest physical inertia
//! (`inertia = repair`), or used as written (`inertia = as_written`).
//!
//! A rigid body's inertia has principal moments (a, b, c) with each at most
//! the sum of the other two (which makes them non-negative): the second-moment
//! matrix tr(I)/2·E − I is positive semidefinite. That set is closed, convex
//! and depends on the eigenvalues alone, so its nearest point in the Frobenius
//! norm keeps the principal axes and moves the moments to their Euclidean
//! projection onto the cone {a ≤ b + c, b ≤ c + a, c ≤ a + b}.

use super::model::{Number, ReadError, Robot};
use super::options::InertiaRule;

/// A repaired inertia: the link, the entries (ixx, iyy, izz, ixy, ixz, iyz)
/// as written and as used.
pub type Repaired = (String, [f64; 6], [f64; 6]);

/// Applies `rule` to every link's inertia; with `Repair`, the changed links.
pub fn apply(robot: &mut Robot, rule: InertiaRule) -> Result<Vec<Repaired>, ReadError> {
    let mut repaired = Vec::new();
    for link in &mut robot.links {
        let Some(inertial) = &mut link.inertial else {
            continue;
        };
        let written = inertial.inertia.clone().map(|n| n.value);
        if is_physical(&written) || rule == InertiaRule::AsWritten {
            continue;
        }
        if rule == InertiaRule::Check {
            return Err(ReadError {
                line: inertial.line,
                message: refusal(&link.name, &written),
            });
        }
        let near = nearest(&written);
        inertial.inertia = near.map(|value| Number {
            text: format!("{value:?}"),
            value,
        });
        repaired.push((link.name.clone(), written, near));
    }
    Ok(repaired)
}

/// Non-negative moments and a positive semidefinite second-moment matrix, to
/// the round-off the description's own inertias are allowed.
pub fn is_physical(i: &[f64; 6]) -> bool {
    i[..3].iter().all(|&m| m >= 0.0) && crate::mat3::second_moments_psd(i, 1e-12)
}

fn refusal(link: &str, i: &[f64; 6]) -> String {
    let names = ["ixx", "iyy", "izz"];
    let what = match (0..3).find(|&k| i[k] < 0.0) {
        Some(k) => format!(
            "<inertia {}='{}'> is negative: a moment of inertia is ∫ r² dm about an axis",
            names[k], i[k]
        ),
        None => "<inertia> is that of no rigid body: a principal moment exceeds the sum of the \
                 other two, or the products are too large (tr(I)/2·E − I must be positive \
                 semidefinite; URDF's ixy, ixz, iyz are the tensor's entries, −∫xy dm)"
            .to_string(),
    };
    format!(
        "link `{link}`: {what}. To load the file as it is (a placeholder or rounded inertia), \
         write `urdf(\"..\", inertia = repair)` for the nearest physical inertia (listed in \
         `URDF_REPAIRED`), or `inertia = as_written` to use it unchecked"
    )
}

/// The physical inertia nearest `i` (entries ixx, iyy, izz, ixy, ixz, iyz):
/// the principal axes kept, the moments projected onto the triangle cone.
pub fn nearest(i: &[f64; 6]) -> [f64; 6] {
    let [xx, yy, zz, xy, xz, yz] = *i;
    let (moments, axes) = symmetric_eigen([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]);
    let p = project_moments(moments);
    let entry = |a: usize, b: usize| (0..3).map(|k| axes[a][k] * p[k] * axes[b][k]).sum::<f64>();
    [
        entry(0, 0),
        entry(1, 1),
        entry(2, 2),
        entry(0, 1),
        entry(0, 2),
        entry(1, 2),
    ]
}

/// The Euclidean projection of (a, b, c) onto {each ≤ the sum of the other
/// two}: the nearest of the candidates on the cone's faces (the point itself,
/// its projection on each plane a = b + c, on each edge ray (1, 1, 0), and
/// the origin) that lie in the cone; the nearest feasible one is the
/// projection, as the projection lies in some face's relative interior.
pub fn project_moments(m: [f64; 3]) -> [f64; 3] {
    let inside = |p: &[f64; 3]| (0..3).all(|k| p[k] <= p[(k + 1) % 3] + p[(k + 2) % 3]);
    let mut candidates = vec![m, [0.0; 3]];
    for k in 0..3 {
        // The plane p_k = p_j + p_l, normal e_k − e_j − e_l.
        let d = (m[k] - m[(k + 1) % 3] - m[(k + 2) % 3]) / 3.0;
        let mut p = m.map(|x| x + d);
        p[k] = m[k] - d;
        candidates.push(p);
        // The ray where p_k = 0 and the other two are equal.
        let t = ((m[(k + 1) % 3] + m[(k + 2) % 3]) / 2.0).max(0.0);
        let mut r = [t; 3];
        r[k] = 0.0;
        candidates.push(r);
    }
    let distance = |p: &[f64; 3]| (0..3).map(|k| (p[k] - m[k]).powi(2)).sum::<f64>();
    candidates
        .into_iter()
        .filter(|p| inside(p))
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
        .unwrap_or([0.0; 3])
}

/// Eigenvalues and eigenvectors (the columns of the second matrix) of a
/// symmetric 3 × 3 matrix, by cyclic Jacobi rotations.
fn symmetric_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        let scale = (0..3).map(|k| a[k][k].powi(2)).sum::<f64>();
        if off <= 1e-32 * scale || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t / (t * t + 1.0).sqrt();
            for row in &mut a {
                let akp = row[p];
                let akq = row[q];
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let rp = a[p];
            let rq = a[q];
            a[p] = [0, 1, 2].map(|k| c * rp[k] - s * rq[k]);
            a[q] = [0, 1, 2].map(|k| s * rp[k] + c * rq[k]);
            for row in &mut v {
                let vp = row[p];
                let vq = row[q];
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (1, 1, 3) violates c ≤ a + b by 1: its projection onto the plane
    /// c = a + b moves it by 1/3 along (1, 1, −1), to (4/3, 4/3, 8/3).
    #[test]
    fn moments_project_onto_the_nearest_face() {
        let p = project_moments([1.0, 1.0, 3.0]);
        let want = [4.0 / 3.0, 4.0 / 3.0, 8.0 / 3.0];
        assert!((0..3).all(|k| (p[k] - want[k]).abs() < 1e-15), "{p:?}");
        assert_eq!(project_moments([1.0, 2.0, 2.5]), [1.0, 2.0, 2.5]);
        // (−1, 1, 1): the plane b = c + a gives (−2/3, 2/3, 4/3), outside
        // the cone; the nearest point is on the edge (0, t, t), t = 1.
        assert_eq!(project_moments([-1.0, 1.0, 1.0]), [0.0, 1.0, 1.0]);
        assert_eq!(project_moments([-1.0, -1.0, -1.0]), [0.0; 3]);
    }

    /// A tensor with products keeps its principal axes: the repaired tensor
    /// turned back into them is (4/3, 4/3, 8/3) for moments (1, 1, 3).
    #[test]
    fn a_rotated_tensor_keeps_its_axes() {
        // Moments 1 and 3 on the axes (1, 1)/√2 and (1, −1)/√2 of the xy
        // plane, [[2, -1], [-1, 2]], and izz = 1.
        let i = [2.0, 2.0, 1.0, -1.0, 0.0, 0.0];
        assert!(!is_physical(&i));
        let r = nearest(&i);
        // Moments (1, 3, 1) → (4/3, 8/3, 4/3) on the same axes: in the xy
        // plane [[2, -2/3], [-2/3, 2]], izz = 4/3.
        let want = [2.0, 2.0, 4.0 / 3.0, -2.0 / 3.0, 0.0, 0.0];
        assert!((0..6).all(|k| (r[k] - want[k]).abs() < 1e-14), "{r:?}");
        assert!(is_physical(&r));
    }
}
