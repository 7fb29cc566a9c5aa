//! The direct method against DDP and the discrete LQR where both apply (a
//! linear-quadratic problem, a swing-up from DDP's optimum), and on what
//! only it can hold: a final equality kept exactly, hard state limits that
//! the plan rides without crossing, and a final equality out of reach,
//! refused with the best plan; and the IPOPT peer's cart-pole swing-up,
//! to IPOPT's optimum.

use super::ddp::Ddp;
use super::direct::Direct;
use super::problem::OptimalControl;
use crate::error::{Error, PlanError};
use crate::linear::test_systems::{Oscillator, Pendulum};
use crate::linear::{Transition, dlqr};
use crate::system::{Driven, Lagrangian};
use nalgebra::{DMatrix, DVector, Matrix2, SMatrix, Vector1, Vector2};
use std::f64::consts::PI;

fn diagonal(d: &[f64]) -> DMatrix<f64> {
    DMatrix::from_diagonal(&DVector::from_column_slice(d))
}

const OSCILLATOR: Oscillator = Oscillator { k: 4.0, c: 0.3 };

fn oscillator(steps: usize) -> OptimalControl<'static, Oscillator, 1, 1> {
    let tr = Transition::new(&OSCILLATOR, 0.05).unwrap();
    let start = (Vector1::new(2.0), Vector1::new(-1.0));
    OptimalControl::new(tr, steps, start, diagonal(&[1.0, 0.5]), diagonal(&[0.1]))
}

fn swing_up() -> OptimalControl<'static, Pendulum, 1, 1> {
    let tr = Transition::new(&Pendulum, 0.02).unwrap();
    let start = (Vector1::new(0.0), Vector1::new(0.0));
    OptimalControl::new(tr, 200, start, diagonal(&[0.0, 0.0]), diagonal(&[0.01]))
        .goal(Vector1::new(PI), Vector1::new(0.0))
        .final_weight(diagonal(&[1000.0, 100.0]))
        .input_bounds(Vector1::new(-3.0), Vector1::new(3.0))
}

/// A linear system with quadratic costs is one quadratic program: the
/// first step lands on the optimum, the second confirms it, and the plan is
/// the discrete LQR's (and DDP's), gains included.
#[test]
fn a_linear_problem_is_the_discrete_lqr_in_one_step() {
    let tr = Transition::new(&OSCILLATOR, 0.05).unwrap();
    let d = tr
        .derivatives(&Vector1::zeros(), &Vector1::zeros(), &Vector1::zeros(), 0.0)
        .unwrap();
    let lqr = dlqr(&d.dx, &d.du, &diagonal(&[1.0, 0.5]), &diagonal(&[0.1])).unwrap();
    let problem = oscillator(40).final_weight(lqr.riccati.clone());
    let plan = Direct::new().tolerance(1e-8).solve(&problem, &[]).unwrap();
    // One full step; the next ones are below Clarabel's tolerances.
    assert!(plan.log.len() <= 3, "{} iterations", plan.log.len());
    assert_eq!(plan.log[0].step, 1.0);
    assert!((plan.log[0].cost - plan.cost).abs() < 1e-9 * plan.cost);
    for k in [0, 17, 39] {
        let x = DVector::from_column_slice(&[plan.q[k][0], plan.v[k][0]]);
        let lqr_u = -(&lqr.gain * &x)[0];
        // To the interior-point solver's accuracy.
        assert!(
            (plan.u[k][0] - lqr_u).abs() < 1e-6,
            "step {k}: {} vs {lqr_u}",
            plan.u[k][0]
        );
        assert!((&plan.gains[k] + &lqr.gain).amax() < 1e-9);
    }
    let ddp = Ddp::new().tolerance(1e-10).solve(&problem, &[]).unwrap();
    assert!((plan.cost - ddp.cost).abs() < 1e-9 * ddp.cost);
}

