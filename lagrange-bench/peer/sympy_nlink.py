#!/usr/bin/env python3
"""Peer baseline: SymPy's LagrangesMethod on the generic planar n-link pendulum.

The system is the one `lagrange` derives in benches/eval.rs (`Chain10`) and that the
issue benchmarks for n = 1..10:

  * coordinates q_1..q_n, absolute angles from the downward vertical;
  * link k has mass m_k and length l_k (all distinct symbols), a point mass at the
    end of each link:
        x_k =  sum_{j<=k} l_j sin q_j,      y_k = -sum_{j<=k} l_j cos q_j;
  * uniform gravity g pointing along -y.

For every n the script

  1. builds the system with sympy.physics.mechanics the standard way
     (dynamicsymbols, ReferenceFrame, Point, Particle, Lagrangian, LagrangesMethod);
  2. times `LagrangesMethod.form_lagranges_equations()` with time.perf_counter
     (the model set-up -- points, velocities, the Lagrangian -- is timed separately);
  3. takes `mass_matrix` (full n x n) and `forcing` (n x 1), replaces q_k(t) and
     q_k'(t) by plain symbols q_k, u_k (otherwise count_ops would count the
     undefined functions and Derivative nodes as operations), runs ONE `sympy.cse`
     over all n*n + n entries together and times it;
  4. counts operations of the CSE'd result, count_ops(visual=False) summed over the
     replacement right-hand sides and the reduced expressions, plus the split read
     from count_ops(visual=True) (ADD, SUB, NEG, MUL, DIV, POW, SIN, COS, ...);
  5. also counts, for reference, a second CSE over the lower triangle of M (i >= j)
     plus forcing, and the un-CSE'd op count;
  6. checks M and forcing numerically against the closed form
        M_ij = mu_max(i,j) l_i l_j cos(q_i - q_j),
        f_i  = -mu_i g l_i sin q_i - sum_j mu_max(i,j) l_i l_j sin(q_i - q_j) u_j^2,
     with mu_k = sum_{r>=k} m_r (skip with --no-check).

Gravity enters as applied forces -m_k g y_hat in LagrangesMethod's forcelist by
default (like the macro's `gravity = [0, -g]`, which is a generalized force);
`--gravity potential` puts V = sum m_k g y_k into the Lagrangian instead.

Usage:
    python3 lagrange-bench/peer/sympy_nlink.py [N ...] [--quick] [--gravity force|potential]
                                         [--no-check] [--no-lower] [--dynamic-ops]
Default N list: 1 2 3 5 10.  --quick: 1 2 3 5.
"""

import argparse
import platform
import random
import sys
import time

import sympy
from sympy import Matrix, Symbol, cos, count_ops, cse, sin, symbols
from sympy.physics.mechanics import (
    LagrangesMethod,
    Lagrangian,
    Particle,
    Point,
    ReferenceFrame,
    dynamicsymbols,
)


def build(n, gravity):
    """Return (LagrangesMethod, q, qd, m, l, g) for the n-link chain (not yet formed)."""
    q = dynamicsymbols(f"q1:{n + 1}")
    qd = [qi.diff() for qi in q]
    m = symbols(f"m1:{n + 1}")
    l = symbols(f"l1:{n + 1}")
    g = Symbol("g")

    N = ReferenceFrame("N")
    O = Point("O")
    O.set_vel(N, 0)

    particles = []
    forces = []
    prev = O
    for k in range(n):
        P = prev.locatenew(f"P{k + 1}", l[k] * sin(q[k]) * N.x - l[k] * cos(q[k]) * N.y)
        P.set_vel(N, P.pos_from(O).dt(N))
        pa = Particle(f"pa{k + 1}", P, m[k])
        if gravity == "potential":
            # y_k = P.pos_from(O) . N.y
            pa.potential_energy = m[k] * g * P.pos_from(O).dot(N.y)
        else:
            forces.append((P, -m[k] * g * N.y))
        particles.append(pa)
        prev = P

    L = Lagrangian(N, *particles)
    lm = LagrangesMethod(L, q, forcelist=forces if forces else None, frame=N)
    return lm, q, qd, m, l, g


