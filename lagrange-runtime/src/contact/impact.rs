//! Impacts: Newton's restitution law on the contacts that meet at one
//! instant, solved as one impulse problem.
//!
//! The normal impulses Λ ≥ 0 change the velocities by M⁻¹ Nᵀ Λ; each
//! contact's normal speed afterwards must reach at least its target (−e times
//! the speed before for an impact, zero for a contact that closes or stays
//! closed), and a contact that pushes (Λ_i > 0) reaches exactly its target:
//! a linear complementarity problem in the few contacts involved, solved
//! exactly by trying their subsets (the contacts are few; with independent
//! normals N M⁻¹ Nᵀ is positive definite and the answer unique).
//!
//! Where a contact rubs (μ > 0 and a tangent row), Coulomb's cone bounds
//! its tangential impulse too, in Moreau's velocity form of the impact law,
//! the time stepper's (`coulomb`): sticking, the slip after is zero while
//! the impulse stays inside the cone; sliding, the impulse is on the cone
//! against the slip after. Nonsmooth Gauss–Seidel solves that problem to
//! round-off; an answer that would raise the kinetic energy is refused.

use super::coulomb::{Local, gauss_seidel};
use super::form::{ContactForm, has_tangent};
use crate::error::{ContactFault, Error};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::system::Contacts;
use nalgebra::{DMatrix, DVector, SVector};

/// More contacts meeting at one instant than the subsets can be tried for.
const MOST_SIMULTANEOUS: usize = 12;

/// The velocities after the impulses on the contacts `set`, each with its
/// target normal speed, at (t, q, v).
///
/// # Errors
/// [`ContactFault::NoImpulse`] when no subset solves the problem;
/// [`ContactFault::ImpactGainsEnergy`] when the answer would raise the
/// kinetic energy.
pub(crate) fn impulse<S: Contacts<T, N, Q>, T: Real, F, const N: usize, const Q: usize>(
    form: &ContactForm<'_, S, T, F>,
    set: &[(usize, T)],
    t: T,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
) -> Result<SVector<T, N>, Error> {
    let k = set.len();
    if k == 0 {
        return Ok(*v);
    }
    let fail = |fault| form.fault(set[0].0, t, q, fault);
    if k > MOST_SIMULTANEOUS {
        return Err(fail(ContactFault::NoImpulse));
    }
    let m = form.system.mass_matrix(q, t);
    let chol = Cholesky::new(m, form.singular).map_err(|_| fail(ContactFault::NoImpulse))?;
    let locals = frictional(form, set, (t, q, v), &chol)?;
    if locals.iter().any(|c| c.rows.len() > 1) {
        let after = with_friction(locals, v).ok_or_else(|| fail(ContactFault::NoImpulse))?;
        return kept_energy(form, (t, q, v), after, set[0].0);
    }
    // Frictionless: each contact's one row is its normal, with its response.
    let normals: Vec<SVector<T, N>> = locals.iter().map(|c| c.rows[0]).collect();
    let responses: Vec<SVector<T, N>> = locals.iter().map(|c| c.responses[0]).collect();
    let a = DMatrix::from_fn(k, k, |r, c| normals[r].dot(&responses[c]));
    // What each contact's speed lacks: target − speed before.
    let lack = DVector::from_fn(k, |r, _| set[r].1 - normals[r].dot(v));
    let scale = lack.amax().max(T::lit(f64::MIN_POSITIVE));
    let slack = T::lit(1e-12) * scale;
    let impulses = (0..1usize << k)
        .find_map(|subset| pushing(&a, &lack, subset, slack))
        .ok_or_else(|| fail(ContactFault::NoImpulse))?;
    let mut after = *v;
    for (c, response) in responses.iter().enumerate() {
        after += response * impulses[c];
    }
    kept_energy(form, (t, q, v), after, set[0].0)
}

