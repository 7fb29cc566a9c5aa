"""Pinocchio traced into CasADi's C: generates, compiles and checks the C peer.

Set-up (PyPI only; versions that worked, 2026-05):
    pip install pin==4.0.0 casadi==3.8.2 cmeel-eigen==3.4.1
(pin 4.0.0 suits Crocoddyl too; pin 4.1.0 works as well and gives
byte-identical C. `pin` pulls `libpinocchio`, whose headers include pinocchio/autodiff/casadi.hpp;
`cmeel-eigen` gives Eigen's headers; CasADi's wheel ships its C++ headers and
libcasadi.so.) No PyPI wheel of `pin` (4.1.0, 4.0.0, 3.9.0, 3.7.0, 3.4.0
looked at) ships the Python module `pinocchio.casadi`, so the tracing is done
in C++ (trace.cpp), with the same templates that module wraps: Pinocchio's
algorithms on the scalar casadi::SX, emitted by casadi::CodeGenerator.

Steps, into OUT (default $TMPDIR/casadi_peer):
 1. ../pinocchio/urdf_model.py writes the arms of robots/ and Solo 12 (on a
    free flyer) as C++ Pinocchio models (the wheel has no urdfdom headers
    for Pinocchio's parser);
 2. trace.cpp is compiled (g++ -O1: it only traces; minutes, so only when
    it or a model changed) and run: casadi_gen.c/.h
    and casadi_registry.h; every robot's states go into casadi_states.h;
 3. harness.c + casadi_gen.c are compiled with gcc -O3 -march=native, as
    the program `harness` and as `libharness.so` (for the interleaved
    timing of examples/casadi_peer/);
 4. the harness's values (through the compiled C) are checked against plain
    numeric Pinocchio at the same state, to 1e-10 relative to each output's
    largest entry (or 1); the max difference per output is printed, and the
    exit status is 1 if any exceeds it. (Our side's values, which compare.py
    checks the same way, are in our coordinates: for Solo 12 the reference
    is mapped to them by floating_reference.py.)

    python3 casadi_codegen.py [OUT]

Both sides are timed at two states (ANGLES): "small", every joint angle
within 0.55 rad, and "wide", spread over a turn (`harness [values] wide`,
`casadi_peer --wide`).
"""
import os
import subprocess
import sys

import numpy as np
import pinocchio as pin

from floating_reference import Mapped

HERE = os.path.dirname(os.path.abspath(__file__))
ROBOTS_DIR = os.path.normpath(os.path.join(HERE, "../../../robots"))
ARMS = ["ur5", "ur10", "kinova", "z1", "xarm7"]
# On a free-flyer root (Pinocchio's JointModelFreeFlyer, our `base = floating`).
FLOATING = ["solo12"]
ROBOTS = ARMS + FLOATING
TOLERANCE = 1e-10


def site_prefix():
    """Where the cmeel wheels (pin, libpinocchio, cmeel-eigen) put their files."""
    return os.path.abspath(os.path.join(os.path.dirname(pin.__file__), "../../../.."))


def casadi_dir():
    import casadi

    return os.path.dirname(casadi.__file__)


def run(cmd, **kw):
    print("+", " ".join(cmd), file=sys.stderr)
    subprocess.run(cmd, check=True, **kw)


