"""The UR5's tool drawn 20 cm in 0.6 s under torques within ±40 N·m, solved
by Crocoddyl's box-constrained FDDP: the problem of `tests/planning.rs` and
of `examples/ur5_reach.rs` here, term for term.

- 30 steps of RK4 (`IntegratedActionModelRK`, four stages, the input held
  over the step) of 20 ms on the UR5 of `robots/ur5.urdf`, gravity −9.81 z;
  or, with `--method euler`, of semi-implicit Euler
  (`IntegratedActionModelEuler`: v⁺ = v + h q̈, q⁺ = q + h v⁺, our
  `StepMethod::SemiImplicitEuler`). Crocoddyl's RK4 integrates the running
  cost over the step with the stages' weights where ours takes it at the
  step's start, so the two RK4 problems differ in that term (their optima
  by 5e-3 of the cost); with Euler both take it at the start and the
  problems are the same;
- running cost ½ Σ 0.01 v² + ½ 1e-4 |u − u_g|², u_g gravity compensation at
  home (Crocoddyl multiplies a running cost by dt, so its weights here are
  divided by dt);
- final cost ½ Σ 100 v² + ½ 1e5 |p_tool0 − p*|², p* the tool's home position
  + (0.1, 0.15, −0.05);
- from u = u_g at every step (and its rollout).

Prints one line per run: iterations, cost, seconds per solve (median of
`--repeats`), seconds per iteration, and writes the plan's inputs to
`--out` (CSV) so that `compare.py` checks both sides found the same plan.

    python3 ur5_reach.py --urdf ../../../robots/ur5.urdf [--iterations N] [--repeats R] [--out u.csv]
"""

import argparse
import statistics
import time

import crocoddyl
import numpy as np
import pinocchio as pin

DT, STEPS, LIMIT = 0.02, 30, 40.0
HOME = np.array([0.0, -1.2, 1.5, -1.8, -1.57, 0.0])


def problem(urdf, method="rk4"):
    model = pin.buildModelFromUrdf(urdf)
    model.gravity.linear = np.array([0.0, 0.0, -9.81])
    data = model.createData()
    tool = model.getFrameId("tool0")
    pin.framesForwardKinematics(model, data, HOME)
    target = data.oMf[tool].translation + np.array([0.1, 0.15, -0.05])
    u_g = pin.computeGeneralizedGravity(model, data, HOME)
    state = crocoddyl.StateMultibody(model)
    actuation = crocoddyl.ActuationModelFull(state)
    nu = actuation.nu
    speeds = np.array([0.0] * 6 + [1.0] * 6)

    def weighted_state(weights):
        activation = crocoddyl.ActivationModelWeightedQuad(weights)
        residual = crocoddyl.ResidualModelState(state, np.zeros(12), nu)
        return crocoddyl.CostModelResidual(state, activation, residual)

    running = crocoddyl.CostModelSum(state, nu)
    running.addCost("speed", weighted_state(0.01 * speeds), 1.0 / DT)
    effort = crocoddyl.CostModelResidual(state, crocoddyl.ResidualModelControl(state, u_g))
    running.addCost("effort", effort, 1e-4 / DT)
    final = crocoddyl.CostModelSum(state, nu)
    final.addCost("still", weighted_state(100.0 * speeds), 1.0)
    reach = crocoddyl.ResidualModelFrameTranslation(state, tool, target, nu)
    final.addCost("reach", crocoddyl.CostModelResidual(state, reach), 1e5)
    dynamics = crocoddyl.DifferentialActionModelFreeFwdDynamics(state, actuation, running)
    if method == "rk4":
        step = crocoddyl.IntegratedActionModelRK(dynamics, crocoddyl.RKType.four, DT)
    else:
        step = crocoddyl.IntegratedActionModelEuler(dynamics, DT)
    step.u_lb = -LIMIT * np.ones(nu)
    step.u_ub = LIMIT * np.ones(nu)
    end = crocoddyl.IntegratedActionModelEuler(
        crocoddyl.DifferentialActionModelFreeFwdDynamics(state, actuation, final), 0.0
    )
    x0 = np.concatenate([HOME, np.zeros(6)])
    shooting = crocoddyl.ShootingProblem(x0, [step] * STEPS, end)
    # One thread, as the other side: on a shared two-core machine its
    # OpenMP threads made each pass twenty times slower.
    shooting.nthreads = 1
    return shooting, u_g


def solve(shooting, u_g, iterations):
    solver = crocoddyl.SolverBoxFDDP(shooting)
    solver.th_stop = 1e-12
    us = [u_g.copy() for _ in range(STEPS)]
    xs = shooting.rollout(us)
    start = time.perf_counter()
    solver.solve(xs, us, iterations, True)
    return solver, time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--urdf", required=True)
    parser.add_argument("--iterations", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--out")
    parser.add_argument("--method", choices=["rk4", "euler"], default="rk4")
    args = parser.parse_args()
    shooting, u_g = problem(args.urdf, args.method)
    times = []
    for _ in range(args.repeats):
        solver, seconds = solve(shooting, u_g, args.iterations)
        times.append(seconds)
    median = statistics.median(times)
    print(
        f"crocoddyl iterations {solver.iter} cost {solver.cost:.12e} "
        f"per_solve {median:.6e} per_iteration {median / max(solver.iter, 1):.6e}"
    )
    if args.out:
        np.savetxt(args.out, np.array(solver.us), delimiter=",")


if __name__ == "__main__":
    main()