def to_plain(exprs, q, qd):
    """Replace q_k(t) -> q_k and q_k'(t) -> u_k (plain symbols)."""
    n = len(q)
    qs = symbols(f"q1:{n + 1}")
    us = symbols(f"u1:{n + 1}")
    rep = {}
    for a, b in zip(qd, us):
        rep[a] = b
    for a, b in zip(q, qs):
        rep[a] = b
    # xreplace matches top-down, so Derivative(q(t), t) is replaced before q(t).
    out = [e.xreplace(rep) for e in exprs]
    for e in out:
        if e.atoms(sympy.Derivative, sympy.core.function.AppliedUndef):
            raise RuntimeError(f"left-over dynamic symbols in {e}")
    return out, qs, us


def split_counts(exprs):
    """Sum of count_ops(visual=True) over exprs, as a dict {NAME: count}."""
    total = sympy.Integer(0)
    for e in exprs:
        total += count_ops(e, visual=True)
    d = {}
    for term in sympy.Add.make_args(total):
        if term == 0:
            continue
        c, sym = term.as_coeff_Mul()
        d[str(sym)] = d.get(str(sym), 0) + int(c)
    return d


def cse_ops(exprs):
    """CSE exprs together; return (seconds, n_replacements, total_ops, split dict)."""
    t0 = time.perf_counter()
    repl, red = cse(exprs)
    dt = time.perf_counter() - t0
    pieces = [rhs for _, rhs in repl] + list(red)
    total = sum(count_ops(e, visual=False) for e in pieces)
    split = split_counts(pieces)
    assert total == sum(split.values()), (total, split)
    return dt, len(repl), int(total), split


def check(M, f, qs, us, m, l, g, n, trials=2):
    """Numeric check of M and forcing against the closed form; returns max abs error."""
    rng = random.Random(12345 + n)
    worst = 0.0
    for _ in range(trials):
        vals = {}
        for s in list(qs) + list(us):
            vals[s] = rng.uniform(-2, 2)
        for s in list(m) + list(l):
            vals[s] = rng.uniform(0.5, 2)
        vals[g] = 9.81
        qv = [vals[s] for s in qs]
        uv = [vals[s] for s in us]
        mv = [vals[s] for s in m]
        lv = [vals[s] for s in l]
        mu = [sum(mv[k:]) for k in range(n)]
        import math

        for i in range(n):
            fi = -mu[i] * 9.81 * lv[i] * math.sin(qv[i])
            for j in range(n):
                mij = mu[max(i, j)] * lv[i] * lv[j] * math.cos(qv[i] - qv[j])
                got = float(M[i, j].xreplace(vals))
                worst = max(worst, abs(got - mij))
                fi -= mu[max(i, j)] * lv[i] * lv[j] * math.sin(qv[i] - qv[j]) * uv[j] ** 2
            got = float(f[i].xreplace(vals))
            worst = max(worst, abs(got - fi))
    return worst


def run(n, args):
    t0 = time.perf_counter()
    lm, q, qd, m, l, g = build(n, args.gravity)
    t_setup = time.perf_counter() - t0

    t0 = time.perf_counter()
    lm.form_lagranges_equations()
    t_form = time.perf_counter() - t0

    Mdyn = lm.mass_matrix
    fdyn = lm.forcing
    assert Mdyn.shape == (n, n) and fdyn.shape == (n, 1)

    full_dyn = [Mdyn[i, j] for i in range(n) for j in range(n)] + [fdyn[i] for i in range(n)]
    full, qs, us = to_plain(full_dyn, q, qd)
    M = Matrix(n, n, full[: n * n])
    f = Matrix(full[n * n:])

    raw_ops = int(sum(count_ops(e, visual=False) for e in full))
    t_cse, n_repl, total, split = cse_ops(full)

    res = dict(n=n, setup=t_setup, form=t_form, cse=t_cse, repl=n_repl, total=total,
               split=split, raw=raw_ops)

    if not args.no_lower:
        lower = [M[i, j] for i in range(n) for j in range(i + 1)] + list(f)
        t_cse_lo, _, total_lo, split_lo = cse_ops(lower)
        res.update(cse_lo=t_cse_lo, total_lo=total_lo, split_lo=split_lo)
        # Is the full M structurally symmetric (so CSE shares M_ij and M_ji)?
        res["sym"] = all(M[i, j] == M[j, i] for i in range(n) for j in range(i))

    if args.dynamic_ops:
        # Same CSE, but on the raw LagrangesMethod output: q_k(t) and q_k'(t) stay
        # undefined functions / Derivative nodes, which count_ops counts as FUNC_Q*
        # and DERIVATIVE operations.
        _, _, total_dyn, split_dyn = cse_ops(full_dyn)
        res.update(total_dyn=total_dyn, split_dyn=split_dyn)

    if not args.no_check:
        res["err"] = check(M, f, qs, us, m, l, g, n)

    return res


