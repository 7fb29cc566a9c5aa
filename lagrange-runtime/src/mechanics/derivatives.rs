//! ∂q̈/∂q and ∂q̈/∂q̇ from the system's right-hand-side Jacobians
//! ([`Lagrangian::rhs_jacobians`], `emit(jacobians)`): M⁻¹ J_q and M⁻¹ J_v,
//! and ∂q̈/∂τ = M⁻¹ from the same factorisation, on the stack (the
//! counterpart of Pinocchio's `computeABADerivatives`: `ddq_dq`, `ddq_dv`,
//! `Minv`).
//! With orientations the derivatives are in the tangent space: ∂/∂δ along
//! q ⊕ δ, an orientation's δ the rotation vector in body axes, at fixed ω.

use nalgebra::{SMatrix, SVector};

use super::dynamics::{Dynamics, all_finite};
use super::forcing::{Forcing, NoForcing};
use crate::error::{Error, check_finite_inputs};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::inverse::{product, spd_inverse};
pub use crate::system::AccelerationDerivatives;
use crate::system::{Driven, Lagrangian};

/// q̈ of a driven system at (q, q̇, u, t) and its derivatives: what one
/// stage of a discrete step needs, on the stack.
#[derive(Clone, Debug, PartialEq)]
pub struct InputDerivatives<T, const N: usize, const P: usize> {
    /// q̈ at the inputs u.
    pub acceleration: SVector<T, N>,
    /// ∂q̈/∂q, the inputs' own dependence on q included.
    pub dq: SMatrix<T, N, N>,
    /// ∂q̈/∂q̇, the inputs' own dependence on q̇ included.
    pub dv: SMatrix<T, N, N>,
    /// ∂q̈/∂u = M⁻¹ ∂Q/∂u.
    pub du: SMatrix<T, N, P>,
}

/// A forcing's own Jacobians (∂ΔQ/∂δ, ∂ΔQ/∂q̇), N × N each.
pub type ForceJacobians<T, const N: usize> = (SMatrix<T, N, N>, SMatrix<T, N, N>);

