"""The cart-pole's swing-up with hard constraints, solved by IPOPT through
CasADi: the problem of `lagrange-bench/examples/cart_pole_direct.rs`, term
for term, for `plan::Direct` to be compared with.

- the catalog's cart-pole (`examples/catalog/control.rs`): a 1 kg cart, a
  0.1 kg bob on a 0.5 m rod, θ from the upward vertical, g = 9.81; its
  equations M q̈ = Q − h written out:
  [m_c + m_p, m_p l cos θ; m_p l cos θ, m_p l²] q̈ = [F + m_p l θ̇² sin θ, m_p g l sin θ];
- 50 steps of 50 ms of RK4 with the force held over the step (multiple
  shooting: every state and input an unknown, the steps equality
  constraints);
- from hanging at rest (x, θ) = (0, π) to upright at rest at the rail's
  centre, exactly (a final equality), the force within ±5 N and the cart
  within ±0.5 m of the centre (state limits on x₁ … x_K);
- cost ½ Σ 0.01 F_k² (and, with `--state-weight w`, ½ Σ_{k<K} w (x² + θ² +
  0.1 ẋ² + 0.1 θ̇²), on every state but the last);
- from the rollout of F = 0 (hanging at rest throughout).

IPOPT with CasADi's exact Hessian (the defaults), tolerance 1e-10, MUMPS.
Prints the cost, the iterations and the median wall time of `--repeats`
solves (the call of CasADi's solver, IPOPT and the generated derivatives'
evaluation inside it), and writes the forces to `--out`.
"""

import argparse
import statistics
import time

import casadi as ca
import numpy as np

MC, MP, L, G = 1.0, 0.1, 0.5, 9.81
FORCE, RAIL, HORIZON = 5.0, 0.5, 2.5
# Set by --steps: K steps of 2.5 s / K (50 of 50 ms by default).
H, STEPS = 0.05, 50


def acceleration(x, u):
    theta, v, omega = x[1], x[2], x[3]
    m = ca.vertcat(
        ca.horzcat(MC + MP, MP * L * ca.cos(theta)),
        ca.horzcat(MP * L * ca.cos(theta), MP * L * L),
    )
    rhs = ca.vertcat(u + MP * L * omega**2 * ca.sin(theta), MP * G * L * ca.sin(theta))
    qdd = ca.solve(m, rhs)
    return ca.vertcat(v, omega, qdd)


def step():
    x, u = ca.SX.sym("x", 4), ca.SX.sym("u")
    k1 = acceleration(x, u)
    k2 = acceleration(x + H / 2 * k1, u)
    k3 = acceleration(x + H / 2 * k2, u)
    k4 = acceleration(x + H * k3, u)
    return ca.Function("F", [x, u], [x + H / 6 * (k1 + 2 * k2 + 2 * k3 + k4)])


def problem(w=0.0):
    f = step()
    xs = [ca.SX.sym(f"x{k}", 4) for k in range(STEPS + 1)]
    us = [ca.SX.sym(f"u{k}") for k in range(STEPS)]
    start, goal = np.array([0.0, np.pi, 0.0, 0.0]), np.zeros(4)
    g = [xs[0] - start] + [f(xs[k], us[k]) - xs[k + 1] for k in range(STEPS)] + [xs[-1] - goal]
    z = ca.vertcat(*[v for k in range(STEPS) for v in (xs[k], us[k])], xs[-1])
    weights = np.array([1.0, 1.0, 0.1, 0.1]) * w
    cost = sum(0.5 * 0.01 * u**2 for u in us) + sum(
        0.5 * ca.dot(weights * x, x) for x in xs[:STEPS]
    )
    lbz, ubz = [], []
    for k in range(STEPS + 1):
        rail = np.inf if k == 0 else RAIL
        lbz += [-rail, -np.inf, -np.inf, -np.inf]
        ubz += [rail, np.inf, np.inf, np.inf]
        if k < STEPS:
            lbz.append(-FORCE)
            ubz.append(FORCE)
    nlp = {"x": z, "f": cost, "g": ca.vertcat(*g)}
    options = {"ipopt.tol": 1e-10, "ipopt.print_level": int(__import__("os").environ.get("IPOPT_PRINT", "0")), "print_time": False}
    solver = ca.nlpsol("direct", "ipopt", nlp, options)
    # The rollout of F = 0: hanging at rest throughout.
    guess = []
    for k in range(STEPS):
        guess += list(start) + [0.0]
    guess += list(start)
    zeros = np.zeros(ca.vertcat(*g).shape[0])
    return solver, dict(x0=guess, lbx=lbz, ubx=ubz, lbg=zeros, ubg=zeros)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=10)
    parser.add_argument("--out")
    parser.add_argument("--state-weight", type=float, default=0.0)
    parser.add_argument("--steps", type=int, default=50)
    args = parser.parse_args()
    global H, STEPS
    STEPS, H = args.steps, HORIZON / args.steps
    solver, data = problem(args.state_weight)
    times = []
    for _ in range(args.repeats):
        start = time.perf_counter()
        solution = solver(**data)
        times.append(time.perf_counter() - start)
        stats = solver.stats()
    z = np.array(solution["x"]).ravel()
    forces = z[4 : 5 * STEPS : 5]
    print(
        f"ipopt status {stats['return_status']} iterations {stats['iter_count']} "
        f"cost {float(solution['f']):.12e} per_solve {statistics.median(times):.6e}"
    )
    if args.out:
        np.savetxt(args.out, forces, delimiter=",")


if __name__ == "__main__":
    main()
