//! Forward dynamics of a nonholonomic system in reduced form (independent speeds).
//!
//! The integrators carry (q, q̇), not (q, u): the reduced form then plugs into every
//! integrator unchanged, and trajectories look the same whichever form produced
//! them. The price is that a Runge–Kutta combination of q̇'s need not lie in the
//! image of W u + w when W depends on q, and [`SecondOrder::project`] rebuilds q̇
//! from its independent part after every step, which keeps
//! the velocity constraints at round-off (it reports a change, and so costs an
//! FSAL integrator an evaluation, only when q̇ moved by more than a few ulps).
//!
//! W and κ come from the stacked rows A = [U; G] solved at each state by
//! Gauss–Jordan elimination with complete pivoting (module `pivot`): the form
//! on your speeds ([`ReducedDynamics::form`], the linearisation, the initial
//! velocities) is finite wherever A is regular, and where it is not the
//! dependent rows are named ([`Error::ReducedFormBreakdown`]). Along the motion
//! the accelerations do not depend on which speeds complete the constraints,
//! so the solve and the projection use the velocities the constraints leave
//! free at each state (coordinate partitioning): they are finite wherever the
//! constraints are independent, and a speed that is nearly dependent on them
//! costs no digits.
//!
//! With free orientations (Q = N + 1 per orientation) q holds unit
//! quaternions and v their body-axis angular velocities: the rows and the
//! form are read in v, a stage off the unit sphere reads the rotation it is
//! closest to, and the integrators step the quaternions on the group
//! ([`SecondOrder::ORIENTATIONS`]); the projection rebuilds v only.

use crate::error::{Error, check_tolerance, to_vec};
use crate::mechanics::dynamics::{DEFAULT_SINGULAR_TOLERANCE, all_finite, on_sphere};
use crate::mechanics::{Forcing, NoForcing};
use crate::numeric::Real;
use crate::numeric::cholesky::Cholesky;
use crate::numeric::elimination::{Dependent, Partition, invert};
use crate::numeric::func::abs;
use crate::numeric::orientation::Orientation;
use crate::ode::SecondOrder;
use crate::system::Reduced;
use nalgebra::{SMatrix, SVector};

/// The forward dynamics of a [`Reduced`] system with K independent speeds:
/// u = speeds(q, q̇), M* u̇ = F* by Cholesky, q̈ = W u̇ + κ.
///
/// `F` is an extra generalized force ΔQ(t, q, q̇) (see
/// [`Dynamics`](crate::Dynamics) and [`with_forcing`](Self::with_forcing)),
/// projected onto the speeds: F* += Wᵀ ΔQ. The default [`NoForcing`] adds nothing.
#[derive(Debug)]
pub struct ReducedDynamics<'a, S, T, const K: usize, F = NoForcing> {
    system: &'a S,
    singular_tolerance: T,
    forcing: F,
    /// The system's parameter-only terms, if computed once for the run.
    terms: &'a [T],
}

// Manual impls: derive would demand `S: Clone`, but only a reference is held.
impl<S, T: Copy, const K: usize, F: Copy> Clone for ReducedDynamics<'_, S, T, K, F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, T: Copy, const K: usize, F: Copy> Copy for ReducedDynamics<'_, S, T, K, F> {}

impl<'a, S, T: Real, const K: usize> ReducedDynamics<'a, S, T, K> {
    /// Dynamics of `system` with the default singular tolerance (1e-12), unforced.
    pub fn new(system: &'a S) -> Self {
        Self {
            system,
            singular_tolerance: T::lit(DEFAULT_SINGULAR_TOLERANCE),
            forcing: NoForcing,
            terms: &[],
        }
    }
}

