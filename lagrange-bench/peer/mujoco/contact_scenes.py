"""MuJoCo's side of "Contact beside MuJoCo" (BENCHMARKS.md): the scenes of
lagrange-bench/benches/contact.rs (the catalog's contact systems) in MJCF,
run at several steps and integrators, each against the same closed forms the
Rust tests check, with the penetration and the wall time per simulated second.

    python3 lagrange-bench/peer/mujoco/contact_scenes.py [--csv out.csv] [--quick]

Scenes (as examples/catalog/contact.rs and tests/contact.rs):
  ball             solid sphere r = 0.1, m = 0.3, dropped from h0 = 0.5 (gap)
                   on a plane, e = 0.5: impacts at t1 (1 + 2e + ... ), rebound
                   k to e^(2k) h0, at rest at t1 (1 + e)/(1 - e)
  sphere_slide     the same ball thrown at v0 = 2 m/s without spin on the
                   plane, mu = 0.3: rolls from 2 v0/(7 mu g) at 5/7 v0
  sphere_backspin  thrown at v0 = 2 m/s with backspin 80 rad/s: rolls from
                   2 (v0 + r w0)/(7 mu g) at (5 v0 - 2 r w0)/7
  block            a block (a = 0.2, m = 1.5, no rotation) pushed at (3, 4)
                   m/s, mu = 0.4, e = 0: stops at |v0|/(mu g) after
                   |v0|^2/(2 mu g), on the line
  pendulum         point mass 0.7 on l = 1.3 released at 1.2 rad against a
                   joint limit at 0, e = 0.6: impacts at T(th0)/4 and
                   + T(th1)/2, 1 - cos th1 = e^2 (1 - cos th0)

The mapping of restitution (MuJoCo has no restitution coefficient): the
contact (and the joint limit) is MuJoCo's soft constraint with a constant
impedance d (solimp = "0.99 0.99 0.001": d0 = dwidth, so d does not depend
on the penetration) and solref = (timeconst, dampratio). With a constant d
the reference dynamics is a linear oscillator in the normal distance, with
damping ratio dampratio and natural frequency 1/(timeconst dampratio); a
damped linear oscillator kept in contact would rebound with
e = exp(-pi zeta/sqrt(1 - zeta^2)), i.e. zeta = -ln e/sqrt(pi^2 + ln^2 e)
(0.2155 for e = 0.5). That is not what MuJoCo's contact keeps: the
constraint cannot pull, so the body leaves before the gap closes, and the
step resolves the contact in a few steps. So the dampratio is calibrated
instead: bisection on dampratio until one impact, in the model as run (same
step, integrator and timeconst) without gravity, leaves at e times the
speed it came in with (calibrate()); the system is linear, so that holds at
any impact speed and any step with the same timeconst/step ratio. For the
block (e = 0) dampratio = 1 (critical). The timeconst is scaled with the
step, timeconst = TC_STEPS * dt = 25 dt (a ball impact lasts ~15 steps), so
that refining the step also stiffens the contact and the run can converge to
the rigid closed forms; a fixed timeconst (MuJoCo's default 0.02 s) cannot,
and is run too at dt = 1e-4 for reference (timeconst 2e-02 rows).

Friction: condim = 3 (sliding friction only, no torsional or rolling
resistance, which the closed forms do not have), the same mu on both geoms
(MuJoCo takes the larger), the elliptic cone; the block is also run with the
pyramidal cone. The ball, sphere and block move on slide joints (x, z and a
hinge about y for the ball, as the catalog's coordinates; x, y, z for the
block, which does not turn), the pendulum on a hinge with range [0, 3].

Wall time: mj_step(model, data, nstep) over the whole span from the initial
state (C loop, no Python per step, nothing recorded), repeated, the median of
the repeats per simulated second; MuJoCo runs single-threaded (no thread
pool). The errors come from a separate, recorded run (Python loop).
"""

import argparse
import csv
import math
import statistics
import sys
import time

import mujoco
import numpy as np

G = 9.81
R, M_BALL, E_BALL, MU_BALL = 0.1, 0.3, 0.5, 0.3
A_BLOCK, M_BLOCK, MU_BLOCK = 0.2, 1.5, 0.4
L, M_PEND, E_STOP, TH0 = 1.3, 0.7, 0.6, 1.2
H0 = 0.5
TC_STEPS = 25.0
# The second family: timeconst = TC_SQRT sqrt(dt) (25 steps at dt = 1e-3,
# 79 at 1e-4, 250 at 1e-5).
TC_SQRT = 0.79
SOLIMP = "0.99 0.99 0.001"
# A slip (sphere) or a speed (block) below this counts as rolling / stopped.
SLIP_TOL = 1e-4
# The ball counts as settled once its gap stays within this of its last.
SETTLED = 1e-6
SPANS = {"ball": 1.5, "sphere_slide": 1.5, "sphere_backspin": 1.5, "block": 1.6, "pendulum": 3.0}