impl<S, T, F> Dynamics<'_, S, T, F>
where
    T: Real,
{
    /// Refuses the pivot ratio of M's factorisation in an emitted program
    /// (at most 1, −1 for a pivot that is not finite) below the singular
    /// tolerance: [`Error::SingularMassMatrix`] at q as given, with M at its
    /// unit-quaternion form.
    fn check_pivots<const N: usize, const Q: usize>(
        &self,
        t: T,
        (q, unit): (&SVector<T, Q>, &SVector<T, Q>),
        ratio: T,
    ) -> Result<(), Error>
    where
        S: Lagrangian<T, N, Q>,
    {
        if ratio.is_finite() && ratio >= self.singular_tolerance() {
            return Ok(());
        }
        let m = self.system().mass_matrix(unit, t);
        let names = (&S::VELOCITIES[..], S::ATLAS);
        Err(Error::singular_mass(t, q, ratio, &m, names))
    }

    /// ∂q̈/∂δ, ∂q̈/∂q̇ and ∂q̈/∂τ at (q, v, t), with the forcing's own
    /// Jacobians (∂ΔQ/∂δ, ∂ΔQ/∂v) added when it has any; `Ok(None)` when the
    /// system does not emit its Jacobians. Where the system emits q̈ and its
    /// derivatives as one program ([`Differentiable`]) they come from it,
    /// at the forcing's τ, the forcing's Jacobians through its M⁻¹; else
    /// from M's Cholesky factorisation and [`Lagrangian::rhs_jacobians`].
    ///
    /// # Errors
    /// As [`acceleration`](Self::acceleration); [`Error::NonFiniteState`] for
    /// a non-finite derivative.
    pub fn acceleration_derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        forced: Option<ForceJacobians<T, N>>,
    ) -> Result<Option<AccelerationDerivatives<T, N>>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let d = match self.derivatives(t, q, v, forced)? {
            Some(Solved::Emitted(d)) => d,
            Some(Solved::Factorised(chol, acceleration, dq, dv)) => AccelerationDerivatives {
                acceleration,
                dq,
                dv,
                dtau: chol.solve_columns(SMatrix::identity()),
            },
            None => return Ok(None),
        };
        if !all_finite(d.dtau.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Some(d))
    }

    /// ∂q̈/∂δ and ∂q̈/∂q̇ alone: what a linearisation without inputs reads,
    /// without forming M⁻¹ where M is factorised at run time.
    ///
    /// # Errors
    /// As [`acceleration_derivatives`](Self::acceleration_derivatives).
    pub(crate) fn state_derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        forced: Option<ForceJacobians<T, N>>,
    ) -> Result<Option<ForceJacobians<T, N>>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        Ok(self.derivatives(t, q, v, forced)?.map(|found| match found {
            Solved::Emitted(d) => (d.dq, d.dv),
            Solved::Factorised(_, _, dq, dv) => (dq, dv),
        }))
    }

    /// q̈, M⁻¹ J_q and M⁻¹ J_v (the forcing's Jacobians added to J), by the
    /// emitted program where there is one, else by M's factorisation, which
    /// is handed back for M⁻¹.
    fn derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        forced: Option<ForceJacobians<T, N>>,
    ) -> Result<Option<Solved<T, N>>, Error>
    where
        S: Lagrangian<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (unit, tau) = self.checked(t, q, v)?;
        let found = match self.system().emitted_derivatives(&unit, v, &tau, t) {
            Some((mut d, ratio)) => {
                self.check_pivots(t, (q, &unit), ratio)?;
                if !all_finite(d.acceleration.as_slice()) {
                    return Err(Error::non_finite(t, q, v));
                }
                if let Some((fq, fv)) = forced {
                    d.dq += d.dtau * fq;
                    d.dv += d.dtau * fv;
                }
                Solved::Emitted(d)
            }
            None => {
                let (chol, accel) = self.factorised(t, &unit, v, tau)?;
                let Some((mut jq, mut jv)) = self.system().rhs_jacobians(&unit, v, &accel, t)
                else {
                    return Ok(None);
                };
                if let Some((fq, fv)) = forced {
                    jq += fq;
                    jv += fv;
                }
                let (dq, dv) = (chol.solve_columns(jq), chol.solve_columns(jv));
                Solved::Factorised(chol, accel, dq, dv)
            }
        };
        let (dq, dv) = match &found {
            Solved::Emitted(d) => (&d.dq, &d.dv),
            Solved::Factorised(_, _, dq, dv) => (dq, dv),
        };
        if !(all_finite(dq.as_slice()) && all_finite(dv.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Some(found))
    }
}

/// q̈ and its derivatives as [`Dynamics::derivatives`] found them.
enum Solved<T: Real, const N: usize> {
    /// From the emitted program, M⁻¹ among them.
    Emitted(AccelerationDerivatives<T, N>),
    /// From M's factorisation at run time: the factor, q̈, M⁻¹ J_q, M⁻¹ J_v.
    Factorised(
        Cholesky<T, N>,
        SVector<T, N>,
        SMatrix<T, N, N>,
        SMatrix<T, N, N>,
    ),
}

