//! Radau IIA of order 5 for stiff systems, following Hairer & Wanner's RADAU5
//! (*Solving ODEs II*, 2nd ed., §IV.8, and the Fortran code `radau5.f`).

// Index loops mirror the formulas of radau5.f, component by component.
#![allow(clippy::needless_range_loop)]

use super::settings::{StepControl, step_control_builders};
use super::{DenseSegment, Integrator, Pair, Sample, SecondOrder, Stats, check_problem};
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::numeric::lu::{lu_factor, lu_solve};
use crate::ode::{Record, Trajectory};
use nalgebra::{DMatrix, SVector};

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
/// the counters follow it: [`Stats::jacobians`] = NJAC, [`Stats::factorizations`]
/// = NDEC, [`Stats::accepted`] = NACCPT, and [`Stats::steps`] = NSTEP (every
/// attempt, so [`Stats::rejected`] includes the steps abandoned because Newton
/// converged too slowly, which Hairer's NREJCT does not). [`Stats::evaluations`]
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
            return Err(Error::InvalidSettings(
                "RADAU5: max_newton must be positive".into(),
            ));
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

/// Everything a run needs, sized once.
struct Work<T: Real> {
    n: usize,
    jac: DMatrix<T>,
    e1: DMatrix<T>,
    e2: DMatrix<T>,
    ip1: Vec<usize>,
    ip2: Vec<usize>,
    z: [Vec<T>; 3],
    f: [Vec<T>; 3],
    /// Solution of the complex system, real and imaginary parts stacked.
    c2: Vec<T>,
    cont: [Vec<T>; 3],
    scal: Vec<T>,
    tmp: Vec<T>,
}

fn to_pair<T: Real, const N: usize>(y: &[T]) -> Pair<T, N> {
    Pair::new(
        SVector::from_fn(|i, _| y[i]),
        SVector::from_fn(|i, _| y[N + i]),
    )
}

/// ẏ = (v, a) at (t, y) into `out`, counting one evaluation.
fn rhs_into<T: Real, const N: usize, F: SecondOrder<T, N>>(
    rhs: &F,
    t: T,
    y: &[T],
    out: &mut [T],
    evaluations: &mut usize,
) -> Result<(), Error> {
    *evaluations += 1;
    let p = to_pair::<T, N>(y);
    let a = rhs.acceleration(t, &p.q, &p.v)?;
    for i in 0..N {
        out[i] = p.v[i];
        out[N + i] = a[i];
    }
    Ok(())
}

