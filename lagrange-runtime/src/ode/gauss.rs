//! Gauss–Legendre collocation in (q, p): symplectic for any mass matrix M(q).

// Index loops mirror the block-matrix formulas they implement.
#![allow(clippy::needless_range_loop)]

use super::canonical::Canonical;
use super::run::{Run, fixed_steps};
use super::verlet::fixed_step_count;
use super::{
    DenseSegment, Integrator, Pair, SecondOrder, Stats, check_orientations, check_problem,
};
use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::abs;
use crate::numeric::lu::{lu_factor, lu_solve};
use crate::numeric::orientation;
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::{DMatrix, SVector};

/// Gauss–Legendre collocation with a fixed step: s = 2 stages (order 4, the
/// default) or s = 1 (the implicit midpoint rule, order 2).
///
/// The method is applied to Hamilton's equations in (q, p), p = ∂L/∂q̇,
/// q̇ = M(q)⁻¹(p − a), ṗ = ∂T/∂q + Q (see [`Mechanical`](super::Mechanical)), where it is
/// symplectic and symmetric for *any* configuration-dependent mass matrix: the
/// energy error of a conservative system stays bounded over very long runs, and
/// quadratic invariants (angular momentum) are conserved to round-off. Applied to
/// (q, q̇) instead it would not be symplectic unless M is constant.
///
/// With free orientations (quaternions in q, body-axis ω in v) each
/// quaternion u is a coordinate of its own with a four-number momentum P,
/// π = ½ Im(ū ⊗ P) the body angular momentum (the quaternion embedding of
/// Miller et al., 2002). There |u|² is a quadratic first integral, so the
/// quaternions stay unit to round-off without a projection, and the world
/// angular momentum of a torque-free system (a top's vertical and axial
/// momenta) is kept to round-off as well: the method is a symplectic
/// integrator on the rotation group.
///
/// The system must provide that form: [`SecondOrder::mechanical`] must return
/// `Some` — [`Dynamics`](crate::Dynamics) does when the system implements
/// [`Lagrangian::kinetic_gradient`](crate::Lagrangian::kinetic_gradient).
///
/// The stage equations are solved by simplified Newton with a finite-difference
/// Jacobian of (q̇, ṗ) evaluated once per step (2Q + 1 evaluations, counted in
/// [`Stats::jacobians`] and [`Stats::evaluations`]) and one LU factorisation of
/// the 2sQ × 2sQ iteration matrix per step, iterating until the correction
/// reaches round-off. Failure to converge within [`max_iterations`](Self::max_iterations)
/// is [`Error::NewtonFailure`], and so is an iterate where the dynamics are
/// not finite (the iteration diverging: a step too large). The dense output is the cubic Hermite
/// interpolant in (q, q̇, q̈).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gauss {
    h: f64,
    stages: usize,
    max_steps: usize,
    max_iterations: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Gauss {
    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// The 2-stage, order-4 method with step size `h`.
    pub fn step(h: f64) -> Self {
        Self {
            record: Record::Steps,
            h,
            stages: 2,
            max_steps: 10_000_000,
            max_iterations: 50,
        }
    }

    /// The implicit midpoint rule (1 stage, order 2) with step size `h`.
    pub fn midpoint(h: f64) -> Self {
        Self {
            record: Record::Steps,
            stages: 1,
            ..Self::step(h)
        }
    }

    /// Refuses spans that need more than `n` steps (default 10⁷), before starting.
    pub fn max_steps(mut self, n: usize) -> Self {
        self.max_steps = n;
        self
    }

    /// Newton iterations allowed per step (default 50).
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The step size.
    pub fn step_size(&self) -> f64 {
        self.h
    }

    /// The number of stages (1 or 2).
    pub fn stages(&self) -> usize {
        self.stages
    }
}

impl Integrator for Gauss {
    fn continue_run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        from: Continuation<T>,
        t0: T,
        t1: T,
        q0: SVector<T, Q>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N, Q>, Failure<Trajectory<T, N, Q>>> {
        let mut run = Run::of(self.record, from, rhs, t0, q0, v0);
        // Everything computed before a failure goes back with it.
        let outcome = self.run_stages(rhs, (t0, t1, q0, v0), &mut run);
        run.finish(outcome)
    }

