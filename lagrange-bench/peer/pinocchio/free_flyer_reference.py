"""Reference values for a floating-base arm from Pinocchio (PyPI `pin`), for
`tests/free_bodies.rs`: a hub on a free-flyer joint with a two-joint arm
(revolute z at the hub's point (0.3, 0.1, 0.2), revolute y 0.4 further out).

Pinocchio's free flyer stores q = (x, y, z, qx, qy, qz, qw, joints) and
v = (linear velocity of the hub's frame in hub axes, ω in hub axes, joint
rates). lagrange's description stores q = (x, y, z, j1, j2, w, qx, qy, qz)
and v = (ẋ, ẏ, ż in world axes, j̇1, j̇2, ω in body axes). With
v_pin = P v: M = Pᵀ M_pin P, and the accelerations map as
ẍ = R (v̇_lin + ω × v_lin). Printed in lagrange's conventions, 17 digits.

    python3 lagrange-bench/peer/pinocchio/free_flyer_reference.py
"""
import numpy as np
import pinocchio as pin

model = pin.Model()
hub = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "hub")
model.appendBodyToJoint(hub, pin.Inertia(5.0, np.zeros(3), np.diag([0.4, 0.5, 0.6])), pin.SE3.Identity())
j1 = model.addJoint(hub, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([0.3, 0.1, 0.2])), "j1")
model.appendBodyToJoint(j1, pin.Inertia(1.5, np.array([0.2, 0, 0]), np.diag([0.01, 0.05, 0.05])), pin.SE3.Identity())
j2 = model.addJoint(j1, pin.JointModelRY(), pin.SE3(np.eye(3), np.array([0.4, 0, 0])), "j2")
model.appendBodyToJoint(j2, pin.Inertia(1.0, np.array([0.15, 0, 0]), np.diag([0.005, 0.02, 0.02])), pin.SE3.Identity())
data = model.createData()

quat = np.array([0.8, 0.2, -0.4, 0.3])
w, x, y, z = quat / np.linalg.norm(quat)
position, joints = np.array([0.1, -0.2, 0.3]), np.array([0.7, -0.4])
xdot, jdot, omega = np.array([0.3, -0.1, 0.2]), np.array([0.5, -0.8]), np.array([0.4, -0.6, 0.9])

q_pin = np.concatenate([position, [x, y, z, w], joints])
R = pin.Quaternion(w, x, y, z).toRotationMatrix()
v_pin = np.concatenate([R.T @ xdot, omega, jdot])
P = np.zeros((8, 8))
P[0:3, 0:3] = R.T
P[3:6, 5:8] = np.eye(3)
P[6:8, 3:5] = np.eye(2)
M = P.T @ pin.crba(model, data, q_pin) @ P
M = np.triu(M) + np.triu(M, 1).T
a_pin = pin.aba(model, data, q_pin, v_pin, np.zeros(8))
a = np.concatenate([R @ (a_pin[0:3] + np.cross(omega, v_pin[0:3])), a_pin[6:8], a_pin[3:6]])
def row(xs):
    return "[" + ", ".join(repr(float(x)) for x in xs) + "]"

print("q =", row(np.concatenate([position, joints, [w, x, y, z]])))
print("v =", row(np.concatenate([xdot, jdot, omega])))
print("M = [" + ", ".join(row(r) for r in M) + "]")
print("accel =", row(a))
