//! Dormand–Prince 8(5,3), following Hairer & Wanner's DOP853 (Hairer, Nørsett,
//! Wanner, *Solving ODEs I*, 2nd ed., §II.5 and §II.10, and the Fortran code
//! `dop853.f`).
//!
//! What is kept from DOP853: the 12-stage tableau of order 8, the error estimate
//! that combines the 5th-order and 3rd-order embedded differences
//!
//! ```text
//! err = |h| · ‖e₅‖² / sqrt(N (‖e₅‖² + 0.01 ‖e₃‖²))
//! ```
//!
//! (which behaves like an 8th-order estimate for small h yet stays robust when h
//! is large), the step-size controller with fac1 = 0.333, fac2 = 6, safe = 0.9,
//! β = 0 and exponent 1/8, the `hinit` starting step for order 8, the rule that a
//! step following a rejection may not grow, the "stretch the last step by up to
//! 1 %" rule, and the 7th-order continuous extension (three extra evaluations per
//! accepted step), and the stiffness test (every 1000 accepted steps, then at
//! every step while h·|λ| stays beyond 6.1; 15 times ends the run with
//! [`Error::ProbablyStiff`]). What is left out: per-component tolerances.

use super::controller::PiController;
use super::dopri5::hinit;
use super::settings::{StepControl, step_control_builders};
use super::{DenseSegment, Integrator, Pair, Sample, SecondOrder, Stats, check_problem};
use crate::error::{Error, Failure};
use crate::numeric::Real;
use crate::numeric::func::{abs, sqrt};
use crate::ode::{Record, Trajectory};
use nalgebra::SVector;

/// Adaptive Dormand–Prince 8(5,3) with dense output of order 7.
///
/// The method of choice for smooth problems at tight tolerances (1e-8 and
/// below), where it needs far fewer evaluations than [`Dopri5`](crate::Dopri5).
///
/// Evaluations per run: 1 at the start, 1 for the starting-step guess (unless
/// [`h0`](Self::h0) is given), 11 per attempted step, 1 per accepted step (the
/// derivative at the new point, reused as the next step's first stage) and 3 per
/// accepted step for the 7th-order dense output (none with
/// [`hermite_dense`](Self::hermite_dense)). Hairer's code reports the same count,
/// except that it counts the starting-step evaluation even when h0 is given.
///
/// ```
/// use lagrange_runtime::Dop853;
/// let method = Dop853::tol(1e-12).hmax(0.5).max_steps(1_000_000);
/// # let _ = method;
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dop853 {
    control: StepControl,
    dense7: bool,
    stiffness_test: usize,
    /// What the trajectory keeps of the steps.
    record: Record,
}

impl Default for Dop853 {
    /// rtol = atol = 1e-10.
    fn default() -> Self {
        Self::tol(1e-10)
    }
}

impl Dop853 {
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

    /// Relative tolerance `rtol` and absolute tolerance `atol`. A component is
    /// accurate enough when its local error is below atol + rtol·|y|.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            record: Record::Steps,
            control: StepControl::new(rtol, atol),
            dense7: true,
            stiffness_test: 1000,
        }
    }

    step_control_builders!("Hairer's `hinit` estimates it");

    /// Tests for stiffness every `n` accepted steps (Hairer's NSTIFF, default
    /// 1000); 0 switches the test off. A stiff problem then ends in
    /// [`Error::ProbablyStiff`], which names Radau5, instead of creeping to the
    /// step budget at the stability limit.
    pub fn stiffness_test(mut self, n: usize) -> Self {
        self.stiffness_test = n;
        self
    }

    /// Replaces the 7th-order continuous extension by the cubic Hermite
    /// interpolant, saving 3 of the 15 evaluations per accepted step when only
    /// the step end points matter (the dense output is then 3rd order).
    pub fn hermite_dense(mut self) -> Self {
        self.dense7 = false;
        self
    }

    fn validate(&self) -> Result<(), Error> {
        self.control.validate("DOP853", 0.0, false)
    }
}

