//! Physical consistency of inertial parameters: a body's ten parameters are
//! those of a real mass distribution exactly when its 4 × 4 pseudo-inertia
//! J = [[Σ, h], [hᵀ, m]] is positive definite, Σ = ∫ r rᵀ dm = ½ tr(I) 𝟙 − I
//! (Wensing, Kim and Slotine 2017): m > 0, and I satisfies the triangle
//! inequalities with room for the first moment h = m c. The log-Cholesky
//! parametrisation J = U Uᵀ (Rucker and Wensing 2022) maps every θ ∈ ℝ¹⁰
//! onto such a J, smoothly and one to one. A joint's damping, armature and
//! friction are physical when positive, and are written e^θ.

use nalgebra::{DMatrix, DVector, Matrix3, Matrix4};

use crate::error::IdentifyError;

/// One entry of π's layout: a body's ten parameters from `first`, a point
/// mass's one, or a joint's coefficient (named in full, `elbow.damping`).
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Block {
    Body { name: String, first: usize },
    Point { name: String, index: usize },
    Joint { name: String, index: usize },
}

impl Block {
    pub(super) fn name(&self) -> &str {
        match self {
            Block::Body { name, .. } | Block::Point { name, .. } | Block::Joint { name, .. } => {
                name
            }
        }
    }
}

/// The suffixes of a joint's coefficients.
const JOINT: [&str; 3] = ["damping", "armature", "friction"];

/// The body suffixes, in π's order (Pinocchio's).
const BODY: [&str; 10] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// π's blocks from its names: ten consecutive `body.m` … `body.Izz`, a
/// point's `point.m`, or a joint's `q.damping`, `q.armature`, `q.friction`.
///
/// # Errors
/// [`IdentifyError::UnknownParameter`] for a name that fits none.
pub(super) fn layout(names: &[&str]) -> Result<Vec<Block>, IdentifyError> {
    let mut blocks = Vec::new();
    let mut k = 0;
    while k < names.len() {
        let joint = names[k].rsplit_once('.').map(|(_, s)| s);
        if joint.is_some_and(|s| JOINT.contains(&s)) {
            blocks.push(Block::Joint {
                name: names[k].to_string(),
                index: k,
            });
            k += 1;
            continue;
        }
        let Some(prefix) = names[k].strip_suffix(".m") else {
            return Err(IdentifyError::UnknownParameter {
                name: names[k].to_string(),
            });
        };
        let body = names.len() >= k + 10
            && (1..10).all(|j| names[k + j] == format!("{prefix}.{}", BODY[j]));
        if body {
            blocks.push(Block::Body {
                name: prefix.to_string(),
                first: k,
            });
            k += 10;
        } else {
            blocks.push(Block::Point {
                name: prefix.to_string(),
                index: k,
            });
            k += 1;
        }
    }
    Ok(blocks)
}

/// J = [[Σ, h], [hᵀ, m]] of one body's parameters [m, mx, my, mz, Ixx, Ixy,
/// Iyy, Ixz, Iyz, Izz] (inertia about the body's reference point).
pub fn pseudo_inertia(block: &[f64; 10]) -> Matrix4<f64> {
    let [m, hx, hy, hz, ixx, ixy, iyy, ixz, iyz, izz] = *block;
    let inertia = Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz);
    let sigma = Matrix3::identity() * (0.5 * inertia.trace()) - inertia;
    let mut j = Matrix4::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&sigma);
    for (i, h) in [hx, hy, hz].into_iter().enumerate() {
        j[(i, 3)] = h;
        j[(3, i)] = h;
    }
    j[(3, 3)] = m;
    j
}

/// The parameters of a pseudo-inertia, the inverse of [`pseudo_inertia`]:
/// linear, so also the map of a change of J.
fn parameters_of(j: &Matrix4<f64>) -> [f64; 10] {
    let sigma = j.fixed_view::<3, 3>(0, 0);
    let inertia = Matrix3::identity() * sigma.trace() - sigma;
    [
        j[(3, 3)],
        j[(0, 3)],
        j[(1, 3)],
        j[(2, 3)],
        inertia[(0, 0)],
        inertia[(0, 1)],
        inertia[(1, 1)],
        inertia[(0, 2)],
        inertia[(1, 2)],
        inertia[(2, 2)],
    ]
}