def fmt_split(s):
    adds = s.get("ADD", 0) + s.get("SUB", 0)
    neg = s.get("NEG", 0)
    muls = s.get("MUL", 0)
    divs = s.get("DIV", 0)
    pows = s.get("POW", 0)
    trig = s.get("SIN", 0) + s.get("COS", 0)
    known = {"ADD", "SUB", "NEG", "MUL", "DIV", "POW", "SIN", "COS"}
    other = {k: v for k, v in s.items() if k not in known}
    return adds, neg, muls, divs, pows, trig, other


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("n", nargs="*", type=int, help="link counts (default 1 2 3 5 10)")
    ap.add_argument("--quick", action="store_true", help="n = 1 2 3 5 only")
    ap.add_argument("--gravity", choices=["force", "potential"], default="force")
    ap.add_argument("--no-check", action="store_true", help="skip the numeric check")
    ap.add_argument("--no-lower", action="store_true",
                    help="skip the lower-triangle CSE variant")
    ap.add_argument("--dynamic-ops", action="store_true",
                    help="also count ops with q(t), q'(t) left as dynamicsymbols")
    args = ap.parse_args()
    ns = args.n or ([1, 2, 3, 5] if args.quick else [1, 2, 3, 5, 10])

    print(f"python {platform.python_version()}, sympy {sympy.__version__}, "
          f"gravity as {args.gravity}", flush=True)

    rows = []
    for n in ns:
        r = run(n, args)
        rows.append(r)
        adds, neg, muls, divs, pows, trig, other = fmt_split(r["split"])
        msg = (f"n={n}: setup {r['setup']:.3f} s, form {r['form']:.3f} s, "
               f"cse {r['cse']:.3f} s, ops {r['total']} ({r['repl']} replacements), "
               f"un-CSE'd ops {r['raw']}")
        if "total_lo" in r:
            msg += (f", lower-tri M + f: {r['total_lo']} ops (cse {r['cse_lo']:.3f} s), "
                    f"M structurally symmetric: {r['sym']}")
        if "total_dyn" in r:
            sd = r["split_dyn"]
            fn = sum(v for k, v in sd.items() if k.startswith("FUNC_"))
            msg += (f", ops with dynamicsymbols kept: {r['total_dyn']} "
                    f"(of which FUNC_* {fn}, DERIVATIVE {sd.get('DERIVATIVE', 0)})")
        if "err" in r:
            msg += f", max |err| vs closed form {r['err']:.2e}"
        if other:
            msg += f", other ops {other}"
        print(msg, flush=True)

    print()
    print("Full M (n x n) + forcing, one cse over all entries:")
    print()
    print("| n | formation s | cse s | total ops | adds (+,-) | negs | muls | divs | pows "
          "| sin/cos calls |")
    print("|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for r in rows:
        adds, neg, muls, divs, pows, trig, _ = fmt_split(r["split"])
        print(f"| {r['n']} | {r['form']:.3f} | {r['cse']:.3f} | {r['total']} | {adds} | {neg} "
              f"| {muls} | {divs} | {pows} | {trig} |")

    if rows and "total_lo" in rows[0]:
        print()
        print("Lower triangle of M (i >= j) + forcing, one cse over all entries:")
        print()
        print("| n | cse s | total ops | adds (+,-) | negs | muls | divs | pows "
              "| sin/cos calls |")
        print("|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
        for r in rows:
            adds, neg, muls, divs, pows, trig, _ = fmt_split(r["split_lo"])
            print(f"| {r['n']} | {r['cse_lo']:.3f} | {r['total_lo']} | {adds} | {neg} "
                  f"| {muls} | {divs} | {pows} | {trig} |")

    print()
    print("| n | setup s | un-CSE'd ops | cse replacements | max abs err |")
    print("|--:|--:|--:|--:|--:|")
    for r in rows:
        err = f"{r['err']:.1e}" if "err" in r else "-"
        print(f"| {r['n']} | {r['setup']:.3f} | {r['raw']} | {r['repl']} | {err} |")


if __name__ == "__main__":
    sys.exit(main())