/// The DOP853 tableau, its error weights and the dense-output coefficients, with
/// the digits of `dop853.f`.
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
mod tableau {
    pub const C: [f64; 16] = [
        0.0,
        0.526001519587677318785587544488e-01,
        0.789002279381515978178381316732e-01,
        0.118350341907227396726757197510e+00,
        0.281649658092772603273242802490e+00,
        0.333333333333333333333333333333e+00,
        0.25e+00,
        0.307692307692307692307692307692e+00,
        0.651282051282051282051282051282e+00,
        0.6e+00,
        0.857142857142857142857142857142e+00,
        1.0,
        1.0,
        0.1e+00,
        0.2e+00,
        0.777777777777777777777777777778e+00,
    ];

    // Stage rows; the stages they combine are named in the integrator loop.
    pub const A2: [f64; 1] = [5.26001519587677318785587544488e-2];
    pub const A3: [f64; 2] = [
        1.97250569845378994544595329183e-2,
        5.91751709536136983633785987549e-2,
    ];
    pub const A4: [f64; 2] = [
        2.95875854768068491816892993775e-2,
        8.87627564304205475450678981324e-2,
    ];
    pub const A5: [f64; 3] = [
        2.41365134159266685502369798665e-1,
        -8.84549479328286085344864962717e-1,
        9.24834003261792003115737966543e-1,
    ];
    pub const A6: [f64; 3] = [
        3.7037037037037037037037037037e-2,
        1.70828608729473871279604482173e-1,
        1.25467687566822425016691814123e-1,
    ];
    pub const A7: [f64; 4] = [
        3.7109375e-2,
        1.70252211019544039314978060272e-1,
        6.02165389804559606850219397283e-2,
        -1.7578125e-2,
    ];
    pub const A8: [f64; 5] = [
        3.70920001185047927108779319836e-2,
        1.70383925712239993810214054705e-1,
        1.07262030446373284651809199168e-1,
        -1.53194377486244017527936158236e-2,
        8.27378916381402288758473766002e-3,
    ];
    pub const A9: [f64; 6] = [
        6.24110958716075717114429577812e-1,
        -3.36089262944694129406857109825e0,
        -8.68219346841726006818189891453e-1,
        2.75920996994467083049415600797e1,
        2.01540675504778934086186788979e1,
        -4.34898841810699588477366255144e1,
    ];
    pub const A10: [f64; 7] = [
        4.77662536438264365890433908527e-1,
        -2.48811461997166764192642586468e0,
        -5.90290826836842996371446475743e-1,
        2.12300514481811942347288949897e1,
        1.52792336328824235832596922938e1,
        -3.32882109689848629194453265587e1,
        -2.03312017085086261358222928593e-2,
    ];
    pub const A11: [f64; 8] = [
        -9.3714243008598732571704021658e-1,
        5.18637242884406370830023853209e0,
        1.09143734899672957818500254654e0,
        -8.14978701074692612513997267357e0,
        -1.85200656599969598641566180701e1,
        2.27394870993505042818970056734e1,
        2.49360555267965238987089396762e0,
        -3.0467644718982195003823669022e0,
    ];
    pub const A12: [f64; 9] = [
        2.27331014751653820792359768449e0,
        -1.05344954667372501984066689879e1,
        -2.00087205822486249909675718444e0,
        -1.79589318631187989172765950534e1,
        2.79488845294199600508499808837e1,
        -2.85899827713502369474065508674e0,
        -8.87285693353062954433549289258e0,
        1.23605671757943030647266201528e1,
        6.43392746015763530355970484046e-1,
    ];
    /// The 8th-order weights on stages 1, 6..12.
    pub const B: [f64; 8] = [
        5.42937341165687622380535766363e-2,
        4.45031289275240888144113950566e0,
        1.89151789931450038304281599044e0,
        -5.8012039600105847814672114227e0,
        3.1116436695781989440891606237e-1,
        -1.52160949662516078556178806805e-1,
        2.01365400804030348374776537501e-1,
        4.47106157277725905176885569043e-2,
    ];
    /// The 3rd-order embedded weights on stages 1, 9, 12.
    pub const BHH: [f64; 3] = [
        0.244094488188976377952755905512e+00,
        0.733846688281611857341361741547e+00,
        0.220588235294117647058823529412e-01,
    ];
    /// The 5th-order error weights on stages 1, 6..12.
    pub const ER: [f64; 8] = [
        0.1312004499419488073250102996e-01,
        -0.1225156446376204440720569753e+01,
        -0.4957589496572501915214079952e+00,
        0.1664377182454986536961530415e+01,
        -0.3503288487499736816886487290e+00,
        0.3341791187130174790297318841e+00,
        0.8192320648511571246570742613e-01,
        -0.2235530786388629525884427845e-01,
    ];
    /// The three extra stages of the continuous extension.
    pub const A14: [f64; 8] = [
        5.61675022830479523392909219681e-2,
        2.53500210216624811088794765333e-1,
        -2.46239037470802489917441475441e-1,
        -1.24191423263816360469010140626e-1,
        1.5329179827876569731206322685e-1,
        8.20105229563468988491666602057e-3,
        7.56789766054569976138603589584e-3,
        -8.298e-3,
    ];
    pub const A15: [f64; 8] = [
        3.18346481635021405060768473261e-2,
        2.83009096723667755288322961402e-2,
        5.35419883074385676223797384372e-2,
        -5.49237485713909884646569340306e-2,
        -1.08347328697249322858509316994e-4,
        3.82571090835658412954920192323e-4,
        -3.40465008687404560802977114492e-4,
        1.41312443674632500278074618366e-1,
    ];
    pub const A16: [f64; 8] = [
        -4.28896301583791923408573538692e-1,
        -4.69762141536116384314449447206e0,
        7.68342119606259904184240953878e0,
        4.06898981839711007970213554331e0,
        3.56727187455281109270669543021e-1,
        -1.39902416515901462129418009734e-3,
        2.9475147891527723389556272149e0,
        -9.15095847217987001081870187138e0,
    ];
    /// Dense-output rows r₅..r₈ on stages 1, 6..16 (12 weights each).
    pub const D: [[f64; 12]; 4] = [
        [
            -0.84289382761090128651353491142e+01,
            0.56671495351937776962531783590e+00,
            -0.30689499459498916912797304727e+01,
            0.23846676565120698287728149680e+01,
            0.21170345824450282767155149946e+01,
            -0.87139158377797299206789907490e+00,
            0.22404374302607882758541771650e+01,
            0.63157877876946881815570249290e+00,
            -0.88990336451333310820698117400e-01,
            0.18148505520854727256656404962e+02,
            -0.91946323924783554000451984436e+01,
            -0.44360363875948939664310572000e+01,
        ],
        [
            0.10427508642579134603413151009e+02,
            0.24228349177525818288430175319e+03,
            0.16520045171727028198505394887e+03,
            -0.37454675472269020279518312152e+03,
            -0.22113666853125306036270938578e+02,
            0.77334326684722638389603898808e+01,
            -0.30674084731089398182061213626e+02,
            -0.93321305264302278729567221706e+01,
            0.15697238121770843886131091075e+02,
            -0.31139403219565177677282850411e+02,
            -0.93529243588444783865713862664e+01,
            0.35816841486394083752465898540e+02,
        ],
        [
            0.19985053242002433820987653617e+02,
            -0.38703730874935176555105901742e+03,
            -0.18917813819516756882830838328e+03,
            0.52780815920542364900561016686e+03,
            -0.11573902539959630126141871134e+02,
            0.68812326946963000169666922661e+01,
            -0.10006050966910838403183860980e+01,
            0.77771377980534432092869265740e+00,
            -0.27782057523535084065932004339e+01,
            -0.60196695231264120758267380846e+02,
            0.84320405506677161018159903784e+02,
            0.11992291136182789328035130030e+02,
        ],
        [
            -0.25693933462703749003312586129e+02,
            -0.15418974869023643374053993627e+03,
            -0.23152937917604549567536039109e+03,
            0.35763911791061412378285349910e+03,
            0.93405324183624310003907691704e+02,
            -0.37458323136451633156875139351e+02,
            0.10409964950896230045147246184e+03,
            0.29840293426660503123344363579e+02,
            -0.43533456590011143754432175058e+02,
            0.96324553959188282948394950600e+02,
            -0.39177261675615439165231486172e+02,
            -0.14972683625798562581422125276e+03,
        ],
    ];
}