impl<S, T: Real> Dynamics<'_, S, T, NoForcing> {
    /// q̈ = M⁻¹(Q − h + ΔQ(u)) of a driven system at (q, q̇, u, t) and
    /// ∂q̈/∂q (with orientations ∂q̈/∂δ, along q ⊕ δ, the inputs' own
    /// Jacobians taken so by the derive), ∂q̈/∂q̇, ∂q̈/∂u: from the one
    /// program of q̈ and its derivatives where the system emits it
    /// ([`Differentiable`]: M factorised in it, its M⁻¹ applied to the
    /// inputs' Jacobians, [`Driven::input_jacobians`]), else from one
    /// factorisation of M and the emitted Jacobians
    /// ([`Lagrangian::rhs_jacobians`]); on the stack: nothing is allocated,
    /// named or checked beyond the state and the result (the parameters are
    /// not: check them once, before a loop). `Ok(None)` when the system
    /// does not emit its Jacobians (`emit(jacobians)`).
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a non-finite state or result,
    /// [`Error::NonFiniteInput`] for a non-finite u,
    /// [`Error::SingularMassMatrix`] below the singular tolerance.
    pub fn input_derivatives<const N: usize, const P: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
    ) -> Result<Option<InputDerivatives<T, N, P>>, Error>
    where
        S: Driven<T, N, P, Q>,
    {
        check_finite_inputs(&S::INPUTS, t, q, v, u)?;
        let (unit, _) = self.checked(t, q, v)?;
        let system = self.system();
        let tau = system.input_forces(&unit, v, u, t);
        let (bu, fq, fv) = system.input_jacobians(&unit, v, u, t);
        let d = if let Some((d, ratio)) = system.emitted_derivatives(&unit, v, &tau, t) {
            // The one program (M factorised in it): ∂q̈/∂(q, q̇) at fixed τ,
            // and M⁻¹ for the inputs' own Jacobians.
            self.check_pivots(t, (q, &unit), ratio)?;
            // Inputs that are forces on coordinates (∂Q/∂u = I, no
            // dependence on the state, an arm's torques) leave the program's
            // blocks as they are: the products by 0 and I are skipped.
            let zero = |f: &SMatrix<T, N, N>| f.iter().all(|x| *x == T::zero());
            InputDerivatives {
                acceleration: d.acceleration,
                dq: if zero(&fq) { d.dq } else { d.dq + d.dtau * fq },
                dv: if zero(&fv) { d.dv } else { d.dv + d.dtau * fv },
                du: identity_or_product(&d.dtau, &bu),
            }
        } else {
            let (chol, acceleration) = self.factorised(t, &unit, v, tau)?;
            let Some((jq, jv)) = system.rhs_jacobians(&unit, v, &acceleration, t) else {
                return Ok(None);
            };
            InputDerivatives {
                acceleration,
                dq: chol.solve_columns(jq + fq),
                dv: chol.solve_columns(jv + fv),
                du: chol.solve_columns(bu),
            }
        };
        let parts = [
            d.acceleration.as_slice(),
            d.dq.as_slice(),
            d.dv.as_slice(),
            d.du.as_slice(),
        ];
        if !parts.iter().all(|p| all_finite(p)) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(Some(d))
    }
}

/// M⁻¹ ∂Q/∂u, which is M⁻¹ itself when ∂Q/∂u is the identity (P = N).
fn identity_or_product<T: Real, const N: usize, const P: usize>(
    inverse: &SMatrix<T, N, N>,
    bu: &SMatrix<T, N, P>,
) -> SMatrix<T, N, P> {
    let identity = P == N
        && (0..N).all(|j| (0..N).all(|i| bu[(i, j)] == if i == j { T::one() } else { T::zero() }));
    match identity {
        true => SMatrix::from_fn(|i, j| inverse[(i, j)]),
        false => inverse * bu,
    }
}