/// From DDP's swing-up, states and inputs, the direct method comes back to
/// the same plan: both solve the same problem. (The interior point starts
/// inside the torque bounds and at its first barrier, as IPOPT does, so it
/// takes a dozen iterations to return to the bounds the optimum rides.)
#[test]
fn from_ddps_optimum_it_stays() {
    let problem = swing_up();
    let ddp = Ddp::new().tolerance(1e-8).solve(&problem, &[]).unwrap();
    let plan = Direct::new()
        .tolerance(1e-9)
        .solve_from(&problem, &ddp.q, &ddp.v, &ddp.u)
        .unwrap();
    assert!(plan.log.len() <= 20, "{} iterations", plan.log.len());
    assert!(
        (plan.cost - ddp.cost).abs() < 1e-8 * ddp.cost,
        "{} vs {}",
        plan.cost,
        ddp.cost
    );
}

/// The swing-up with the last state held at the top: q_K = π and v_K = 0
/// to round-off, from hanging at rest, the torque within its bounds.
#[test]
fn a_final_equality_is_kept_exactly() {
    let problem = swing_up()
        .final_weight(diagonal(&[0.0, 0.0]))
        .final_equality();
    let plan = Direct::new().solve(&problem, &[]).unwrap();
    assert!(
        (plan.q[200][0] - PI).abs() < 1e-9,
        "q_K = {}",
        plan.q[200][0]
    );
    assert!(plan.v[200][0].abs() < 1e-9, "v_K = {}", plan.v[200][0]);
    assert!(plan.gap < 1e-9);
    // The KKT conditions at the plan: the Lagrangian's gradient.
    let kkt = plan.log.last().unwrap().stationarity;
    eprintln!("KKT residual {kkt:e} after {} iterations", plan.log.len());
    assert!(kkt < 1e-6, "KKT residual {kkt:e}");
    assert!(plan.u.iter().all(|u| u[0].abs() <= 3.0 + 1e-9));
    // No feedback gains that would not know the constraint.
    assert!(plan.gains.is_empty());
    // DDP refuses the problem, naming the direct method.
    let refused = Ddp::new().solve(&problem, &[]).unwrap_err();
    assert!(
        refused.error.to_string().contains("plan::Direct"),
        "{}",
        refused.error
    );
}

/// The oscillator's speed held to 80 % of the peak its free plan reaches:
/// as a hard limit the plan rides it and never crosses it, where DDP's
/// penalty (`StateBounds`) crosses it slightly.
#[test]
fn state_limits_are_never_crossed() {
    let free = Direct::new().solve(&oscillator(60), &[]).unwrap();
    let peak = |v: &[Vector1<f64>]| v.iter().map(|v| v[0].abs()).fold(0.0, f64::max);
    let limit = 0.8 * peak(&free.v);
    let inf = f64::INFINITY;
    let problem = oscillator(60).state_limits(
        (Vector1::new(-inf), Vector1::new(-limit)),
        (Vector1::new(inf), Vector1::new(limit)),
    );
    let plan = Direct::new().solve(&problem, &[]).unwrap();
    let reached = peak(&plan.v[1..]);
    assert!(reached <= limit + 1e-9, "peak {reached} against {limit}");
    let kkt = plan.log.last().unwrap().stationarity;
    assert!(kkt < 1e-6, "KKT residual {kkt:e}");
    let riding = plan.v.iter().filter(|v| v[0].abs() > limit - 1e-6).count();
    assert!(riding >= 3, "{riding} states on the limit");
    assert!(plan.cost > free.cost);
}

