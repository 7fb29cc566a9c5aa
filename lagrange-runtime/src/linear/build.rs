//! Building a [`Linear`] model from a system at an operating point.

use super::dense::{dm, dv, finite};
use super::errors::{missing, redundant, singular};
use super::partition::{embeddings, holonomic};
use super::settings::{Linearizer, OperatingPoint};
use super::solve::{MassFactor, SaddleError, SaddleFactor};
use super::{Linear, LinearError, SecondOrderForm};
use crate::error::{Error, to_vec};
use crate::mechanics::reduced::{ReducedDynamics, ReducedForm};
use crate::numeric::Real;
use crate::system::{Constrained, Driven, Reduced};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// M, Q − h + ΔQ, G, γ, Φ (holonomic rows) and G q̇ + g at one state, as
/// f64, and M and G as the system computed them (for the dynamics'
/// factorisations).
struct Evaluated<T, const N: usize, const K: usize> {
    ms: SMatrix<T, N, N>,
    gs: SMatrix<T, K, N>,
    m: DMatrix<f64>,
    f: DVector<f64>,
    g: DMatrix<f64>,
    gamma: DVector<f64>,
    phi: DVector<f64>,
    vel: DVector<f64>,
}

impl Linearizer {
    /// Linearises an unconstrained (possibly driven) system about `op`:
    /// q̈0 = M⁻¹(Q − h + ΔQ(u0)), then
    ///
    /// ```text
    /// A = [[0, I], [M⁻¹(J_q + ∂ΔQ/∂q), M⁻¹(J_v + ∂ΔQ/∂q̇)]],   B = [[0], [M⁻¹ ∂Q/∂u]]
    /// ```
    ///
    /// with J_q, J_v the system's [`rhs_jacobians`](crate::Lagrangian::rhs_jacobians)
    /// at a = q̈0. The second-order form has C = −(J_v + ∂ΔQ/∂q̇),
    /// K = −(J_q + ∂ΔQ/∂q), B_u = ∂Q/∂u. States `q…`, `q…'`.
    ///
    /// A system with free orientations (q holding Q = N + 1 per orientation
    /// numbers, the point made with [`OperatingPoint::on_group`]) is
    /// linearised in its tangent space instead, as
    /// [`tangent_driven`](Self::tangent_driven) does: the states are δ (an
    /// orientation's rotation vector `<name>.θx`, … in body axes) and δv, and
    /// a gain designed on it becomes a controller with
    /// [`StateFeedback::from_tangent_gain`](crate::StateFeedback::from_tangent_gain).
    /// That model has no second-order form, and without `emit(jacobians)` it
    /// takes central differences (relative error about 1e-10) instead of
    /// failing with [`Error::MissingDerivatives`].
    ///
    /// # Errors
    /// [`Error::NonFiniteState`]; [`Error::SingularMassMatrix`];
    /// [`Error::MissingDerivatives`] if the system has no `rhs_jacobians`.
    /// Before any of these: [`Error::Settings`] for a negative or
    /// non-finite tolerance or a zero Newton limit, [`Error::NonPhysicalParameter`]
    /// from [`check_parameters`](crate::Lagrangian::check_parameters), and
    /// [`Error::NonFiniteInput`] naming a non-finite input of the point.
    pub fn unconstrained<S, T, const N: usize, const P: usize, const U: usize, const Q: usize>(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U, Q>,
    ) -> Result<Linear, Error>
    where
        S: Driven<T, N, P, Q>,
        T: Real,
    {
        const {
            assert!(
                !<S as crate::system::Lagrangian<T, N, Q>>::CONSTRAINED,
                "this system has constraints, which an unconstrained linearisation would ignore: use `Linearizer::constrained` (multipliers) or `Linearizer::reduced` (with orientations `Linearizer::constrained_tangent` or `Linearizer::reduced_tangent`)"
            )
        };
        if !S::ORIENTATIONS.is_empty() {
            let u = self.inputs_at(sys, op)?;
            return self.tangent_driven(sys, &op.q, &op.v, &u, op.t);
        }
        let u0 = self.inputs_at(sys, op)?;
        let q = &op.q;
        let v = &op.v;
        let u = &u0;
        let t = op.t;
        let non_finite = || Error::non_finite(t, q, v);
        let (m_s, rhs) = sys.mass_matrix_and_rhs(q, v, t);
        let rhs = rhs + sys.input_forces(q, v, u, t);
        let m = dm(&m_s);
        if !(finite(&m) && finite(&dm(&rhs)) && finite(&dm(q)) && finite(&dm(v))) {
            return Err(non_finite());
        }
        let chol = MassFactor::new(&m_s, self.tolerances.singular)
            .map_err(|ratio| singular(t, q, ratio))?;
        let a0 = chol.solve(&dm(&rhs));
        let acc: SVector<T, N> = SVector::from_fn(|i, _| T::lit(a0[i]));
        let (jq, jv) = sys
            .rhs_jacobians(q, v, &acc, t)
            .ok_or(missing("Lagrangian::rhs_jacobians"))?;
        let (bu, dqq, dqv) = sys.input_jacobians(q, v, u, t);
        let k = -(dm(&jq) + dm(&dqq));
        let c = -(dm(&jv) + dm(&dqv));
        let bu = dm(&bu);
        if !(finite(&k) && finite(&c) && finite(&bu)) {
            return Err(non_finite());
        }
        let a21 = chol.solve(&-&k);
        let a22 = chol.solve(&-&c);
        let b2 = chol.solve(&bu);
        let mut a = DMatrix::zeros(2 * N, 2 * N);
        a.view_mut((0, N), (N, N)).fill_with_identity();
        a.view_mut((N, 0), (N, N)).copy_from(&a21);
        a.view_mut((N, N), (N, N)).copy_from(&a22);
        let mut b = DMatrix::zeros(2 * N, P);
        b.view_mut((N, 0), (N, P)).copy_from(&b2);
        let names: Vec<String> = S::COORDINATES.iter().map(|s| s.to_string()).collect();
        let mut states = names.clone();
        states.extend(names.iter().map(|s| format!("{s}'")));
        Ok(Linear::from_parts(
            a,
            b,
            states,
            S::INPUTS.iter().map(|s| s.to_string()).collect(),
            N,
            Some(SecondOrderForm {
                mass: m,
                damping: c,
                stiffness: k,
                input: bu,
                coordinates: names.clone(),
                speeds: names,
            }),
        ))
    }

