//! Linearisation about an operating point, eigen-analysis, stability boundaries
//! and LQR design.
//!
//! # Which formulation when
//!
//! - **Unconstrained** ([`linearize`], a [`Lagrangian`](crate::Lagrangian) or
//!   [`Driven`](crate::Driven) system in minimal coordinates): the state is
//!   (δq, δq̇), `A = [[0, I], [M⁻¹(J_q + ∂ΔQ/∂q), M⁻¹(J_v + ∂ΔQ/∂q̇)]]` with J_q taken at
//!   the acceleration q̈0 of the operating point (the ∂M/∂q q̈0 term matters about a
//!   steady motion), `B = [[0], [M⁻¹ ∂Q/∂u]]`; the second-order form
//!   M δq̈ + C δq̇ + K δq = B_u δu comes with it.
//! - **Multiplier form** ([`linearize_constrained`], a
//!   [`Constrained`](crate::Constrained) system): holonomic and nonholonomic
//!   constraints kept with multipliers, linearised by differentiating the
//!   saddle-point system and then eliminating the dependent coordinates (position
//!   level) and the dependent speeds (velocity level, linearised in both δq and
//!   δq̇), as SymPy's `Linearizer` (Peterson, Gede & Hubbard 2015) does. The state is
//!   (δq_i, δq̇_s): independent coordinates and independent speeds, named by the
//!   user or chosen by column pivoting ([`Linearizer`] documents the rule). Use it
//!   for closed loops, rolling contact, published benchmarks (the bicycle).
//! - **Multiplier form with orientations**
//!   ([`Linearizer::constrained_tangent`], a [`Constrained`](crate::Constrained)
//!   system whose q holds unit quaternions, Q ≠ N): the same elimination in
//!   the tangent space (δ: the coordinates' changes and each orientation's
//!   rotation vector; δv: the velocities' changes), an orientation's read in
//!   its body axes at the operating point held fixed in space, so that a
//!   steady spin about an axis of symmetry (a rolling disk or sphere) is an
//!   equilibrium. Its derivatives are central differences on the group.
//! - **Reduced form** ([`linearize_reduced`], a [`Reduced`](crate::Reduced)
//!   system): the state is (δq, δu) with the system's own independent speeds u;
//!   no elimination is needed, the speeds' equations are linearised directly.
//!
//! The unconstrained, multiplier and reduced forms need the symbolic
//! derivatives `#[derive(Lagrangian)]` emits with `emit(jacobians)`; a system
//! without them is an [`Error::MissingDerivatives`] (never silent finite
//! differences). The multiplier form with orientations differentiates
//! numerically, as its documentation states (a description with
//! orientations has no emitted `constraint_derivatives`). The result is a [`Linear`]: A, B, state and
//! input names, the second-order form when there is one. [`Linear::select`] drops
//! ignorable states (heading, position, wheel angles) before a stability analysis;
//! [`Linear::eigenvalues`], [`Linear::modes`] and [`Linear::stability`] analyse it;
//! [`sweep`] follows the eigenvalues over a parameter and
//! [`EigenSweep::boundaries`] locates where the stability changes; [`Linear::lqr`]
//! designs a linear-quadratic regulator.
//!
//! ```
//! use lagrange_runtime::linear::{Linear, Verdict, sweep};
//! use nalgebra::DMatrix;
//!
//! // m ẍ + c ẋ + k x = 0 with a "negative damping" c = 0.5 − p: stable for p < 0.5.
//! let model = |p: f64| {
//!     let m = DMatrix::from_element(1, 1, 1.0);
//!     let c = DMatrix::from_element(1, 1, 0.5 - p);
//!     let k = DMatrix::from_element(1, 1, 4.0);
//!     Linear::from_second_order(m, c, k, DMatrix::zeros(1, 0), &["x"], &[])
//! };
//! assert_eq!(model(0.0)?.stability(1e-12)?.verdict, Verdict::AsymptoticallyStable);
//! let params: Vec<f64> = (0..=10).map(|i| 0.1 * i as f64).collect();
//! let mut eigen = sweep(&params, model)?;
//! let boundaries = eigen.boundaries(1e-12, 1e-12)?;
//! assert_eq!(boundaries.len(), 1);
//! assert!((boundaries[0].parameter - 0.5).abs() < 1e-11);
//! assert!(boundaries[0].oscillatory && boundaries[0].destabilising);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```
//!
//! With a system: a point (x, y) on a rod x² + y² = 1 under gravity, a
//! [`Constrained`](crate::Constrained) system with the derivatives
//! `emit(jacobians)` would generate (written by hand here, as in
//! [`mechanics::constraint`](crate::mechanics::constraint)). Naming only the
//! coordinate of interest is enough; the speed is chosen and
//! [`Linear::completed`] names it:
//!
//! ```
//! # use lagrange_runtime::{Constrained, Driven, Lagrangian};
//! use lagrange_runtime::linear::{Linearizer, OperatingPoint, Verdict};
//! # use nalgebra::{Matrix1x2, Matrix2, Vector1, Vector2};
//! # struct Bob;
//! # impl Lagrangian<f64, 2> for Bob {
//! #     const COORDINATES: [&'static str; 2] = ["x", "y"];
//! #     const RHEONOMIC: bool = false;
//! #     const CONSTRAINED: bool = true;
//! #     fn visit_form<F: lagrange_runtime::FormVisitor<f64, 2, Self>>(&self, f: F) -> F::Output {
//! #         f.multipliers::<1>(self)
//! #     }
//! #     fn mass_matrix(&self, _: &Vector2<f64>, _: f64) -> Matrix2<f64> { Matrix2::identity() }
//! #     fn bias(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::zeros() }
//! #     fn generalized_forces(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> { Vector2::new(0.0, -9.81) }
//! #     fn mass_matrix_and_rhs(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> (Matrix2<f64>, Vector2<f64>) {
//! #         (self.mass_matrix(q, t), self.generalized_forces(q, v, t))
//! #     }
//! #     fn kinetic_energy(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> f64 { 0.5 * v.norm_squared() }
//! #     fn potential_energy(&self, q: &Vector2<f64>, _: f64) -> f64 { 9.81 * q[1] }
//! #     fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
//! #         self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
//! #     }
//! #     fn rhs_jacobians(&self, _: &Vector2<f64>, _: &Vector2<f64>, _: &Vector2<f64>, _: f64)
//! #         -> Option<(Matrix2<f64>, Matrix2<f64>)> { Some((Matrix2::zeros(), Matrix2::zeros())) }
//! # }
//! # impl Constrained<f64, 2, 1> for Bob {
//! #     const CONSTRAINTS: [&'static str; 1] = ["rod"];
//! #     const HOLONOMIC: usize = 1;
//! #     fn constraint_positions(&self, q: &Vector2<f64>, _: f64) -> Vector1<f64> { Vector1::new(q.norm_squared() - 1.0) }
//! #     fn constraint_jacobian(&self, q: &Vector2<f64>, _: f64) -> (Matrix1x2<f64>, Vector1<f64>) {
//! #         (Matrix1x2::new(2.0 * q[0], 2.0 * q[1]), Vector1::zeros())
//! #     }
//! #     fn constraint_rhs(&self, _: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> Vector1<f64> { Vector1::new(-2.0 * v.norm_squared()) }
//! #     fn constrained_system(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64)
//! #         -> (Matrix2<f64>, Vector2<f64>, Matrix1x2<f64>, Vector1<f64>) {
//! #         let (m, f) = self.mass_matrix_and_rhs(q, v, t);
//! #         (m, f, self.constraint_jacobian(q, t).0, self.constraint_rhs(q, v, t))
//! #     }
//! #     fn constraint_derivatives(&self, _: &Vector2<f64>, v: &Vector2<f64>, a: &Vector2<f64>, nu: &Vector1<f64>, _: f64)
//! #         -> Option<(Matrix2<f64>, Matrix1x2<f64>, Matrix1x2<f64>, Matrix1x2<f64>)> {
//! #         Some((Matrix2::identity() * (2.0 * nu[0]), -2.0 * a.transpose(), -4.0 * v.transpose(), 2.0 * v.transpose()))
//! #     }
//! # }
//! # impl Driven<f64, 2, 0> for Bob {}
//! let bottom = OperatingPoint::new(Vector2::new(0.0, -1.0), Vector2::zeros());
//! let lin = Linearizer::new().coordinates(&["x"]).constrained(&Bob, &bottom)?;
//! assert_eq!(lin.states(), ["x", "x'"]);
//! assert_eq!(lin.completed(), ["x'"]);
//! let stability = lin.stability(1e-9)?; // eigenvalues ±i √(g/l)
//! assert_eq!(stability.verdict, Verdict::Marginal);
//! assert!((stability.critical.im - 9.81_f64.sqrt()).abs() < 1e-9);
//!
//! // A consistent state from the independent coordinate: y follows from x.
//! let (q, _) = Linearizer::new()
//!     .coordinates(&["x"])
//!     .complete_state(&Bob, Vector2::new(0.6, -0.5), Vector2::zeros(), 0.0)?;
//! assert!((q[1] + 0.8).abs() < 1e-12);
//! # Ok::<(), lagrange_runtime::Error>(())
//! ```