def zeta(e):
    """Damping ratio of a linear oscillator whose rebound keeps e of the speed."""
    if e <= 0.0:
        return 1.0
    le = math.log(e)
    return -le / math.sqrt(math.pi**2 + le * le)


def elliptic_k(k):
    a, b = 1.0, math.sqrt(1.0 - k * k)
    for _ in range(60):
        a, b = (a + b) / 2.0, math.sqrt(a * b)
        if abs(a - b) < 1e-17:
            break
    return math.pi / (2.0 * a)


def mjcf(scene, dt, integrator, cone, tc, dampratio=None, gravity=G):
    """The scene's MJCF; dampratio None: the calibrated one (see calibrate)."""
    if dampratio is None:
        dampratio = calibrate(scene, dt, integrator, tc)
    opt = (
        f'<compiler angle="radian"/>'
        f'<option timestep="{dt!r}" integrator="{integrator}" cone="{cone}" gravity="0 0 -{gravity!r}"/>'
    )
    if scene == "pendulum":
        sr = f"{tc!r} {dampratio!r}"
        body = f"""
    <body name="arm" pos="0 0 2">
      <joint name="th" type="hinge" axis="0 -1 0" limited="true" range="0 3"
             solreflimit="{sr}" solimplimit="{SOLIMP}"/>
      <inertial pos="0 0 -{L}" mass="{M_PEND}" diaginertia="1e-9 1e-9 1e-9"/>
    </body>"""
        return f"<mujoco>{opt}<worldbody>{body}</worldbody></mujoco>"
    if scene == "block":
        mu, sr = MU_BLOCK, f"{tc!r} {dampratio!r}"
        body = f"""
    <body name="block" pos="0 0 {A_BLOCK / 2}">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="y" type="slide" axis="0 1 0"/>
      <joint name="z" type="slide" axis="0 0 1"/>
      <geom type="box" size="{A_BLOCK / 2} {A_BLOCK / 2} {A_BLOCK / 2}" mass="{M_BLOCK}"
            condim="3" friction="{mu} 0 0" solref="{sr}" solimp="{SOLIMP}"/>
    </body>"""
    else:
        mu, sr = MU_BALL, f"{tc!r} {dampratio!r}"
        body = f"""
    <body name="ball">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="z" type="slide" axis="0 0 1"/>
      <joint name="th" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="{R}" mass="{M_BALL}"
            condim="3" friction="{mu} 0 0" solref="{sr}" solimp="{SOLIMP}"/>
    </body>"""
    floor = (
        f'<geom type="plane" size="0 0 1" condim="3" friction="{mu} 0 0" '
        f'solref="{sr}" solimp="{SOLIMP}"/>'
    )
    return f"<mujoco>{opt}<worldbody>{floor}{body}</worldbody></mujoco>"


_CALIBRATED = {}


def restitution(scene, dt, integrator, tc, dampratio):
    """The normal speed kept by one impact of the scene's contact (limit), in
    the model as run (step, integrator, timeconst), without gravity: the
    ball (block) arriving at 1 m/s at the plane, the pendulum at 1 rad/s at
    its limit; e is the speed it leaves with once it is clear."""
    model = mujoco.MjModel.from_xml_string(
        mjcf(scene, dt, integrator, "elliptic", tc, dampratio, gravity=0.0)
    )
    data = mujoco.MjData(model)
    if scene == "pendulum":
        data.qpos[0], data.qvel[0], k, clear = 1e-12, -1.0, 0, 0.0
    elif scene == "block":
        data.qpos[2], data.qvel[2], k, clear = 1e-12, -1.0, 2, 0.0
    else:
        data.qpos[1], data.qvel[1], k, clear = R + 1e-12, -1.0, 1, R
    for _ in range(int(100 * tc / dt) + 100):
        mujoco.mj_step(model, data)
        if data.qpos[k] > clear and data.qvel[k] > 0.0:
            return data.qvel[k]
    return 0.0


def calibrate(scene, dt, integrator, tc):
    """The dampratio whose impact keeps the scene's e (bisection; e falls as
    the damping rises), for e = 0 critical damping (1)."""
    e = {"pendulum": E_STOP, "block": 0.0}.get(scene, E_BALL)
    if e <= 0.0:
        return 1.0
    key = (scene == "pendulum", round(tc / dt, 9), integrator, tc if tc / dt > 100 else None)
    if key not in _CALIBRATED:
        lo, hi = 0.01, 2.0
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if restitution(scene, dt, integrator, tc, mid) > e:
                lo = mid
            else:
                hi = mid
        _CALIBRATED[key] = 0.5 * (lo + hi)
    return _CALIBRATED[key]