impl<'a, S, T: Real, const K: usize, F> ReducedDynamics<'a, S, T, K, F> {
    /// The same dynamics with the generalized force `forcing` added to Q − h, so
    /// that F* gains Wᵀ ΔQ (replacing any forcing set before).
    pub fn with_forcing<G>(self, forcing: G) -> ReducedDynamics<'a, S, T, K, G> {
        ReducedDynamics {
            system: self.system,
            singular_tolerance: self.singular_tolerance,
            forcing,
            terms: self.terms,
        }
    }

    /// The same dynamics reading the system's parameter-only terms from `terms`
    /// (see [`Dynamics::with_parameter_terms`](crate::Dynamics::with_parameter_terms)).
    pub fn with_parameter_terms<'b>(self, terms: &'b [T]) -> ReducedDynamics<'b, S, T, K, F>
    where
        'a: 'b,
    {
        // Shortening the borrow is a coercion (the dynamics only hold
        // references), so the rest of the settings carry over as they are.
        let shorter: ReducedDynamics<'b, S, T, K, F> = self;
        ReducedDynamics { terms, ..shorter }
    }

    /// The forcing in use.
    pub fn forcing(&self) -> &F {
        &self.forcing
    }

    /// Sets the threshold on the pivot ratio of M* below which it is reported as
    /// singular; a negative or non-finite one is refused
    /// ([`Error::Settings`]) at the first evaluation.
    pub fn with_singular_tolerance(mut self, tolerance: T) -> Self {
        self.singular_tolerance = tolerance;
        self
    }

    /// The system.
    pub fn system(&self) -> &'a S {
        self.system
    }

    /// The speed derivatives u̇ and the accelerations q̈ at (t, q, v).
    ///
    /// q̈ does not depend on which speeds complete the constraints, so the
    /// solve uses the best conditioned ones at q: the K velocities left free
    /// when the constraint rows are eliminated with complete pivoting
    /// (coordinate partitioning). Speeds that are dependent on the constraints
    /// at q, or nearly so, then cost neither finiteness nor digits, and u̇ is
    /// read back from A q̈ = (u̇, 0) + c.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] if the state, the system's terms or the result
    /// are not finite; [`Error::ReducedFormBreakdown`] if the constraint rows are
    /// dependent at q; [`Error::SingularMassMatrix`] if M* is not positive
    /// definite or its pivot ratio is below the singular tolerance; whatever the
    /// forcing reports (e.g. [`Error::NonFiniteInput`]).
    pub fn solve<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<(SVector<T, K>, SVector<T, N>), Error>
    where
        S: Reduced<T, N, K, Q>,
        F: Forcing<T, N, Q>,
    {
        check_state(t, q, v)?;
        // As in the other forms: a stage off the unit sphere reads the
        // rotation it is closest to.
        let unit = on_sphere::<S, T, N, Q>(q);
        let q = &unit;
        check_tolerance(
            "ReducedDynamics",
            "singular tolerance",
            self.singular_tolerance.to_f64(),
        )?;
        let rows = self.rows(t, q)?;
        let part = self.partition(t, q, &rows)?;
        let (mut form, rates) = self.partitioned_form(t, q, &rows, &part, v)?;
        if F::ACTIVE {
            form.force += form.w.tr_mul(&self.forcing.force(t, q, v)?);
        }
        if !all_finite(form.force.as_slice()) {
            return Err(Error::non_finite(t, q, v));
        }
        let dw = Cholesky::new(form.mass, self.singular_tolerance)
            // M* is in the independent speeds, which have no names here.
            .map_err(|ratio| Error::singular_mass(t, q, ratio, &form.mass, (&[], false)))?
            .solve(form.force);
        let a = form.w * dw + form.kappa;
        let du = (rows.a * a - rates).fixed_rows::<K>(0).into_owned();
        if !(all_finite(du.as_slice()) && all_finite(a.as_slice())) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok((du, a))
    }

    /// The reduced form at (t, q) with the speeds u: W, κ, q̇ = W u + w,
    /// M* and F* (without the forcing).
    ///
    /// # Errors
    /// [`Error::ReducedFormBreakdown`] if the stacked rows are dependent at q;
    /// [`Error::NonFiniteState`] if the system's terms are not finite.
    pub fn form<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        u: &SVector<T, K>,
    ) -> Result<ReducedForm<T, N, K>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        let unit = on_sphere::<S, T, N, Q>(q);
        let q = &unit;
        let rows = self.rows(t, q)?;
        let inverse = self.invert_rows(t, q, &rows.a)?;
        self.assemble(t, q, &rows, inverse, u)
    }

    /// q̇ = W u + w at (t, q): the velocities with the speeds u that satisfy
    /// the constraints.
    ///
    /// # Errors
    /// [`Error::ReducedFormBreakdown`] if the stacked rows are dependent at q;
    /// [`Error::NonFiniteState`] if they are not finite.
    pub fn velocities<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        u: &SVector<T, K>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        let unit = on_sphere::<S, T, N, Q>(q);
        let q = &unit;
        let rows = self.rows(t, q)?;
        let inverse = self.invert_rows(t, q, &rows.a)?;
        Ok(rows.velocities(&inverse, u))
    }

    /// The velocities that satisfy the constraints with the speeds of v:
    /// velocities(q, speeds(q, v)). Speeds the macro chose
    /// ([`Reduced::FREE_SPEEDS`]) give way, where the constraints fix them, to
    /// the velocities the constraints leave free at q; speeds you named do not.
    ///
    /// # Errors
    /// As [`velocities`](Self::velocities).
    pub fn consistent_velocities<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        self.projected(t, q, v, !S::FREE_SPEEDS)
    }

    /// v projected onto the constraints keeping its speeds (`keep_speeds`), or
    /// keeping the velocities the constraints leave free at q (see
    /// [`solve`](Self::solve)).
    fn projected<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
        keep_speeds: bool,
    ) -> Result<SVector<T, N>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        check_state(t, q, v)?;
        let unit = on_sphere::<S, T, N, Q>(q);
        let q = &unit;
        let rows = self.rows(t, q)?;
        if keep_speeds {
            let inverse = self.invert_rows(t, q, &rows.a)?;
            return Ok(rows.velocities(&inverse, &rows.speeds(v)));
        }
        let part = self.partition(t, q, &rows)?;
        let mut w = *v;
        part.complete(&mut w, &-rows.b);
        Ok(w)
    }

    /// The stacked rows at (t, q), checked finite.
    fn rows<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
    ) -> Result<Rows<T, N, K>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        let (a, b) = self.system.velocity_rows(q, t);
        if !(all_finite(a.as_slice()) && all_finite(b.as_slice())) {
            return Err(Error::non_finite(t, q, &SVector::<T, N>::zeros()));
        }
        Ok(Rows { a, b })
    }

    /// A⁻¹, or the breakdown naming the dependent rows.
    fn invert_rows<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        a: &SMatrix<T, N, N>,
    ) -> Result<SMatrix<T, N, N>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        invert(a, self.singular_tolerance).map_err(|d| self.breakdown(t, q, d))
    }

    /// The constraint rows eliminated with complete pivoting: which K
    /// velocities they leave free at q, and the others in terms of those.
    fn partition<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        rows: &Rows<T, N, K>,
    ) -> Result<Partition<T, N>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        Partition::new(&rows.a, K..N, self.singular_tolerance).map_err(|d| self.breakdown(t, q, d))
    }

    /// The reduced form on the free velocities of the partition: q̇ keeps the
    /// free velocities of v, W spans the constraints' null space with a unit
    /// entry per free velocity, κ solves G κ = γ with its free entries zero.
    /// Also returns the system's rates c (all rows) at q̇.
    fn partitioned_form<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        rows: &Rows<T, N, K>,
        part: &Partition<T, N>,
        v: &SVector<T, N>,
    ) -> Result<(Partitioned<T, N, K>, SVector<T, N>), Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        let mut velocities = *v;
        part.complete(&mut velocities, &-rows.b);
        let (mass, rhs) = self
            .system
            .mass_matrix_and_rhs_with(self.terms, q, &velocities, t);
        let rates = self.system.row_rates(q, &velocities, t);
        if !(all_finite(mass.as_slice())
            && all_finite(rhs.as_slice())
            && all_finite(rates.as_slice()))
        {
            return Err(Error::non_finite(t, q, &velocities));
        }
        let w: SMatrix<T, N, K> = part.basis();
        let mut kappa = SVector::<T, N>::zeros();
        part.complete(&mut kappa, &rates);
        let mw = mass * w;
        let form = Partitioned {
            force: w.tr_mul(&(rhs - mass * kappa)),
            mass: w.tr_mul(&mw),
            w,
            kappa,
        };
        Ok((form, rates))
    }

    /// W, κ, q̇, M* and F* from the inverted rows at the speeds u.
    fn assemble<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        rows: &Rows<T, N, K>,
        inverse: SMatrix<T, N, N>,
        u: &SVector<T, K>,
    ) -> Result<ReducedForm<T, N, K>, Error>
    where
        S: Reduced<T, N, K, Q>,
    {
        let velocities = rows.velocities(&inverse, u);
        let (mass, rhs) = self
            .system
            .mass_matrix_and_rhs_with(self.terms, q, &velocities, t);
        let rates = self.system.row_rates(q, &velocities, t);
        if !(all_finite(mass.as_slice())
            && all_finite(rhs.as_slice())
            && all_finite(rates.as_slice()))
        {
            return Err(Error::non_finite(t, q, &velocities));
        }
        let w: SMatrix<T, N, K> = inverse.fixed_columns::<K>(0).into_owned();
        let kappa = inverse * rates;
        let mw = mass * w;
        Ok(ReducedForm {
            speeds: *u,
            velocities,
            force: w.tr_mul(&(rhs - mass * kappa)),
            mass: w.tr_mul(&mw),
            w,
            kappa,
            rows_inverse: inverse,
            full_mass: mass,
            rhs,
        })
    }

    fn breakdown<const N: usize, const Q: usize>(
        &self,
        t: T,
        q: &SVector<T, Q>,
        d: Dependent,
    ) -> Error
    where
        S: Reduced<T, N, K, Q>,
    {
        Error::ReducedFormBreakdown {
            t: t.to_f64(),
            q: to_vec(q),
            coordinates: S::COORDINATES.to_vec(),
            rows: d.rows.iter().map(|&i| S::ROWS[i]).collect(),
            ratio: d.ratio,
        }
    }
}

