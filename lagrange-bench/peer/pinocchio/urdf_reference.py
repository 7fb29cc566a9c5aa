"""Reference values for the URDF robots in `robots/` from Pinocchio (PyPI `pin`).

Prints M, nle = C(q, v) v + g(q) (so Q - h = -nle in lagrange's terms) and the
the inverse dynamics (`rnea`) at q̈_k = 0.1 + 0.05 k and the gravity torques, at a fixed state, for the tests in
`tests/urdf.rs`. Fixed base, gravity (0, 0, -9.81) (Pinocchio's default).
The frame Jacobians (LOCAL_WORLD_ALIGNED), the frames' classical
acceleration at zero q̈, the centre of mass and its Jacobian are printed too.
The Panda's second finger mimics the first in the URDF; Pinocchio reads it as
a joint of its own, so only the arm's 7 x 7 block is compared, at finger
velocities zero.

    python3 lagrange-bench/peer/pinocchio/urdf_reference.py
"""
import os
import numpy as np
import pinocchio as pin

ROOT = os.path.join(os.path.dirname(__file__), "..", "..", "..", "robots")

def state(n):
    q = np.array([0.3 - 0.17 * k for k in range(n)])
    v = np.array([0.5 - 0.21 * k for k in range(n)])
    return q, v

for name, n_arm in [("ur5.urdf", 6), ("panda.urdf", 7)]:
    model = pin.buildModelFromUrdf(os.path.join(ROOT, name))
    data = model.createData()
    q, v = state(model.nq)
    if model.nq > n_arm:
        q[n_arm:] = 0.02
        v[n_arm:] = 0.0
    m = pin.crba(model, data, q)
    m = np.triu(m) + np.triu(m, 1).T
    nle = pin.nonLinearEffects(model, data, q, v)
    print(f"// {name}: nq = {model.nq}")
    print("M row 0:", [float(x) for x in m[0, :n_arm]])
    print("M diag:", [float(x) for x in np.diag(m)[:n_arm]])
    print("Q - h:", [float(x) for x in -nle[:n_arm]])
    a = np.array([0.1 + 0.05 * k for k in range(model.nv)])
    a[n_arm:] = 0.0
    print("rnea:", [float(x) for x in pin.rnea(model, data, q, v, a)[:n_arm]])
    print("gravity:", [float(x) for x in pin.computeGeneralizedGravity(model, data, q)[:n_arm]])
    frame = {"ur5.urdf": "tool0", "panda.urdf": "panda_hand"}[name]
    fid = model.getFrameId(frame)
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
