//! The discrete dynamics of one fixed step, x⁺ = F(x, u) with x = (q, v) and
//! the input held over the step, and its derivatives ∂F/∂x and ∂F/∂u: what
//! trajectory optimisation (DDP, multiple shooting) and MPC work with.
//!
//! The derivatives are exact for the step as computed: the chain rule
//! through the stages, each stage's ∂f/∂x and ∂f/∂u (f = (v, q̈)) with its
//! q̈ in one evaluation on the stack ([`Dynamics::input_derivatives`]: the
//! system's emitted Jacobians where it has them, `emit(jacobians)`, else
//! central differences of q̈), the chain rule in N × N blocks
//! (`transition_chain`). For RK4 with
//! stages k₁ … k₄ at x + c h k,
//!
//! ```text
//! dk₁ = A₁ dx + B₁ du,   dk₂ = A₂ (dx + h/2 dk₁) + B₂ du,   …
//! dx⁺ = dx + h/6 (dk₁ + 2 dk₂ + 2 dk₃ + dk₄)
//! ```
//!
//! and for the semi-implicit Euler step v⁺ = v + h q̈(q, v, u),
//! q⁺ = q + h v⁺ (symplectic for a constant mass matrix, as in MuJoCo's
//! default), dv⁺ = dv + h (A_q dq + A_v dv + B du), dq⁺ = dq + h dv⁺.
//!
//! A system with free orientations is stepped on the rotation group
//! (`transition_group`: the same methods in the chart at the step's start,
//! q = q₀ ⊕ ξ, the end q₀ ⊕ ξ⁺ with unit quaternions), and its derivatives
//! are in the tangent space the linearisations use: x ⊕ (δ, δv) =
//! (q ⊕ δ, v + δv), so ∂F/∂x is 2N × 2N with δ⁺ = F(x ⊕ dx) ⊖ F(x).

use super::difference::{column, unit};
use super::settings::Linearizer;
use super::tangent::Held;
use crate::error::{Error, SettingsError, check_finite_inputs, unit_quaternions};
use crate::mechanics::{Dynamics, InputDerivatives};
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation;
use crate::system::Driven;
use group::{Chart, chart_rates};
use nalgebra::{DMatrix, SMatrix, SVector};

// A step's curvature serves the direct method's Newton steps (feature
// `direct`); its tests run in every build.
#[cfg(any(feature = "direct", test))]
#[path = "transition_blocks.rs"]
mod blocks;
#[path = "transition_chain.rs"]
mod chain;
#[cfg(any(feature = "direct", test))]
#[path = "transition_curvature.rs"]
mod curvature;
#[path = "transition_group.rs"]
mod group;

/// The one-step method of a [`Transition`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepMethod {
    /// The classic fourth-order Runge–Kutta step.
    Rk4,
    /// Semi-implicit (symplectic) Euler: the velocity first, then the
    /// configuration with the new velocity. First order.
    SemiImplicitEuler,
}

/// The discrete dynamics of a driven system over steps of `h` seconds with
/// its inputs held (zero-order hold): [`step`](Self::step) gives
/// x⁺ = F(x, u), [`derivatives`](Self::derivatives) also ∂F/∂x (2N × 2N)
/// and ∂F/∂u (2N × P), the state ordered (q, v): with orientations, in the
/// tangent space (δ, δv) at x and at x⁺ (see the module notes).
pub struct Transition<'a, S> {
    system: &'a S,
    h: f64,
    method: StepMethod,
    linearizer: Linearizer,
    through_linearizer: bool,
}

// By hand: the system need be neither `Clone` nor `Debug`.
impl<S> Clone for Transition<'_, S> {
    fn clone(&self) -> Self {
        Self {
            system: self.system,
            h: self.h,
            method: self.method,
            linearizer: self.linearizer.clone(),
            through_linearizer: self.through_linearizer,
        }
    }
}

impl<S> std::fmt::Debug for Transition<'_, S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Transition")
            .field("h", &self.h)
            .field("method", &self.method)
            .finish_non_exhaustive()
    }
}

