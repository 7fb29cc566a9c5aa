//! An optimal control problem over a fixed horizon of fixed steps.

use super::cost::{Cost, CostModel};
use crate::error::{Error, SettingsError, unit_quaternions};
use crate::linear::Transition;
use crate::numeric::orientation::{self, Orientation};
use crate::numeric::products;
use crate::system::Driven;
use nalgebra::{DMatrix, DVector, Matrix3, SVector};

/// Minimise, over the inputs u₀ … u_{K−1} held on each step,
///
/// ```text
/// Σ_k ½ (x_k − x*)ᵀ W_x (x_k − x*) + ½ (u_k − u*)ᵀ W_u (u_k − u*)   +   ½ (x_K − x*)ᵀ W_f (x_K − x*)
/// ```
///
/// subject to x_{k+1} = F(x_k, u_k) (a [`Transition`]: RK4 or semi-implicit
/// Euler of the system's dynamics), x₀ given and lower ≤ u_k ≤ upper. The
/// state is x = (q, v) (2N numbers); the goal x* defaults to zero, the input
/// target u* to zero, W_f to W_x and the bounds to none.
///
/// With free orientations (q of Q = N + 1 per orientation numbers) the
/// problem lives on the group: x − x* is x ⊖ x*, the tangent vector from
/// the goal (an orientation's rotation vector, whose length is the angle
/// between the two attitudes), so the weights are 2N × 2N on (δ, δv) as in
/// [`Linearizer::tangent`](crate::linear::Linearizer::tangent), and the
/// goal's default is the identity turn. The cost's model is Gauss–Newton's,
/// Jᵀ W J with J = ∂(x ⊖ x*)/∂δ (J_r⁻¹ of the error on an orientation's
/// block), exact at the goal.
///
/// Without orientations Q is N and may be left out. More terms join
/// either sum with [`running_cost`](Self::running_cost) and
/// [`final_cost`](Self::final_cost): a frame's position
/// ([`FramePosition`](super::FramePosition)), or your own
/// ([`CostFn`](super::CostFn)).
pub struct OptimalControl<'a, S, const N: usize, const P: usize, const Q: usize = N> {
    pub(super) transition: Transition<'a, S>,
    pub(super) steps: usize,
    pub(super) start: DVector<f64>,
    pub(super) t0: f64,
    pub(super) weight_x: DMatrix<f64>,
    pub(super) weight_u: DMatrix<f64>,
    pub(super) weight_final: Option<DMatrix<f64>>,
    pub(super) goal: DVector<f64>,
    pub(super) input_target: DVector<f64>,
    pub(super) lower: DVector<f64>,
    pub(super) upper: DVector<f64>,
    pub(super) running_terms: Vec<Box<dyn Cost<N, P, Q> + 'a>>,
    pub(super) final_terms: Vec<Box<dyn Cost<N, P, Q> + 'a>>,
    /// x_K = x* held exactly (the direct method only).
    pub(super) final_equality: bool,
    /// Hard bounds on x₁ … x_K (the direct method only).
    pub(super) state_limits: Option<(DVector<f64>, DVector<f64>)>,
}

/// (q, v) as one state vector of Q + N numbers.
pub(super) fn state<const N: usize, const Q: usize>(
    q: &SVector<f64, Q>,
    v: &SVector<f64, N>,
) -> DVector<f64> {
    DVector::from_iterator(Q + N, q.iter().chain(v.iter()).copied())
}

/// A state vector split into (q, v).
pub(super) fn split<const N: usize, const Q: usize>(
    x: &DVector<f64>,
) -> (SVector<f64, Q>, SVector<f64, N>) {
    (
        SVector::from_fn(|i, _| x[i]),
        SVector::from_fn(|i, _| x[Q + i]),
    )
}