    /// Linearises a constrained system (multiplier form) in independent
    /// coordinates and speeds about a consistent `op`.
    ///
    /// q̈0 and ν0 solve M q̈ − Gᵀν = Q − h + ΔQ, G q̈ = γ. Differentiating both
    /// equations at fixed (q̈0, ν0) gives the first-order changes δq̈, δν from
    ///
    /// ```text
    /// [ M  −Gᵀ ] [ δq̈ ]   [ (J_q + ∂ΔQ/∂q + ∂(Gᵀν)/∂q) δq + (J_v + ∂ΔQ/∂q̇) δq̇ + ∂Q/∂u δu ]
    /// [ G   0  ] [ δν ] = [ ∂(γ − G q̈)/∂q δq + ∂γ/∂q̇ δq̇                                     ]
    /// ```
    ///
    /// (J_q at q̈0). The admissible variations are δq = C_q δq_i with the rows of the
    /// dependent coordinates −Φ_{q_d}⁻¹ Φ_{q_i} (holonomic rows), and
    /// δq̇ = C_v δq̇_s + C_vq δq_i from ∂(G q̇ + g)/∂q δq + G δq̇ = 0 (the δq term matters
    /// about a steady motion): rows d of C_v = −G_d⁻¹ G_s, of C_vq = −G_d⁻¹ ∂(Gq̇+g)/∂q C_q.
    /// With x = (δq_i, δq̇_s):
    ///
    /// ```text
    /// A = [[ C_vq[i],                    C_v[i]      ],
    ///      [ (X_q C_q + X_v C_vq)[s],     (X_v C_v)[s] ]],   B = [[0], [X_u[s]]]
    /// ```
    ///
    /// with δq̈ = X_q δq + X_v δq̇ + X_u δu. States are named `q_i…`, `q_s…'`. When the
    /// independent speeds are rates of independent coordinates the second-order
    /// form has M_r = C_vᵀ M C_v, C = −M_r A₂₂, K = −M_r A₂₁, B_u = M_r B₂.
    ///
    /// # Errors
    /// [`LinearError::InconsistentOperatingPoint`] naming the residuals and the
    /// worst constraint; [`LinearError::InvalidPartition`],
    /// [`LinearError::SingularPartition`] for a bad choice of independent
    /// coordinates or speeds; [`Error::RedundantConstraints`];
    /// [`Error::SingularMassMatrix`]; [`Error::NonFiniteState`];
    /// [`Error::MissingDerivatives`] without `rhs_jacobians` or
    /// `constraint_derivatives`.
    /// Before any of these: [`Error::Settings`] for a negative or
    /// non-finite tolerance or a zero Newton limit, [`Error::NonPhysicalParameter`]
    /// from [`check_parameters`](crate::Lagrangian::check_parameters), and
    /// [`Error::NonFiniteInput`] naming a non-finite input of the point.
    pub fn constrained<S, T, const N: usize, const K: usize, const P: usize, const U: usize>(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U>,
    ) -> Result<Linear, Error>
    where
        S: Constrained<T, N, K> + Driven<T, N, P>,
        T: Real,
    {
        let u0 = self.inputs_at(sys, op)?;
        let q = &op.q;
        let v = &op.v;
        let u = &u0;
        let t = op.t;
        let ev = self.evaluate(sys, q, v, u, t)?;
        self.check_consistent::<S, T, N, K, N>([&ev.phi, &ev.vel], q, t)?;
        let part = self.partition::<S, T, N, K, N>(&ev.g, (q, t), [&S::COORDINATES; 2])?;
        let saddle = self.saddle::<S, T, N, K>(&ev, q, t)?;
        let (a0, nu0) = saddle.solve(
            &DMatrix::from_column_slice(N, 1, ev.f.as_slice()),
            &DMatrix::from_column_slice(K, 1, ev.gamma.as_slice()),
        );
        let acc: SVector<T, N> = SVector::from_fn(|i, _| T::lit(a0[i]));
        let nu: SVector<T, K> = SVector::from_fn(|i, _| T::lit(nu0[i]));
        let (jq, jv) = sys
            .rhs_jacobians(q, v, &acc, t)
            .ok_or(missing("Lagrangian::rhs_jacobians"))?;
        let (dgn, dga, dgv, dvel) = sys
            .constraint_derivatives(q, v, &acc, &nu, t)
            .ok_or(missing("Constrained::constraint_derivatives"))?;
        let (bu, dqq, dqv) = sys.input_jacobians(q, v, u, t);
        let rq = dm(&jq) + dm(&dqq) + dm(&dgn);
        let rv = dm(&jv) + dm(&dqv);
        let bu = dm(&bu);
        let dga = dm(&dga);
        let dgv = dm(&dgv);
        let dvel = dm(&dvel);
        let all = [&rq, &rv, &bu, &dga, &dgv, &dvel];
        if !all.iter().all(|m| finite(m)) {
            return Err(Error::non_finite(t, q, v));
        }
        let [xq, xv, xu] = sensitivities(&saddle, [&rq, &rv, &bu], [&dga, &dgv]);

        let (cq, cv, cvq) = embeddings(&part, &ev.g, &dvel, holonomic::<S, T, N, K, N>());
        let ni = part.ci.len();
        let ns = part.si.len();
        let a21 = (&xq * &cq + &xv * &cvq).select_rows(part.si.iter());
        let a22 = (&xv * &cv).select_rows(part.si.iter());
        let b2 = xu.select_rows(part.si.iter());
        let mut a = DMatrix::zeros(ni + ns, ni + ns);
        a.view_mut((0, 0), (ni, ni))
            .copy_from(&cvq.select_rows(part.ci.iter()));
        a.view_mut((0, ni), (ni, ns))
            .copy_from(&cv.select_rows(part.ci.iter()));
        a.view_mut((ni, 0), (ns, ni)).copy_from(&a21);
        a.view_mut((ni, ni), (ns, ns)).copy_from(&a22);
        let mut b = DMatrix::zeros(ni + ns, P);
        b.view_mut((ni, 0), (ns, P)).copy_from(&b2);
        if !(finite(&a) && finite(&b)) {
            return Err(Error::non_finite(t, q, v));
        }
        let name = |i: &usize| S::COORDINATES[*i].to_string();
        let coordinates: Vec<String> = part.ci.iter().map(name).collect();
        let speeds: Vec<String> = part.si.iter().map(name).collect();
        let states: Vec<String> = coordinates
            .iter()
            .cloned()
            .chain(speeds.iter().map(|s| format!("{s}'")))
            .collect();
        let second_order = part.si.iter().all(|s| part.ci.contains(s)).then(|| {
            let mr = cv.transpose() * &ev.m * &cv;
            SecondOrderForm {
                damping: -&mr * &a22,
                stiffness: -&mr * &a21,
                input: &mr * &b2,
                mass: mr,
                coordinates,
                speeds,
            }
        });
        let named = |names: &Option<Vec<String>>| names.as_ref().map_or(0, Vec::len);
        let mut completed = states[named(&self.coordinates)..ni].to_vec();
        completed.extend(states[ni + named(&self.speeds)..].iter().cloned());
        let inputs = S::INPUTS.iter().map(|s| s.to_string()).collect();
        Ok(Linear::from_parts(a, b, states, inputs, ni, second_order).with_completed(completed))
    }