def build(out):
    os.makedirs(out, exist_ok=True)
    prefix, cas = site_prefix(), casadi_dir()
    models = os.path.join(out, "models.hpp")
    run([sys.executable, os.path.join(HERE, "../pinocchio/urdf_model.py"), ROBOTS_DIR, models])
    tracer = os.path.join(out, "trace")
    sources = [os.path.join(HERE, "trace.cpp"), os.path.join(HERE, "../pinocchio/urdf_model.py")]
    sources += [os.path.join(ROBOTS_DIR, f"{robot}.urdf") for robot in ROBOTS]
    stale = not os.path.exists(tracer) or os.path.getmtime(tracer) < max(map(os.path.getmtime, sources))
    if stale:  # minutes: Pinocchio's templates on casadi::SX
        run(["g++", "-O1", "-std=c++17", "-DNDEBUG", "-w",
             "-DBOOST_MPL_LIMIT_LIST_SIZE=30", "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30",
             "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS", "-DBOOST_FUSION_INVOKE_MAX_ARITY=12",
             f'-DURDF_MODELS="{models}"', os.path.join(HERE, "trace.cpp"), "-o", tracer,
             f"-I{prefix}/include", f"-I{prefix}/include/eigen3", f"-I{cas}/include",
             f"-L{prefix}/lib", f"-Wl,-rpath,{prefix}/lib", "-lpinocchio_default",
             f"-L{cas}", f"-Wl,-rpath,{cas}", "-lcasadi"])
    run([tracer, out])
    write_states(os.path.join(out, "casadi_states.h"))
    # casadi_gen.c compiled once (gcc takes minutes on it), position
    # independent, for the harness and for libharness.so.
    cc = ["gcc", "-O3", "-march=native", "-w", "-fPIC", f"-I{out}"]
    gen = os.path.join(out, "casadi_gen.o")
    run(cc + ["-c", os.path.join(out, "casadi_gen.c"), "-o", gen])
    harness = os.path.join(out, "harness")
    run(cc + [os.path.join(HERE, "harness.c"), gen, "-o", harness, "-lm"])
    run(cc + ["-shared", "-DCASADI_PEER_LIBRARY", os.path.join(HERE, "harness.c"), gen,
              "-o", os.path.join(out, "libharness.so"), "-lm"])
    return harness


def load(robot):
    """Pinocchio's model of a robot of robots/, on a free flyer if it floats."""
    path = os.path.join(ROBOTS_DIR, f"{robot}.urdf")
    if robot in FLOATING:
        return pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    return pin.buildModelFromUrdf(path)


def write_states(path):
    """Each robot's state for the harness: <robot>_q, _v, _a (the small
    state; a is also τ) and <robot>_q_wide, with the table WIDE."""
    def array(name, x):
        return f"static const double {name}[] = {{{', '.join(repr(float(v)) for v in x)}}};\n"

    rows = []
    with open(path, "w") as f:
        f.write("// Written by casadi_codegen.py: each robot's state (casadi_codegen.state).\n")
        for robot in ROBOTS:
            model = load(robot)
            q, v, a = state(model, "small")
            f.write(array(f"{robot}_q", q) + array(f"{robot}_v", v) + array(f"{robot}_a", a))
            f.write(array(f"{robot}_q_wide", state(model, "wide")[0]))
            rows.append(f'  {{"{robot}", {robot}_q_wide}}')
        f.write("static const struct { const char* robot; const double* q; } WIDE[] = {\n")
        f.write(",\n".join(rows) + "\n};\n")


def parse(text):
    """`value robot quantity output numbers` lines -> {(robot, quantity, output): array}."""
    values = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 5 and parts[0] == "value":
            values[tuple(parts[1:4])] = np.array([float(x) for x in parts[4].split(",")])
    return values


# The joint angles of the two states the peers are timed at: "small", every
# angle within 0.55 rad (where the C library's sin and cos take their short
# path), and "wide", spread over a turn, as a moving arm's are.
ANGLES = {
    "small": lambda k: 0.3 - 0.17 * k,
    "wide": lambda k: 2.8 - 0.93 * k,
}


# A free flyer's pose in both states: its position, and its orientation as
# the unit quaternion (x, y, z, w) of these numbers.
ROOT_POSITION = [0.1, -0.2, 0.3]
ROOT_QUATERNION = [0.1, -0.15, 0.25, 0.95]