/// A finite time and state, or the typed error.
fn check_state<T: Real, const N: usize, const Q: usize>(
    t: T,
    q: &SVector<T, Q>,
    v: &SVector<T, N>,
) -> Result<(), Error> {
    if t.is_finite() && all_finite(q.as_slice()) && all_finite(v.as_slice()) {
        Ok(())
    } else {
        Err(Error::non_finite(t, q, v))
    }
}

/// The reduced form on the free velocities of a partition (see `solve`).
struct Partitioned<T: Real, const N: usize, const K: usize> {
    w: SMatrix<T, N, K>,
    kappa: SVector<T, N>,
    mass: SMatrix<T, K, K>,
    force: SVector<T, K>,
}

/// Stacked velocity rows A q̇ + b = (u, 0).
struct Rows<T: Real, const N: usize, const K: usize> {
    a: SMatrix<T, N, N>,
    b: SVector<T, N>,
}

impl<T: Real, const N: usize, const K: usize> Rows<T, N, K> {
    /// u = (A v + b) in the first K rows.
    fn speeds(&self, v: &SVector<T, N>) -> SVector<T, K> {
        (self.a * v + self.b).fixed_rows::<K>(0).into_owned()
    }

    /// q̇ = A⁻¹ ((u, 0) − b).
    fn velocities(&self, inverse: &SMatrix<T, N, N>, u: &SVector<T, K>) -> SVector<T, N> {
        let mut target = -self.b;
        for (x, &ui) in target.iter_mut().zip(u.iter()) {
            *x += ui;
        }
        inverse * target
    }
}

