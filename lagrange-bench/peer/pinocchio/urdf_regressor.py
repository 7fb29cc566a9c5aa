"""Pinocchio's (PyPI `pin`) computeJointTorqueRegressor for arms of
`robots/` (the UR5, Kinova, Z1 and xArm7), at two states (q, q̇, q̈) each:
Y (row-major, 10 columns per joint in Pinocchio's order
[m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz], about the joint frame)
the number of base parameters (the stacked regressor's numerical rank, 1e-9 relative tolerance)
and, per joint, the URDF link it moves (the body frame at the joint's
origin), written to `tests/data/urdf_regressor.txt` for
`tests/regressor_pinocchio.rs`, which compares each moving link's ten
columns of the emitted Y with the block of its joint.

    python3 lagrange-bench/peer/pinocchio/urdf_regressor.py

Result (pin 4.0.0, 2026-11-29): the emitted Y agrees with Pinocchio's to
3.3e-15 relative (max |Y − Y_pin| / (1 + |Y_pin|): UR5 8.6e-16, Kinova
3.3e-15, Z1 1.3e-15, xArm7 3.3e-15). The Panda is left out as in
`urdf_derivatives.py` (Pinocchio reads its mimic finger as a second joint).
"""
import os

import numpy as np
import pinocchio as pin

from urdf_derivatives import configuration

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")


def states(n):
    yield (np.array([0.3 - 0.17 * k for k in range(n)]), np.array([0.5 - 0.21 * k for k in range(n)]),
           np.array([-0.4 + 0.23 * k for k in range(n)]))
    yield (np.array([1.1, -0.7, 2.0, 0.4, -1.3, 0.9, 0.5][:n]), np.array([-0.8, 1.2, 0.3, -2.0, 0.6, 1.5, -0.4][:n]),
           np.array([0.7, 1.9, -1.1, 0.2, -0.6, 1.3, -1.7][:n]))


def moved_links(model):
    """Each joint's child link: the body frame on the joint at its origin."""
    names = []
    for j in range(1, model.njoints):
        bodies = [f.name for f in model.frames
                  if f.type == pin.FrameType.BODY and f.parentJoint == j and f.placement.isIdentity()]
        names.append(bodies[0])
    return names


def base_count(model, data):
    """The number of base parameters: the numerical rank of the regressor
    stacked at random states (twice as many equations as parameters and four
    states more), singular values below 1e-9 of the largest counted as zero.
    numpy's default tolerance (largest × max(rows, columns) × ε, 3e-12 here)
    is too tight: on the Kinova two columns that are round-off of zeros (a
    placement's cos(π/2) = 6e-17) leave singular values of 8.7e-12 and
    6.4e-12, where the genuine ones end at 3.6."""
    rng = np.random.default_rng(34)
    n = model.nv
    count = 2 * 10 * (model.njoints - 1) // n + 4
    w = np.vstack([pin.computeJointTorqueRegressor(model, data, configuration(model, rng.uniform(-np.pi, np.pi, n)),
                                                   rng.uniform(-2, 2, n), rng.uniform(-2, 2, n))
                   for _ in range(count)])
    singular = np.linalg.svd(w, compute_uv=False)
    return int((singular > 1e-9 * singular[0]).sum())


def main():
    lines = ["# Pinocchio " + pin.__version__ + ", written by lagrange-bench/peer/pinocchio/urdf_regressor.py"]
    for robot in ["ur5", "kinova", "z1", "xarm7"]:
        model = pin.buildModelFromUrdf(os.path.join(ROOT, "robots", robot + ".urdf"))
        data = model.createData()
        lines.append(f"{robot} links " + " ".join(moved_links(model)))
        lines.append(f"{robot} rank {base_count(model, data)}")
        for k, (q, v, a) in enumerate(states(model.nv)):
            y = pin.computeJointTorqueRegressor(model, data, configuration(model, q), v, a)
            tau = pin.rnea(model, data, configuration(model, q), v, a)
            params = np.concatenate([model.inertias[j].toDynamicParameters() for j in range(1, model.njoints)])
            assert np.abs(y @ params - tau).max() < 1e-10
            for key, values in [("q", q), ("v", v), ("a", a), ("y", y.ravel())]:
                lines.append(f"{robot} {k} {key} " + " ".join(repr(float(x)) for x in values))
    path = os.path.normpath(os.path.join(ROOT, "tests", "data", "urdf_regressor.txt"))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