def initial(scene):
    """(qpos, qvel) as the Rust runs start."""
    if scene == "ball":
        return [0.0, H0 + R, 0.0], [0.0, 0.0, 0.0]
    if scene == "sphere_slide":
        return [0.0, R, 0.0], [2.0, 0.0, 0.0]
    if scene == "sphere_backspin":
        # Backspin: theta-dot = -80 (rolling forward is x-dot = r theta-dot).
        return [0.0, R, 0.0], [2.0, 0.0, -80.0]
    if scene == "block":
        return [0.0, 0.0, 0.0], [3.0, 4.0, 0.0]
    return [TH0], [0.0]


def crossings(t, f, down=True):
    """Times where f crosses 0 downward (or upward), linearly interpolated."""
    if down:
        idx = np.nonzero((f[:-1] > 0.0) & (f[1:] <= 0.0))[0]
    else:
        idx = np.nonzero((f[:-1] <= 0.0) & (f[1:] > 0.0))[0]
    return [t[i] + (t[i + 1] - t[i]) * f[i] / (f[i] - f[i + 1]) for i in idx]


def record(model, scene):
    data = mujoco.MjData(model)
    q0, v0 = initial(scene)
    data.qpos[:] = q0
    data.qvel[:] = v0
    n = int(round(SPANS[scene] / model.opt.timestep))
    t = np.empty(n + 1)
    q = np.empty((n + 1, model.nq))
    v = np.empty((n + 1, model.nv))
    t[0], q[0], v[0] = 0.0, data.qpos, data.qvel
    for i in range(1, n + 1):
        mujoco.mj_step(model, data)
        t[i], q[i], v[i] = data.time, data.qpos, data.qvel
    return t, q, v


def errors(scene, t, q, v):
    """[(quantity, error, note)] against the closed forms."""
    out = []
    if scene == "ball":
        e, gap = E_BALL, q[:, 1] - R
        t1 = math.sqrt(2.0 * H0 / G)
        impacts = crossings(t, gap, down=True)
        lifts = crossings(t, gap, down=False)
        exact, worst = t1, 0.0
        for k in range(5):
            if k >= len(impacts):
                worst = math.nan
                break
            worst = max(worst, abs(impacts[k] - exact))
            exact += 2.0 * t1 * e ** (k + 1)
        out.append(("impact times (first 5)", worst, f"{len(impacts)} impacts"))
        hw = 0.0
        for k in range(3):
            if k + 1 >= len(impacts) or k >= len(lifts):
                hw = math.nan
                break
            seg = (t >= lifts[k]) & (t <= impacts[k + 1])
            apex = gap[seg].max() if seg.any() else math.nan
            hw = max(hw, abs(apex - e ** (2 * k + 2) * H0))
        out.append(("bounce heights (first 3)", hw, ""))
        t_rest = t1 * (1.0 + e) / (1.0 - e)
        # Settled: the gap stays within SETTLED of where it ends (the ball
        # sinks a little into the soft contact). The rigid ball's last rebound
        # above 1 um leaves at most 2 sqrt(2e-6/g)/(1 - e) = 1.8 ms before
        # t_rest, the bias of this reading.
        away = np.nonzero(np.abs(gap - gap[-1]) > SETTLED)[0]
        settled = t[away[-1] + 1] if len(away) and away[-1] + 1 < len(t) else math.nan
        tail = t >= t[-1] - 0.3
        out.append(
            (
                "rest time",
                abs(settled - t_rest),
                f"settled within {SETTLED:.0e} m; {len(impacts)} impacts in the span; "
                f"vz over the last 0.3 s up to {np.abs(v[tail, 1]).max():.1e} m/s; sinks {-gap[-1]:.1e} m",
            )
        )
        out.append(("penetration", max(0.0, -gap.min()), ""))
    elif scene.startswith("sphere"):
        v0, spin = 2.0, (80.0 if scene == "sphere_backspin" else 0.0)
        slip = v[:, 0] - R * v[:, 2]
        t_roll = 2.0 * (v0 + R * spin) / (7.0 * MU_BALL * G)
        v_roll = (5.0 * v0 - 2.0 * R * spin) / 7.0
        below = np.nonzero(np.abs(slip) <= SLIP_TOL)[0]
        tr = t[below[0]] if len(below) else math.nan
        out.append(("roll time", abs(tr - t_roll), f"slip <= {SLIP_TOL:.0e} m/s in size; slip at end {slip[-1]:.1e} m/s"))
        out.append(("roll speed", abs(v[-1, 0] - v_roll), ""))
        out.append(("penetration", max(0.0, -(q[:, 1] - R).min()), ""))
    elif scene == "block":
        speed = np.hypot(v[:, 0], v[:, 1])
        t_stop, dist = 5.0 / (MU_BLOCK * G), 25.0 / (2.0 * MU_BLOCK * G)
        below = np.nonzero(speed <= SLIP_TOL)[0]
        ts = t[below[0]] if len(below) else math.nan
        out.append(("stop time", abs(ts - t_stop), f"speed <= {SLIP_TOL:.0e} m/s; at end {speed[-1]:.1e} m/s"))
        out.append(("stop distance", abs(math.hypot(q[-1, 0], q[-1, 1]) - dist), ""))
        out.append(("off the line", abs(0.8 * q[-1, 0] - 0.6 * q[-1, 1]), ""))
        out.append(("penetration", max(0.0, -q[:, 2].min()), ""))
    else:
        e = E_STOP
        period = lambda a: 4.0 * math.sqrt(L / G) * elliptic_k(math.sin(a / 2.0))
        th1 = math.acos(1.0 - e * e * (1.0 - math.cos(TH0)))
        first = period(TH0) / 4.0
        exact = [first, first + period(th1) / 2.0]
        impacts = crossings(t, q[:, 0], down=True)
        worst = max(abs(impacts[k] - exact[k]) if k < len(impacts) else math.nan for k in range(2))
        lifts = crossings(t, q[:, 0], down=False)
        seg = (t >= lifts[0]) & (t <= impacts[1]) if lifts and len(impacts) > 1 else None
        amp = q[seg, 0].max() if seg is not None and seg.any() else math.nan
        out.append(("impact times (first 2)", worst, f"rebound to {amp:.5f} rad, rigid {th1:.5f}"))
        out.append(("penetration", max(0.0, -q[:, 0].min()), "rad"))
    return out