/// One step and its derivatives: x⁺ = (q⁺, v⁺), ∂x⁺/∂x and ∂x⁺/∂u.
#[derive(Clone, Debug, PartialEq)]
pub struct StepDerivatives<const N: usize, const Q: usize = N> {
    /// q⁺ (Q numbers: four per orientation).
    pub q: SVector<f64, Q>,
    /// v⁺.
    pub v: SVector<f64, N>,
    /// ∂x⁺/∂x, 2N × 2N, rows and columns (q, v), or with orientations
    /// (δ, δv) in the tangent spaces at x and x⁺.
    pub dx: DMatrix<f64>,
    /// ∂x⁺/∂u, 2N × P.
    pub du: DMatrix<f64>,
}

impl<'a, S> Transition<'a, S> {
    /// Steps of `h` seconds of `system` by RK4.
    ///
    /// # Errors
    /// [`Error::Settings`] unless `h` is positive and finite.
    pub fn new(system: &'a S, h: f64) -> Result<Self, Error> {
        if !(h.is_finite() && h > 0.0) {
            return Err(SettingsError::Value {
                owner: "Transition",
                setting: "step h",
                value: h,
                requirement: "positive and finite (seconds)".into(),
            }
            .into());
        }
        Ok(Self {
            system,
            h,
            method: StepMethod::Rk4,
            linearizer: Linearizer::new(),
            through_linearizer: false,
        })
    }

    /// The one-step method (RK4 by default).
    pub fn method(mut self, method: StepMethod) -> Self {
        self.method = method;
        self
    }

    /// The linearisation settings each stage's derivatives are taken with.
    pub fn linearizer(mut self, linearizer: Linearizer) -> Self {
        self.linearizer = linearizer;
        self
    }

    /// Takes each stage's derivatives through
    /// [`Linearizer::tangent_driven`] (which checks the parameters, builds
    /// and names a [`Linear`](super::Linear) at every stage) instead of
    /// [`Dynamics::input_derivatives`]: the same numbers at about twice the
    /// work, kept only to measure and test the fast path against.
    #[doc(hidden)]
    pub fn through_linearizer(mut self, yes: bool) -> Self {
        self.through_linearizer = yes;
        self
    }

