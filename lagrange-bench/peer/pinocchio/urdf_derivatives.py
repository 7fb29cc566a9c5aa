"""Pinocchio's (PyPI `pin`) computeABADerivatives for the UR5 of `robots/`, at
the state of the URDF tests (q_k = 0.3 − 0.17 k, q̇_k = 0.5 − 0.21 k) and at
a second state, with τ = 0: ∂q̈/∂q and ∂q̈/∂q̇ (row-major), written to
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
    yield np.array([1.1, -0.7, 2.0, 0.4, -1.3, 0.9][:n]), np.array([-0.8, 1.2, 0.3, -2.0, 0.6, 1.5][:n])


def main():
    lines = ["# Pinocchio " + pin.__version__ + ", written by lagrange-bench/peer/pinocchio/urdf_derivatives.py"]
    model = pin.buildModelFromUrdf(os.path.join(ROOT, "robots", "ur5.urdf"))
    data = model.createData()
    for k, (q, v) in enumerate(states(model.nq)):
        pin.computeABADerivatives(model, data, q, v, np.zeros(model.nv))
        for key, values in [("q", q), ("v", v), ("dadq", data.ddq_dq.ravel()), ("dadv", data.ddq_dv.ravel())]:
            lines.append(f"ur5 {k} {key} " + " ".join(repr(float(x)) for x in values))
    path = os.path.normpath(os.path.join(ROOT, "tests", "data", "urdf_derivatives.txt"))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
