"""Pinocchio's (PyPI `pin`) computeABADerivatives for the arms of `robots/`
(the UR5, UR10, Kinova, Z1 and xArm7; not the Panda, whose mimic finger
Pinocchio reads as a second joint), at
the state of the URDF tests (q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k) and at
a second state, with τ = 0: ∂q̈/∂q, ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ (`Minv`; row-major), written to
`tests/data/urdf_derivatives.txt` for `tests/urdf_derivatives.rs`.

    python3 lagrange-bench/peer/pinocchio/urdf_derivatives.py
"""
import os

import numpy as np
import pinocchio as pin

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")


def states(n):
    yield np.array([0.3 - 0.17 * k for k in range(n)]), np.array([0.5 - 0.21 * k for k in range(n)])
    yield np.array([1.1, -0.7, 2.0, 0.4, -1.3, 0.9, 0.5][:n]), np.array([-0.8, 1.2, 0.3, -2.0, 0.6, 1.5, -0.4][:n])


def configuration(model, angles):
    """Pinocchio's q for joint angles: a continuous joint is (cos, sin)."""
    q = np.zeros(model.nq)
    for j in model.joints[1:]:
        a = angles[j.idx_v]
        if j.nq == 2:
            q[j.idx_q : j.idx_q + 2] = [np.cos(a), np.sin(a)]
        else:
            q[j.idx_q] = a
    return q


def main():
    lines = ["# Pinocchio " + pin.__version__ + ", written by lagrange-bench/peer/pinocchio/urdf_derivatives.py"]
    for robot in ["ur5", "ur10", "kinova", "z1", "xarm7"]:
        model = pin.buildModelFromUrdf(os.path.join(ROOT, "robots", robot + ".urdf"))
        data = model.createData()
        for k, (q, v) in enumerate(states(model.nv)):
            pin.computeABADerivatives(model, data, configuration(model, q), v, np.zeros(model.nv))
            minv = data.Minv.copy()
            for key, values in [("q", q), ("v", v), ("dadq", data.ddq_dq.ravel()), ("dadv", data.ddq_dv.ravel()),
                                ("dadtau", minv.ravel())]:
                lines.append(f"{robot} {k} {key} " + " ".join(repr(float(x)) for x in values))
    path = os.path.normpath(os.path.join(ROOT, "tests", "data", "urdf_derivatives.txt"))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