/// The tableau converted once per run to the system's scalar.
struct Coefficients<T> {
    c: [T; 16],
    a2: [T; 1],
    a3: [T; 2],
    a4: [T; 2],
    a5: [T; 3],
    a6: [T; 3],
    a7: [T; 4],
    a8: [T; 5],
    a9: [T; 6],
    a10: [T; 7],
    a11: [T; 8],
    a12: [T; 9],
    b: [T; 8],
    bhh: [T; 3],
    er: [T; 8],
    a14: [T; 8],
    a15: [T; 8],
    a16: [T; 8],
    d: [[T; 12]; 4],
}

impl<T: Real> Coefficients<T> {
    fn new() -> Self {
        use tableau::*;
        fn lits<T: Real, const K: usize>(xs: [f64; K]) -> [T; K] {
            xs.map(T::lit)
        }
        Self {
            c: lits(C),
            a2: lits(A2),
            a3: lits(A3),
            a4: lits(A4),
            a5: lits(A5),
            a6: lits(A6),
            a7: lits(A7),
            a8: lits(A8),
            a9: lits(A9),
            a10: lits(A10),
            a11: lits(A11),
            a12: lits(A12),
            b: lits(B),
            bhh: lits(BHH),
            er: lits(ER),
            a14: lits(A14),
            a15: lits(A15),
            a16: lits(A16),
            d: D.map(lits),
        }
    }
}

