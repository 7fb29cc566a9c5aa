"""A free-flyer robot's state and numeric references in lagrange's convention,
for our side of the CasADi comparison (Solo 12).

Pinocchio: q = (x, y, z, qx, qy, qz, qw, joints depth-first), v = (the
root's linear velocity in its own axes, ω in its axes, joint rates).
lagrange: q = (x, y, z, joints breadth-first, qw, qx, qy, qz), v = (ẋ in
world axes, joint rates, ω in body axes). v_pin = P v with P the
permutation of block-diag(Rᵀ, I, ..) (orthogonal, so P⁻¹ = Pᵀ), and the
time derivative Ṗ v = (−ω × v_lin, 0, ..) (v_lin in root axes). Both sides
compute the same physical quantities at the same physical state: our τ is
Pᵀ τ_pin, our q̈ is Pᵀ (q̈_pin − Ṗ v) (so a_pin = P a + Ṗ v), and our M,
Q − h and M⁻¹ are Pᵀ M P, −Pᵀ (h + M Ṗ v) and Pᵀ M⁻¹ P.

Our derivatives are in the tangent space at fixed ω: δ = (δx in world axes,
δ joints, δθ the rotation vector in body axes), q ⊕ δ turning R into
R exp([δθ]×). They are taken here by central differences of the mapped
Pinocchio functions along δ and v, extrapolated (Richardson) to sixth order,
which leaves about 1e-12 of the entries' scale: within the comparison's
check of 1e-10.
"""
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../pinocchio"))
from floating import velocity_map  # noqa: E402  (the map tests/floating_bases.rs's data use)


def breadth_first(model):
    """lagrange's joint k is Pinocchio's joint `order[k]` (after the root,
    0-based): breadth-first, siblings in the file's order, where Pinocchio
    goes depth-first."""
    depth = [0] * model.njoints
    for j in range(2, model.njoints):
        depth[j] = depth[model.parents[j]] + 1
    return sorted(range(model.njoints - 2), key=lambda k: (depth[k + 2], k))


class Mapped:
    """Pinocchio's functions of a free-flyer model as functions of our state."""

    def __init__(self, model):
        self.model, self.data = model, model.createData()
        self.order = breadth_first(model)
        self.nj = model.nv - 6

    def to_pin(self, pos, R, joints, u):
        """(q_pin, v_pin, Ṗ v) from our position, rotation, joints (our
        order) and velocity."""
        nj, q_pin = self.nj, np.zeros(self.model.nq)
        quat = pin.Quaternion(R)
        q_pin[0:3], q_pin[3:7] = pos, [quat.x, quat.y, quat.z, quat.w]
        v_pin = self.P(R) @ u
        for k, p in enumerate(self.order):
            q_pin[7 + p] = joints[k]
        pdot_v = np.zeros(self.model.nv)
        pdot_v[0:3] = -np.cross(v_pin[3:6], v_pin[0:3])
        return q_pin, v_pin, pdot_v

    def P(self, R):
        return velocity_map(R, self.order, self.model.nv)

    def acceleration(self, pos, R, joints, u, tau):
        q_pin, v_pin, pdot_v = self.to_pin(pos, R, joints, u)
        P = self.P(R)
        return P.T @ (pin.aba(self.model, self.data, q_pin, v_pin, P @ tau) - pdot_v)

    def torques(self, pos, R, joints, u, a):
        q_pin, v_pin, pdot_v = self.to_pin(pos, R, joints, u)
        P = self.P(R)
        return P.T @ pin.rnea(self.model, self.data, q_pin, v_pin, P @ a + pdot_v)

    def tangent_jacobians(self, f, pos, R, joints, u, extra):
        """∂f/∂δ and ∂f/∂v of f(pos, R, joints, u, extra), sixth order."""
        nj, n = self.nj, self.model.nv

        def moved(delta, du):
            return f(pos + delta[0:3], R @ pin.exp3(delta[3 + nj:]), joints + delta[3:3 + nj],
                     u + du, extra)

        def column(along):
            def central(h):
                return (along(h) - along(-h)) / (2 * h)
            h = 1e-2
            d = [central(h / 2 ** i) for i in range(3)]
            d1 = [(4 * d[i + 1] - d[i]) / 3 for i in range(2)]
            return (16 * d1[1] - d1[0]) / 15

        e = np.eye(n)
        dq = np.column_stack([column(lambda h, k=k: moved(h * e[k], 0 * e[k])) for k in range(n)])
        dv = np.column_stack([column(lambda h, k=k: moved(0 * e[k], h * e[k])) for k in range(n)])
        return dq, dv

    def reference(self, q_pin, v_pin, a_pin, tau_pin):
        """Every quantity our side of the comparison prints, at the physical
        state of Pinocchio's (q_pin, v_pin) with its a_pin and tau_pin, in our
        convention: {(quantity, output): array}, matrices row-major."""
        model, data, nj = self.model, self.data, self.nj
        x, y, z, w = q_pin[3:7]
        R = pin.Quaternion(w, x, y, z).toRotationMatrix()
        P = self.P(R)
        pos, joints = q_pin[0:3], np.array([q_pin[7 + p] for p in self.order])
        u = P.T @ v_pin
        pdot_v = np.zeros(model.nv)
        pdot_v[0:3] = -np.cross(v_pin[3:6], v_pin[0:3])
        tau, a = P.T @ tau_pin, P.T @ (a_pin - pdot_v)
        M = pin.crba(model, data, q_pin)
        M = np.triu(M) + np.triu(M, 1).T
        nle = pin.nonLinearEffects(model, data, q_pin, v_pin)
        ref = {("crba_nle", "M"): P.T @ M @ P, ("crba_nle", "rhs"): -P.T @ (nle + M @ pdot_v),
               ("rnea", "tau"): self.torques(pos, R, joints, u, a)}
        ddq = self.acceleration(pos, R, joints, u, tau)
        ref["aba", "ddq"] = ref["chol", "ddq"] = ddq
        dq, dv = self.tangent_jacobians(self.acceleration, pos, R, joints, u, tau)
        ref["aba_derivatives", "ddq_dq"], ref["aba_derivatives", "ddq_dv"] = dq, dv
        ref["aba_derivatives", "Minv"] = P.T @ np.linalg.inv(M) @ P
        dq, dv = self.tangent_jacobians(self.torques, pos, R, joints, u, a)
        ref["rnea_derivatives", "dtau_dq"], ref["rnea_derivatives", "dtau_dv"] = dq, dv
        return {key: np.asarray(x).reshape(-1) for key, x in ref.items()}