// Tolerance tests are written `!(x <= tol)` on purpose: a NaN residual fails them.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod atlas;
mod build;
mod complete;
mod constrained_tangent;
mod defaults;
mod dense;
mod difference;
mod discrete;
mod eigen;
mod equilibrium;
mod equilibrium_constrained;
mod errors;
mod jordan;
mod lqr;
mod partition;
mod reduced_tangent;
mod settings;
mod solve;
mod tangent;
#[cfg(test)]
pub(crate) mod test_systems;
mod transition;

pub use defaults::{complete_state, linearize, linearize_constrained, linearize_reduced};
pub use discrete::{Discrete, dlqr, zero_order_hold};
pub use eigen::{Boundary, EigenSweep, Mode, Stability, SweepPoint, Verdict, sweep};
pub use equilibrium::{Equilibrium, Trim};
pub use jordan::RANK_TOLERANCE;
pub use lqr::{Lqr, RICCATI_TOLERANCE, lqr};
pub use settings::{
    DEFAULT_NEWTON_ITERATIONS, DEFAULT_NEWTON_TOLERANCE, Linearizer, OperatingPoint,
};
pub(crate) use tangent::states as tangent_states;
pub use transition::{StepDerivatives, StepMethod, Transition};

use crate::error::Error;
pub use crate::error::LinearError;
use crate::error::SettingsError;
use nalgebra::DMatrix;

