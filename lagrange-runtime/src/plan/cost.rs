//! Cost terms beyond the problem's quadratic one: a frame's position
//! against a target (through the system's emitted kinematics), a state to
//! pass through at one time, and any user's term given with its
//! derivatives.
//!
//! Each term gives its value and a quadratic model at (x, u): the gradient
//! and a Hessian, Gauss–Newton's JᵀWJ for a squared residual (what DDP
//! needs: positive semidefinite, exact at a zero residual).

use super::problem::{difference, state, weighted};
use crate::error::{Error, SettingsError};
use crate::numeric::orientation::Orientation;
use crate::pose::Kinematics;
use crate::system::Lagrangian;
use nalgebra::{DMatrix, DVector, SVector, Vector3};

/// A cost term's value and quadratic model at (x, u), x = (q, v) with 2N
/// numbers (with orientations, its derivatives along x ⊕ (δ, δv), the
/// tangent space); at the final state the u parts are empty.
#[derive(Clone, Debug, PartialEq)]
pub struct CostModel {
    /// The value.
    pub value: f64,
    /// ∂l/∂x (2N).
    pub lx: DVector<f64>,
    /// ∂l/∂u (P, or 0 at the final state).
    pub lu: DVector<f64>,
    /// ∂²l/∂x² (2N × 2N), or a positive semidefinite model of it.
    pub lxx: DMatrix<f64>,
    /// ∂²l/∂u² (P × P).
    pub luu: DMatrix<f64>,
    /// ∂²l/∂u∂x (P × 2N).
    pub lux: DMatrix<f64>,
}

impl CostModel {
    /// A zero model for 2N states and `p` inputs.
    pub fn zero(n2: usize, p: usize) -> Self {
        Self {
            value: 0.0,
            lx: DVector::zeros(n2),
            lu: DVector::zeros(p),
            lxx: DMatrix::zeros(n2, n2),
            luu: DMatrix::zeros(p, p),
            lux: DMatrix::zeros(p, n2),
        }
    }

    /// Adds another term's model.
    pub(super) fn add(&mut self, other: &CostModel) {
        self.value += other.value;
        self.lx += &other.lx;
        self.lu += &other.lu;
        self.lxx += &other.lxx;
        self.luu += &other.luu;
        self.lux += &other.lux;
    }
}

/// A cost term of an [`OptimalControl`](super::OptimalControl) problem: at
/// each step (time t, state (q, v), input u) or, with `u = None`, at the
/// final state. With orientations q has Q numbers and the model's
/// derivatives are along q ⊕ δ.
pub trait Cost<const N: usize, const P: usize, const Q: usize = N> {
    /// The term's value.
    fn value(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> f64;

    /// The term's value, gradient and a positive semidefinite Hessian model.
    fn model(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> CostModel;
}

/// ½ w ‖p(q) − p*‖²: a body's frame origin p (its reference point, world
/// axes) against a target, through the system's
/// [`Kinematics`]: the gradient w J_pᵀ (p − p*) and the Gauss–Newton
/// Hessian w J_pᵀ J_p, J_p the frame Jacobian's rows 0–2.
pub struct FramePosition<'s, S> {
    system: &'s S,
    body: usize,
    target: Vector3<f64>,
    weight: f64,
}

impl<'s, S> FramePosition<'s, S> {
    /// The origin of body `body` (an index into `Posed::BODIES`; see
    /// `Posed::body_index`) drawn to `target` with weight `weight`.
    pub fn new(system: &'s S, body: usize, target: Vector3<f64>, weight: f64) -> Self {
        Self {
            system,
            body,
            target,
            weight,
        }
    }

