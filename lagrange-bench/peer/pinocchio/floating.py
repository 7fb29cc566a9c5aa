"""Pinocchio (PyPI `pin`) references for the floating-base trees of
`examples/catalog/floating.rs`: a quadruped (trunk on a free flyer, four
legs of three joints) and a satellite with a six-joint arm. Writes
`tests/data/floating_pinocchio.txt`, read by `tests/floating_bases.rs`.

Conventions. Pinocchio: q = (x, y, z, qx, qy, qz, qw, joints), v = (linear
velocity of the root frame in root axes, ω in root axes, joint rates).
lagrange: q = (x, y, z, joints, w, qx, qy, qz), v = (ẋ, ẏ, ż in world axes,
joint rates, ω in body axes). v_pin = P v with P = diag(Rᵀ, ..) permuted, and
Ṗ v = (−ω × v_lin, 0, ..), so M = Pᵀ M_pin P, Q − h = −Pᵀ(nle + M_pin Ṗ v),
τ(a) = Pᵀ rnea(q, v_pin, P a + Ṗ v) and q̈ = P⁻¹(aba − Ṗ v).

    python3 lagrange-bench/peer/pinocchio/floating.py
"""
import os

import numpy as np
import pinocchio as pin


def rot_x(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def add(model, parent, joint, rotation, offset, name, mass, com, inertia):
    j = model.addJoint(parent, joint, pin.SE3(rotation, np.array(offset, float)), name)
    model.appendBodyToJoint(j, pin.Inertia(mass, np.array(com, float), np.diag(inertia)), pin.SE3.Identity())
    return j


def quadruped():
    model = pin.Model()
    root = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "trunk")
    model.appendBodyToJoint(root, pin.Inertia(12.0, np.zeros(3), np.diag([0.12, 0.35, 0.40])), pin.SE3.Identity())
    eye = np.eye(3)
    for leg, x, y in [("fl", 0.25, 0.12), ("fr", 0.25, -0.12), ("hl", -0.25, 0.12), ("hr", -0.25, -0.12)]:
        side = 0.03 if y > 0 else -0.03
        a = add(model, root, pin.JointModelRX(), eye, [x, y, 0], "a_" + leg, 0.6, [0, side, 0], [0.0008, 0.0012, 0.0010])
        h = add(model, a, pin.JointModelRY(), eye, [0, 0, 0], "h_" + leg, 1.0, [0, 0, -0.1], [0.010, 0.011, 0.002])
        add(model, h, pin.JointModelRY(), eye, [0, 0, -0.2], "k_" + leg, 0.3, [0, 0, -0.1], [0.004, 0.004, 0.0004])
    return model


def satellite():
    model = pin.Model()
    root = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "bus")
    model.appendBodyToJoint(root, pin.Inertia(100.0, np.zeros(3), np.diag([10.0, 12.0, 9.0])), pin.SE3.Identity())
    eye = np.eye(3)
    j = add(model, root, pin.JointModelRZ(), rot_x(0.3), [0.6, 0, 0.4], "j1", 4.0, [0, 0, 0.1], [0.05, 0.05, 0.02])
    j = add(model, j, pin.JointModelRY(), eye, [0, 0, 0.2], "j2", 3.0, [0.25, 0, 0], [0.01, 0.08, 0.08])
    j = add(model, j, pin.JointModelRY(), eye, [0.5, 0, 0], "j3", 2.0, [0.2, 0, 0], [0.005, 0.05, 0.05])
    j = add(model, j, pin.JointModelRX(), eye, [0.4, 0, 0], "j4", 0.8, [0.05, 0, 0], [0.002, 0.003, 0.003])
    j = add(model, j, pin.JointModelRY(), eye, [0.1, 0, 0], "j5", 0.5, [0.03, 0, 0], [0.001, 0.0012, 0.0011])
    add(model, j, pin.JointModelRX(), eye, [0.06, 0, 0], "j6", 0.3, [0.05, 0.01, 0], [0.0008, 0.001, 0.0009])
    return model


def states(model, rng):
    """A generic state and one with the root pitched by exactly π/2 (where
    the Euler z-y-x chart is singular), both in Pinocchio's convention."""
    nj = model.nv - 6
    out = []
    for quat in [rng.normal(size=4), np.array([np.cos(np.pi / 4), 0.0, np.sin(np.pi / 4), 0.0])]:
        w, x, y, z = quat / np.linalg.norm(quat)
        q = np.concatenate([rng.normal(size=3), [x, y, z, w], rng.uniform(-1.5, 1.5, nj)])
        v = rng.normal(size=model.nv)
        a = rng.normal(size=model.nv)
        out.append((q, v, a))
    return out


def velocity_map(R, perm, nv):
    """P with v_pin = P v: this crate's (ẋ in world axes, joints, ω) to
    Pinocchio's (root velocity and ω in root axes, joints); this crate's
    joint k is Pinocchio's `perm[k]`. P is orthogonal."""
    nj = nv - 6
    P = np.zeros((nv, nv))
    P[0:3, 0:3] = R.T
    P[3:6, 3 + nj:] = np.eye(3)
    for k, p in enumerate(perm):
        P[6 + p, 3 + k] = 1.0
    return P