impl Integrator for Radau5 {
    fn integrate<T: Real, const N: usize, F: SecondOrder<T, N>>(
        &self,
        rhs: &F,
        t0: T,
        t1: T,
        q0: SVector<T, N>,
        v0: SVector<T, N>,
    ) -> Result<Trajectory<T, N>, Failure<Trajectory<T, N>>> {
        let started = crate::numeric::clock::Stopwatch::start();
        let mut stats = Stats::default();
        let mut traj =
            Trajectory::start_recording(self.record, t0, q0, v0, Sample::of(rhs, t0, &q0, &v0));
        // Everything computed before a failure goes back with it.
        let outcome = (|| -> Result<(), Error> {
            self.record.check()?;
            self.validate()?;
            self.control.check_precision::<T>("RADAU5")?;
            check_problem(t0, t1, &q0, &v0)?;
            let k = constants::<T>();
            let n = 2 * N;
            let nv = |x: T| vec![x; n];
            let mut w = Work {
                n,
                jac: DMatrix::zeros(n, n),
                e1: DMatrix::zeros(n, n),
                e2: DMatrix::zeros(2 * n, 2 * n),
                ip1: vec![0; n],
                ip2: vec![0; 2 * n],
                z: [nv(T::zero()), nv(T::zero()), nv(T::zero())],
                f: [nv(T::zero()), nv(T::zero()), nv(T::zero())],
                c2: vec![T::zero(); 2 * n],
                cont: [nv(T::zero()), nv(T::zero()), nv(T::zero())],
                scal: nv(T::zero()),
                tmp: nv(T::zero()),
            };
            // radau5.f's tolerance transformation and Newton stopping criterion.
            let uround = T::default_epsilon();
            let rtol_t = 0.1 * self.control.rtol.powf(2.0 / 3.0);
            let (rtol, atol) = (
                T::lit(rtol_t),
                T::lit(rtol_t * self.control.atol / self.control.rtol),
            );
            let fnewt = (T::lit(10.0) * uround / rtol).max(T::lit(0.03f64.min(rtol_t.sqrt())));
            let nit = self.max_newton;
            let safe = T::lit(0.9);
            let thet = T::lit(0.001);
            let (quot1, quot2) = (T::one(), T::lit(1.2));
            let (facl, facr) = (T::lit(5.0), T::lit(0.125));
            let cfac = safe * T::lit((1 + 2 * nit) as f64);

            let hmaxn = self.control.hmax.map_or(t1 - t0, T::lit).min(t1 - t0);
            let mut h = T::lit(self.control.h0.unwrap_or(1e-6)).min(hmaxn);
            let mut last = false;
            if t0 + h * T::lit(1.0001) - t1 >= T::zero() {
                h = t1 - t0;
                last = true;
            }
            let mut hold = h;
            let mut faccon = T::one();
            let (mut reject, mut first) = (false, true);
            // A state-dependent failure of the right-hand side inside a Newton iteration,
            // kept so that repeated failures down to underflow report it.
            let mut pending_error: Option<Error> = None;
            let mut t = t0;
            let mut y: Vec<T> = q0.iter().chain(v0.iter()).copied().collect();
            let set_scal = |scal: &mut [T], y: &[T]| {
                for i in 0..n {
                    scal[i] = atol + rtol * abs(y[i]);
                }
            };
            set_scal(&mut w.scal, &y);
            let mut y0 = nv(T::zero());
            rhs_into(rhs, t, &y, &mut y0, &mut stats.evaluations)?;
            let (mut hacc, mut erracc) = (h, T::lit(1e-2));
            let mut theta: T;

            // The goto structure of radau5.f as a small state machine: where the
            // next attempt starts.
            #[derive(PartialEq)]
            enum Entry {
                Jacobian,
                Factorise,
                Step,
            }
            let mut entry = Entry::Jacobian;
            let mut caljac = false;
            loop {
                if entry == Entry::Jacobian {
                    self.jacobian(rhs, t, &y, &y0, &mut w.jac, &mut stats)?;
                    stats.jacobians += 1;
                    caljac = true;
                    entry = Entry::Factorise;
                }
                let (fac1, alphn, betan) = (k.u1 / h, k.alph / h, k.beta / h);
                if entry == Entry::Factorise {
                    stats.factorizations += 1;
                    if !decompose(&mut w, fac1, alphn, betan) {
                        // Singular iteration matrix: halve the step (label 78).
                        h *= T::lit(0.5);
                        reject = true;
                        last = false;
                        entry = if caljac {
                            Entry::Factorise
                        } else {
                            Entry::Jacobian
                        };
                        if abs(h) <= abs(t) * uround {
                            return Err(Error::NewtonFailure {
                                t: t.to_f64(),
                                h: h.to_f64(),
                                iterations: 0,
                            });
                        }
                        continue;
                    }
                }
                // Label 30: a new attempt with the current factorisation.
                if stats.steps() >= self.control.max_steps {
                    return Err(too_many(t, self.control.max_steps));
                }
                if T::lit(0.1) * abs(h) <= abs(t) * uround || !h.is_finite() {
                    if let Some(e) = pending_error.take() {
                        return Err(e);
                    }
                    return Err(Error::StepSizeUnderflow {
                        t: t.to_f64(),
                        h: h.to_f64(),
                    });
                }
                let xph = t + h;
                // Starting values: zero, or the previous collocation polynomial
                // extrapolated.
                if first {
                    for s in 0..3 {
                        w.z[s].fill(T::zero());
                        w.f[s].fill(T::zero());
                    }
                } else {
                    let c3q = h / hold;
                    let cq = [k.c1 * c3q, k.c2 * c3q, c3q];
                    for i in 0..n {
                        let (ak1, ak2, ak3) = (w.cont[0][i], w.cont[1][i], w.cont[2][i]);
                        let zi = cq.map(|c| c * (ak1 + (c - k.c2m1) * (ak2 + (c - k.c1m1) * ak3)));
                        for s in 0..3 {
                            w.z[s][i] = zi[s];
                        }
                        for s in 0..3 {
                            w.f[s][i] =
                                k.ti[s][0] * zi[0] + k.ti[s][1] * zi[1] + k.ti[s][2] * zi[2];
                        }
                    }
                }
                // Simplified Newton.
                let mut newt = 0;
                faccon = faccon.max(uround).powf(T::lit(0.8));
                theta = abs(thet);
                let (mut dynold, mut thqold) = (T::zero(), T::zero());
                let mut stage_error: Option<Error> = None;
                let outcome = loop {
                    if newt >= nit {
                        break Newton::Failed;
                    }
                    let cs = [k.c1, k.c2, T::one()];
                    for s in 0..3 {
                        for i in 0..n {
                            w.tmp[i] = y[i] + w.z[s][i];
                        }
                        let ts = if s == 2 { xph } else { t + cs[s] * h };
                        let (tmp, zs) = (&w.tmp, &mut w.z[s]);
                        match rhs_into::<T, N, F>(rhs, ts, tmp, zs, &mut stats.evaluations) {
                            Ok(()) => {}
                            // A Newton iterate the right-hand side cannot evaluate (far
                            // off the solution) is a failed iteration, as in RADAU5's
                            // handling of a diverging Newton: halve the step. If the
                            // steps underflow, this error is the one reported.
                            Err(e) if e.is_state_dependent() => {
                                stage_error = Some(e);
                                break;
                            }
                            Err(e) => return Err(e),
                        }
                    }
                    if let Some(e) = stage_error.take() {
                        pending_error = Some(e);
                        break Newton::Failed;
                    }
                    for i in 0..n {
                        let a = [w.z[0][i], w.z[1][i], w.z[2][i]];
                        for s in 0..3 {
                            w.z[s][i] = k.ti[s][0] * a[0] + k.ti[s][1] * a[1] + k.ti[s][2] * a[2];
                        }
                    }
                    solve_stages(&mut w, fac1, alphn, betan);
                    newt += 1;
                    let mut dyno = T::zero();
                    for i in 0..n {
                        for s in 0..3 {
                            let r = w.z[s][i] / w.scal[i];
                            dyno += r * r;
                        }
                    }
                    dyno = sqrt(dyno / T::lit((3 * n) as f64));
                    if !dyno.is_finite() {
                        break Newton::Failed;
                    }
                    if newt > 1 && newt < nit {
                        let thq = dyno / dynold;
                        theta = if newt == 2 { thq } else { sqrt(thq * thqold) };
                        thqold = thq;
                        if theta < T::lit(0.99) {
                            faccon = theta / (T::one() - theta);
                            let dyth = faccon * dyno * theta.powi((nit - 1 - newt) as i32) / fnewt;
                            if dyth >= T::one() {
                                let qnewt = T::lit(1e-4).max(T::lit(20.0).min(dyth));
                                let expo = -T::one() / T::lit((4 + nit - 1 - newt) as f64);
                                break Newton::Slow(T::lit(0.8) * qnewt.powf(expo));
                            }
                        } else {
                            break Newton::Failed;
                        }
                    }
                    dynold = dyno.max(uround);
                    for i in 0..n {
                        let fi = [0, 1, 2].map(|s| w.f[s][i] + w.z[s][i]);
                        for s in 0..3 {
                            w.f[s][i] = fi[s];
                        }
                        for s in 0..3 {
                            w.z[s][i] = k.t[s][0] * fi[0] + k.t[s][1] * fi[1] + k.t[s][2] * fi[2];
                        }
                    }
                    if faccon * dyno <= fnewt {
                        break Newton::Converged;
                    }
                };
                match outcome {
                    Newton::Converged => {}
                    Newton::Slow(hhfac) => {
                        h *= hhfac;
                        reject = true;
                        last = false;
                        stats.rejected += 1;
                        entry = if caljac {
                            Entry::Factorise
                        } else {
                            Entry::Jacobian
                        };
                        continue;
                    }
                    Newton::Failed => {
                        h *= T::lit(0.5);
                        reject = true;
                        last = false;
                        stats.rejected += 1;
                        // Repeated failures shrink h until the underflow test
                        // reports them.
                        entry = if caljac {
                            Entry::Factorise
                        } else {
                            Entry::Jacobian
                        };
                        continue;
                    }
                }
                let err = estimate(rhs, &k, &mut w, t, h, &y, &y0, first || reject, &mut stats)?;
                let fac = safe.min(cfac / T::lit((newt + 2 * nit) as f64));
                let mut quot = facr.max(facl.min(err.powf(T::lit(0.25)) / fac));
                let mut hnew = h / quot;
                if err < T::one() {
                    first = false;
                    stats.accepted += 1;
                    pending_error = None;
                    if stats.accepted > 1 {
                        let facgus = (hacc / h) * (err * err / erracc).powf(T::lit(0.25)) / safe;
                        let facgus = facr.max(facl.min(facgus));
                        quot = quot.max(facgus);
                        hnew = h / quot;
                    }
                    hacc = h;
                    erracc = T::lit(1e-2).max(err);
                    hold = h;
                    let y_old = to_pair::<T, N>(&y);
                    let f_old = to_pair::<T, N>(&y0);
                    for i in 0..n {
                        y[i] += w.z[2][i];
                        let (z1, z2, z3) = (w.z[0][i], w.z[1][i], w.z[2][i]);
                        w.cont[0][i] = (z2 - z3) / k.c2m1;
                        let ak = (z1 - z2) / k.c1mc2;
                        let acont3 = (ak - z1 / k.c1) / k.c2;
                        w.cont[1][i] = (ak - w.cont[0][i]) / k.c1m1;
                        w.cont[2][i] = w.cont[1][i] - acont3;
                    }
                    let t_prev = t;
                    t = xph;
                    if last {
                        t = t1;
                    }
                    let mut p = to_pair::<T, N>(&y);
                    if !p.is_finite() {
                        return Err(Error::non_finite(t, &p.q, &p.v));
                    }
                    // The derivative at the new point: the next step's y0 and the
                    // Hermite end slope.
                    rhs_into::<T, N, F>(rhs, t, &y, &mut y0, &mut stats.evaluations)?;
                    let segment =
                        DenseSegment::hermite(t_prev, t, &y_old, &f_old, &p, &to_pair::<T, N>(&y0));
                    if rhs.project(t, &mut p.q, &mut p.v)? {
                        for i in 0..N {
                            y[i] = p.q[i];
                            y[N + i] = p.v[i];
                        }
                        rhs_into::<T, N, F>(rhs, t, &y, &mut y0, &mut stats.evaluations)?;
                    }
                    set_scal(&mut w.scal, &y);
                    let stop = rhs.after_step(&segment, &p.q, &p.v)?;
                    traj.push_sampled(segment, p.q, p.v, |t, q, v| Sample::of(rhs, t, q, v));
                    caljac = false;
                    if last || stop {
                        break;
                    }
                    hnew = hnew.min(hmaxn);
                    if reject {
                        hnew = hnew.min(h);
                    }
                    reject = false;
                    if t + hnew / quot1 - t1 >= T::zero() {
                        h = t1 - t;
                        last = true;
                    } else {
                        let qt = hnew / h;
                        if theta <= thet && qt >= quot1 && qt <= quot2 {
                            entry = Entry::Step;
                            continue;
                        }
                        h = hnew;
                    }
                    entry = if theta <= thet {
                        Entry::Factorise
                    } else {
                        Entry::Jacobian
                    };
                } else {
                    reject = true;
                    last = false;
                    stats.rejected += 1;
                    h = if first { h * T::lit(0.1) } else { hnew };
                    entry = if caljac {
                        Entry::Factorise
                    } else {
                        Entry::Jacobian
                    };
                }
            }
            Ok(())
        })();
        super::finish(traj, stats, started, outcome)
    }
}