    fn max_steps(&self) -> usize {
        self.max_steps
    }
}

impl Gauss {
    /// Checks the settings and runs the method with the chosen stages,
    /// recording into `run`.
    fn run_stages<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        (t0, t1, q0, v0): (T, T, SVector<T, Q>, SVector<T, N>),
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        check_problem(t0, t1, &q0, &v0)?;
        check_orientations(rhs, &q0)?;
        if self.max_iterations == 0 {
            let setting = "max_iterations";
            return Err(SettingsError::ZeroCount {
                owner: "Gauss",
                setting,
            }
            .into());
        }
        let n = fixed_step_count("Gauss", self.h, self.max_steps, t0, t1)?;
        let Some(mechanical) = rhs.mechanical() else {
            return Err(SettingsError::Unsupported {
                owner: "Gauss",
                needs: "the system in Hamilton's form (momentum, mass matrix and ∂T/∂q)".into(),
                remedy: "SecondOrder::mechanical returned None; choose another integrator".into(),
            }
            .into());
        };
        let mech = Canonical::new(mechanical, F::ORIENTATIONS);
        let mech = &mech;
        let s3 = 3f64.sqrt() / 6.0;
        match self.stages {
            1 => self.run(rhs, mech, (t0, t1, q0, v0), n, [[0.5]], [1.0], [0.5], run),
            2 => self.run(
                rhs,
                mech,
                (t0, t1, q0, v0),
                n,
                [[0.25, 0.25 - s3], [0.25 + s3, 0.25]],
                [0.5, 0.5],
                [0.5 - s3, 0.5 + s3],
                run,
            ),
            s => Err(SettingsError::Choice {
                owner: "Gauss",
                setting: "stages",
                value: s,
                allowed: "1 or 2",
            }
            .into()),
        }
    }
}

/// The workspace of one run: sized once, reused at every step.
struct Work<T: Real> {
    /// Jacobian of (q̇, Ṗ) with respect to (q, P), 2Q × 2Q.
    jac: DMatrix<T>,
    /// The LU factors of I − h A ⊗ J, 2sQ × 2sQ.
    lu: DMatrix<T>,
    pivots: Vec<usize>,
    /// Right-hand side and solution of the Newton system.
    b: Vec<T>,
}

/// The Newton iteration matrix I − h A ⊗ J of the stage equations, into
/// `work.lu` (from the Jacobian in `work.jac`).
fn iteration_matrix<T: Real, const S: usize>(h: T, a: &[[T; S]; S], work: &mut Work<T>) {
    let dim = work.jac.nrows();
    for i in 0..S {
        for j in 0..S {
            for r in 0..dim {
                for col in 0..dim {
                    let delta = if i == j && r == col {
                        T::one()
                    } else {
                        T::zero()
                    };
                    work.lu[(i * dim + r, j * dim + col)] =
                        delta - h * a[i][j] * work.jac[(r, col)];
                }
            }
        }
    }
}

/// z0 + h Σ_j b_j F_j, added one stage at a time.
fn update<T: Real, const N: usize, const Q: usize, const S: usize>(
    z0: &Pair<T, N, Q>,
    h: T,
    b: &[T; S],
    fs: &[Pair<T, N, Q>; S],
) -> Pair<T, N, Q> {
    let mut z1 = *z0;
    for j in 0..S {
        z1 = z1.add_combination(h, [b[j]], [&fs[j]]);
    }
    z1
}

/// Component k of the 2Q vector (q, P) stored as a pair.
#[inline]
fn get<T: Real, const N: usize, const Q: usize>(z: &Pair<T, N, Q>, k: usize) -> T {
    if k < Q { z.q[k] } else { z.v[k - Q] }
}

#[inline]
fn get_mut<T: Real, const N: usize, const Q: usize>(z: &mut Pair<T, N, Q>, k: usize) -> &mut T {
    if k < Q { &mut z.q[k] } else { &mut z.v[k - Q] }
}