    /// The system stepped.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The step h.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// x⁺ = F(x, u) from (q, v) at t.
    ///
    /// # Errors
    /// [`Error::NonFiniteInput`] for a non-finite u; the dynamics' errors at
    /// a stage ([`Error::NonFiniteState`], [`Error::SingularMassMatrix`],
    /// [`Error::NonUnitQuaternion`] for a start off the unit sphere).
    pub fn step<const N: usize, const P: usize, const Q: usize>(
        &self,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
    ) -> Result<(SVector<f64, Q>, SVector<f64, N>), Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        let stages = self.stages(q, v, u, t)?;
        Ok(self.combine::<N, Q>(S::ORIENTATIONS, q, v, &stages))
    }

    /// The step and its derivatives by the chain rule through the stages
    /// (see the module notes). Each stage's q̈ and its derivatives come
    /// from one evaluation on the stack
    /// ([`Dynamics::input_derivatives`]: M factorised once, the emitted
    /// Jacobians solved), or, for a system without `emit(jacobians)`, from
    /// central differences of q̈ at that stage.
    ///
    /// # Errors
    /// As [`step`](Self::step); a stage's linearisation errors;
    /// [`Error::Settings`] for `through_linearizer` with orientations.
    pub fn derivatives<const N: usize, const P: usize, const Q: usize>(
        &self,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
    ) -> Result<StepDerivatives<N, Q>, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        let layout = S::ORIENTATIONS;
        if self.through_linearizer {
            return self.derivatives_through_linearizer(q, v, u, t);
        }
        let q = &unit_quaternions(layout, &S::COORDINATES, *q)?;
        let first = self.stage_derivatives(q, v, u, t)?;
        let h = self.h;
        if self.method == StepMethod::SemiImplicitEuler {
            let v1 = v + first.acceleration * h;
            let xi = v1 * h;
            let (dx, du) = match layout.is_empty() {
                true => chain::semi_implicit(&first, h),
                false => group::semi_implicit(&first, &Chart::at(layout, &xi, &v1), h),
            };
            let q = orientation::plus(layout, q, &xi);
            return Ok(StepDerivatives { q, v: v1, dx, du });
        }
        let mut stages = [first.clone(), first.clone(), first.clone(), first];
        // Each stage's chart coordinates ξ and velocity.
        let mut states = [(SVector::zeros(), *v); 4];
        for i in 1..4 {
            let c = RK4_NODES[i] * h;
            let (xi, sv) = &states[i - 1];
            let k = (chart_rates(layout, xi, sv), stages[i - 1].acceleration);
            states[i] = (k.0 * c, v + k.1 * c);
            let at = orientation::plus(layout, q, &states[i].0);
            stages[i] = self.stage_derivatives(&at, &states[i].1, u, t + c)?;
        }
        let (mut d_xi, mut dv) = (SVector::zeros(), SVector::zeros());
        for ((s, d), w) in states.iter().zip(&stages).zip(RK4_WEIGHTS) {
            d_xi += chart_rates(layout, &s.0, &s.1) * w;
            dv += d.acceleration * w;
        }
        let xi = d_xi * (h / 6.0);
        let (dx, du) = if layout.is_empty() {
            chain::rk4(&stages, RK4_NODES, RK4_WEIGHTS, h)
        } else {
            let paired = std::array::from_fn(|i| {
                let (xi, sv) = &states[i];
                (stages[i].clone(), Chart::at(layout, xi, sv))
            });
            group::rk4(
                &paired,
                &Chart::at(layout, &xi, v),
                RK4_NODES,
                RK4_WEIGHTS,
                h,
            )
        };
        Ok(StepDerivatives {
            q: orientation::plus(layout, q, &xi),
            v: v + dv * (h / 6.0),
            dx,
            du,
        })
    }

    /// Semi-implicit Euler's one stage's q̈ derivatives in the plane, from
    /// which ∂F/∂x = P + B [A_q A_v] and ∂F/∂u = B A_u
    /// (B = [h² I; h I], P = [[I, h I], [0, I]]): what DDP's backward pass
    /// multiplies by in place of the dense matrices, at half the work.
    /// `None` for RK4, for orientations and through the linearizer, where
    /// [`derivatives`](Self::derivatives) is the only form.
    ///
    /// # Errors
    /// As [`derivatives`](Self::derivatives).
    pub(crate) fn euler_stage<const N: usize, const P: usize, const Q: usize>(
        &self,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
    ) -> Result<Option<InputDerivatives<f64, N, P>>, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        let plane = S::ORIENTATIONS.is_empty();
        if self.method != StepMethod::SemiImplicitEuler || !plane || self.through_linearizer {
            return Ok(None);
        }
        self.stage_derivatives(q, v, u, t).map(Some)
    }

    /// One stage's q̈ and ∂q̈/∂(q, q̇, u): the system's emitted Jacobians
    /// where it has them, else central differences of q̈ (the step rule of
    /// every numerical linearisation; along q ⊕ δ with orientations) and
    /// ∂q̈/∂u = M⁻¹ ∂Q/∂u.
    fn stage_derivatives<const N: usize, const P: usize, const Q: usize>(
        &self,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
    ) -> Result<InputDerivatives<f64, N, P>, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        let tolerance = self.linearizer.tolerances.singular;
        let dynamics = Dynamics::new(self.system).with_singular_tolerance(tolerance);
        if let Some(d) = dynamics.input_derivatives(t, q, v, u)? {
            return Ok(d);
        }
        let held = dynamics.with_forcing(Held {
            system: self.system,
            u: *u,
        });
        let accel = |q: &SVector<f64, Q>, v: &SVector<f64, N>| held.acceleration(t, q, v);
        let along = |d: SVector<f64, N>| accel(&orientation::plus(S::ORIENTATIONS, q, &d), v);
        let (mut dq, mut dv) = (SMatrix::<f64, N, N>::zeros(), SMatrix::<f64, N, N>::zeros());
        for j in 0..N {
            let (step, e) = unit::<f64, N>(j, v[j]);
            let column_q = column(along(e)?, along(-e)?, step);
            let column_v = column(accel(q, &(v + e))?, accel(q, &(v - e))?, step);
            dq.set_column(j, &SVector::<f64, N>::from_column_slice(&column_q));
            dv.set_column(j, &SVector::<f64, N>::from_column_slice(&column_v));
        }
        let (bu, _, _) = self.system.input_jacobians(q, v, u, t);
        let m = self.system.mass_matrix(q, t);
        let chol = Cholesky::new(m, tolerance)
            .map_err(|ratio| Error::singular_mass(t, q, ratio, &m, (&S::VELOCITIES, S::ATLAS)))?;
        Ok(InputDerivatives {
            acceleration: accel(q, v)?,
            dq,
            dv,
            du: chol.solve_columns(bu),
        })
    }

    /// The derivatives through [`Linearizer::tangent_driven`] at every
    /// stage, the path before [`Dynamics::input_derivatives`]: kept to
    /// compare against (`through_linearizer`), for systems without
    /// orientations (its chain rule is the flat one).
    fn derivatives_through_linearizer<const N: usize, const P: usize, const Q: usize>(
        &self,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
    ) -> Result<StepDerivatives<N, Q>, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        if !S::ORIENTATIONS.is_empty() {
            return Err(SettingsError::Data {
                owner: "Transition",
                problem: "`through_linearizer` takes the flat chain rule: not for a system \
                          with orientations"
                    .into(),
            }
            .into());
        }
        let stages = self.stages(q, v, u, t)?;
        let (q_next, v_next) = self.combine::<N, Q>(S::ORIENTATIONS, q, v, &stages);
        let mut jacobians = Vec::with_capacity(stages.len());
        for s in &stages {
            let lin = self
                .linearizer
                .tangent_driven(self.system, &s.q, &s.v, u, s.t)?;
            jacobians.push((lin.a().clone(), lin.b().clone()));
        }
        let (dx, du) = match self.method {
            StepMethod::SemiImplicitEuler => semi_implicit_chain(&jacobians[0], N, self.h),
            StepMethod::Rk4 => rk4_chain(&jacobians, self.h),
        };
        Ok(StepDerivatives {
            q: q_next,
            v: v_next,
            dx,
            du,
        })
    }

    /// The stages' states and accelerations: one for semi-implicit Euler,
    /// four for RK4 (each at ξ = c h k^ξ, v + c h k^v of the one before, in
    /// the chart at q).
    fn stages<const N: usize, const P: usize, const Q: usize>(
        &self,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        u: &SVector<f64, P>,
        t: f64,
    ) -> Result<Vec<Stage<N, Q>>, Error>
    where
        S: Driven<f64, N, P, Q>,
    {
        check_finite_inputs(&S::INPUTS, t, q, v, u)?;
        let layout = S::ORIENTATIONS;
        let q = &unit_quaternions(layout, &S::COORDINATES, *q)?;
        let held = Held {
            system: self.system,
            u: *u,
        };
        let dynamics = Dynamics::new(self.system).with_forcing(held);
        let at = |xi: SVector<f64, N>, v: SVector<f64, N>, t: f64| {
            let q = orientation::plus(layout, q, &xi);
            let a = dynamics.acceleration(t, &q, &v)?;
            Ok::<_, Error>(Stage { q, xi, v, t, a })
        };
        let first = at(SVector::zeros(), *v, t)?;
        if self.method == StepMethod::SemiImplicitEuler {
            return Ok(vec![first]);
        }
        let h = self.h;
        let mut stages = vec![first];
        for c in RK4_NODES[1..].iter().copied() {
            let k = stages.last().expect("the first stage is in");
            let xi = chart_rates(layout, &k.xi, &k.v) * (c * h);
            let next = at(xi, v + k.a * (c * h), t + c * h)?;
            stages.push(next);
        }
        Ok(stages)
    }

    /// x⁺ from the stages: q ⊕ ξ⁺ and v⁺.
    fn combine<const N: usize, const Q: usize>(
        &self,
        layout: &[orientation::Orientation],
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        stages: &[Stage<N, Q>],
    ) -> (SVector<f64, Q>, SVector<f64, N>) {
        let h = self.h;
        match self.method {
            StepMethod::SemiImplicitEuler => {
                let v1 = v + stages[0].a * h;
                (orientation::plus(layout, q, &(v1 * h)), v1)
            }
            StepMethod::Rk4 => {
                let (mut d_xi, mut dv) = (SVector::zeros(), SVector::zeros());
                for (s, w) in stages.iter().zip(RK4_WEIGHTS) {
                    d_xi += chart_rates(layout, &s.xi, &s.v) * w;
                    dv += s.a * w;
                }
                let xi = d_xi * (h / 6.0);
                (orientation::plus(layout, q, &xi), v + dv * (h / 6.0))
            }
        }
    }
}