enum Newton<T> {
    Converged,
    /// Converging too slowly: retry with h multiplied by this factor.
    Slow(T),
    /// Diverging or out of iterations: retry with h / 2.
    Failed,
}

fn too_many<T: Real>(t: T, max_steps: usize) -> Error {
    Error::TooManySteps {
        t: t.to_f64(),
        max_steps,
    }
}

impl Radau5 {
    /// J = ∂(v, a)/∂(q, v) at (t, y); `f0` = (v, a) there.
    fn jacobian<T: Real, const N: usize, F: SecondOrder<T, N>>(
        &self,
        rhs: &F,
        t: T,
        y: &[T],
        f0: &[T],
        jac: &mut DMatrix<T>,
        stats: &mut Stats,
    ) -> Result<(), Error> {
        jac.fill(T::zero());
        for i in 0..N {
            jac[(i, N + i)] = T::one();
        }
        let p = to_pair::<T, N>(y);
        if let Some(blocks) = rhs.jacobian(t, &p.q, &p.v) {
            let (aq, av) = blocks?;
            for i in 0..N {
                for j in 0..N {
                    jac[(N + i, j)] = aq[(i, j)];
                    jac[(N + i, N + j)] = av[(i, j)];
                }
            }
            return Ok(());
        }
        let eps = T::default_epsilon();
        for col in 0..2 * N {
            let mut pp = p;
            let x = if col < N {
                &mut pp.q[col]
            } else {
                &mut pp.v[col - N]
            };
            let delta = sqrt(eps * T::lit(1e-5).max(abs(*x)));
            *x += delta;
            stats.evaluations += 1;
            let a = rhs.acceleration(t, &pp.q, &pp.v)?;
            for i in 0..N {
                jac[(N + i, col)] = (a[i] - f0[N + i]) / delta;
            }
        }
        Ok(())
    }
}