impl Integrator for Dop853 {
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
            self.control.check_precision::<T>("DOP853")?;
            check_problem(t0, t1, &q0, &v0)?;
            let co = Coefficients::<T>::new();
            let (rtol, atol) = (T::lit(self.control.rtol), T::lit(self.control.atol));
            let hmax = self.control.hmax.map_or(t1 - t0, T::lit);
            let underflow = T::lit(16.0) * T::default_epsilon();
            let stretch = T::lit(1.01);

            let mut y = Pair::new(q0, v0);
            let mut k1 = y.derivative(rhs, t0, &mut stats.evaluations)?;
            let mut h = match self.control.h0 {
                Some(h0) => T::lit(h0).min(hmax),
                None => hinit(
                    rhs,
                    t0,
                    &y,
                    &k1,
                    hmax,
                    rtol,
                    atol,
                    8,
                    &mut stats.evaluations,
                )?,
            };
            let mut ctrl = PiController::<T>::dop853();
            let mut stiffness = super::StiffnessTest::new("DOP853", self.stiffness_test, 6.1);
            let mut t = t0;
            let mut reject = false;
            let c = co.c;
            loop {
                if stats.steps() >= self.control.max_steps {
                    return Err(Error::TooManySteps {
                        t: t.to_f64(),
                        max_steps: self.control.max_steps,
                    });
                }
                if h <= underflow * abs(t) || !h.is_finite() {
                    return Err(Error::StepSizeUnderflow {
                        t: t.to_f64(),
                        h: h.to_f64(),
                    });
                }
                let last = t + stretch * h - t1 > T::zero();
                if last {
                    h = t1 - t;
                }
                let t_new = if last { t1 } else { t + h };

                let ev = &mut stats.evaluations;
                let stages = (|| {
                    let stage =
                        |a: Pair<T, N>, ci: T, ev: &mut usize| a.derivative(rhs, t + ci * h, ev);
                    let k2 = stage(y.add_combination(h, co.a2, [&k1]), c[1], ev)?;
                    let k3 = stage(y.add_combination(h, co.a3, [&k1, &k2]), c[2], ev)?;
                    let k4 = stage(y.add_combination(h, co.a4, [&k1, &k3]), c[3], ev)?;
                    let k5 = stage(y.add_combination(h, co.a5, [&k1, &k3, &k4]), c[4], ev)?;
                    let k6 = stage(y.add_combination(h, co.a6, [&k1, &k4, &k5]), c[5], ev)?;
                    let k7 = stage(y.add_combination(h, co.a7, [&k1, &k4, &k5, &k6]), c[6], ev)?;
                    let k8 = stage(
                        y.add_combination(h, co.a8, [&k1, &k4, &k5, &k6, &k7]),
                        c[7],
                        ev,
                    )?;
                    let k9 = stage(
                        y.add_combination(h, co.a9, [&k1, &k4, &k5, &k6, &k7, &k8]),
                        c[8],
                        ev,
                    )?;
                    let k10 = stage(
                        y.add_combination(h, co.a10, [&k1, &k4, &k5, &k6, &k7, &k8, &k9]),
                        c[9],
                        ev,
                    )?;
                    let k11 = stage(
                        y.add_combination(h, co.a11, [&k1, &k4, &k5, &k6, &k7, &k8, &k9, &k10]),
                        c[10],
                        ev,
                    )?;
                    let y12 = y.add_combination(
                        h,
                        co.a12,
                        [&k1, &k4, &k5, &k6, &k7, &k8, &k9, &k10, &k11],
                    );
                    let k12 = y12.derivative(rhs, t_new, ev)?;
                    Ok::<_, Error>((k6, k7, k8, k9, k10, k11, y12, k12))
                })();
                let (k6, k7, k8, k9, k10, k11, y12, k12) = match stages {
                    Ok(k) => k,
                    Err(e) if e.is_state_dependent() => {
                        // A trial state the right-hand side cannot evaluate: reject and
                        // retry smaller (see `retry_smaller`).
                        let floor = underflow * abs(t).max(abs(t1 - t0));
                        h = super::dopri5::retry_smaller(h, floor, e)?;
                        reject = true;
                        stats.rejected += 1;
                        continue;
                    }
                    Err(e) => return Err(e),
                };
                let main = [&k1, &k6, &k7, &k8, &k9, &k10, &k11, &k12];
                // Σ b_i k_i, kept without the factor h for the 3rd-order estimate.
                let slope = Pair::combination(T::one(), co.b, main);
                let y_new = y.add_combination(h, [T::one()], [&slope]);
                let e5 = Pair::combination(T::one(), co.er, main);
                let e3 = slope.add_combination(-T::one(), co.bhh, [&k1, &k9, &k12]);
                let err = error_norm(h, &e5, &e3, &y, &y_new, atol, rtol);
                if err.partial_cmp(&T::zero()).is_none() {
                    // NaN (unordered): only a right-hand side that returns NaN without
                    // an error gets here.
                    return Err(Error::non_finite(t_new, &y_new.q, &y_new.v));
                }
                let mut h_new = ctrl.propose(h, err);
                if err <= T::one() {
                    ctrl.accept(err);
                    stats.accepted += 1;
                    let k13 = y_new.derivative(rhs, t_new, &mut stats.evaluations)?;
                    // The step is accepted: a stiffness verdict is reported after it
                    // is recorded, so the partial trajectory ends where the error says.
                    let stiff =
                        stiffness.check(stats.accepted, t_new, h, [&y_new, &y12, &k13, &k12]);
                    let segment = if self.dense7 {
                        let ks = [&k1, &k6, &k7, &k8, &k9, &k10, &k11, &k12];
                        self.dense(rhs, &co, t, h, &y, &y_new, ks, &k13, &mut stats)?
                    } else {
                        DenseSegment::hermite(t, t_new, &y, &k1, &y_new, &k13)
                    };
                    // As in DOPRI5: the dense output keeps the unprojected polynomial;
                    // the next first stage is re-evaluated at the projected state.
                    let (mut y_new, mut k13) = (y_new, k13);
                    if rhs.project(t_new, &mut y_new.q, &mut y_new.v)? {
                        k13 = y_new.derivative(rhs, t_new, &mut stats.evaluations)?;
                    }
                    let stop = rhs.after_step(&segment, &y_new.q, &y_new.v)?;
                    traj.push_sampled(segment, y_new.q, y_new.v, |t, q, v| {
                        Sample::of(rhs, t, q, v)
                    });
                    stiff?;
                    (t, y, k1) = (t_new, y_new, k13);
                    if last || stop {
                        break;
                    }
                    h_new = h_new.min(hmax);
                    if reject {
                        h_new = h_new.min(h);
                    }
                    reject = false;
                } else {
                    h_new = ctrl.reject(h);
                    reject = true;
                    stats.rejected += 1;
                }
                h = h_new;
            }
            Ok(())
        })();
        super::finish(traj, stats, started, outcome)
    }
}