/// x₁ ⊖ x₀ (2N numbers): q₁ ⊖ q₀ (an orientation's rotation vector of
/// q₀⁻¹ q₁, in q₀'s body axes) and v₁ − v₀; x₁ − x₀ without orientations.
pub(super) fn difference<const N: usize, const Q: usize>(
    layout: &[Orientation],
    x0: &DVector<f64>,
    x1: &DVector<f64>,
) -> DVector<f64> {
    let mut d = DVector::zeros(2 * N);
    difference_into::<N, Q>(layout, x0, x1, d.as_mut_slice());
    d
}

/// [`difference`] written into `out` (2N entries), allocating nothing.
fn difference_into<const N: usize, const Q: usize>(
    layout: &[Orientation],
    x0: &DVector<f64>,
    x1: &DVector<f64>,
    out: &mut [f64],
) {
    let (x0, x1) = (x0.as_slice(), x1.as_slice());
    if layout.is_empty() {
        out.iter_mut()
            .zip(x1.iter().zip(x0))
            .for_each(|(d, (a, b))| *d = a - b);
        return;
    }
    orientation::difference(layout, &x0[..Q], &x1[..Q], &mut out[..N]);
    for i in 0..N {
        out[N + i] = x1[Q + i] - x0[Q + i];
    }
}

/// eᵀ W e, with W e on the stack (the cost is evaluated at every step of
/// every forward pass) by the vector kernel of `products`.
fn quadratic_form(w: &DMatrix<f64>, e: &[f64]) -> f64 {
    with_scratch(e.len(), |we| {
        products::product(we, 1.0, (w.as_slice(), e.len()), (e, e.len()), 0.0);
        we.iter().zip(e).map(|(a, b)| a * b).sum()
    })
}

/// `f` of `len` numbers of scratch, on the stack up to 32 of them.
fn with_scratch<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    let mut stack = [0.0; 32];
    match len <= stack.len() {
        true => f(&mut stack[..len]),
        false => f(&mut vec![0.0; len]),
    }
}

/// x ⊕ d: q ⊕ d_q and v + d_v; x + d without orientations.
pub(super) fn retract<const N: usize, const Q: usize>(
    layout: &[Orientation],
    x: &DVector<f64>,
    d: &DVector<f64>,
) -> DVector<f64> {
    if layout.is_empty() {
        return x + d;
    }
    let mut out = DVector::zeros(Q + N);
    let q = &x.as_slice()[..Q];
    orientation::integrate(layout, q, &d.as_slice()[..N], &mut out.as_mut_slice()[..Q]);
    out.rows_mut(Q, N).copy_from(&(x.rows(Q, N) + d.rows(N, N)));
    out
}

/// The gradient and Gauss–Newton Hessian of ½ eᵀ W e on the tangent at x,
/// for e = x ⊖ x*: (Jᵀ W e, Jᵀ W J), J = ∂e/∂δ (W e and W without
/// orientations).
pub(super) fn weighted<const N: usize>(
    layout: &[Orientation],
    w: &DMatrix<f64>,
    e: &DVector<f64>,
) -> (DVector<f64>, DMatrix<f64>) {
    match error_jacobian::<N>(layout, e) {
        None => (w * e, w.clone()),
        Some(j) => (j.transpose() * (w * e), j.transpose() * w * &j),
    }
}

/// ∂(x ⊖ x*)/∂δ at the error e = x ⊖ x* (x moved to x ⊕ δ): J_r(e)⁻¹ on
/// an orientation's block (x* exp(e) exp(δ) = x* exp(e + J_r(e)⁻¹ δ) to
/// first order), the identity elsewhere; `None` without orientations.
fn error_jacobian<const N: usize>(
    layout: &[Orientation],
    e: &DVector<f64>,
) -> Option<DMatrix<f64>> {
    if layout.is_empty() {
        return None;
    }
    let mut j = DMatrix::identity(2 * N, 2 * N);
    for o in layout {
        let jr = orientation::right_jacobian([e[o.v], e[o.v + 1], e[o.v + 2]]);
        // J_r is invertible for angles below 2π, and a log's is at most π.
        let inverse = Matrix3::from_fn(|i, k| jr[i][k])
            .try_inverse()
            .unwrap_or_else(|| Matrix3::from_element(f64::NAN));
        j.fixed_view_mut::<3, 3>(o.v, o.v).copy_from(&inverse);
    }
    Some(j)
}