/// A system whose derive emitted q̈ and its derivatives as one program
/// (`emit(jacobians)` on a system without constraints): M, Q − h, M's
/// factorisation M = Lᵀ D L (in the tree's sparsity where M comes from a
/// kinematic tree), q̈ = M⁻¹(Q − h + τ), the right-hand side's Jacobians at
/// that q̈ and their solves, sharing their subexpressions. Where that
/// program would pass 8,000 operations (a seven-joint arm with general
/// axes, the Panda, Solo 12) and `emit(batched)` is not asked for, the derive
/// emits this trait as the emitted M, Q − h and Jacobians around M's
/// factorisation at run time instead (`factored_derivatives`), which
/// runs faster than so long a straight-line program. Read it through
/// [`acceleration_derivatives`], which checks the state and the result.
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not emit q̈ and its derivatives as one program",
    label = "needs `Differentiable`",
    note = "add `jacobians` to the description's `emit(...)`; it gives this trait to a system without constraints (with constraints, linearise through `Linearizer::constrained_tangent` or `Linearizer::reduced_tangent`, which read `emit(jacobians)`'s constraint derivatives)"
)]
pub trait Differentiable<T: Real, const N: usize, const Q: usize = N>: Lagrangian<T, N, Q> {
    /// q̈ and its derivatives at (q, v, τ, t), unchecked, with the ratio of
    /// M's smallest pivot to its largest ([`func::pivot_ratio`]: −1 where a
    /// pivot is not finite or none is positive).
    ///
    /// [`func::pivot_ratio`]: crate::func::pivot_ratio
    fn acceleration_derivatives_unchecked(
        &self,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: &SVector<T, N>,
        t: T,
    ) -> (AccelerationDerivatives<T, N>, T);
}