    /// Linearises a reduced system (independent speeds u, q̇ = W u + w,
    /// M* u̇ = F*) about `op`, state (δq, δu):
    ///
    /// ```text
    /// δq̇ = ∂(Wu + w)/∂q δq + W δu
    /// M* δu̇ = [∂(F* − M* u̇)/∂q + Wᵀ(∂ΔQ/∂q + ∂ΔQ/∂q̇ ∂(Wu+w)/∂q)] δq
    ///        + [∂F*/∂u + Wᵀ ∂ΔQ/∂q̇ W] δu + Wᵀ ∂Q/∂u δu_in
    /// ```
    ///
    /// with the inputs' forces e = ΔQ(u0) included in F*, at the speed rates u̇0
    /// of the operating point (the derivatives are composed from the system's
    /// [`rhs_jacobians`](crate::Lagrangian::rhs_jacobians) and
    /// [`row_derivatives`](crate::Reduced::row_derivatives); see
    /// `reduced_jacobians` in the source for the chain rule).
    /// States are the coordinates' names then the speeds' names. No second-order
    /// form.
    ///
    /// Systems in coordinates alone (Q = N: the bound is [`Reduced`] with its
    /// default Q); a reduced form with free orientations is linearised by
    /// [`reduced_tangent`](Self::reduced_tangent), in the tangent space.
    ///
    /// # Errors
    /// [`LinearError::InconsistentOperatingPoint`] if q̇0 ≠ W u0 + w beyond the
    /// tolerance (u0 = speeds(q0, q̇0)); [`Error::SingularMassMatrix`] (M*);
    /// [`Error::NonFiniteState`]; [`Error::ReducedFormBreakdown`] if the
    /// stacked rows are dependent at q0; [`Error::MissingDerivatives`] without
    /// `rhs_jacobians` or `row_derivatives` (`emit(jacobians)`).
    /// Before any of these: [`Error::Settings`] for a negative or
    /// non-finite tolerance or a zero Newton limit, [`Error::NonPhysicalParameter`]
    /// from [`check_parameters`](crate::Lagrangian::check_parameters), and
    /// [`Error::NonFiniteInput`] naming a non-finite input of the point.
    pub fn reduced<S, T, const N: usize, const K: usize, const P: usize, const U: usize>(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U>,
    ) -> Result<Linear, Error>
    where
        S: Reduced<T, N, K> + Driven<T, N, P>,
        T: Real,
    {
        let u0 = self.inputs_at(sys, op)?;
        let q = &op.q;
        let v = &op.v;
        let uin = &u0;
        let t = op.t;
        if !(t.is_finite() && finite(&dm(q)) && finite(&dm(v))) {
            return Err(Error::non_finite(t, q, v));
        }
        let u = sys.speeds(q, v, t);
        let form = ReducedDynamics::new(sys)
            .with_singular_tolerance(T::lit(self.tolerances.singular))
            .form(t, q, &u)?;
        let d = dv(&(form.velocities - v));
        let res = d.amax();
        if !(res <= self.tolerances.consistency) {
            return Err(LinearError::InconsistentOperatingPoint {
                t: t.to_f64(),
                q: to_vec(q),
                coordinates: S::COORDINATES.to_vec(),
                position_residual: 0.0,
                velocity_residual: res,
                tolerance: self.tolerances.consistency,
                worst: format!(
                    "velocity of `{}` differs from W u + w",
                    S::COORDINATES[d.iamax()]
                ),
            }
            .into());
        }
        let e = sys.input_forces(q, v, uin, t);
        let ms = dm(&form.mass);
        let w_d = dm(&form.w);
        let f = dv(&form.force) + w_d.transpose() * dv(&e);
        if !(finite(&ms) && finite(&w_d) && f.iter().all(|x| x.is_finite())) {
            return Err(Error::non_finite(t, q, v));
        }
        let chol = MassFactor::new(&form.mass, self.tolerances.singular)
            .map_err(|ratio| singular(t, q, ratio))?;
        let du0 = chol.solve(&DMatrix::from_column_slice(K, 1, f.as_slice()));
        let du: SVector<T, K> = SVector::from_fn(|i, _| T::lit(du0[i]));
        let (dq, dfu, wq) = reduced_jacobians(sys, q, &form, &du, &e, t)?;
        let (bu, dqq, dqv) = sys.input_jacobians(q, v, uin, t);
        let bu = dm(&bu);
        let dqq = dm(&dqq);
        let dqv = dm(&dqv);
        let wt = w_d.transpose();
        let rq = dq + &wt * (dqq + &dqv * &wq);
        let ru = dfu + &wt * &dqv * &w_d;
        let rb = &wt * bu;
        let mut a = DMatrix::zeros(N + K, N + K);
        a.view_mut((0, 0), (N, N)).copy_from(&wq);
        a.view_mut((0, N), (N, K)).copy_from(&w_d);
        a.view_mut((N, 0), (K, N)).copy_from(&chol.solve(&rq));
        a.view_mut((N, N), (K, K)).copy_from(&chol.solve(&ru));
        let mut b = DMatrix::zeros(N + K, P);
        b.view_mut((N, 0), (K, P)).copy_from(&chol.solve(&rb));
        if !(finite(&a) && finite(&b)) {
            return Err(Error::non_finite(t, q, v));
        }
        let mut states: Vec<String> = S::COORDINATES.iter().map(|s| s.to_string()).collect();
        states.extend(S::SPEEDS.iter().map(|s| s.to_string()));
        Ok(Linear::from_parts(
            a,
            b,
            states,
            S::INPUTS.iter().map(|s| s.to_string()).collect(),
            N,
            None,
        ))
    }

