//! What a linearisation is about and how it is done: the operating point and
//! the [`Linearizer`]'s settings.

use crate::error::{Error, SettingsError, check_finite_inputs, check_tolerance};
use crate::mechanics::Tolerances;
use crate::numeric::Real;
use crate::system::Driven;
use nalgebra::SVector;

/// Default absolute tolerance on max |Φ| of the Newton iteration in
/// [`Linearizer::complete_state`].
pub const DEFAULT_NEWTON_TOLERANCE: f64 = 1e-12;
/// Default limit on Newton iterations in [`Linearizer::complete_state`].
pub const DEFAULT_NEWTON_ITERATIONS: usize = 20;

/// An operating point (q0, q̇0, u0, t0) with U inputs given.
///
/// [`new`](Self::new) makes a point with no inputs given, which every
/// linearisation reads as all of the system's inputs zero, so a driven system
/// needs no annotation; [`input`](Self::input) gives them (their number must be
/// the system's, checked at compile time). A system whose configuration holds
/// orientations has Q ≠ N numbers in q (each quaternion's four components) and
/// N in v (body-axis angular velocities): [`on_group`](Self::on_group) makes
/// its point, for [`Linearizer::constrained_tangent`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OperatingPoint<T: Real, const N: usize, const U: usize = 0, const Q: usize = N> {
    /// Coordinates q0 (with orientations, the quaternions' components).
    pub q: SVector<T, Q>,
    /// Velocities q̇0.
    pub v: SVector<T, N>,
    /// Inputs u0 (none: all zero).
    pub u: SVector<T, U>,
    /// Time t0.
    pub t: T,
}

impl<T: Real, const N: usize> OperatingPoint<T, N> {
    /// The point (q, v) at t = 0 with all inputs zero.
    pub fn new(q: SVector<T, N>, v: SVector<T, N>) -> Self {
        Self {
            q,
            v,
            u: SVector::zeros(),
            t: T::zero(),
        }
    }
}

impl<T: Real, const N: usize, const Q: usize> OperatingPoint<T, N, 0, Q> {
    /// The point (q, v) at t = 0 with all inputs zero, q holding Q numbers
    /// (each orientation's unit quaternion) and v N (each orientation's
    /// angular velocity in body axes).
    pub fn on_group(q: SVector<T, Q>, v: SVector<T, N>) -> Self {
        Self {
            q,
            v,
            u: SVector::zeros(),
            t: T::zero(),
        }
    }
}

impl<T: Real, const N: usize, const U: usize, const Q: usize> OperatingPoint<T, N, U, Q> {
    /// Sets the inputs u0.
    pub fn input<const P: usize>(self, u: SVector<T, P>) -> OperatingPoint<T, N, P, Q> {
        OperatingPoint {
            q: self.q,
            v: self.v,
            u,
            t: self.t,
        }
    }

    /// Sets the time t0.
    pub fn time(mut self, t: T) -> Self {
        self.t = t;
        self
    }

    /// The system's P inputs: the given ones, or zeros when none were given.
    pub(crate) fn inputs<const P: usize>(&self) -> SVector<T, P> {
        const {
            assert!(
                U == 0 || U == P,
                "the operating point's inputs must be as many as the system's (or none, for all zero)"
            )
        };
        SVector::from_fn(|i, _| if U == 0 { T::zero() } else { self.u[i] })
    }
}

/// Settings of a linearisation: the independent coordinates and speeds of a
/// constrained system and the tolerances.
///
/// **Automatic choice** (of what is not named): the dependent coordinates are
/// the columns of Φ_q outside the named coordinates (and, where the constraints
/// allow, outside the named speeds) chosen by QR with column pivoting (largest remaining column
/// norm first, the later coordinate on ties), so Φ_{q_d} is as well conditioned
/// as this greedy rule gets; the dependent speeds are the rates of the dependent
/// coordinates plus, for the nonholonomic rows, the columns chosen by the same
/// pivoting on those rows restricted to the holonomic motions,
/// A_i − A_d Φ_{q_d}⁻¹ Φ_{q_i}. The independent speeds are then rates of
/// independent coordinates, so the second-order form is always available. Names
/// keep the order they are given in; automatic ones follow the coordinates'.
#[derive(Clone, Debug, PartialEq)]
pub struct Linearizer {
    pub(super) coordinates: Option<Vec<String>>,
    pub(super) speeds: Option<Vec<String>>,
    pub(super) tolerances: Tolerances,
    pub(super) newton_tolerance: f64,
    pub(super) newton_iterations: usize,
}

