//! The equations of motion with a given set of contacts in force: each closed
//! contact a constraint on the acceleration, its force solved for with the
//! motion.
//!
//! With the contacts' rows J (normal rows, and the tangent rows of the
//! sticking ones) and the force columns W (the same rows, except that a
//! sliding contact's column is n − μ û·t, Coulomb's force −μ λ_n û riding on
//! its normal force), the accelerations solve
//! M q̈ = Q − h + W λ and J q̈ = −J̇ q̇. Eliminating q̈ leaves
//! (J M⁻¹ W) λ = −J̇ q̇ − J M⁻¹ (Q − h), a system of a few unknowns, square
//! but not symmetric when a contact slides, solved by LU with pivoting.
//! Dry friction has no normal unknown: sliding, its force −fc û·t is
//! known and joins Q; sticking, its tangent rows are constraints.

use crate::error::{ContactError, ContactFault, Error, to_vec};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::orientation::Orientation;
use crate::ode::SecondOrder;
use crate::system::{ContactLaw, ContactRows, Contacts};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};

/// What one contact does in the present stretch of motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Mode<T> {
    /// Apart (or touching without force): the gap is free.
    Open,
    /// In force and slipping: Coulomb's force opposes the slip, whose
    /// direction is `hint` (a unit vector in the tangent axes) while the slip
    /// speed is below the stick speed (just after it starts).
    Sliding { hint: [T; 2] },
    /// In force and not slipping: the tangent rows are constraints too.
    Sticking,
}

/// The contact forces and the accelerations at one state.
#[derive(Clone, Debug)]
pub(crate) struct Solution<T: Real, const N: usize> {
    pub accel: SVector<T, N>,
    /// λ_n per contact (zero for an open one).
    pub normal: Vec<T>,
    /// The tangential force per contact in the tangent axes: the sticking
    /// force, or Coulomb's sliding force.
    pub tangential: Vec<[T; 2]>,
    /// The effective normal compliance n M⁻¹ wᵀ of each sliding contact
    /// (zero for the others): not positive is Painlevé's paradox.
    pub compliance: Vec<T>,
}

/// One unknown force: contact `contact`'s normal force, or its tangent `k`.
#[derive(Clone, Copy)]
enum Unknown {
    Normal(usize),
    Tangent(usize, usize),
}

/// The unknown forces of the contacts in force, each with the row it
/// constrains, that row's bias and the force's column.
struct Unknowns<T: Real, const N: usize> {
    unknowns: Vec<Unknown>,
    rows: Vec<SVector<T, N>>,
    bias: Vec<T>,
    columns: Vec<SVector<T, N>>,
}

/// A system's dynamics with its contacts in the modes given, and the forces
/// of its inputs, if a source drives it (`F`, [`NoForcing`] otherwise).
pub(crate) struct ContactForm<'s, S, T: Real, F = NoForcing> {
    pub system: &'s S,
    pub forcing: &'s F,
    pub laws: &'s [ContactLaw],
    pub modes: Vec<Mode<T>>,
    pub singular: T,
    /// Below this slip speed a sliding contact's direction is its hint.
    pub stick_speed: T,
}

/// A tangent row counts when it is not a zero row (planar motion, stops).
pub(crate) fn has_tangent<T: Real, const N: usize>(row: &SVector<T, N>) -> bool {
    row.iter().any(|x| *x != T::zero())
}

