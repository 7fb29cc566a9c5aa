//! Radau IIA of order 5 for stiff systems, following Hairer & Wanner's RADAU5
//! (*Solving ODEs II*, 2nd ed., §IV.8, and the Fortran code `radau5.f`).

mod linear;
mod step;

use super::run::Run;
use super::settings::{StepControl, step_control_builders};
use super::{Integrator, SecondOrder, check_orientations, check_problem};
use crate::error::SettingsError;
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::ode::{Continuation, Record, Trajectory};
use nalgebra::SVector;
use step::{Newton, State};

/// The 3-stage Radau IIA method (order 5, L-stable) with Hairer's RADAU5
/// machinery, applied to the first-order system y = (q, v), ẏ = (v, a(t,q,v)) of
/// dimension 2N:
///
/// - simplified Newton on the stage equations transformed by the eigenvectors of
///   A⁻¹, so that one real (γ/h − J) and one complex ((α + iβ)/h − J) system are
///   factorised per step instead of one of size 6N (the complex one is solved in
///   its real 4N × 4N form);
/// - the Jacobian J = [[0, I], [∂a/∂q, ∂a/∂v]] from [`SecondOrder::jacobian`]
///   when the system provides it, else by forward differences (2N evaluations of
///   a); it is reused across steps while the Newton iteration converges fast
///   (θ ≤ 0.001), and the factorisations too while h changes by less than 20 %;
/// - the error estimate filtered through (γ₀/h − J)⁻¹, so that it stays bounded
///   for stiff components, with the extra evaluation after a rejection;
/// - Gustafsson's predictive step-size controller, fac bounds 0.2..8, and the
///   Newton-based step reductions of `radau5.f`.
///
/// The tolerances are transformed as in `radau5.f` (rtol ← 0.1 rtol^(2/3)), and
/// the counters follow it: [`Stats::jacobians`](crate::Stats::jacobians) = NJAC, [`Stats::factorizations`](crate::Stats::factorizations)
/// = NDEC, [`Stats::accepted`](crate::Stats::accepted) = NACCPT, and [`Stats::steps`](crate::Stats::steps) = NSTEP (every
/// attempt, so [`Stats::rejected`](crate::Stats::rejected) includes the steps abandoned because Newton
/// converged too slowly, which Hairer's NREJCT does not). [`Stats::evaluations`](crate::Stats::evaluations)
/// counts NFCN plus the finite-difference Jacobian's evaluations.
///
/// The dense output is the cubic Hermite interpolant between accepted steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radau5 {
    control: StepControl,
    max_newton: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Default for Radau5 {
    /// rtol = atol = 1e-6.
    fn default() -> Self {
        Self::tol(1e-6)
    }
}

impl Radau5 {
    /// What the trajectory keeps of the steps (default: every step with its
    /// dense output); see [`Record`].
    pub fn record(mut self, record: Record) -> Self {
        self.record = record;
        self
    }

    /// Relative and absolute tolerance both equal to `tol`.
    pub fn tol(tol: f64) -> Self {
        Self::new(tol, tol)
    }

    /// Relative tolerance `rtol` and absolute tolerance `atol` (as given to
    /// `radau5.f`, before its internal transformation).
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            record: Record::Steps,
            control: StepControl::new(rtol, atol),
            max_newton: 7,
        }
    }

    step_control_builders!("1e-6, as in `radau5.f`");

    /// Sets the Newton iterations allowed per attempt (NIT, default 7).
    pub fn max_newton(mut self, n: usize) -> Self {
        self.max_newton = n;
        self
    }

    fn validate(&self) -> Result<(), Error> {
        self.control.validate("RADAU5", 1e-15, true)?;
        if self.max_newton == 0 {
            let setting = "max_newton";
            return Err(SettingsError::ZeroCount {
                owner: "RADAU5",
                setting,
            }
            .into());
        }
        Ok(())
    }
}

/// The method's constants, as computed in `radau5.f`.
struct Constants<T> {
    c1: T,
    c2: T,
    c1m1: T,
    c2m1: T,
    c1mc2: T,
    dd: [T; 3],
    /// γ = 1/u1, and α, β of the complex eigenvalue, all already inverted.
    u1: T,
    alph: T,
    beta: T,
    t: [[T; 3]; 3],
    ti: [[T; 3]; 3],
}