    /// The frame's origin at q (NaN for a body index past the bodies, which
    /// a plan then refuses as a non-finite cost).
    fn origin<const N: usize, const Q: usize>(&self, q: &SVector<f64, Q>, t: f64) -> Vector3<f64>
    where
        S: Kinematics<f64, N, Q>,
    {
        (self.system.frame_pose(self.body, q, t)).map_or(Vector3::repeat(f64::NAN), |b| b.origin)
    }
}

impl<S, const N: usize, const P: usize, const Q: usize> Cost<N, P, Q> for FramePosition<'_, S>
where
    S: Kinematics<f64, N, Q>,
{
    fn value(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        _: &SVector<f64, N>,
        _: Option<&SVector<f64, P>>,
    ) -> f64 {
        0.5 * self.weight * (self.origin::<N, Q>(q, t) - self.target).norm_squared()
    }

    fn model(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> CostModel {
        let p = if u.is_some() { P } else { 0 };
        let mut model = CostModel::zero(2 * N, p);
        let residual = self.origin::<N, Q>(q, t) - self.target;
        model.value = self.value(t, q, v, u);
        let Some(jacobian) = self.system.frame_jacobian(self.body, q, t) else {
            model.value = f64::NAN;
            return model;
        };
        let jp = jacobian.fixed_rows::<3>(0);
        let gradient = jp.transpose() * residual * self.weight;
        let hessian = jp.transpose() * jp * self.weight;
        model.lx.rows_mut(0, N).copy_from(&gradient);
        model.lxx.view_mut((0, 0), (N, N)).copy_from(&hessian);
        model
    }
}

/// A user's term from closures: `value(t, q, v, u)` and `model(t, q, v, u)`
/// (which must agree with it). `u` is `None` at the final state.
pub struct CostFn<V, M> {
    value: V,
    model: M,
}

impl<V, M> CostFn<V, M> {
    /// The term of these closures.
    pub fn new(value: V, model: M) -> Self {
        Self { value, model }
    }
}

impl<V, M, const N: usize, const P: usize, const Q: usize> Cost<N, P, Q> for CostFn<V, M>
where
    V: Fn(f64, &SVector<f64, Q>, &SVector<f64, N>, Option<&SVector<f64, P>>) -> f64,
    M: Fn(f64, &SVector<f64, Q>, &SVector<f64, N>, Option<&SVector<f64, P>>) -> CostModel,
{
    fn value(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> f64 {
        (self.value)(t, q, v, u)
    }

    fn model(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> CostModel {
        (self.model)(t, q, v, u)
    }
}

/// ½ (x ⊖ x*)ᵀ W (x ⊖ x*) at one time of the horizon: a state to pass
/// through on the way (a running cost, zero at every other step). With
/// orientations x ⊖ x* is the tangent vector from x* and the model
/// Gauss–Newton's, as the problem's own quadratic cost: what a flip needs,
/// since its goal alone cannot ask for a whole turn (a turn by 2π ends
/// where it started, and the shortest way there is to stay).
#[derive(Clone, Debug, PartialEq)]
pub struct Waypoint {
    layout: &'static [Orientation],
    time: f64,
    target: DVector<f64>,
    weight: DMatrix<f64>,
}

impl Waypoint {
    /// The state (q*, v*) of `system` to pass at time `time` (the step whose
    /// time t₀ + k h is within 1e-9 s of it), weighted by W (2N × 2N, on
    /// (q, v), or (δ, δv) with orientations).
    ///
    /// # Errors
    /// [`Error::Settings`] for a weight that is not 2N × 2N and finite, or
    /// a time or target that is not finite.
    pub fn new<S, const N: usize, const Q: usize>(
        system: &S,
        time: f64,
        (q, v): (SVector<f64, Q>, SVector<f64, N>),
        weight: DMatrix<f64>,
    ) -> Result<Self, Error>
    where
        S: Lagrangian<f64, N, Q>,
    {
        let _ = system;
        let finite = weight.iter().all(|w| w.is_finite());
        if weight.shape() != (2 * N, 2 * N) || !finite {
            return Err(SettingsError::Shape {
                owner: "Waypoint",
                name: "W",
                expected: (2 * N, 2 * N),
                got: weight.shape(),
                finite,
                meaning: "",
            }
            .into());
        }
        let target = state(&q, &v);
        if !time.is_finite() || !target.iter().all(|x| x.is_finite()) {
            return Err(SettingsError::Data {
                owner: "Waypoint",
                problem: "the time and the target state must be finite".into(),
            }
            .into());
        }
        Ok(Self {
            layout: S::ORIENTATIONS,
            time,
            target,
            weight,
        })
    }

    fn active(&self, t: f64) -> bool {
        (t - self.time).abs() <= 1e-9
    }
}

impl<const N: usize, const P: usize, const Q: usize> Cost<N, P, Q> for Waypoint {
    fn value(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        _: Option<&SVector<f64, P>>,
    ) -> f64 {
        if !self.active(t) {
            return 0.0;
        }
        let e = difference::<N, Q>(self.layout, &self.target, &state(q, v));
        0.5 * e.dot(&(&self.weight * &e))
    }

    fn model(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: Option<&SVector<f64, P>>,
    ) -> CostModel {
        let mut model = CostModel::zero(2 * N, if u.is_some() { P } else { 0 });
        if self.active(t) {
            let e = difference::<N, Q>(self.layout, &self.target, &state(q, v));
            (model.lx, model.lxx) = weighted::<N>(self.layout, &self.weight, &e);
            model.value = 0.5 * e.dot(&(&self.weight * &e));
        }
        model
    }
}