/// `after`, unless it has more kinetic energy than `v` (beyond round-off).
fn kept_energy<S: Contacts<T, N, Q>, T: Real, F, const N: usize, const Q: usize>(
    form: &ContactForm<'_, S, T, F>,
    (t, q, v): (T, &SVector<T, Q>, &SVector<T, N>),
    after: SVector<T, N>,
    first: usize,
) -> Result<SVector<T, N>, Error> {
    let before_energy = form.system.kinetic_energy(q, v, t);
    let after_energy = form.system.kinetic_energy(q, &after, t);
    let allowance = T::lit(1e-12) * before_energy.abs() + T::lit(f64::MIN_POSITIVE);
    if after_energy > before_energy + allowance {
        let fault = ContactFault::ImpactGainsEnergy {
            before: before_energy.to_f64(),
            after: after_energy.to_f64(),
        };
        return Err(form.fault(first, t, q, fault));
    }
    Ok(after)
}

/// The contacts of `set` as Coulomb problems at the velocity level: the
/// normal row with the target as its bias (its speed after must reach the
/// target), and the tangent rows a contact with friction rubs along.
fn frictional<S: Contacts<T, N, Q>, T: Real, F, const N: usize, const Q: usize>(
    form: &ContactForm<'_, S, T, F>,
    set: &[(usize, T)],
    (t, q, v): (T, &SVector<T, Q>, &SVector<T, N>),
    chol: &Cholesky<T, N>,
) -> Result<Vec<Local<T, N>>, Error> {
    let mut locals = Vec::with_capacity(set.len());
    for &(i, target) in set {
        let r = form.rows(i, t, q, v)?;
        let mu = T::lit(form.laws[i].friction);
        let mut rows = vec![r.normal];
        let mut tangents = Vec::new();
        for (k, row) in r.tangents.iter().enumerate() {
            if mu > T::zero() && has_tangent(row) {
                rows.push(*row);
                tangents.push(k);
            }
        }
        let responses = rows.iter().map(|row| chol.solve(*row)).collect();
        locals.push(Local::new(i, (rows, tangents), responses, -target, mu));
    }
    Ok(locals)
}

/// The velocities after the frictional impulses (Newton's law on the
/// normals, Coulomb's cone on the impulses, the velocity form of Moreau's
/// impact law), by Gauss–Seidel to round-off; `None` when it does not
/// settle or a contact's problem has no answer.
fn with_friction<T: Real, const N: usize>(
    mut locals: Vec<Local<T, N>>,
    v: &SVector<T, N>,
) -> Option<SVector<T, N>> {
    let mut after = *v;
    let scale = T::one() + v.amax();
    let tolerance = T::lit(1e-13) * scale;
    gauss_seidel(&mut locals, &mut after, FRICTION_SWEEPS, tolerance).ok()?;
    Some(after)
}

/// The most Gauss–Seidel sweeps of a frictional impact.
const FRICTION_SWEEPS: usize = 10_000;

/// The impulses if the contacts in `subset` (a bit mask) push and reach their
/// targets while the others, not pushing, reach theirs or more; `None`
/// otherwise.
fn pushing<T: Real>(
    a: &DMatrix<T>,
    lack: &DVector<T>,
    subset: usize,
    slack: T,
) -> Option<DVector<T>> {
    let k = lack.len();
    let inside: Vec<usize> = (0..k).filter(|r| subset >> r & 1 == 1).collect();
    let mut impulses = DVector::zeros(k);
    if !inside.is_empty() {
        let sub = DMatrix::from_fn(inside.len(), inside.len(), |r, c| a[(inside[r], inside[c])]);
        let rhs = DVector::from_fn(inside.len(), |r, _| lack[inside[r]]);
        let solved = sub.lu().solve(&rhs)?;
        for (r, &i) in inside.iter().enumerate() {
            if !solved[r].is_finite() || solved[r] < T::zero() {
                return None;
            }
            impulses[i] = solved[r];
        }
    }
    let reached = a * &impulses - lack;
    (0..k)
        .all(|r| subset >> r & 1 == 1 || reached[r] >= -slack)
        .then_some(impulses)
}