#[allow(clippy::excessive_precision)]
fn constants<T: Real>() -> Constants<T> {
    let sq6 = 6f64.sqrt();
    let c1 = (4.0 - sq6) / 10.0;
    let c2 = (4.0 + sq6) / 10.0;
    let cbrt81 = 81f64.powf(1.0 / 3.0);
    let cbrt9 = 9f64.powf(1.0 / 3.0);
    let u1 = (6.0 + cbrt81 - cbrt9) / 30.0;
    let alph = (12.0 - cbrt81 + cbrt9) / 60.0;
    let beta = (cbrt81 + cbrt9) * 3f64.sqrt() / 60.0;
    let cno = alph * alph + beta * beta;
    let l = T::lit;
    Constants {
        c1: l(c1),
        c2: l(c2),
        c1m1: l(c1 - 1.0),
        c2m1: l(c2 - 1.0),
        c1mc2: l(c1 - c2),
        dd: [
            l(-(13.0 + 7.0 * sq6) / 3.0),
            l((-13.0 + 7.0 * sq6) / 3.0),
            l(-1.0 / 3.0),
        ],
        u1: l(1.0 / u1),
        alph: l(alph / cno),
        beta: l(beta / cno),
        t: [
            [
                l(9.1232394870892942792e-02),
                l(-0.14125529502095420843),
                l(-3.0029194105147424492e-02),
            ],
            [
                l(0.24171793270710701896),
                l(0.20412935229379993199),
                l(0.38294211275726193779),
            ],
            [l(0.96604818261509293619), l(1.0), l(0.0)],
        ],
        ti: [
            [
                l(4.3255798900631553510),
                l(0.33919925181580986954),
                l(0.54177053993587487119),
            ],
            [
                l(-4.1787185915519047273),
                l(-0.32768282076106238708),
                l(0.47662355450055045196),
            ],
            [
                l(-0.50287263494578687595),
                l(2.5719269498556054292),
                l(-0.59603920482822492497),
            ],
        ],
    }
}

impl Integrator for Radau5 {
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
        let outcome = self.run(rhs, (t0, t1), (q0, v0), &mut run);
        run.finish(outcome)
    }

    fn max_steps(&self) -> usize {
        self.control.max_steps
    }
}

impl Radau5 {
    /// Checks the settings and the problem, then steps from (q0, v0) at t0 to
    /// t1: each attempt prepares the iteration matrices, solves the stage
    /// equations by simplified Newton, estimates the error, and accepts or
    /// retries (the phases are in [`step`]).
    fn run<T: Real, const N: usize, const Q: usize, F: SecondOrder<T, N, Q>>(
        &self,
        rhs: &F,
        (t0, t1): (T, T),
        (q0, v0): (SVector<T, Q>, SVector<T, N>),
        run: &mut Run<T, N, Q>,
    ) -> Result<(), Error> {
        self.record.check_span(t0, t1, Q + N)?;
        self.validate()?;
        self.control.check_precision::<T>("RADAU5")?;
        check_problem(t0, t1, &q0, &v0)?;
        check_orientations(rhs, &q0)?;
        let mut state = State::new(self, rhs, (t0, t1), (q0, v0), &mut run.stats)?;
        loop {
            if !state.prepare(rhs, &mut run.stats)? {
                continue;
            }
            state.check_attempt(&run.stats)?;
            state.starting_values();
            let newt = match state.newton(rhs, &mut run.stats)? {
                Newton::Converged(newt) => newt,
                Newton::Slow(hhfac) => {
                    run.stats.rejected += 1;
                    state.retry(state.h * hhfac);
                    continue;
                }
                Newton::Failed => {
                    // Repeated failures shrink h until the underflow test
                    // reports them.
                    run.stats.rejected += 1;
                    state.retry(state.h * T::lit(0.5));
                    continue;
                }
            };
            let err = state.error(rhs, &mut run.stats)?;
            let proposal = state.proposal(err, newt);
            if err < T::one() {
                if state.accept(rhs, err, proposal, run)? {
                    return Ok(());
                }
            } else {
                run.stats.rejected += 1;
                let h = if state.first {
                    state.h * T::lit(0.1)
                } else {
                    proposal.1
                };
                state.retry(h);
            }
        }
    }
}