impl<S, T: Real> Dynamics<'_, S, T, NoForcing> {
    /// q̈ = M⁻¹(Q − h + τ), ∂q̈/∂δ, ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ at (q, v, τ, t)
    /// from the system's emitted program, checked.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] for a non-finite state or result,
    /// [`Error::NonFiniteInput`] for a non-finite τ (named by its velocity),
    /// [`Error::SingularMassMatrix`] when M's pivot ratio is below the
    /// singular tolerance.
    pub fn emitted_derivatives<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        tau: &SVector<T, N>,
    ) -> Result<AccelerationDerivatives<T, N>, Error>
    where
        S: Differentiable<T, N, Q>,
    {
        let (unit, _) = self.checked(t, q, v)?;
        check_finite_inputs(&S::VELOCITIES, t, q, v, tau)?;
        let (d, ratio) = self
            .system()
            .acceleration_derivatives_unchecked(&unit, v, tau, t);
        self.check_pivots(t, (q, &unit), ratio)?;
        let parts = [d.acceleration.as_slice(), d.dq.as_slice(), d.dv.as_slice()];
        if !(parts.iter().all(|p| all_finite(p)) && all_finite(d.dtau.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(d)
    }
}

/// q̈ = M⁻¹(Q − h + τ) of `sys` at (q, v, τ, t) and its derivatives ∂q̈/∂δ,
/// ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ (Pinocchio's `computeABADerivatives`: `ddq_dq`,
/// `ddq_dv`, `Minv`), from the program `emit(jacobians)` emits, with the
/// default singular tolerance. With orientations ∂q̈/∂δ is along q ⊕ δ, an
/// orientation's δ its rotation vector in body axes, at fixed ω.
///
/// # Errors
/// [`Error::NonFiniteState`], [`Error::NonFiniteInput`] (τ) or
/// [`Error::SingularMassMatrix`]; see [`Dynamics::emitted_derivatives`].
pub fn acceleration_derivatives<S, T, const N: usize, const Q: usize>(
    sys: &S,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
    tau: &SVector<T, N>,
    t: T,
) -> Result<AccelerationDerivatives<T, N>, Error>
where
    S: Differentiable<T, N, Q>,
    T: Real,
{
    Dynamics::<S, T, NoForcing>::new(sys).emitted_derivatives(t, q, v, tau)
}

/// q̈ = M⁻¹ b and its derivatives, with M factorised at run time: M = L D Lᵀ,
/// M⁻¹ = L⁻ᵀ D⁻¹ L⁻¹, q̈ = M⁻¹ b, then ∂q̈/∂δ = M⁻¹ J_q and ∂q̈/∂q̇ = M⁻¹ J_v
/// from the right-hand side's Jacobians at that q̈ (as `computeABADerivatives`
/// forms them from `Minv`). What `#[derive(Lagrangian)]` emits as
/// [`Differentiable`] where the one program of q̈ and its derivatives would
/// be long (the derive's `emit::output::solved` says how long): its solves
/// then run from a few hundred bytes of loops instead of thousands of
/// straight-line operations, which no instruction cache holds. Returns the
/// pivot ratio beside, min d / max d as the emitted programs give it (≤ 0
/// where M is not positive definite or not finite, and then every result
/// NaN, as when `jacobians` gives none: the checked readers refuse both).
#[doc(hidden)]
pub fn factored_derivatives<T: Real, const N: usize>(
    m: SMatrix<T, N, N>,
    b: SVector<T, N>,
    jacobians: impl FnOnce(&SVector<T, N>) -> Option<ForceJacobians<T, N>>,
) -> (AccelerationDerivatives<T, N>, T) {
    let not_a_number = T::zero() / T::zero();
    let nan = || SMatrix::<T, N, N>::from_element(not_a_number);
    let failed = |ratio: T| {
        let d = AccelerationDerivatives {
            acceleration: SVector::from_element(not_a_number),
            dq: nan(),
            dv: nan(),
            dtau: nan(),
        };
        (d, ratio)
    };
    let (dtau, ratio) = spd_inverse(&m);
    // Never NaN: −1 where a pivot is not finite.
    if ratio <= T::zero() {
        return failed(ratio);
    }
    // q̈ as M⁻¹ b, a sum of M⁻¹'s columns whose terms run side by side,
    // where two triangular solves are one long chain that ∂(Q − h) at q̈
    // waits for.
    let acceleration = product(&dtau, &b);
    let (jq, jv) = jacobians(&acceleration).unwrap_or_else(|| (nan(), nan()));
    let d = AccelerationDerivatives {
        acceleration,
        dq: product(&dtau, &jq),
        dv: product(&dtau, &jv),
        dtau,
    };
    (d, ratio)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    fn jacobians() -> ForceJacobians<f64, 3> {
        let jq = Matrix3::new(0.3, -1.0, 2.0, 0.0, 1.5, -0.2, 0.7, 0.1, -0.4);
        (jq, jq.transpose() * 0.5)
    }

    /// q̈ = M⁻¹ b, the Jacobians taken at that q̈ and multiplied by M⁻¹, which
    /// is symmetric to the bit; the pivot ratio positive.
    #[test]
    fn factored_derivatives_solve_with_m() {
        let m = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0);
        let b = Vector3::new(1.0, -2.0, 0.5);
        let inverse = m.try_inverse().unwrap();
        let mut seen = None;
        let (d, ratio) = factored_derivatives(m, b, |a| {
            seen = Some(*a);
            Some(jacobians())
        });
        let (jq, jv) = jacobians();
        assert!((d.acceleration - inverse * b).amax() < 1e-15);
        assert_eq!(seen, Some(d.acceleration), "the Jacobians at q̈");
        assert!((d.dq - inverse * jq).amax() < 1e-14);
        assert!((d.dv - inverse * jv).amax() < 1e-14);
        assert_eq!(d.dtau, d.dtau.transpose());
        assert!(ratio > 0.0 && ratio <= 1.0);
    }

    /// An M that is not positive definite gives a ratio of at most 0 and no
    /// numbers; Jacobians that are not there give none either, so the
    /// checked readers refuse both.
    #[test]
    fn factored_derivatives_refuse_what_they_cannot_solve() {
        let m = Matrix3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        let b = Vector3::new(1.0, 0.0, 0.0);
        let (d, ratio) = factored_derivatives(m, b, |_| Some(jacobians()));
        assert!(ratio <= 0.0, "{ratio}");
        assert!(
            d.acceleration
                .iter()
                .chain(d.dtau.iter())
                .all(|x| x.is_nan())
        );
        let m = Matrix3::identity();
        let (d, ratio) = factored_derivatives(m, b, |_| None);
        assert_eq!(ratio, 1.0);
        assert!(d.dq.iter().chain(d.dv.iter()).all(|x| x.is_nan()));
    }
}