def wall_per_simulated_second(model, scene, budget=0.2, repeats=5):
    data = mujoco.MjData(model)
    q0, v0 = initial(scene)
    n = int(round(SPANS[scene] / model.opt.timestep))
    samples = []
    spent = 0.0
    repeats = repeats if n < 100_000 else 3
    while len(samples) < repeats or (spent < budget and len(samples) < 50):
        mujoco.mj_resetData(model, data)
        data.qpos[:] = q0
        data.qvel[:] = v0
        start = time.perf_counter()
        mujoco.mj_step(model, data, nstep=n)
        elapsed = time.perf_counter() - start
        spent += elapsed
        samples.append(elapsed)
    return statistics.median(samples) / SPANS[scene], n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", default="mujoco_contact.csv")
    ap.add_argument("--quick", action="store_true", help="steps 1e-3 and 1e-4 only")
    args = ap.parse_args()
    steps = [1e-3, 1e-4] if args.quick else [1e-2, 1e-3, 1e-4, 1e-5]
    integrators = ["Euler", "implicitfast", "RK4"]
    runs = []
    for scene in SPANS:
        cones = ["elliptic", "pyramidal"] if scene == "block" else ["elliptic"]
        for cone in cones:
            for integ in integrators:
                for dt in steps:
                    runs.append((scene, cone, integ, dt, TC_STEPS * dt))
            # A contact that stiffens more slowly than the step shrinks, so
            # that the steps per contact grow: timeconst = TC_SQRT sqrt(dt).
            for dt in steps:
                runs.append((scene, cone, "implicitfast", dt, TC_SQRT * math.sqrt(dt)))
            # MuJoCo's default timeconst, fixed: the soft model's own error.
            runs.append((scene, cone, "implicitfast", 1e-4, 0.02))
    rows = []
    print(f"MuJoCo {mujoco.__version__}, numpy {np.__version__}, Python {sys.version.split()[0]}")
    print()
    print("| scene | cone | integrator | dt | timeconst | quantity | error | µs per simulated s | note |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, cone, integ, dt, tc in runs:
        model = mujoco.MjModel.from_xml_string(mjcf(scene, dt, integ, cone, tc))
        t, q, v = record(model, scene)
        per_s, nsteps = wall_per_simulated_second(model, scene)
        for quantity, err, note in errors(scene, t, q, v):
            row = dict(
                scene=scene,
                cone=cone,
                integrator=integ,
                dt=dt,
                timeconst=tc,
                quantity=quantity,
                error=err,
                us_per_simulated_s=per_s * 1e6,
                steps=nsteps,
                note=note,
            )
            rows.append(row)
            print(
                f"| {scene} | {cone} | {integ} | {dt:.0e} | {tc:.1e} | {quantity} | {err:.1e} "
                f"| {per_s * 1e6:.0f} | {note} |",
                flush=True,
            )
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"\nwrote {args.csv}")


if __name__ == "__main__":
    main()