/// The Newton right-hand side −G = h Σ_j a_ij F_j − Z_i, stage after stage.
fn newton_rhs<T: Real, const Q: usize, const S: usize>(
    h: T,
    a: &[[T; S]; S],
    fs: &[Pair<T, Q, Q>; S],
    zs: &[Pair<T, Q, Q>; S],
    out: &mut [T],
) {
    let dim = 2 * Q;
    for i in 0..S {
        for r in 0..dim {
            let mut s = T::zero();
            for j in 0..S {
                s += a[i][j] * get(&fs[j], r);
            }
            out[i * dim + r] = h * s - get(&zs[i], r);
        }
    }
}

/// (q̇, Ṗ) at the canonical state z = (q, P), counting one evaluation. A
/// non-finite value is reported as such at the step's start (the system's
/// NaN, a force that overflows); at a Newton iterate the iteration reads it
/// as divergence.
fn hamilton<T: Real, const N: usize, const Q: usize>(
    mech: &Canonical<'_, T, N, Q>,
    t: T,
    z: &Pair<T, Q, Q>,
    evaluations: &mut usize,
) -> Result<Pair<T, Q, Q>, Error> {
    *evaluations += 1;
    let field = mech.field(t, &z.q, &z.v)?;
    let f = Pair::new(field.q_rate, field.p_rate);
    if !f.is_finite() {
        return Err(Error::non_finite(t, &z.q, &field.velocity));
    }
    Ok(f)
}