/// Half a second with a torque of 0.1 cannot bring the pendulum to the top:
/// the program has no solution, and the error says so with the plan reached.
#[test]
fn an_unreachable_final_equality_is_an_error() {
    let tr = Transition::new(&Pendulum, 0.02).unwrap();
    let problem = OptimalControl::new(
        tr,
        25,
        (Vector1::new(0.0), Vector1::new(0.0)),
        diagonal(&[0.0, 0.0]),
        diagonal(&[0.01]),
    )
    .goal(Vector1::new(PI), Vector1::new(0.0))
    .input_bounds(Vector1::new(-0.1), Vector1::new(0.1))
    .final_equality();
    let failure = Direct::new().solve(&problem, &[]).unwrap_err();
    match &failure.error {
        Error::Plan(PlanError::Stalled { reason, .. }) => {
            assert!(reason.contains("cannot all be met"), "{reason}")
        }
        // The torque's best is full effort one way: the top stays ~3 rad away.
        e => panic!("{e}"),
    }
    assert_eq!(failure.partial.q.len(), 26);
}

/// A guess with NaN in it, or of the wrong length, is refused before any
/// program is built.
#[test]
fn bad_guesses_are_refused() {
    let problem = oscillator(10);
    let q = vec![Vector1::new(0.0); 11];
    let mut v = vec![Vector1::new(0.0); 11];
    let u = vec![Vector1::new(0.0); 10];
    v[4][0] = f64::NAN;
    let nan = Direct::new().solve_from(&problem, &q, &v, &u).unwrap_err();
    assert!(nan.error.to_string().contains("finite"), "{}", nan.error);
    let short = Direct::new()
        .solve_from(&problem, &q[..5], &v, &u)
        .unwrap_err();
    assert!(
        short.error.to_string().contains("5 configurations"),
        "{}",
        short.error
    );
}

/// The catalog's cart-pole by hand (a cart of 1 kg, a bob of 0.1 kg on a
/// rod of 0.5 m, θ from upright, the force on the cart).
struct CartPole;

const CART: (f64, f64, f64, f64) = (1.0, 0.1, 0.5, 9.81);