def ours(model, q_pin, v_pin, a_ours, perm):
    """`perm[k]` is Pinocchio's index (after the root) of this crate's joint k."""
    data = model.createData()
    nv, nj = model.nv, model.nv - 6
    x, y, z, w = q_pin[3:7]
    R = pin.Quaternion(w, x, y, z).toRotationMatrix()
    P = velocity_map(R, perm, nv)
    v = np.linalg.solve(P, v_pin)
    pdot_v = np.zeros(nv)
    pdot_v[0:3] = -np.cross(v_pin[3:6], v_pin[0:3])
    M_pin = pin.crba(model, data, q_pin)
    M_pin = np.triu(M_pin) + np.triu(M_pin, 1).T
    M = P.T @ M_pin @ P
    rhs = -P.T @ (pin.nonLinearEffects(model, data, q_pin, v_pin) + M_pin @ pdot_v)
    accel = np.linalg.solve(P, pin.aba(model, data, q_pin, v_pin, np.zeros(nv)) - pdot_v)
    tau = P.T @ pin.rnea(model, data, q_pin, v_pin, P @ a_ours + pdot_v)
    gravity = P.T @ pin.computeGeneralizedGravity(model, data, q_pin)
    q = np.concatenate([q_pin[0:3], q_pin[7:][perm], [w, x, y, z]])
    dq, dv = tangent_derivatives(model, data, q_pin, v_pin, R, perm)
    frame = {}
    if model.existFrame("FL_FOOT"):
        frame = foot(model, data, q_pin, v_pin, P, pdot_v)
    return frame | {"q_pin": q_pin, "v_pin": v_pin, "q": q, "v": v, "M": M.ravel(), "rhs": rhs,
            "accel": accel, "a": a_ours, "tau": tau, "gravity": gravity,
            "dadq": dq.ravel(), "dadv": dv.ravel(), "perm": np.array(perm, float)}


def foot(model, data, q_pin, v_pin, P, pdot_v):
    """The FL_FOOT frame's Jacobian (LOCAL_WORLD_ALIGNED) in this crate's
    velocities, J P, and its classical acceleration at v̇ = 0 (Pinocchio's
    acceleration Ṗ v then)."""
    fid = model.getFrameId("FL_FOOT")
    frame = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    pin.computeJointJacobians(model, data, q_pin)
    pin.updateFramePlacements(model, data)
    J = pin.getFrameJacobian(model, data, fid, frame) @ P
    pin.forwardKinematics(model, data, q_pin, v_pin, pdot_v)
    pin.updateFramePlacements(model, data)
    bias = pin.getFrameClassicalAcceleration(model, data, fid, frame).vector
    return {"foot_J": J.ravel(), "foot_bias": bias}


def skew(u):
    return np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def tangent_derivatives(model, data, q_pin, v_pin, R, perm):
    """∂v̇/∂δ and ∂v̇/∂v in lagrange's convention from computeABADerivatives
    (Pinocchio's local tangent: δ = (δp in root axes, δθ, δjoints)).
    Ours: δ = (δx world, δjoints, δθ), v = (ẋ world, q̇, ω), and
    v̇_lin = R (a_lin + ω × v_lin) with v_lin = Rᵀ ẋ. By the chain rule:
    δx = R δp; δθ turns v_lin by [v_lin]× δθ and v̇_lin by −R [y]× δθ,
    y = a_lin + ω × v_lin."""
    nv, nj = model.nv, model.nv - 6
    tau = np.zeros(nv)
    pin.computeABADerivatives(model, data, q_pin, v_pin, tau)
    A_q, A_v = data.ddq_dq.copy(), data.ddq_dv.copy()
    a = pin.aba(model, data, q_pin, v_pin, tau)
    v_lin, w = v_pin[0:3], v_pin[3:6]
    y = a[0:3] + np.cross(w, v_lin)
    # Pinocchio's a as a function of our variables: columns (δx, δθ, δj), (ẋ, ω, q̇).
    dq_pin = np.hstack([A_q[:, 0:3] @ R.T, A_q[:, 3:6] + A_v[:, 0:3] @ skew(v_lin), A_q[:, 6:]])
    dv_pin = np.hstack([A_v[:, 0:3] @ R.T, A_v[:, 3:6], A_v[:, 6:]])
    # Our v̇ rows: (ẍ, ω̇, q̈) before reordering.
    dq, dv = dq_pin.copy(), dv_pin.copy()
    dq[0:3] = R @ dq_pin[0:3]
    dq[0:3, 3:6] += R @ (-skew(y) + skew(w) @ skew(v_lin))
    dv[0:3] = R @ dv_pin[0:3]
    dv[0:3, 0:3] += R @ skew(w) @ R.T
    dv[0:3, 3:6] += R @ (-skew(v_lin))
    # Reorder rows and columns from (lin, ang, joints) to (lin, joints, ang).
    order = list(range(0, 3)) + [6 + p for p in perm] + list(range(3, 6))
    return dq[np.ix_(order, order)], dv[np.ix_(order, order)]


def main():
    rng = np.random.default_rng(2026)
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.join(here, "../../../tests/data/floating_pinocchio.txt")
    lines = ["# Pinocchio " + pin.__version__ + ", written by lagrange-bench/peer/pinocchio/floating.py"]
    solo = pin.buildModelFromUrdf(os.path.join(here, "../../../robots/solo12.urdf"), pin.JointModelFreeFlyer())
    # lagrange orders a URDF's joints breadth-first (the hips, then the
    # thighs, then the knees), Pinocchio depth-first (leg by leg).
    names = list(solo.names)[2:]
    solo_order = [leg + "_" + j for j in ("HAA", "HFE", "KFE") for leg in ("FL", "FR", "HL", "HR")]
    for name, model, perm in [
        ("quadruped", quadruped(), list(range(12))),
        ("satellite", satellite(), list(range(6))),
        ("solo12", solo, [names.index(n) for n in solo_order]),
    ]:
        for k, (q, v, a) in enumerate(states(model, rng)):
            for key, values in ours(model, q, v, a, perm).items():
                lines.append(f"{name} {k} {key} " + " ".join(repr(float(x)) for x in values))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", os.path.normpath(path))


if __name__ == "__main__":
    main()