/// RK4's nodes c and weights (×6).
const RK4_NODES: [f64; 4] = [0.0, 0.5, 0.5, 1.0];
const RK4_WEIGHTS: [f64; 4] = [1.0, 2.0, 2.0, 1.0];

/// A stage: its configuration (q ⊕ ξ) and chart coordinates ξ, velocity,
/// time and acceleration.
struct Stage<const N: usize, const Q: usize> {
    q: SVector<f64, Q>,
    xi: SVector<f64, N>,
    v: SVector<f64, N>,
    t: f64,
    a: SVector<f64, N>,
}

/// (∂/∂x, ∂/∂u) of something over the step's (dx, du).
type Jacobians = (DMatrix<f64>, DMatrix<f64>);

/// RK4's chain rule: each stage's state is x + c h k_{i−1}, so
/// d(stage) = dx + c h dk_{i−1} and dk_i = A_i d(stage) + B_i du;
/// dx⁺ = dx + h/6 Σ w_i dk_i.
fn rk4_chain(stages: &[Jacobians], h: f64) -> Jacobians {
    let (n2, p) = (stages[0].0.nrows(), stages[0].1.ncols());
    let identity = DMatrix::<f64>::identity(n2, n2);
    let (mut sum_x, mut sum_u) = (DMatrix::zeros(n2, n2), DMatrix::zeros(n2, p));
    let mut previous: Option<Jacobians> = None;
    for ((a, b), (c, w)) in stages.iter().zip(RK4_NODES.into_iter().zip(RK4_WEIGHTS)) {
        let (ds_x, ds_u) = match &previous {
            None => (identity.clone(), DMatrix::zeros(n2, p)),
            Some((dk_x, dk_u)) => (&identity + dk_x * (c * h), dk_u * (c * h)),
        };
        let dk = (a * ds_x, a * ds_u + b);
        sum_x += &dk.0 * w;
        sum_u += &dk.1 * w;
        previous = Some(dk);
    }
    (identity + sum_x * (h / 6.0), sum_u * (h / 6.0))
}