impl Default for Linearizer {
    fn default() -> Self {
        Self::new()
    }
}

impl Linearizer {
    /// Automatic choice of independent coordinates and speeds; consistency
    /// tolerance 1e-10, singular and redundancy tolerances 1e-12, Newton to 1e-12
    /// in at most 20 iterations.
    pub fn new() -> Self {
        Self {
            coordinates: None,
            speeds: None,
            tolerances: Tolerances::default(),
            newton_tolerance: DEFAULT_NEWTON_TOLERANCE,
            newton_iterations: DEFAULT_NEWTON_ITERATIONS,
        }
    }

    /// Names independent coordinates, at most N − HOLONOMIC of them, in the
    /// order the states will have; fewer is enough: the rest are chosen (see
    /// [`Linear::completed`](crate::linear::Linear::completed)).
    pub fn coordinates(mut self, names: &[&str]) -> Self {
        self.coordinates = Some(names.iter().map(|s| s.to_string()).collect());
        self
    }

    /// Names independent speeds, at most N − K of them, by the coordinates
    /// whose rates they are, in the order the states will have; fewer is
    /// enough: the rest are chosen. With orientations
    /// ([`constrained_tangent`](Self::constrained_tangent)) the speeds are
    /// named by the velocities (`x`, `<name>.wx`, …) and the coordinates by
    /// the tangent directions (`x`, `<name>.θx`, …).
    pub fn speeds(mut self, names: &[&str]) -> Self {
        self.speeds = Some(names.iter().map(|s| s.to_string()).collect());
        self
    }

    /// Sets every tolerance at once: the same [`Tolerances`] a
    /// [`Simulation`](crate::Simulation) takes
    /// ([`Simulation::tolerances`](crate::Simulation::tolerances)), so that
    /// both judge singularity, redundancy and consistency at the same
    /// thresholds.
    pub fn tolerances(mut self, tolerances: Tolerances) -> Self {
        self.tolerances = tolerances;
        self
    }

    /// Absolute tolerance on max |Φ| and max |G q̇ + g| at the operating point
    /// (default 1e-10).
    pub fn consistency_tolerance(mut self, tol: f64) -> Self {
        self.tolerances.consistency = tol;
        self
    }

    /// Threshold on the mass matrix's Cholesky pivot ratio (default 1e-12).
    pub fn singular_tolerance(mut self, tol: f64) -> Self {
        self.tolerances.singular = tol;
        self
    }

    /// Threshold on σ_min/σ_max (or the pivot ratio) below which constraint rows,
    /// Φ_{q_d} or G_d count as singular (default 1e-12).
    pub fn redundant_tolerance(mut self, tol: f64) -> Self {
        self.tolerances.redundant = tol;
        self
    }

    /// Tolerance on max |Φ| and iteration limit of the Newton iteration of
    /// [`complete_state`](Self::complete_state).
    pub fn newton(mut self, tol: f64, max_iter: usize) -> Self {
        self.newton_tolerance = tol;
        self.newton_iterations = max_iter;
        self
    }
}

impl Linearizer {
    /// What every linearisation checks first: the tolerances (non-negative
    /// and finite), the Newton budget, the system's physical parameters
    /// ([`Lagrangian::check_parameters`](crate::Lagrangian::check_parameters)),
    /// and the operating point's inputs
    /// (a NaN input is named, not reported as a non-finite state). Returns
    /// the system's P inputs at the point.
    pub(super) fn inputs_at<S, T, const N: usize, const P: usize, const U: usize, const Q: usize>(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U, Q>,
    ) -> Result<SVector<T, P>, Error>
    where
        S: Driven<T, N, P, Q>,
        T: Real,
    {
        self.check_settings()?;
        sys.check_parameters()?;
        let u = op.inputs::<P>();
        check_finite_inputs(&S::INPUTS, op.t, &op.q, &op.v, &u)?;
        Ok(u)
    }

    /// The tolerances non-negative and finite, the Newton budget positive.
    pub(super) fn check_settings(&self) -> Result<(), Error> {
        let t = &self.tolerances;
        for (name, tol) in [
            ("consistency tolerance", t.consistency),
            ("singular tolerance", t.singular),
            ("redundant tolerance", t.redundant),
            ("Newton tolerance", self.newton_tolerance),
        ] {
            check_tolerance("Linearizer", name, tol)?;
        }
        if self.newton_iterations == 0 {
            return Err(SettingsError::ZeroCount {
                owner: "Linearizer",
                setting: "Newton iteration limit",
            }
            .into());
        }
        Ok(())
    }
}
