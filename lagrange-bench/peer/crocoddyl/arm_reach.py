"""An arm's tool drawn to a point under its torque limits, solved by
Crocoddyl's box-constrained FDDP: the problems of `examples/arm_reach.rs`
here, term for term (`--arm`):

- `ur5`: the problem of `tests/planning.rs`, the UR5's tool 20 cm away in
  0.6 s, 30 steps of 20 ms, torques within ±40 N·m;
- `xarm7`: the xArm7's tool 25 cm away in 1 s, 100 steps of 10 ms, torques
  within the file's effort limits.

- steps of semi-implicit Euler
  (`IntegratedActionModelEuler`: v⁺ = v + h q̈, q⁺ = q + h v⁺, our
  `StepMethod::SemiImplicitEuler`), gravity −9.81 z; or, with `--method
  rk4`, of RK4 (`IntegratedActionModelRK`, four stages, the input held
  over the step). Crocoddyl's RK4 integrates the running
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

    python3 arm_reach.py --urdf ../../../robots/ur5.urdf [--arm ur5|xarm7] [--method euler|rk4] [--iterations N] [--repeats R] [--out u.csv]
"""

import argparse
import statistics
import time

import crocoddyl
import numpy as np
import pinocchio as pin

# Per arm: home, tool frame, the target's offset from the tool at home,
# steps, step length, torque limits.
ARMS = {
    "ur5": dict(
        home=[0.0, -1.2, 1.5, -1.8, -1.57, 0.0],
        tool="tool0",
        offset=[0.1, 0.15, -0.05],
        steps=30,
        dt=0.02,
        limits=[40.0] * 6,
    ),
    "xarm7": dict(
        home=[0.0, -0.3, 0.0, 0.6, 0.0, 0.9, 0.0],
        tool="link_eef",
        offset=[0.15, 0.15, -0.1],
        steps=100,
        dt=0.01,
        limits=[50.0, 50.0, 30.0, 30.0, 30.0, 20.0, 20.0],
    ),
}


def problem(urdf, arm, method):
    DT, STEPS, HOME = arm["dt"], arm["steps"], np.array(arm["home"])
    limits = np.array(arm["limits"])
    model = pin.buildModelFromUrdf(urdf)
    model.gravity.linear = np.array([0.0, 0.0, -9.81])
    data = model.createData()
    tool = model.getFrameId(arm["tool"])
    pin.framesForwardKinematics(model, data, HOME)
    target = data.oMf[tool].translation + np.array(arm["offset"])
    u_g = pin.computeGeneralizedGravity(model, data, HOME)
    state = crocoddyl.StateMultibody(model)
    actuation = crocoddyl.ActuationModelFull(state)
    nu = actuation.nu
    speeds = np.array([0.0] * model.nv + [1.0] * model.nv)

    def weighted_state(weights):
        activation = crocoddyl.ActivationModelWeightedQuad(weights)
        residual = crocoddyl.ResidualModelState(state, np.zeros(2 * model.nv), nu)
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
    step.u_lb = -limits
    step.u_ub = limits
    end = crocoddyl.IntegratedActionModelEuler(
        crocoddyl.DifferentialActionModelFreeFwdDynamics(state, actuation, final), 0.0
    )
    x0 = np.concatenate([HOME, np.zeros(model.nv)])
    shooting = crocoddyl.ShootingProblem(x0, [step] * STEPS, end)
    # One thread, as the other side: on a shared two-core machine its
    # OpenMP threads made each pass twenty times slower.
    shooting.nthreads = 1
    return shooting, u_g


def solve(shooting, u_g, iterations):
    solver = crocoddyl.SolverBoxFDDP(shooting)
    solver.th_stop = 1e-12
    us = [u_g.copy() for _ in range(shooting.T)]
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
    parser.add_argument("--method", choices=["rk4", "euler"], default="euler")
    parser.add_argument("--arm", choices=sorted(ARMS), default="ur5")
    args = parser.parse_args()
    shooting, u_g = problem(args.urdf, ARMS[args.arm], args.method)
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