impl Dop853 {
    /// The 7th-order continuous extension of an accepted step: three more stages
    /// (at 0.1, 0.2 and 7/9 of the step) and the coefficients r₁..r₈.
    #[allow(clippy::too_many_arguments)]
    fn dense<T: Real, const N: usize, F: SecondOrder<T, N>>(
        &self,
        rhs: &F,
        co: &Coefficients<T>,
        t: T,
        h: T,
        y: &Pair<T, N>,
        y_new: &Pair<T, N>,
        [k1, k6, k7, k8, k9, k10, k11, k12]: [&Pair<T, N>; 8],
        k13: &Pair<T, N>,
        stats: &mut Stats,
    ) -> Result<DenseSegment<T, N>, Error> {
        let ev = &mut stats.evaluations;
        let c = co.c;
        let k14 = y
            .add_combination(h, co.a14, [k1, k7, k8, k9, k10, k11, k12, k13])
            .derivative(rhs, t + c[13] * h, ev)?;
        let k15 = y
            .add_combination(h, co.a15, [k1, k6, k7, k8, k11, k12, k13, &k14])
            .derivative(rhs, t + c[14] * h, ev)?;
        let k16 = y
            .add_combination(h, co.a16, [k1, k6, k7, k8, k9, k13, &k14, &k15])
            .derivative(rhs, t + c[15] * h, ev)?;
        let (r1, r2, r3, r4) = DenseSegment::cubic_part(h, y, k1, y_new, k13);
        let ks = [k1, k6, k7, k8, k9, k10, k11, k12, k13, &k14, &k15, &k16];
        let [r5, r6, r7, r8] = co.d.map(|d| Pair::combination(h, d, ks));
        let t_new = t + h;
        Ok(DenseSegment::new(
            t,
            t_new,
            h,
            [r1, r2, r3, r4, r5, r6, r7, r8],
        ))
    }
}