impl<'a, S, const N: usize, const P: usize, const Q: usize> OptimalControl<'a, S, N, P, Q>
where
    S: Driven<f64, N, P, Q>,
{
    /// `steps` steps of `transition` from (q₀, v₀) at t = 0, with the
    /// running weights W_x (2N × 2N, on (q, v), or (δ, δv) with
    /// orientations) and W_u (P × P).
    pub fn new(
        transition: Transition<'a, S>,
        steps: usize,
        start: (SVector<f64, Q>, SVector<f64, N>),
        weight_x: DMatrix<f64>,
        weight_u: DMatrix<f64>,
    ) -> Self {
        let mut rest = SVector::<f64, Q>::zeros();
        S::ORIENTATIONS.iter().for_each(|o| rest[o.q] = 1.0);
        Self {
            transition,
            steps,
            start: state(&start.0, &start.1),
            t0: 0.0,
            weight_x,
            weight_u,
            weight_final: None,
            goal: state(&rest, &SVector::<f64, N>::zeros()),
            input_target: DVector::zeros(P),
            lower: DVector::from_element(P, f64::NEG_INFINITY),
            upper: DVector::from_element(P, f64::INFINITY),
            running_terms: Vec::new(),
            final_terms: Vec::new(),
            final_equality: false,
            state_limits: None,
        }
    }

    /// Holds the last state at the goal exactly, x_K = x*, as a constraint
    /// rather than a cost. Only the direct method
    /// (`plan::Direct`, feature `direct`) takes constraints on
    /// states; [`Ddp`](super::Ddp) refuses the problem (give it a large
    /// [`final_weight`](Self::final_weight) instead).
    pub fn final_equality(mut self) -> Self {
        self.final_equality = true;
        self
    }

    /// Hard box bounds on every state after the start, x₁ … x_K, as
    /// (q, v) pairs (±∞ for none): constraints the plan never leaves. Only
    /// the direct method takes them; for [`Ddp`](super::Ddp), which refuses
    /// them, the same bounds as a penalty are
    /// [`StateBounds`](super::StateBounds).
    pub fn state_limits(
        mut self,
        lower: (SVector<f64, Q>, SVector<f64, N>),
        upper: (SVector<f64, Q>, SVector<f64, N>),
    ) -> Self {
        self.state_limits = Some((state(&lower.0, &lower.1), state(&upper.0, &upper.1)));
        self
    }

    /// Whether the problem constrains states beyond the dynamics and the
    /// start (a final equality, state limits).
    pub(super) fn constrains_states(&self) -> bool {
        self.final_equality || self.state_limits.is_some()
    }

    /// Adds a term to the running cost (at every step).
    pub fn running_cost(mut self, term: impl Cost<N, P, Q> + 'a) -> Self {
        self.running_terms.push(Box::new(term));
        self
    }

    /// Adds a term to the final cost (at the last state).
    pub fn final_cost(mut self, term: impl Cost<N, P, Q> + 'a) -> Self {
        self.final_terms.push(Box::new(term));
        self
    }

    /// The goal state x* = (q*, v*) both costs measure from.
    pub fn goal(mut self, q: SVector<f64, Q>, v: SVector<f64, N>) -> Self {
        self.goal = state(&q, &v);
        self
    }

    /// The input target u* the running cost measures from (a hover's thrust).
    pub fn input_target(mut self, u: SVector<f64, P>) -> Self {
        self.input_target = DVector::from_column_slice(u.as_slice());
        self
    }

    /// The terminal weight W_f (2N × 2N).
    pub fn final_weight(mut self, weight: DMatrix<f64>) -> Self {
        self.weight_final = Some(weight);
        self
    }

    /// Box bounds on every input (±∞ for none).
    pub fn input_bounds(mut self, lower: SVector<f64, P>, upper: SVector<f64, P>) -> Self {
        self.lower = DVector::from_column_slice(lower.as_slice());
        self.upper = DVector::from_column_slice(upper.as_slice());
        self
    }

    /// The time of x₀ (for time-dependent systems).
    pub fn start_time(mut self, t0: f64) -> Self {
        self.t0 = t0;
        self
    }

    /// The number of steps K.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The step's time t_k = t₀ + k h.
    pub(super) fn time(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.transition.h()
    }

    /// W_f, or W_x when none was given.
    pub(super) fn final_weight_or_running(&self) -> &DMatrix<f64> {
        self.weight_final.as_ref().unwrap_or(&self.weight_x)
    }

    /// x₁ ⊖ x₀ of two of the problem's states (2N numbers).
    pub(super) fn minus(&self, x1: &DVector<f64>, x0: &DVector<f64>) -> DVector<f64> {
        difference::<N, Q>(S::ORIENTATIONS, x0, x1)
    }

    /// x₁ ⊖ x₀ written into `out` (2N), allocating nothing.
    pub(super) fn minus_into(&self, x1: &DVector<f64>, x0: &DVector<f64>, out: &mut DVector<f64>) {
        difference_into::<N, Q>(S::ORIENTATIONS, x0, x1, out.as_mut_slice());
    }

    /// x ⊕ d of a state and a tangent vector.
    pub(super) fn plus(&self, x: &DVector<f64>, d: &DVector<f64>) -> DVector<f64> {
        retract::<N, Q>(S::ORIENTATIONS, x, d)
    }

    /// The weighted error's gradient and Gauss–Newton Hessian (`weighted`).
    fn quadratic(&self, w: &DMatrix<f64>, e: &DVector<f64>) -> (DVector<f64>, DMatrix<f64>) {
        weighted::<N>(S::ORIENTATIONS, w, e)
    }

    /// (x ⊖ x*)ᵀ W (x ⊖ x*), the error in scratch.
    fn state_form(&self, w: &DMatrix<f64>, x: &DVector<f64>) -> f64 {
        with_scratch(2 * N, |e| {
            difference_into::<N, Q>(S::ORIENTATIONS, &self.goal, x, e);
            quadratic_form(w, e)
        })
    }

    /// The running cost of (x, u) at step k.
    pub(super) fn running(&self, k: usize, x: &DVector<f64>, u: &DVector<f64>) -> f64 {
        let du = with_scratch(P, |e| {
            for (i, d) in e.iter_mut().enumerate() {
                *d = u[i] - self.input_target[i];
            }
            quadratic_form(&self.weight_u, e)
        });
        let quadratic = 0.5 * (self.state_form(&self.weight_x, x) + du);
        let (q, v) = split::<N, Q>(x);
        let u = SVector::<f64, P>::from_column_slice(u.as_slice());
        let t = self.time(k);
        let terms: f64 = self
            .running_terms
            .iter()
            .map(|c| c.value(t, &q, &v, Some(&u)))
            .sum();
        quadratic + terms
    }

    /// The terminal cost of x.
    pub(super) fn terminal(&self, x: &DVector<f64>) -> f64 {
        let (q, v) = split::<N, Q>(x);
        let t = self.time(self.steps);
        let terms: f64 = self
            .final_terms
            .iter()
            .map(|c| c.value(t, &q, &v, None))
            .sum();
        0.5 * self.state_form(self.final_weight_or_running(), x) + terms
    }

    /// The running cost's quadratic model at step k
    /// ([`running_model_into`](Self::running_model_into) in a new model).
    #[cfg(feature = "direct")]
    pub(super) fn running_model(
        &self,
        k: usize,
        x: &DVector<f64>,
        u: &DVector<f64>,
    ) -> Result<CostModel, Error> {
        let mut model = CostModel::zero(2 * N, P);
        self.running_model_into(k, x, u, &mut model)?;
        Ok(model)
    }

    /// The running cost's quadratic model at step k, written over `model`
    /// (2N states, P inputs): no allocation without orientations, where
    /// the backward pass asks for one a step.
    ///
    /// # Errors
    /// [`Error::Settings`] for a term whose model has the wrong sizes or is
    /// not finite.
    pub(super) fn running_model_into(
        &self,
        k: usize,
        x: &DVector<f64>,
        u: &DVector<f64>,
        model: &mut CostModel,
    ) -> Result<(), Error> {
        model.value = 0.0;
        if S::ORIENTATIONS.is_empty() {
            // lx = W e and lxx = W for e = x − x*.
            with_scratch(2 * N, |e| {
                difference_into::<N, Q>(S::ORIENTATIONS, &self.goal, x, e);
                let w = (self.weight_x.as_slice(), 2 * N);
                products::product(model.lx.as_mut_slice(), 1.0, w, (e, 2 * N), 0.0);
            });
            (model.lxx.as_mut_slice()).copy_from_slice(self.weight_x.as_slice());
        } else {
            (model.lx, model.lxx) = self.quadratic(&self.weight_x, &self.minus(x, &self.goal));
        }
        with_scratch(P, |d| {
            let pairs = d
                .iter_mut()
                .zip(u.as_slice().iter().zip(self.input_target.as_slice()));
            pairs.for_each(|(d, (u, target))| *d = u - target);
            let w = (self.weight_u.as_slice(), P);
            products::product(model.lu.as_mut_slice(), 1.0, w, (d, P), 0.0);
        });
        (model.luu.as_mut_slice()).copy_from_slice(self.weight_u.as_slice());
        model.lux.fill(0.0);
        let (q, v) = split::<N, Q>(x);
        let u = SVector::<f64, P>::from_column_slice(u.as_slice());
        for term in &self.running_terms {
            let m = term.model(self.time(k), &q, &v, Some(&u));
            check_model(&m, 2 * N, P)?;
            model.add(&m);
        }
        Ok(())
    }

    /// The final cost's quadratic model (its u parts empty).
    ///
    /// # Errors
    /// As [`running_model_into`](Self::running_model_into).
    pub(super) fn final_model(&self, x: &DVector<f64>) -> Result<CostModel, Error> {
        let w = self.final_weight_or_running();
        let (lx, lxx) = self.quadratic(w, &self.minus(x, &self.goal));
        let mut model = CostModel {
            value: 0.0,
            lx,
            lu: DVector::zeros(0),
            lxx,
            luu: DMatrix::zeros(0, 0),
            lux: DMatrix::zeros(0, 2 * N),
        };
        let (q, v) = split::<N, Q>(x);
        for term in &self.final_terms {
            let m = term.model(self.time(self.steps), &q, &v, None);
            check_model(&m, 2 * N, 0)?;
            model.add(&m);
        }
        Ok(model)
    }

    /// The whole cost of a state and input sequence.
    pub(super) fn cost(&self, xs: &[DVector<f64>], us: &[DVector<f64>]) -> f64 {
        let running: f64 = (xs.iter().zip(us).enumerate())
            .map(|(k, (x, u))| self.running(k, x, u))
            .sum();
        running + self.terminal(&xs[self.steps])
    }

    /// u clamped into the bounds.
    pub(super) fn clamp(&self, u: &DVector<f64>) -> DVector<f64> {
        let mut out = DVector::zeros(P);
        self.clamp_into(u, &mut out);
        out
    }

    /// `u` clamped into the bounds, written into `out` (P).
    pub(super) fn clamp_into(&self, u: &DVector<f64>, out: &mut DVector<f64>) {
        let bounds = self.lower.as_slice().iter().zip(self.upper.as_slice());
        let inputs = out.as_mut_slice().iter_mut().zip(u.as_slice());
        for ((o, u), (lower, upper)) in inputs.zip(bounds) {
            *o = u.clamp(*lower, *upper);
        }
    }

    /// The problem's sizes, weights and bounds, checked before solving.
    pub(super) fn check(&self) -> Result<(), Error> {
        if self.steps == 0 {
            return Err(SettingsError::ZeroCount {
                owner: "OptimalControl",
                setting: "steps",
            }
            .into());
        }
        // Once here: the steps' derivatives do not check them.
        self.transition.system().check_parameters()?;
        let n2 = 2 * N;
        check_weight("W_x", &self.weight_x, n2)?;
        check_weight("W_u", &self.weight_u, P)?;
        if let Some(w) = &self.weight_final {
            check_weight("W_f", w, n2)?;
        }
        let finite = |x: &DVector<f64>| x.iter().all(|v| v.is_finite());
        if !finite(&self.start) || !finite(&self.goal) || !finite(&self.input_target) {
            return Err(data(
                "the start, the goal and the input target must be finite",
            ));
        }
        for x in [&self.start, &self.goal] {
            let q = SVector::<f64, Q>::from_fn(|i, _| x[i]);
            unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, q)?;
        }
        let ordered = (0..P).all(|i| self.lower[i] <= self.upper[i] && !self.lower[i].is_nan());
        if !ordered {
            return Err(data(
                "each input's lower bound must be at most its upper bound",
            ));
        }
        if let Some((lower, upper)) = &self.state_limits {
            let ordered = (0..Q + N).all(|i| lower[i] <= upper[i] && !lower[i].is_nan());
            if !ordered {
                return Err(data(
                    "each state limit's lower bound must be at most its upper bound",
                ));
            }
        }
        Ok(())
    }
}