/// Builds and factorises E1 = fac1·I − J and the real form of
/// E2 = (α + iβ)/h·I − J. False if either is singular.
fn decompose<T: Real>(w: &mut Work<T>, fac1: T, alphn: T, betan: T) -> bool {
    let n = w.n;
    for i in 0..n {
        for j in 0..n {
            let d = if i == j { T::one() } else { T::zero() };
            let jij = w.jac[(i, j)];
            w.e1[(i, j)] = fac1 * d - jij;
            let re = alphn * d - jij;
            w.e2[(i, j)] = re;
            w.e2[(n + i, n + j)] = re;
            w.e2[(i, n + j)] = -betan * d;
            w.e2[(n + i, j)] = betan * d;
        }
    }
    lu_factor(&mut w.e1, &mut w.ip1).is_ok() && lu_factor(&mut w.e2, &mut w.ip2).is_ok()
}

/// radau5.f's SLVRAD for M = I: the Newton corrections of the transformed
/// stages, in place in z.
fn solve_stages<T: Real>(w: &mut Work<T>, fac1: T, alphn: T, betan: T) {
    let n = w.n;
    for i in 0..n {
        let (s2, s3) = (-w.f[1][i], -w.f[2][i]);
        w.z[0][i] -= w.f[0][i] * fac1;
        w.z[1][i] += s2 * alphn - s3 * betan;
        w.z[2][i] += s3 * alphn + s2 * betan;
    }
    lu_solve(&w.e1, &w.ip1, &mut w.z[0]);
    for i in 0..n {
        w.c2[i] = w.z[1][i];
        w.c2[n + i] = w.z[2][i];
    }
    lu_solve(&w.e2, &w.ip2, &mut w.c2);
    for i in 0..n {
        w.z[1][i] = w.c2[i];
        w.z[2][i] = w.c2[n + i];
    }
}