/// Whether one body's ten parameters (in π's order) are those of a real
/// body: finite, and its pseudo-inertia positive definite (a Cholesky
/// factorisation exists). A thin rod (inertia of rank two about its centre)
/// lies on the boundary and is refused, as is any inertia that breaks a
/// triangle inequality such as Ixx + Iyy ≥ Izz about the centre of mass.
pub fn is_physically_consistent(block: &[f64; 10]) -> bool {
    block.iter().all(|x| x.is_finite()) && pseudo_inertia(block).cholesky().is_some()
}

/// The bodies (and point masses and joints' coefficients) of π, named by
/// `names` (a system's `Lagrangian::REGRESSOR_PARAMETERS`), whose
/// parameters are not physically consistent: a body by
/// [`is_physically_consistent`], a point mass whose mass is not positive, a
/// joint's damping, armature or friction that is negative (zero is a joint
/// without it). A body whose ten parameters are all zero (a URDF
/// frame without `<inertial>`) is no mass at all and is not listed.
///
/// # Errors
/// [`IdentifyError::Lengths`] when π and `names` differ in length;
/// [`IdentifyError::UnknownParameter`] for a name that is not a body's or a
/// point's parameter.
pub fn inconsistent_bodies(
    names: &[&str],
    pi: &DVector<f64>,
) -> Result<Vec<String>, IdentifyError> {
    if pi.len() != names.len() {
        return Err(IdentifyError::Lengths {
            what: "π",
            got: pi.len(),
            expected: names.len(),
        });
    }
    let blocks = layout(names)?;
    Ok(blocks
        .iter()
        .filter(|block| !block_consistent(block, pi))
        .map(|block| block.name().to_string())
        .collect())
}

fn block_consistent(block: &Block, pi: &DVector<f64>) -> bool {
    match *block {
        Block::Body { first, .. } => {
            let block = ten(pi, first);
            block.iter().all(|&x| x == 0.0) || is_physically_consistent(&block)
        }
        Block::Point { index, .. } => pi[index].is_finite() && pi[index] > 0.0,
        Block::Joint { index, .. } => pi[index].is_finite() && pi[index] >= 0.0,
    }
}

fn ten(pi: &DVector<f64>, first: usize) -> [f64; 10] {
    std::array::from_fn(|k| pi[first + k])
}

/// U = e^α [[e^d1, s12, s13, t1], [0, e^d2, s23, t2], [0, 0, e^d3, t3],
/// [0, 0, 0, 1]] of θ = (α, d1, d2, d3, s12, s23, s13, t1, t2, t3).
fn factor(theta: &[f64]) -> Matrix4<f64> {
    let [alpha, d1, d2, d3, s12, s23, s13, t1, t2, t3] = std::array::from_fn(|k| theta[k]);
    #[rustfmt::skip]
    let u = Matrix4::new(
        d1.exp(), s12, s13, t1,
        0.0, d2.exp(), s23, t2,
        0.0, 0.0, d3.exp(), t3,
        0.0, 0.0, 0.0, 1.0,
    );
    u * alpha.exp()
}

/// Each of θ's entries' position in U (α scales all of U).
const ENTRIES: [(usize, usize); 9] = [
    (0, 0),
    (1, 1),
    (2, 2),
    (0, 1),
    (1, 2),
    (0, 2),
    (0, 3),
    (1, 3),
    (2, 3),
];