/// Default tolerance of [`Linear::select`]: a kept state may depend on a dropped
/// one by at most this much relative to the largest entry of A.
pub const DEFAULT_COUPLING_TOLERANCE: f64 = 1e-10;

/// The second-order form of a linearisation:
///
/// ```text
/// M δq̈_s + C δq̇_s + K δq_c = B_u δu
/// ```
///
/// with δq_c the coordinate states (columns of K) and δq̇_s the speed states, each
/// the rate of one of the coordinates (rows of every matrix, columns of M and C).
/// Without nonholonomic constraints the two sets coincide and M, C, K are square.
/// For a constrained linearisation M is the projected mass matrix
/// M_r = C_vᵀ M C_v (C_v the velocity embedding), C = −M_r A₂₂, K = −M_r A₂₁ and
/// B_u = M_r B₂, the form published linearisations (the bicycle's M, C, K) use.
#[derive(Debug, Clone, PartialEq)]
pub struct SecondOrderForm {
    /// M (speeds × speeds).
    pub mass: DMatrix<f64>,
    /// C (speeds × speeds): damping plus gyroscopic terms.
    pub damping: DMatrix<f64>,
    /// K (speeds × coordinates): stiffness plus circulatory terms.
    pub stiffness: DMatrix<f64>,
    /// B_u (speeds × inputs).
    pub input: DMatrix<f64>,
    /// Names of the coordinates (columns of K).
    pub coordinates: Vec<String>,
    /// Names of the speeds, each the name of the coordinate whose rate it is.
    pub speeds: Vec<String>,
}

fn sym(m: &DMatrix<f64>) -> DMatrix<f64> {
    (m + m.transpose()) * 0.5
}

fn skew(m: &DMatrix<f64>) -> DMatrix<f64> {
    (m - m.transpose()) * 0.5
}

impl SecondOrderForm {
    /// The damping matrix, the symmetric part (C + Cᵀ)/2 of C.
    pub fn symmetric_damping(&self) -> DMatrix<f64> {
        sym(&self.damping)
    }

    /// The gyroscopic matrix, the skew part (C − Cᵀ)/2 of C.
    pub fn gyroscopic(&self) -> DMatrix<f64> {
        skew(&self.damping)
    }