impl Gauss {
    #[allow(clippy::too_many_arguments)]
    fn run<T: Real, const N: usize, const Q: usize, const S: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        mech: &Canonical<'_, T, N, Q>,
        (t0, t1, q0, v0): (T, T, SVector<T, Q>, SVector<T, N>),
        n: usize,
        a: [[f64; S]; S],
        b: [f64; S],
        c: [f64; S],
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        let a = a.map(|r| r.map(T::lit));
        let b = b.map(T::lit);
        let c = c.map(T::lit);
        let dim = 2 * Q;
        let mut work = Work {
            jac: DMatrix::zeros(dim, dim),
            lu: DMatrix::zeros(S * dim, S * dim),
            pivots: vec![0; S * dim],
            b: vec![T::zero(); S * dim],
        };
        let h = T::lit(self.h);
        let mut q = q0;
        let mut v = v0;
        // Started on the unit sphere (within the tolerance the start was
        // checked to), the method keeps it there.
        orientation::normalise(F::ORIENTATIONS, q.as_mut_slice());
        // The canonical state: its quaternions are kept unit by the method
        // itself, so the step goes on from (q, P) as the method left them.
        let mut z = Pair::new(q, mech.momentum(t0, &q, &v)?);
        let stats = &mut run.stats;
        stats.evaluations += 1;
        let mut acc = rhs.acceleration(t0, &q, &v)?;
        run.traj.reserve(n);
        for (t, t_next) in fixed_steps(t0, t1, h, n) {
            let stats = &mut run.stats;
            let hk = t_next - t;
            let z1 = self.advance(mech, t, hk, &z, &a, &b, &c, &mut work, stats)?;
            let mut q1 = z1.q;
            let mut v1 = mech.velocity(t_next, &z1.q, &z1.v)?;
            stats.evaluations += 1;
            let mut acc1 = rhs.acceleration(t_next, &q1, &v1)?;
            let segment = DenseSegment::hermite(
                t,
                t_next,
                &Pair::new(q, v),
                &Pair::new(rhs.rate(&q, &v), acc),
                &Pair::new(q1, v1),
                &Pair::new(rhs.rate(&q1, &v1), acc1),
            );
            z = z1;
            // No normalisation: |u|² is a first integral the method keeps,
            // and the recorded unit error shows that it does.
            if rhs.project(t_next, &mut q1, &mut v1)? {
                z = Pair::new(q1, mech.momentum(t_next, &q1, &v1)?);
                stats.evaluations += 1;
                acc1 = rhs.acceleration(t_next, &q1, &v1)?;
            }
            let stop = run.record(rhs, segment, q1, v1)?;
            run.stats.accepted += 1;
            (q, v, acc) = (q1, v1, acc1);
            if stop {
                break;
            }
        }
        Ok(())
    }

    /// One step from z0 = (q, p) at t: returns (q, p) at t + h.
    #[allow(clippy::too_many_arguments)]
    fn advance<T: Real, const N: usize, const Q: usize, const S: usize>(
        &self,
        mech: &Canonical<'_, T, N, Q>,
        t: T,
        h: T,
        z0: &Pair<T, Q, Q>,
        a: &[[T; S]; S],
        b: &[T; S],
        c: &[T; S],
        work: &mut Work<T>,
        stats: &mut Stats,
    ) -> Result<Pair<T, Q, Q>, Error> {
        let dim = 2 * Q;
        let eps = T::default_epsilon();
        let f0 = hamilton(mech, t, z0, &mut stats.evaluations)?;
        self.jacobian(mech, t, z0, &f0, &mut work.jac, &mut stats.evaluations)?;
        stats.jacobians += 1;
        iteration_matrix(h, a, work);
        stats.factorizations += 1;
        if lu_factor(&mut work.lu, &mut work.pivots).is_err() {
            return Err(Error::NewtonFailure {
                t: t.to_f64(),
                h: h.to_f64(),
                iterations: 0,
            });
        }
        // Stage increments Z_i = z(t + c_i h) − z0, started on the tangent.
        let mut zs: [Pair<T, Q, Q>; S] = std::array::from_fn(|i| f0.scale(c[i] * h));
        let mut fs = [Pair::<T, Q, Q>::zeros(); S];
        let mut previous = T::max_value().unwrap_or(T::one() / eps);
        let iterations = 'iterate: {
            for iteration in 1..=self.max_iterations {
                for i in 0..S {
                    let zi = z0.add_combination(T::one(), [T::one()], [&zs[i]]);
                    // Finite at z0, not at an iterate: the iteration diverges.
                    fs[i] = match hamilton(mech, t + c[i] * h, &zi, &mut stats.evaluations) {
                        Err(Error::NonFiniteState { .. }) => break 'iterate iteration,
                        f => f?,
                    };
                }
                newton_rhs(h, a, &fs, &zs, &mut work.b);
                lu_solve(&work.lu, &work.pivots, &mut work.b);
                let mut size = T::zero();
                for i in 0..S {
                    for r in 0..dim {
                        let d = work.b[i * dim + r];
                        *get_mut(&mut zs[i], r) += d;
                        size = size.max(abs(d) / (T::one() + abs(get(z0, r))));
                    }
                }
                if !size.is_finite() {
                    break 'iterate iteration;
                }
                // Converged at round-off, or stagnating there (the correction no
                // longer shrinks although it is already tiny).
                let floor = T::lit(10.0) * eps;
                let stagnant = size >= previous && size <= T::lit(1e3) * eps;
                if size <= floor || stagnant {
                    // One more evaluation would only move the result by round-off:
                    // update with the stage derivatives of the last iterate.
                    return Ok(update(z0, h, b, &fs));
                }
                previous = size;
            }
            self.max_iterations
        };
        Err(Error::NewtonFailure {
            t: t.to_f64(),
            h: h.to_f64(),
            iterations,
        })
    }

    /// Forward-difference Jacobian of (q̇, Ṗ) at z0 (f0 = its value there), with
    /// Hairer's increment sqrt(ε · max(1e-5, |z_k|)).
    fn jacobian<T: Real, const N: usize, const Q: usize>(
        &self,
        mech: &Canonical<'_, T, N, Q>,
        t: T,
        z0: &Pair<T, Q, Q>,
        f0: &Pair<T, Q, Q>,
        jac: &mut DMatrix<T>,
        evaluations: &mut usize,
    ) -> Result<(), Error> {
        let eps = T::default_epsilon();
        for col in 0..2 * Q {
            let mut z = *z0;
            let zk = get(z0, col);
            let delta = (eps * T::lit(1e-5).max(abs(zk))).sqrt();
            *get_mut(&mut z, col) = zk + delta;
            let f = hamilton(mech, t, &z, evaluations)?;
            for r in 0..2 * Q {
                jac[(r, col)] = (get(&f, r) - get(f0, r)) / delta;
            }
        }
        Ok(())
    }
}