/// A weight: `n` × `n`, finite, symmetric and positive semidefinite.
fn check_weight(name: &'static str, w: &DMatrix<f64>, n: usize) -> Result<(), Error> {
    let finite = w.iter().all(|x| x.is_finite());
    if w.shape() != (n, n) || !finite {
        return Err(SettingsError::Shape {
            owner: "OptimalControl",
            name,
            expected: (n, n),
            got: w.shape(),
            finite,
            meaning: "",
        }
        .into());
    }
    if (w - w.transpose()).amax() > 1e-12 * w.amax() {
        return Err(data(&format!("the weight {name} must be symmetric")));
    }
    if n > 0 && w.clone().symmetric_eigenvalues().min() < -1e-12 * w.amax().max(1.0) {
        return Err(data(&format!(
            "the weight {name} must be positive semidefinite"
        )));
    }
    Ok(())
}

fn data(problem: &str) -> Error {
    SettingsError::Data {
        owner: "OptimalControl",
        problem: problem.into(),
    }
    .into()
}

/// A term's model of the right sizes, every entry finite.
fn check_model(m: &CostModel, n2: usize, p: usize) -> Result<(), Error> {
    let sizes = [
        ("lx", m.lx.shape(), (n2, 1)),
        ("lu", m.lu.shape(), (p, 1)),
        ("lxx", m.lxx.shape(), (n2, n2)),
        ("luu", m.luu.shape(), (p, p)),
        ("lux", m.lux.shape(), (p, n2)),
    ];
    if let Some((name, got, expected)) = sizes.iter().find(|(_, got, expected)| got != expected) {
        return Err(data(&format!(
            "a cost term's model has {name} of shape {got:?}, not {expected:?}"
        )));
    }
    let finite = [&m.lx, &m.lu]
        .iter()
        .all(|x| x.iter().all(|v| v.is_finite()))
        && [&m.lxx, &m.luu, &m.lux]
            .iter()
            .all(|x| x.iter().all(|v| v.is_finite()))
        && m.value.is_finite();
    if !finite {
        return Err(data("a cost term's value or model is not finite"));
    }
    Ok(())
}