def state(model, which="small"):
    """q (cos and sin of a continuous joint's angle), v, a = tau, as the peers' state.

    On a free flyer, the joints after it count from k = 0 for their angles
    and a = tau (zero on the root: forces on an unactuated base, and an
    acceleration that, with these v, is not zero in our convention); v
    counts over every velocity, the root's first."""
    q = np.zeros(model.nq)
    root = 6 if model.joints[1].shortname() == "JointModelFreeFlyer" else 0
    for j in range(1, model.njoints):
        joint = model.joints[j]
        if joint.shortname() == "JointModelFreeFlyer":
            quat = np.array(ROOT_QUATERNION)
            q[joint.idx_q:joint.idx_q + 7] = np.concatenate([ROOT_POSITION, quat / np.linalg.norm(quat)])
            continue
        angle = ANGLES[which](joint.idx_v - root)
        if joint.nq == 2:
            q[joint.idx_q], q[joint.idx_q + 1] = np.cos(angle), np.sin(angle)
        else:
            q[joint.idx_q] = angle
    k = np.arange(model.nv)
    a = np.where(k < root, 0.0, 0.1 * (k - root) - 0.2)
    return q, 0.5 - 0.21 * k, a


def reference(robot, which="small", side="casadi"):
    """Plain numeric Pinocchio at the state: {(quantity, output): array},
    matrices row-major; for our side of a floating robot, in our convention
    (floating_reference)."""
    model = load(robot)
    data = model.createData()
    q, v, a = state(model, which)
    if side == "lagrange" and robot in FLOATING:
        return Mapped(model).reference(q, v, a, a)
    ref = {}
    M = pin.crba(model, data, q).copy()
    M = np.triu(M) + np.triu(M, 1).T
    h = pin.nonLinearEffects(model, data, q, v).copy()
    ref["crba_nle", "M"], ref["crba_nle", "h"] = M, h
    ref["crba_nle", "rhs"] = -h
    ref["rnea", "tau"] = pin.rnea(model, data, q, v, a).copy()
    ddq = pin.aba(model, data, q, v, a).copy()
    for quantity in ("aba", "chol", "chol_qr"):
        ref[quantity, "ddq"] = ddq
    ddq_dq, ddq_dv, minv = pin.computeABADerivatives(model, data, q, v, a)
    ref["aba_derivatives", "ddq_dq"] = ddq_dq.copy()
    ref["aba_derivatives", "ddq_dv"] = ddq_dv.copy()
    minv = np.triu(minv) + np.triu(minv, 1).T
    ref["aba_derivatives", "Minv"] = minv
    dtau_dq, dtau_dv, _ = pin.computeRNEADerivatives(model, data, q, v, a)
    ref["rnea_derivatives", "dtau_dq"] = dtau_dq.copy()
    ref["rnea_derivatives", "dtau_dv"] = dtau_dv.copy()
    return {key: np.asarray(x).reshape(-1) for key, x in ref.items()}


def check(values, label, which="small", side="casadi"):
    """Prints each output's max difference from numeric Pinocchio, absolute and
    relative to the output's largest entry (or 1); True if every relative one
    is within 1e-10 (M⁻¹ of an arm with a light wrist has entries in the
    thousands, where 1e-10 absolute is below the rounding of either side)."""
    ok = True
    print(f"| {label}: robot | quantity | output | max abs difference from pin | / max(1, max |pin|) |")
    print("|---|---|---|---|---|")
    refs = {robot: reference(robot, which, side) for robot in ROBOTS}
    for (robot, quantity, output), x in sorted(values.items()):
        ref = refs[robot].get((quantity, output))
        if ref is None:
            continue
        diff = float(np.max(np.abs(x - ref))) if x.shape == ref.shape else float("inf")
        scaled = diff / max(1.0, float(np.max(np.abs(ref))))
        flag = "" if scaled <= TOLERANCE else " **over 1e-10**"
        ok &= scaled <= TOLERANCE
        print(f"| {robot} | {quantity} | {output} | {diff:.1e} | {scaled:.1e}{flag} |")
    return ok


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.environ.get("TMPDIR", "/tmp"), "casadi_peer")
    harness = build(out)
    ok = True
    for which in ANGLES:
        text = subprocess.run([harness, "values", which], check=True, capture_output=True, text=True).stdout
        ok &= check(parse(text), f"CasADi C, {which} state", which, "casadi")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