/// DOP853's error norm: with sk = atol + rtol·max(|y|, |y_new|) over all 2N
/// components, s₅ = Σ (e₅/sk)², s₃ = Σ (e₃/sk)²,
/// err = |h| s₅ / sqrt(2N (s₅ + 0.01 s₃)).
fn error_norm<T: Real, const N: usize>(
    h: T,
    e5: &Pair<T, N>,
    e3: &Pair<T, N>,
    y: &Pair<T, N>,
    y_new: &Pair<T, N>,
    atol: T,
    rtol: T,
) -> T {
    let (mut s5, mut s3) = (T::zero(), T::zero());
    let parts = [
        (&e5.q, &e3.q, &y.q, &y_new.q),
        (&e5.v, &e3.v, &y.v, &y_new.v),
    ];
    for (e5, e3, y, y_new) in parts {
        for i in 0..N {
            let sk = atol + rtol * abs(y[i]).max(abs(y_new[i]));
            let (a, b) = (e5[i] / sk, e3[i] / sk);
            s5 += a * a;
            s3 += b * b;
        }
    }
    let mut deno = s5 + T::lit(0.01) * s3;
    if deno <= T::zero() {
        deno = T::one();
    }
    abs(h) * s5 * sqrt(T::one() / (deno * T::lit((2 * N) as f64)))
}