impl Lagrangian<f64, 2> for CartPole {
    const COORDINATES: [&'static str; 2] = ["x", "theta"];
    const RHEONOMIC: bool = false;
    const CYCLIC: [bool; 2] = [true, false];
    fn mass_matrix(&self, q: &Vector2<f64>, _: f64) -> Matrix2<f64> {
        let (mc, mp, l, _) = CART;
        let c = mp * l * q[1].cos();
        Matrix2::new(mc + mp, c, c, mp * l * l)
    }
    fn bias(&self, q: &Vector2<f64>, v: &Vector2<f64>, _: f64) -> Vector2<f64> {
        let (_, mp, l, _) = CART;
        Vector2::new(-mp * l * q[1].sin() * v[1] * v[1], 0.0)
    }
    fn generalized_forces(&self, q: &Vector2<f64>, _: &Vector2<f64>, _: f64) -> Vector2<f64> {
        let (_, mp, l, g) = CART;
        Vector2::new(0.0, mp * g * l * q[1].sin())
    }
    fn mass_matrix_and_rhs(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        t: f64,
    ) -> (Matrix2<f64>, Vector2<f64>) {
        let rhs = self.generalized_forces(q, v, t) - self.bias(q, v, t);
        (self.mass_matrix(q, t), rhs)
    }
    fn kinetic_energy(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        0.5 * v.dot(&(self.mass_matrix(q, t) * v))
    }
    fn potential_energy(&self, q: &Vector2<f64>, _: f64) -> f64 {
        let (_, mp, l, g) = CART;
        mp * g * l * q[1].cos()
    }
    fn integral(&self, q: &Vector2<f64>, v: &Vector2<f64>, t: f64) -> f64 {
        self.kinetic_energy(q, v, t) + self.potential_energy(q, t)
    }
    // As `emit(jacobians)` would: J_q = ∂(Q − h)/∂q − [∂M/∂q_j a], J_v =
    // ∂(Q − h)/∂q̇, exact, so that the step's curvature is differenced
    // from exact derivatives as the catalog's derived cart-pole's is.
    fn rhs_jacobians(
        &self,
        q: &Vector2<f64>,
        v: &Vector2<f64>,
        a: &Vector2<f64>,
        _: f64,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        let (_, mp, l, g) = CART;
        let (s, c, w) = (q[1].sin(), q[1].cos(), v[1]);
        let jq = Matrix2::new(
            0.0,
            mp * l * w * w * c + mp * l * s * a[1],
            0.0,
            mp * g * l * c + mp * l * s * a[0],
        );
        let jv = Matrix2::new(0.0, 2.0 * mp * l * w * s, 0.0, 0.0);
        Some((jq, jv))
    }
}

impl Driven<f64, 2, 1> for CartPole {
    const INPUTS: [&'static str; 1] = ["force"];
    const INPUTS_AFFINE: bool = true;
    fn input_forces(
        &self,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        u: &Vector1<f64>,
        _: f64,
    ) -> Vector2<f64> {
        Vector2::new(u[0], 0.0)
    }
    fn input_jacobians(
        &self,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
        _: &Vector1<f64>,
        _: f64,
    ) -> (SMatrix<f64, 2, 1>, SMatrix<f64, 2, 2>, SMatrix<f64, 2, 2>) {
        // ∂Q/∂u, ∂Q/∂q, ∂Q/∂q̇ of the force on the cart.
        (
            SMatrix::<f64, 2, 1>::new(1.0, 0.0),
            SMatrix::zeros(),
            SMatrix::zeros(),
        )
    }
}

/// The IPOPT peer's problem (`lagrange-bench/peer/ipopt/`): swung up from
/// hanging to upright at rest exactly, |F| ≤ 5 N, the cart within ±0.5 m,
/// 50 RK4 steps of 50 ms, ½ Σ 0.01 F² and a running state cost of weight w.
fn cart_pole_swing_up(w: f64) -> OptimalControl<'static, CartPole, 2, 1> {
    let tr = Transition::new(&CartPole, 0.05).unwrap();
    let inf = f64::INFINITY;
    OptimalControl::new(
        tr,
        50,
        (Vector2::new(0.0, PI), Vector2::zeros()),
        diagonal(&[1.0, 1.0, 0.1, 0.1]) * w,
        diagonal(&[0.01]),
    )
    .final_weight(DMatrix::zeros(4, 4))
    .final_equality()
    .input_bounds(Vector1::new(-5.0), Vector1::new(5.0))
    .state_limits(
        (Vector2::new(-0.5, -inf), Vector2::new(-inf, -inf)),
        (Vector2::new(0.5, inf), Vector2::new(inf, inf)),
    )
}

/// IPOPT's optimum (CasADi 3.8.2, tolerance 1e-10), with and without the
/// state cost, in IPOPT's iterations: 55 and 64 Newton steps (a log
/// record each, and one at the plan). Without the state cost the
/// dynamics' curvature shapes the solution: the elastic SQP with a
/// Gauss–Newton Hessian that `Direct` was before stopped 1.4 % above it
/// after 100 iterations.
#[test]
fn the_cart_poles_swing_up_converges_to_ipopts_optimum() {
    for (w, ipopt, steps) in [(0.1, 28.688707311, 55), (0.0, 4.678835145, 64)] {
        let problem = cart_pole_swing_up(w);
        let plan = Direct::new().tolerance(1e-10).solve(&problem, &[]).unwrap();
        let kkt = plan.log.last().unwrap().stationarity;
        let iterations = plan.log.len() - 1;
        eprintln!(
            "w {w}: {iterations} iterations, cost {:.12}, KKT {kkt:e}",
            plan.cost
        );
        assert!(
            (plan.cost - ipopt).abs() < 1e-6 * ipopt,
            "w {w}: {}",
            plan.cost
        );
        assert_eq!(iterations, steps, "w {w}");
        assert!(plan.gap < 1e-9 && kkt < 1e-9);
        assert!(plan.q.iter().all(|q| q[0].abs() <= 0.5));
        assert!(plan.u.iter().all(|u| u[0].abs() <= 5.0));
    }
}