impl<S, T: Real, F> ContactForm<'_, S, T, F> {
    /// The rows of contact `i`, or the error that the system gives none.
    pub fn rows<const N: usize, const Q: usize>(
        &self,
        i: usize,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<ContactRows<T, N>, Error>
    where
        S: Contacts<T, N, Q>,
    {
        self.system.contact_rows(i, q, v, t).ok_or_else(|| {
            self.fault(
                i,
                t,
                q,
                ContactFault::MissingRows {
                    laws: self.laws.len(),
                },
            )
        })
    }

    /// Contact `i`'s touch function where it is not the gap
    /// ([`Contacts::contact_approach`]).
    pub fn approach<const N: usize, const Q: usize>(
        &self,
        i: usize,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Option<T>
    where
        S: Contacts<T, N, Q>,
    {
        self.system.contact_approach(i, q, v, t)
    }

    /// A [`ContactError`] on contact `i`.
    pub fn fault<const Q: usize>(
        &self,
        i: usize,
        t: T,
        q: &SVector<T, Q>,
        fault: ContactFault,
    ) -> Error {
        Error::Contact(ContactError {
            contact: self.laws[i].name.to_string(),
            t: t.to_f64(),
            q: to_vec(q),
            fault,
        })
    }

    /// The slip velocity (t₁·q̇, t₂·q̇) of a contact.
    pub fn slip<const N: usize>(rows: &ContactRows<T, N>, v: &SVector<T, N>) -> [T; 2] {
        [rows.tangents[0].dot(v), rows.tangents[1].dot(v)]
    }

    /// The unit direction of a sliding contact's slip: the slip velocity's,
    /// or the hint while the slip is slower than the stick speed.
    pub fn slip_direction(&self, slip: [T; 2], hint: [T; 2]) -> [T; 2] {
        let speed = (slip[0] * slip[0] + slip[1] * slip[1]).sqrt();
        if speed > self.stick_speed {
            [slip[0] / speed, slip[1] / speed]
        } else {
            hint
        }
    }

    /// M⁻¹ by the stack Cholesky, or the singular mass matrix's error.
    pub fn factor<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        m: SMatrix<T, N, N>,
    ) -> Result<Cholesky<T, N>, Error> {
        Cholesky::new(m, self.singular).map_err(|ratio| Error::SingularMassMatrix {
            t: t.to_f64(),
            q: to_vec(q),
            ratio: ratio.to_f64(),
            direction: String::new(),
            atlas: false,
        })
    }

    /// M and Q − h at (t, q, v), with the inputs' forces.
    pub fn dynamics<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<(SMatrix<T, N, N>, SVector<T, N>), Error>
    where
        S: Contacts<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (m, mut rhs) = self.system.mass_matrix_and_rhs(q, v, t);
        if F::ACTIVE {
            rhs += self.forcing.force(t, q, v)?;
        }
        Ok((m, rhs))
    }

    /// The accelerations and the contact forces at (t, q, v).
    pub fn solve<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<Solution<T, N>, Error>
    where
        S: Contacts<T, N, Q>,
        F: Forcing<T, N, Q>,
    {
        let (m, mut rhs) = self.dynamics(t, q, v)?;
        let chol = self.factor(t, q, m)?;
        let count = self.laws.len();
        let Unknowns {
            unknowns,
            rows,
            bias,
            columns,
        } = self.unknowns(t, q, v, &mut rhs)?;
        let free = chol.solve(rhs);
        let mut solution = Solution {
            accel: free,
            normal: vec![T::zero(); count],
            tangential: vec![[T::zero(); 2]; count],
            compliance: vec![T::zero(); count],
        };
        let k = unknowns.len();
        if k == 0 {
            return Ok(solution);
        }
        let responses: Vec<SVector<T, N>> = columns.iter().map(|c| chol.solve(*c)).collect();
        let a = DMatrix::from_fn(k, k, |r, c| rows[r].dot(&responses[c]));
        let b = DVector::from_fn(k, |r, _| -bias[r] - rows[r].dot(&free));
        let first = match unknowns[0] {
            Unknown::Normal(i) | Unknown::Tangent(i, _) => i,
        };
        let lambda = a
            .clone()
            .lu()
            .solve(&b)
            .filter(|x| x.iter().all(|c| c.is_finite()))
            .ok_or_else(|| self.fault(first, t, q, ContactFault::NoConsistentMode))?;
        for (c, unknown) in unknowns.iter().enumerate() {
            solution.accel += responses[c] * lambda[c];
            match *unknown {
                Unknown::Normal(i) => {
                    solution.normal[i] = lambda[c];
                    solution.compliance[i] = a[(c, c)];
                }
                Unknown::Tangent(i, k) => solution.tangential[i][k] = lambda[c],
            }
        }
        self.sliding_forces(t, q, v, &mut solution)?;
        Ok(solution)
    }

    /// The unknown forces in the present modes; dry friction's sliding
    /// force, known, is added to `rhs` (Q − h) instead.
    fn unknowns<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        rhs: &mut SVector<T, N>,
    ) -> Result<Unknowns<T, N>, Error>
    where
        S: Contacts<T, N, Q>,
    {
        let mut out = Unknowns {
            unknowns: Vec::new(),
            rows: Vec::new(),
            bias: Vec::new(),
            columns: Vec::new(),
        };
        for (i, mode) in self.modes.iter().enumerate() {
            if *mode == Mode::Open {
                continue;
            }
            let r = self.rows(i, t, q, v)?;
            let slide = |hint| {
                let u = self.slip_direction(Self::slip(&r, v), hint);
                (r.tangents[0] * u[0] + r.tangents[1] * u[1]) * T::lit(self.laws[i].friction)
            };
            let dry = self.laws[i].is_dry_friction();
            match *mode {
                // A fixed bound: a known force against the slip, no unknown.
                Mode::Sliding { hint } if dry => *rhs -= slide(hint),
                Mode::Sliding { hint } => out.columns.push(r.normal - slide(hint)),
                _ if dry => {}
                _ => out.columns.push(r.normal),
            }
            if !dry {
                out.unknowns.push(Unknown::Normal(i));
                out.rows.push(r.normal);
                out.bias.push(r.normal_bias);
            }
            if *mode == Mode::Sticking {
                for k in (0..2).filter(|&k| has_tangent(&r.tangents[k])) {
                    out.unknowns.push(Unknown::Tangent(i, k));
                    out.rows.push(r.tangents[k]);
                    out.bias.push(r.tangent_bias[k]);
                    out.columns.push(r.tangents[k]);
                }
            }
        }
        Ok(out)
    }

    /// Coulomb's force −μ λ_n û of each sliding contact, in its tangent axes.
    fn sliding_forces<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        solution: &mut Solution<T, N>,
    ) -> Result<(), Error>
    where
        S: Contacts<T, N, Q>,
    {
        for (i, mode) in self.modes.iter().enumerate() {
            if let Mode::Sliding { hint } = *mode {
                let r = self.rows(i, t, q, v)?;
                let u = self.slip_direction(Self::slip(&r, v), hint);
                let f = -self.laws[i].friction_bound(solution.normal[i]);
                solution.tangential[i] = [f * u[0], f * u[1]];
            } else {
                solution.compliance[i] = T::zero();
            }
        }
        Ok(())
    }
}

impl<S: Contacts<T, N, Q>, T: Real, F: Forcing<T, N, Q>, const N: usize, const Q: usize>
    SecondOrder<T, N, Q> for ContactForm<'_, S, T, F>
{
    const ORIENTATIONS: &'static [Orientation] = S::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        let accel = self.solve(t, q, v)?.accel;
        if accel.iter().all(|a| a.is_finite()) {
            Ok(accel)
        } else {
            Err(Error::non_finite(t, q, v))
        }
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.system.integral(q, v, t)
    }
}