/// Semi-implicit Euler's chain rule: with A = [[0, I], [A_q, A_v]] and
/// B = [[0], [B_u]], dv⁺ = dv + h (A_q dq + A_v dv + B_u du) and
/// dq⁺ = dq + h dv⁺.
fn semi_implicit_chain((a, b): &Jacobians, n: usize, h: f64) -> Jacobians {
    let (n2, p) = (2 * n, b.ncols());
    let mut dv_x = DMatrix::<f64>::zeros(n, n2);
    dv_x.view_mut((0, n), (n, n)).fill_with_identity();
    dv_x += a.view((n, 0), (n, n2)) * h;
    let dv_u = b.view((n, 0), (n, p)) * h;
    let mut dx = DMatrix::zeros(n2, n2);
    let mut dq_x = dv_x.clone() * h;
    for i in 0..n {
        dq_x[(i, i)] += 1.0;
    }
    dx.view_mut((0, 0), (n, n2)).copy_from(&dq_x);
    dx.view_mut((n, 0), (n, n2)).copy_from(&dv_x);
    let mut du = DMatrix::zeros(n2, p);
    du.view_mut((0, 0), (n, p)).copy_from(&(&dv_u * h));
    du.view_mut((n, 0), (n, p)).copy_from(&dv_u);
    (dx, du)
}

#[cfg(test)]
#[path = "transition_tests.rs"]
mod tests;