/// radau5.f's ESTRAD for M = I: the embedded error filtered by (γ₀/h − J)⁻¹,
/// with one more filtered evaluation at the first step and after a rejection if
/// the estimate is ≥ 1.
#[allow(clippy::too_many_arguments)]
fn estimate<T: Real, const N: usize, F: SecondOrder<T, N>>(
    rhs: &F,
    k: &Constants<T>,
    w: &mut Work<T>,
    t: T,
    h: T,
    y: &[T],
    y0: &[T],
    again: bool,
    stats: &mut Stats,
) -> Result<T, Error> {
    let n = w.n;
    let hee = k.dd.map(|d| d / h);
    // f[1] holds the combination F2 of the Fortran code; tmp the filtered error.
    for i in 0..n {
        w.f[1][i] = hee[0] * w.z[0][i] + hee[1] * w.z[1][i] + hee[2] * w.z[2][i];
        w.tmp[i] = w.f[1][i] + y0[i];
    }
    lu_solve(&w.e1, &w.ip1, &mut w.tmp);
    let norm = |e: &[T], scal: &[T]| {
        let mut s = T::zero();
        for i in 0..n {
            let r = e[i] / scal[i];
            s += r * r;
        }
        sqrt(s / T::lit(n as f64)).max(T::lit(1e-10))
    };
    let mut err = norm(&w.tmp, &w.scal);
    if err >= T::one() && again {
        for i in 0..n {
            w.tmp[i] += y[i];
        }
        let (tmp, f0) = (&w.tmp, &mut w.f[0]);
        rhs_into::<T, N, F>(rhs, t, tmp, f0, &mut stats.evaluations)?;
        for i in 0..n {
            w.tmp[i] = w.f[0][i] + w.f[1][i];
        }
        lu_solve(&w.e1, &w.ip1, &mut w.tmp);
        err = norm(&w.tmp, &w.scal);
    }
    Ok(err)
}