    /// K restricted to the coordinates whose rates are the speeds (square, in the
    /// speeds' order); `None` if one of those coordinates is not among the
    /// coordinate states.
    pub fn square_stiffness(&self) -> Option<DMatrix<f64>> {
        let cols: Option<Vec<usize>> = self
            .speeds
            .iter()
            .map(|s| self.coordinates.iter().position(|c| c == s))
            .collect();
        Some(self.stiffness.select_columns(cols?.iter()))
    }

    /// The stiffness matrix, the symmetric part of [`square_stiffness`](Self::square_stiffness).
    pub fn symmetric_stiffness(&self) -> Option<DMatrix<f64>> {
        self.square_stiffness().map(|k| sym(&k))
    }

    /// The circulatory matrix, the skew part of [`square_stiffness`](Self::square_stiffness).
    pub fn circulatory(&self) -> Option<DMatrix<f64>> {
        self.square_stiffness().map(|k| skew(&k))
    }
}

/// A linear model ẋ = A x + B u about an operating point.
///
/// The states are the coordinate states first (`n_coordinates` of them, named by
/// coordinate, e.g. `phi`, `delta`), then the speed states (named by the
/// coordinate whose rate they are with a prime, `phi'`, or by the reduced
/// system's speed name).
#[derive(Debug, Clone, PartialEq)]
pub struct Linear {
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    states: Vec<String>,
    inputs: Vec<String>,
    n_coordinates: usize,
    second_order: Option<SecondOrderForm>,
    completed: Vec<String>,
}

impl Linear {
    /// A linear model from its matrices and names; the first `n_coordinates`
    /// states are coordinates, the others speeds (this only matters to
    /// [`select`](Self::select) and the second-order form, which this constructor
    /// does not provide).
    ///
    /// # Errors
    /// [`Error::Settings`] if the sizes disagree or an entry is not finite.
    pub fn new(
        a: DMatrix<f64>,
        b: DMatrix<f64>,
        states: &[&str],
        inputs: &[&str],
        n_coordinates: usize,
    ) -> Result<Self, Error> {
        let n = states.len();
        check_shape("A", &a, n, n)?;
        check_shape("B", &b, n, inputs.len())?;
        if n_coordinates > n {
            return Err(SettingsError::Data {
                owner: "Linear",
                problem: format!("{n_coordinates} coordinate states out of {n} states"),
            }
            .into());
        }
        Ok(Self {
            a,
            b,
            states: states.iter().map(|s| s.to_string()).collect(),
            inputs: inputs.iter().map(|s| s.to_string()).collect(),
            n_coordinates,
            second_order: None,
            completed: Vec::new(),
        })
    }