    fn evaluate<S, T, const N: usize, const K: usize, const P: usize>(
        &self,
        sys: &S,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
        t: T,
    ) -> Result<Evaluated<T, N, K>, Error>
    where
        S: Constrained<T, N, K> + Driven<T, N, P>,
        T: Real,
    {
        if !(t.is_finite() && finite(&dm(q)) && finite(&dm(v)) && finite(&dm(u))) {
            return Err(Error::non_finite(t, q, v));
        }
        let (m, f, g, gamma) = sys.constrained_system(q, v, t);
        let f = f + sys.input_forces(q, v, u, t);
        let (_, g0) = sys.constraint_jacobian(q, t);
        let mut phi = dv(&sys.constraint_positions(q, t));
        for x in phi.iter_mut().skip(holonomic::<S, T, N, K, N>()) {
            *x = 0.0;
        }
        let ev = Evaluated {
            ms: m,
            gs: g,
            m: dm(&m),
            f: dv(&f),
            g: dm(&g),
            gamma: dv(&gamma),
            phi,
            vel: dv(&(g * v + g0)),
        };
        let parts = [&ev.m, &ev.g];
        let vecs = [&ev.f, &ev.gamma, &ev.phi, &ev.vel];
        if !(parts.iter().all(|m| finite(m))
            && vecs.iter().all(|x| x.iter().all(|y| y.is_finite())))
        {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(ev)
    }

    /// An [`LinearError::InconsistentOperatingPoint`] unless Φ (`phi`, zero
    /// on the nonholonomic rows) and G q̇ + g (`vel`) are within the
    /// consistency tolerance.
    pub(super) fn check_consistent<S, T, const N: usize, const K: usize, const Q: usize>(
        &self,
        residuals: [&DVector<f64>; 2],
        q: &SVector<T, Q>,
        t: T,
    ) -> Result<(), Error>
    where
        S: Constrained<T, N, K, Q>,
        T: Real,
    {
        self.within_tolerance(residuals, (t, q, &S::COORDINATES), &S::CONSTRAINTS)
    }

    /// Whether the residuals [Φ, G v + g] are within the consistency
    /// tolerance, else the error naming the worst of the `rows`.
    pub(super) fn within_tolerance<T: Real, const Q: usize>(
        &self,
        [phi, vel]: [&DVector<f64>; 2],
        (t, q, coordinates): (T, &SVector<T, Q>, &[&'static str]),
        rows: &[&str],
    ) -> Result<(), Error> {
        let res = [phi.amax(), vel.amax()];
        let tol = self.tolerances.consistency;
        let worst = if !(res[0] <= tol) {
            phi.iamax()
        } else if !(res[1] <= tol) {
            vel.iamax()
        } else {
            return Ok(());
        };
        Err(LinearError::InconsistentOperatingPoint {
            t: t.to_f64(),
            q: to_vec(q),
            coordinates: coordinates.to_vec(),
            position_residual: res[0],
            velocity_residual: res[1],
            tolerance: tol,
            worst: format!("constraint `{}`", rows[worst]),
        }
        .into())
    }

    fn saddle<S, T, const N: usize, const K: usize>(
        &self,
        ev: &Evaluated<T, N, K>,
        q: &SVector<T, N>,
        t: T,
    ) -> Result<SaddleFactor<T, N, K>, Error>
    where
        S: Constrained<T, N, K>,
        T: Real,
    {
        SaddleFactor::new(
            &ev.ms,
            &ev.gs,
            self.tolerances.singular,
            self.tolerances.redundant,
        )
        .map_err(|e| match e {
            SaddleError::Mass(ratio) => singular(t, q, ratio),
            SaddleError::Redundant(ratio, rows) => redundant::<S, T, N, K, N>(t, q, ratio, rows),
        })
    }
}

/// ∂(F*(e) − M* u̇)/∂q (K × N), ∂F*/∂u (K × K) and ∂(W u + w)/∂q (N × N) at
/// fixed u, u̇ and e, by the chain rule through A q̇ + b = (u, 0) and
/// A q̈ = (u̇, 0) + c (A⁻¹ from the form, V_q = ∂q̇/∂q, a = q̈):
///
/// ```text
/// V_q = −A⁻¹ ∂(A q̇ + b)/∂q
/// ∂a/∂q = A⁻¹ (∂(c − A a)/∂q + ∂c/∂q̇ V_q)
/// ∂(Wᵀ z)/∂q = Wᵀ (∂z/∂q − ∂(Aᵀμ)/∂q),   z = Q − h + e − M a,  μ = A⁻ᵀ z
/// ∂z/∂q = J_q + J_v V_q − M ∂a/∂q
/// ∂F*/∂u = Wᵀ (J_v − M A⁻¹ ∂c/∂q̇) W
/// ```
///
/// where Wᵀ z = Eᵀ μ (W = A⁻¹ E) is differentiated through Aᵀ μ = z, and J_q,
/// J_v are the system's `rhs_jacobians` at a.
#[allow(clippy::type_complexity)]
fn reduced_jacobians<S, T, const N: usize, const K: usize>(
    sys: &S,
    q: &SVector<T, N>,
    form: &ReducedForm<T, N, K>,
    du: &SVector<T, K>,
    e: &SVector<T, N>,
    t: T,
) -> Result<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>), Error>
where
    S: Reduced<T, N, K>,
    T: Real,
{
    let v = &form.velocities;
    let accel = form.w * du + form.kappa;
    let z = form.rhs + e - form.full_mass * accel;
    let mu = form.rows_inverse.tr_mul(&z);
    let (jq, jv) = sys
        .rhs_jacobians(q, v, &accel, t)
        .ok_or(missing("Lagrangian::rhs_jacobians"))?;
    let (tq, sq, cv, rq) = sys
        .row_derivatives(q, v, &accel, &mu, t)
        .ok_or(missing("Reduced::row_derivatives"))?;
    let inv = dm(&form.rows_inverse);
    let w = dm(&form.w);
    let m = dm(&form.full_mass);
    let jq = dm(&jq);
    let jv = dm(&jv);
    let tq = dm(&tq);
    let sq = dm(&sq);
    let cv = dm(&cv);
    let rq = dm(&rq);
    let vq = -&inv * rq;
    let aq = &inv * (sq + &cv * &vq);
    let zq = jq + &jv * &vq - &m * aq;
    let wt = w.transpose();
    let dres = &wt * (zq - tq);
    let dforce = &wt * (jv - &m * &inv * cv) * &w;
    Ok((dres, dforce, vq))
}

/// X_q, X_v, X_u with δq̈ = X_q δq + X_v δq̇ + X_u δu: the saddle system solved
/// for the columns of the right-hand sides [R_q, R_v, B_u] (force rows) and
/// [∂(γ − G q̈)/∂q, ∂γ/∂q̇, 0] (constraint rows) at once.
fn sensitivities<T: Real, const N: usize, const K: usize>(
    saddle: &SaddleFactor<T, N, K>,
    [rq, rv, bu]: [&DMatrix<f64>; 3],
    [dga, dgv]: [&DMatrix<f64>; 2],
) -> [DMatrix<f64>; 3] {
    let p = bu.ncols();
    let mut f = DMatrix::zeros(N, 2 * N + p);
    f.view_mut((0, 0), (N, N)).copy_from(rq);
    f.view_mut((0, N), (N, N)).copy_from(rv);
    f.view_mut((0, 2 * N), (N, p)).copy_from(bu);
    let mut r = DMatrix::zeros(K, 2 * N + p);
    r.view_mut((0, 0), (K, N)).copy_from(dga);
    r.view_mut((0, N), (K, N)).copy_from(dgv);
    let (x, _) = saddle.solve(&f, &r);
    [
        x.columns(0, N).into_owned(),
        x.columns(N, N).into_owned(),
        x.columns(2 * N, p).into_owned(),
    ]
}
