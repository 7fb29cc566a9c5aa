"""Reference values for the URDF robots in `robots/` from Pinocchio (PyPI `pin`).

Prints M, nle = C(q, v) v + g(q) (so Q - h = -nle in lagrange's terms) and the
the inverse dynamics (`rnea`) at q̈_k = 0.1 + 0.05 k and the gravity torques, at a fixed state, for the tests in
`tests/urdf.rs`. Fixed base, gravity (0, 0, -9.81) (Pinocchio's default).
The frame Jacobians (LOCAL_WORLD_ALIGNED), the frames' classical
acceleration at zero q̈, the centre of mass and its Jacobian are printed too.
The Panda's second finger mimics the first in the URDF; Pinocchio reads it as
a joint of its own, so only the arm's 7 x 7 block is compared, at finger
velocities zero. A continuous joint (the Kinova's 1, 4 and 6) is one angle in
lagrange and (cos, sin) in Pinocchio's q; its velocity is the same.

    python3 lagrange-bench/peer/pinocchio/urdf_reference.py

The arms after the first two are also written, in full (M, Q - h, rnea, the
gravity torques, the tool frame's Jacobians and bias, the centre of mass and
its Jacobian, matrices row by row), to `tests/data/urdf_arms_pinocchio.txt`,
which `tests/urdf_arms.rs` reads.
"""
import os
import numpy as np
import pinocchio as pin

ROOT = os.path.join(os.path.dirname(__file__), "..", "..", "..", "robots")
DATA = os.path.join(ROOT, "..", "tests", "data", "urdf_arms_pinocchio.txt")

from urdf_derivatives import configuration  # noqa: E402 (beside this file)


def state(model, n_arm):
    """q_k = 0.3 - 0.17 k, v_k = 0.5 - 0.21 k on the arm's coordinates (by
    velocity index), the fingers at 0.02 and at rest; Pinocchio's q from it."""
    angle = np.array([0.3 - 0.17 * k if k < n_arm else 0.02 for k in range(model.nv)])
    v = np.array([0.5 - 0.21 * k if k < n_arm else 0.0 for k in range(model.nv)])
    return configuration(model, angle), v

# file, the arm's coordinates, the tool frame
ROBOTS = [
    ("ur5.urdf", 6, "tool0"),
    ("panda.urdf", 7, "panda_hand"),
    ("ur10.urdf", 6, "tool0"),
    ("kinova.urdf", 6, "j2s6s200_end_effector"),
    ("z1.urdf", 7, "gripperStator"),
    ("xarm7.urdf", 7, "link_eef"),
]

def full(robot, model, data, q, v, frame):
    """One line per quantity: `robot key v1 v2 ...`, matrices row by row."""
    n = model.nv
    m = pin.crba(model, data, q)
    m = np.triu(m) + np.triu(m, 1).T
    a = np.array([0.1 + 0.05 * k for k in range(n)])
    fid = model.getFrameId(frame, pin.BODY)
    rows = {
        "M": m,
        "rhs": -pin.nonLinearEffects(model, data, q, v),
        "tau": pin.rnea(model, data, q, v, a),
        "gravity": pin.computeGeneralizedGravity(model, data, q),
        "J": pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED),
        "J_local": pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL),
    }
    pin.forwardKinematics(model, data, q, v, 0 * v)
    acc = pin.getFrameClassicalAcceleration(model, data, fid, pin.LOCAL_WORLD_ALIGNED)
    rows["bias"] = np.concatenate([acc.linear, acc.angular])
    rows["com"] = pin.centerOfMass(model, data, q)
    rows["Jcom"] = pin.jacobianCenterOfMass(model, data, q)
    return [f"{robot} {key} " + " ".join(repr(float(x)) for x in np.ravel(x)) for key, x in rows.items()]


lines = [f"# Pinocchio {pin.__version__}, written by lagrange-bench/peer/pinocchio/urdf_reference.py"]
for name, n_arm, frame in ROBOTS:
    model = pin.buildModelFromUrdf(os.path.join(ROOT, name))
    data = model.createData()
    q, v = state(model, n_arm)
    m = pin.crba(model, data, q)
    m = np.triu(m) + np.triu(m, 1).T
    nle = pin.nonLinearEffects(model, data, q, v)
    print(f"// {name}: nq = {model.nq}, nv = {model.nv}")
    print("M row 0:", [float(x) for x in m[0, :n_arm]])
    print("M diag:", [float(x) for x in np.diag(m)[:n_arm]])
    print("Q - h:", [float(x) for x in -nle[:n_arm]])
    a = np.array([0.1 + 0.05 * k for k in range(model.nv)])
    a[n_arm:] = 0.0
    print("rnea:", [float(x) for x in pin.rnea(model, data, q, v, a)[:n_arm]])
    print("gravity:", [float(x) for x in pin.computeGeneralizedGravity(model, data, q)[:n_arm]])
    fid = model.getFrameId(frame, pin.BODY)
    J = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED)
    print(f"J[{frame}] rows 0 and 5:", [float(x) for x in J[0, :n_arm]], [float(x) for x in J[5, :n_arm]])
    L = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL)
    print(f"J local[{frame}] rows 0 and 5:", [float(x) for x in L[0, :n_arm]], [float(x) for x in L[5, :n_arm]])
    pin.forwardKinematics(model, data, q, v, 0 * v)
    acc = pin.getFrameClassicalAcceleration(model, data, fid, pin.LOCAL_WORLD_ALIGNED)
    print(f"Jdot v[{frame}]:", [float(x) for x in acc.linear] + [float(x) for x in acc.angular])
    print("com:", [float(x) for x in pin.centerOfMass(model, data, q)])
    Jc = pin.jacobianCenterOfMass(model, data, q)
    print("Jcom row 0:", [float(x) for x in Jc[0, :n_arm]])
    if name not in ("ur5.urdf", "panda.urdf"):
        lines += full(name.removesuffix(".urdf"), model, data, q, v, frame)
with open(DATA, "w") as f:
    f.write("\n".join(lines) + "\n")