    /// The linear model of M q̈ + C q̇ + K q = B_u u in the coordinates named
    /// `coordinates`: state (q, q̇), `A = [[0, I], [−M⁻¹K, −M⁻¹C]]`,
    /// `B = [[0], [M⁻¹B_u]]`. Builds a model from published matrices (the bicycle's).
    ///
    /// # Errors
    /// [`Error::Settings`] if the sizes disagree or an entry is not finite;
    /// [`Error::SingularMassMatrix`] if M is not invertible.
    pub fn from_second_order(
        mass: DMatrix<f64>,
        damping: DMatrix<f64>,
        stiffness: DMatrix<f64>,
        input: DMatrix<f64>,
        coordinates: &[&str],
        inputs: &[&str],
    ) -> Result<Self, Error> {
        let n = coordinates.len();
        check_shape("M", &mass, n, n)?;
        check_shape("C", &damping, n, n)?;
        check_shape("K", &stiffness, n, n)?;
        check_shape("B_u", &input, n, inputs.len())?;
        let lu = mass.clone().full_piv_lu();
        let singular = || Error::SingularMassMatrix {
            t: 0.0,
            q: vec![],
            ratio: 0.0,
            direction: String::new(),
            atlas: false,
        };
        let minv_k = lu.solve(&stiffness).ok_or_else(singular)?;
        let minv_c = lu.solve(&damping).ok_or_else(singular)?;
        let minv_b = lu.solve(&input).ok_or_else(singular)?;
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, n)).copy_from(&-minv_k);
        a.view_mut((n, n), (n, n)).copy_from(&-minv_c);
        let mut b = DMatrix::zeros(2 * n, inputs.len());
        b.view_mut((n, 0), (n, inputs.len())).copy_from(&minv_b);
        let names: Vec<String> = coordinates.iter().map(|s| s.to_string()).collect();
        let mut states = names.clone();
        states.extend(names.iter().map(|s| format!("{s}'")));
        Ok(Self {
            a,
            b,
            states,
            inputs: inputs.iter().map(|s| s.to_string()).collect(),
            n_coordinates: n,
            second_order: Some(SecondOrderForm {
                mass,
                damping,
                stiffness,
                input,
                coordinates: names.clone(),
                speeds: names,
            }),
            completed: Vec::new(),
        })
    }

    pub(crate) fn from_parts(
        a: DMatrix<f64>,
        b: DMatrix<f64>,
        states: Vec<String>,
        inputs: Vec<String>,
        n_coordinates: usize,
        second_order: Option<SecondOrderForm>,
    ) -> Self {
        Self {
            a,
            b,
            states,
            inputs,
            n_coordinates,
            second_order,
            completed: Vec::new(),
        }
    }

    /// The model with `names` recorded as the states its linearizer chose.
    pub(crate) fn with_completed(mut self, names: Vec<String>) -> Self {
        self.completed = names;
        self
    }

    /// The states the [`Linearizer`] chose itself, beyond those named with
    /// [`coordinates`](Linearizer::coordinates) and
    /// [`speeds`](Linearizer::speeds) (all of a constrained model's states when
    /// none were named; none for an unconstrained model, whose states are
    /// all its coordinates and velocities).
    pub fn completed(&self) -> &[String] {
        &self.completed
    }

    /// The state matrix A.
    pub fn a(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// The input matrix B (states × inputs).
    pub fn b(&self) -> &DMatrix<f64> {
        &self.b
    }

    /// The state names, in order.
    pub fn states(&self) -> &[String] {
        &self.states
    }

    /// The input names, in order.
    pub fn inputs(&self) -> &[String] {
        &self.inputs
    }

    /// How many of the states (the first ones) are coordinates.
    pub fn n_coordinates(&self) -> usize {
        self.n_coordinates
    }

    /// The second-order form, when the speed states are rates of coordinate
    /// states.
    pub fn second_order(&self) -> Option<&SecondOrderForm> {
        self.second_order.as_ref()
    }

    /// The index of the state named `name`. An orientation's angular
    /// velocity in a tangent model is `<name>.wx` (formerly `<name>.wx'`, a
    /// spelling still accepted here and by [`select`](Self::select)).
    pub fn state_index(&self, name: &str) -> Option<usize> {
        let exact = self.states.iter().position(|s| s == name);
        exact.or_else(|| {
            let former = name.strip_suffix('\'')?;
            let n = self.states.len() / 2;
            self.states[n..]
                .iter()
                .position(|s| s == former && s.contains('.'))
                .map(|i| n + i)
        })
    }

    /// Keeps the named states (in their original order), with the default
    /// tolerance [`DEFAULT_COUPLING_TOLERANCE`]; see
    /// [`select_with_tolerance`](Self::select_with_tolerance).
    ///
    /// # Errors
    /// As [`select_with_tolerance`](Self::select_with_tolerance).
    pub fn select(&self, names: &[&str]) -> Result<Linear, Error> {
        self.select_with_tolerance(names, DEFAULT_COUPLING_TOLERANCE)
    }

    /// Keeps the named states (in their original order), dropping the others:
    /// ignorable coordinates (heading, position, wheel angles) and decoupled
    /// neutral speeds. Valid only if no kept state depends on a dropped one:
    /// |A[kept, dropped]| ≤ `tol` · max |A_ij| (an absolute tolerance `tol` when A
    /// is zero).
    ///
    /// The second-order form survives if every kept speed's coordinate is kept:
    /// the submatrices when the mass matrix does not couple kept and dropped
    /// speeds, otherwise M restricted to the kept speeds with C, K, B_u
    /// recomputed from the selected A (C = −M A₂₂, K = −M A₂₁, B_u = M B₂).
    ///
    /// # Errors
    /// [`LinearError::UnknownState`] for a name that is not a state;
    /// [`LinearError::CoupledStates`] naming the largest coupling to a dropped
    /// state; [`Error::Settings`] for a negative or non-finite `tol`.
    pub fn select_with_tolerance(&self, names: &[&str], tol: f64) -> Result<Linear, Error> {
        crate::error::check_tolerance("Linear::select", "coupling tolerance", tol)?;
        let mut keep = vec![false; self.states.len()];
        for &name in names {
            let i = self
                .state_index(name)
                .ok_or_else(|| LinearError::UnknownState {
                    name: name.to_string(),
                    states: self.states.clone(),
                })?;
            keep[i] = true;
        }
        let kept: Vec<usize> = (0..keep.len()).filter(|&i| keep[i]).collect();
        let dropped: Vec<usize> = (0..keep.len()).filter(|&i| !keep[i]).collect();
        let scale = self.a.amax();
        let abs_tol = if scale > 0.0 { tol * scale } else { tol };
        let mut worst: Option<(usize, usize, f64)> = None;
        for &i in &kept {
            for &j in &dropped {
                let x = self.a[(i, j)];
                if x.abs() > abs_tol && worst.is_none_or(|w| x.abs() > w.2.abs()) {
                    worst = Some((i, j, x));
                }
            }
        }
        if let Some((i, j, x)) = worst {
            return Err(LinearError::CoupledStates {
                kept: self.states[i].clone(),
                dropped: self.states[j].clone(),
                coupling: x,
                tolerance: abs_tol,
            }
            .into());
        }
        let a = self.a.select_rows(kept.iter()).select_columns(kept.iter());
        let b = self.b.select_rows(kept.iter());
        let states: Vec<String> = kept.iter().map(|&i| self.states[i].clone()).collect();
        let n_coordinates = kept.iter().filter(|&&i| i < self.n_coordinates).count();
        let second_order = self
            .second_order
            .as_ref()
            .and_then(|so| self.select_second_order(so, &kept, &a, &b, n_coordinates));
        let completed = self
            .completed
            .iter()
            .filter(|c| states.contains(c))
            .cloned()
            .collect();
        let inputs = self.inputs.clone();
        Ok(
            Linear::from_parts(a, b, states, inputs, n_coordinates, second_order)
                .with_completed(completed),
        )
    }

    fn select_second_order(
        &self,
        so: &SecondOrderForm,
        kept: &[usize],
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        nc: usize,
    ) -> Option<SecondOrderForm> {
        let n0 = self.n_coordinates;
        let kc: Vec<usize> = kept.iter().copied().filter(|&i| i < n0).collect();
        let ks: Vec<usize> = kept.iter().filter(|&&i| i >= n0).map(|&i| i - n0).collect();
        let coordinates: Vec<String> = kc.iter().map(|&i| so.coordinates[i].clone()).collect();
        let speeds: Vec<String> = ks.iter().map(|&j| so.speeds[j].clone()).collect();
        if !speeds.iter().all(|s| coordinates.contains(s)) {
            return None;
        }
        let mass = so.mass.select_rows(ks.iter()).select_columns(ks.iter());
        let decoupled = ks.iter().all(|&i| {
            (0..so.speeds.len())
                .filter(|j| !ks.contains(j))
                .all(|j| so.mass[(i, j)] == 0.0)
        });
        let (damping, stiffness, input) = if decoupled {
            (
                so.damping.select_rows(ks.iter()).select_columns(ks.iter()),
                so.stiffness
                    .select_rows(ks.iter())
                    .select_columns(kc.iter()),
                so.input.select_rows(ks.iter()),
            )
        } else {
            let ns = ks.len();
            let a21 = a.view((nc, 0), (ns, nc));
            let a22 = a.view((nc, nc), (ns, ns));
            let b2 = b.view((nc, 0), (ns, b.ncols()));
            (-&mass * a22, -&mass * a21, &mass * b2)
        };
        Some(SecondOrderForm {
            mass,
            damping,
            stiffness,
            input,
            coordinates,
            speeds,
        })
    }
}

fn check_shape(
    name: &'static str,
    m: &DMatrix<f64>,
    rows: usize,
    cols: usize,
) -> Result<(), Error> {
    let finite = m.iter().all(|x| x.is_finite());
    if m.nrows() != rows || m.ncols() != cols || !finite {
        return Err(SettingsError::Shape {
            owner: "Linear",
            name,
            expected: (rows, cols),
            got: m.shape(),
            finite,
            meaning: "",
        }
        .into());
    }
    Ok(())
}