/// The reduced form evaluated at one state (t, q, u), as
/// [`ReducedDynamics::form`] computes it.
#[derive(Clone, Copy, Debug)]
pub struct ReducedForm<T: Real, const N: usize, const K: usize> {
    /// The speeds u.
    pub speeds: SVector<T, K>,
    /// q̇ = W u + w.
    pub velocities: SVector<T, N>,
    /// W = A⁻¹[I; 0] (N × K).
    pub w: SMatrix<T, N, K>,
    /// κ = A⁻¹ c, so that q̈ = W u̇ + κ.
    pub kappa: SVector<T, N>,
    /// M* = Wᵀ M W.
    pub mass: SMatrix<T, K, K>,
    /// F* = Wᵀ (Q − h − M κ).
    pub force: SVector<T, K>,
    /// A⁻¹ of the stacked rows.
    pub rows_inverse: SMatrix<T, N, N>,
    /// M at (q, q̇).
    pub full_mass: SMatrix<T, N, N>,
    /// Q − h at (q, q̇).
    pub rhs: SVector<T, N>,
}

impl<S, T, F, const N: usize, const K: usize, const Q: usize> SecondOrder<T, N, Q>
    for ReducedDynamics<'_, S, T, K, F>
where
    S: Reduced<T, N, K, Q>,
    T: Real,
    F: Forcing<T, N, Q>,
{
    const ORIENTATIONS: &'static [Orientation] = S::ORIENTATIONS;

    fn acceleration(
        &self,
        t: T,
        q: &SVector<T, Q>,
        v: &SVector<T, N>,
    ) -> Result<SVector<T, N>, Error> {
        Ok(self.solve(t, q, v)?.1)
    }

    fn integral(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> T {
        self.system.integral(&on_sphere::<S, T, N, Q>(q), v, t)
    }

    /// No position constraints are kept (they are built into the coordinates);
    /// the velocity residual is the distance of v from the admissible velocities,
    /// max |v − velocities(q, speeds(q, v))|, zero exactly when the velocity
    /// constraints hold (for U W = I).
    ///
    /// States the trajectory records were accepted, so the rows were regular
    /// there; at a state where they are not, the residual is undefined (NaN).
    fn residuals(&self, t: T, q: &SVector<T, Q>, v: &SVector<T, N>) -> [T; 2] {
        match self.projected(t, q, v, false) {
            Ok(w) => [
                T::zero(),
                (w - v).iter().fold(T::zero(), |m, &x| m.max(abs(x))),
            ],
            Err(_) => [T::zero(), T::lit(f64::NAN)],
        }
    }

    fn project(&self, t: T, q: &mut SVector<T, Q>, v: &mut SVector<T, N>) -> Result<bool, Error> {
        // Along the motion any independent velocities serve, as in `solve`.
        let w = self.projected(t, q, v, false)?;
        // A round trip through the speeds moves an admissible v by a few ulps;
        // taking that as a change would cost FSAL integrators an evaluation per
        // step for nothing, so only a change beyond round-off counts.
        let scale = v.iter().fold(T::zero(), |m, &x| m.max(abs(x)));
        let change = (w - *v).iter().fold(T::zero(), |m, &x| m.max(abs(x)));
        if change <= T::lit(4.0) * T::default_epsilon() * scale {
            return Ok(false);
        }
        *v = w;
        Ok(true)
    }
}