/// θ of a positive definite J: U from the Cholesky factor of J with its
/// rows and columns reversed (J = U Uᵀ with U upper triangular), `None`
/// unless J is positive definite.
fn theta_of_pseudo_inertia(j: &Matrix4<f64>) -> Option<[f64; 10]> {
    let reverse = Matrix4::from_fn(|r, c| if r + c == 3 { 1.0 } else { 0.0 });
    let l = (reverse * j * reverse).cholesky()?.l();
    let u = reverse * l * reverse;
    let scale = u[(3, 3)];
    let mut theta = [scale.ln(), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for (k, &(r, c)) in ENTRIES.iter().enumerate() {
        let x = u[(r, c)] / scale;
        theta[k + 1] = if r == c { x.ln() } else { x };
    }
    Some(theta)
}

/// The parametrisation θ ↦ π over a whole π: each body's log-Cholesky
/// block, each point mass m = e^θ and each joint's coefficient e^θ (so its
/// start must be positive: a joint whose coefficient is truly zero should
/// not have it in the model). A body whose ten parameters are all zero
/// in the π it starts from (a URDF frame without `<inertial>`, such as a
/// tool frame) is no body to estimate: it stays massless, its θ unused.
pub(super) struct Parametrisation {
    blocks: Vec<Block>,
    massless: Vec<bool>,
    len: usize,
}

impl Parametrisation {
    /// The parametrisation of π's layout, and θ of `pi`, physically
    /// consistent but for massless bodies.
    ///
    /// # Errors
    /// [`IdentifyError::Inconsistent`] naming the first body of `pi` that
    /// is not physically consistent (`what` names `pi`);
    /// [`IdentifyError::UnknownParameter`] for a name that is not a body's
    /// or a point's parameter.
    pub(super) fn at(
        names: &[&str],
        pi: &DVector<f64>,
        what: &'static str,
    ) -> Result<(Self, DVector<f64>), IdentifyError> {
        let blocks = layout(names)?;
        let mut theta = DVector::zeros(names.len());
        let mut massless = vec![false; blocks.len()];
        for (b, block) in blocks.iter().enumerate() {
            let inconsistent = || IdentifyError::Inconsistent {
                what,
                body: block.name().to_string(),
            };
            match *block {
                Block::Body { first, .. } if (0..10).all(|k| pi[first + k] == 0.0) => {
                    massless[b] = true;
                }
                Block::Body { first, .. } => {
                    let t = theta_of_pseudo_inertia(&pseudo_inertia(&ten(pi, first)))
                        .filter(|t| t.iter().all(|x| x.is_finite()))
                        .ok_or_else(inconsistent)?;
                    theta.rows_mut(first, 10).copy_from_slice(&t);
                }
                Block::Point { index, .. } | Block::Joint { index, .. }
                    if pi[index] > 0.0 && pi[index].is_finite() =>
                {
                    theta[index] = pi[index].ln();
                }
                Block::Point { .. } | Block::Joint { .. } => return Err(inconsistent()),
            }
        }
        let parametrisation = Parametrisation {
            blocks,
            massless,
            len: names.len(),
        };
        Ok((parametrisation, theta))
    }

    /// π(θ) and ∂π/∂θ (block diagonal), by the chain rule through
    /// J = U Uᵀ: ∂J = ∂U Uᵀ + U ∂Uᵀ, and π is linear in J.
    pub(super) fn pi_and_jacobian(&self, theta: &DVector<f64>) -> (DVector<f64>, DMatrix<f64>) {
        let mut pi = DVector::zeros(self.len);
        let mut jac = DMatrix::zeros(self.len, self.len);
        for (block, &massless) in self.blocks.iter().zip(&self.massless) {
            match *block {
                Block::Body { .. } if massless => {}
                Block::Body { first, .. } => {
                    let t = &theta.as_slice()[first..first + 10];
                    let u = factor(t);
                    pi.rows_mut(first, 10)
                        .copy_from_slice(&parameters_of(&(u * u.transpose())));
                    let scale = t[0].exp();
                    for k in 0..10 {
                        let du = if k == 0 {
                            u
                        } else {
                            let (r, c) = ENTRIES[k - 1];
                            let mut du = Matrix4::zeros();
                            du[(r, c)] = if r == c { u[(r, c)] } else { scale };
                            du
                        };
                        let dj = du * u.transpose() + u * du.transpose();
                        let column = parameters_of(&dj);
                        jac.view_mut((first, first + k), (10, 1))
                            .copy_from_slice(&column);
                    }
                }
                Block::Point { index, .. } | Block::Joint { index, .. } => {
                    pi[index] = theta[index].exp();
                    jac[(index, index)] = pi[index];
                }
            }
        }
        (pi, jac)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box 0.2 × 0.1 × 0.4 of 2 kg, centre at (0.1, −0.05, 0.3), its
    /// inertia carried to the reference point by the parallel-axis rule.
    fn box_block() -> [f64; 10] {
        let (m, c) = (2.0, [0.1, -0.05, 0.3]);
        let (a, b, h) = (0.2f64, 0.1f64, 0.4f64);
        let ic = [
            m * (b * b + h * h) / 12.0,
            m * (a * a + h * h) / 12.0,
            m * (a * a + b * b) / 12.0,
        ];
        let cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        let i = |r: usize, s: usize| {
            let diagonal = if r == s { ic[r] + m * cc } else { 0.0 };
            diagonal - m * c[r] * c[s]
        };
        [
            m,
            m * c[0],
            m * c[1],
            m * c[2],
            i(0, 0),
            i(0, 1),
            i(1, 1),
            i(0, 2),
            i(1, 2),
            i(2, 2),
        ]
    }

    #[test]
    fn a_box_is_consistent_and_its_theta_round_trips() {
        let block = box_block();
        assert!(is_physically_consistent(&block));
        let pi = DVector::from_row_slice(&block);
        let (p, theta) = Parametrisation::at(&BOX_NAMES, &pi, "π").expect("consistent");
        let (back, _) = p.pi_and_jacobian(&theta);
        assert!((back - &pi).abs().max() < 1e-14);
    }

    const BOX_NAMES: [&str; 10] = [
        "b.m", "b.mx", "b.my", "b.mz", "b.Ixx", "b.Ixy", "b.Iyy", "b.Ixz", "b.Iyz", "b.Izz",
    ];

    #[test]
    fn the_jacobian_is_the_derivative_of_pi() {
        let pi = DVector::from_row_slice(&box_block());
        let (p, _) = Parametrisation::at(&BOX_NAMES, &pi, "π").expect("consistent");
        let theta = DVector::from_vec(vec![0.3, -0.2, 0.5, 0.1, 0.4, -0.7, 0.2, 0.05, -0.3, 0.6]);
        let (_, jac) = p.pi_and_jacobian(&theta);
        let h = 1e-6;
        for k in 0..10 {
            let mut up = theta.clone();
            let mut down = theta.clone();
            up[k] += h;
            down[k] -= h;
            let fd = (p.pi_and_jacobian(&up).0 - p.pi_and_jacobian(&down).0) / (2.0 * h);
            assert!((fd - jac.column(k)).abs().max() < 1e-8, "column {k}");
        }
    }

    #[test]
    fn bad_bodies_are_refused() {
        // A rod along z about its centre: Ixx = Iyy, Izz = 0, on the
        // boundary (no thickness).
        assert!(!is_physically_consistent(&[
            1.0, 0.0, 0.0, 0.0, 0.1, 0.0, 0.1, 0.0, 0.0, 0.0
        ]));
        // Izz > Ixx + Iyy: no body has it.
        assert!(!is_physically_consistent(&[
            1.0, 0.0, 0.0, 0.0, 0.1, 0.0, 0.1, 0.0, 0.0, 0.3
        ]));
        // A negative mass, and a NaN.
        assert!(!is_physically_consistent(&[
            -1.0, 0.0, 0.0, 0.0, 0.1, 0.0, 0.1, 0.0, 0.0, 0.1
        ]));
        assert!(!is_physically_consistent(&[
            1.0,
            f64::NAN,
            0.0,
            0.0,
            0.1,
            0.0,
            0.1,
            0.0,
            0.0,
            0.1
        ]));
        // A first moment too far out for the inertia about the reference
        // point: the centre of mass's own inertia would be negative.
        assert!(!is_physically_consistent(&[
            1.0, 2.0, 0.0, 0.0, 0.1, 0.0, 0.1, 0.0, 0.0, 0.1
        ]));
        // A sphere of radius 0.1 about its centre is fine.
        let s = 0.4 * 0.01;
        assert!(is_physically_consistent(&[
            1.0, 0.0, 0.0, 0.0, s, 0.0, s, 0.0, 0.0, s
        ]));
    }

    #[test]
    fn layouts_and_point_masses() {
        let mut names = BOX_NAMES.to_vec();
        names.push("tip.m");
        let blocks = layout(&names).expect("a layout");
        assert_eq!(blocks.len(), 2);
        assert_eq!(
            blocks[1],
            Block::Point {
                name: "tip".into(),
                index: 10
            }
        );
        let mut pi = DVector::from_row_slice(&box_block()).push(0.5);
        assert!(
            inconsistent_bodies(&names, &pi)
                .expect("lengths")
                .is_empty()
        );
        pi[10] = 0.0;
        assert_eq!(inconsistent_bodies(&names, &pi).expect("lengths"), ["tip"]);
        assert!(matches!(
            layout(&["b.mx"]),
            Err(IdentifyError::UnknownParameter { .. })
        ));
    }
}
