"""Reference values for the runtime's discrete-time linear models
(lagrange-runtime/src/linear/discrete.rs tests): SciPy's exact zero-order-hold
discretisation (`cont2discrete`, method "zoh") and discrete algebraic Riccati
equation (`solve_discrete_are`), printed as Rust literals with every digit.

    pip install scipy && python3 lagrange-bench/peer/scipy_discrete.py
"""
import numpy as np
import scipy
from scipy.signal import cont2discrete
from scipy.linalg import solve_discrete_are

CASES = {
    # Double integrator, one force: x = (position, velocity).
    "double_integrator": (
        np.array([[0.0, 1.0], [0.0, 0.0]]),
        np.array([[0.0], [1.0]]),
        0.1,
        np.diag([1.0, 0.5]),
        np.array([[0.2]]),
    ),
    # A cart-pole linearised upright (m_cart 1, m_pole 0.1, l 0.5, g 9.81),
    # x = (x, theta, dot_x, dot_theta), sampled at 50 Hz.
    "cart_pole": (
        np.array(
            [
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
                [0.0, -0.981, 0.0, 0.0],
                [0.0, 21.582, 0.0, 0.0],
            ]
        ),
        np.array([[0.0], [0.0], [1.0], [-2.0]]),
        0.02,
        np.diag([10.0, 100.0, 1.0, 1.0]),
        np.array([[0.1]]),
    ),
    # An unstable, lightly damped pair of modes driven by two inputs, with a
    # cross-coupled cost.
    "two_inputs": (
        np.array(
            [
                [0.0, 1.0, 0.0, 0.0],
                [2.0, -0.1, 0.5, 0.0],
                [0.0, 0.0, 0.0, 1.0],
                [0.3, 0.0, -4.0, -0.05],
            ]
        ),
        np.array([[0.0, 0.0], [1.0, 0.2], [0.0, 0.0], [0.1, 1.0]]),
        0.05,
        np.array(
            [
                [2.0, 0.1, 0.0, 0.0],
                [0.1, 1.0, 0.0, 0.0],
                [0.0, 0.0, 3.0, 0.2],
                [0.0, 0.0, 0.2, 0.5],
            ]
        ),
        np.array([[1.0, 0.1], [0.1, 0.5]]),
    ),
}


def rust(name, m):
    rows = ", ".join(repr(float(v)) for v in np.asarray(m).ravel())
    return f"    const {name}: &[f64] = &[{rows}];"


print(f"// scipy {scipy.__version__}, numpy {np.__version__}")
for case, (a, b, h, q, r) in CASES.items():
    ad, bd, *_ = cont2discrete((a, b, np.eye(a.shape[0]), np.zeros(b.shape)), h, method="zoh")
    p = solve_discrete_are(ad, bd, q, r)
    k = np.linalg.solve(r + bd.T @ p @ bd, bd.T @ p @ ad)
    print(f"// {case}: A_d, B_d (row-major), P, K")
    print(f"mod {case} {{")
    print(rust("AD", ad))
    print(rust("BD", bd))
    print(rust("P", p))
    print(rust("K", k))
    print("}")
