"""Reads the rounds run.sh wrote (DIR/casadi_STATE_<i>.txt from the C harness,
DIR/lagrange_STATE_<i>.txt from examples/casadi_peer/), checks both sides' values
against plain numeric Pinocchio to 1e-10, and prints the markdown table: per
arm and quantity, the CasADi C and lagrange times (ns per call, the median
over rounds) and their ratio (the median over rounds of each round's
CasADi / lagrange: above 1, lagrange is faster); and, where our rounds were
run with `--interleave` (run.sh does), a second table from their `pair`
lines, each ratio from batches of both sides alternated in one process,
which a machine whose speed drifts between the programs' runs does not
disturb. "terms kept": our side with its parameter-only terms
computed once (`parameter_terms`, the `_with` methods), as a loop of its own
calls it; CasADi's C has them folded in as constants.

    python3 compare.py DIR [STATE]

STATE is `small` (the default) or `wide` (casadi_codegen.ANGLES); the rounds
of that state are DIR/casadi_STATE_<i>.txt and DIR/lagrange_STATE_<i>.txt.
"""
import glob
import os
import re
import statistics
import sys

from casadi_codegen import ROBOTS, check, parse

# (CasADi function, our quantity, what is compared)
ROWS = [
    ("crba_nle", "crba_nle", "M (CRBA) + h (NLE) / M + (Q − h)"),
    ("crba_nle", "crba_nle_terms", "M (CRBA) + h (NLE) / M + (Q − h), terms kept"),
    ("rnea", "rnea", "τ: RNEA / inverse_dynamics"),
    ("aba", "aba", "q̈: ABA / articulated q̈"),
    ("aba", "aba_terms", "q̈: ABA / articulated q̈, terms kept"),
    ("chol", "chol", "q̈: CRBA + NLE + LLᵀ in SX / M + Cholesky q̈"),
    ("chol", "chol_terms", "q̈: CRBA + NLE + LLᵀ in SX / M + Cholesky q̈, terms kept"),
    ("chol_qr", "chol", "q̈: CRBA + NLE + SX QR solve / M + Cholesky q̈"),
    ("aba_derivatives", "aba_derivatives", "computeABADerivatives / acceleration_derivatives (the emitted program)"),
    ("aba_derivatives", "aba_derivatives_runtime", "computeABADerivatives / Dynamics::acceleration_derivatives (M factorised at run time)"),
    ("rnea_derivatives", "rnea_derivatives", "computeRNEADerivatives / rhs_jacobians"),
]


def times(text):
    out = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[0] == "time":
            out[parts[1], parts[2]] = float(parts[3])
    return out


def rounds(folder, side, which):
    files = sorted(glob.glob(os.path.join(folder, f"{side}_{which}_*.txt")),
                   key=lambda f: int(re.findall(r"_(\d+)\.txt$", f)[0]))
    return [open(f).read() for f in files]


def main():
    folder = sys.argv[1]
    which = sys.argv[2] if len(sys.argv) > 2 else "small"
    c_runs, r_runs = rounds(folder, "casadi", which), rounds(folder, "lagrange", which)
    ok = check(parse(c_runs[0]), f"CasADi C, {which} state", which, "casadi")
    print()
    ok &= check(parse(r_runs[0]), f"lagrange, {which} state", which, "lagrange")
    print()
    c_times, r_times = [times(t) for t in c_runs], [times(t) for t in r_runs]
    pairs = list(zip(c_times, r_times))
    print(f"{len(pairs)} rounds; ns per call (median over rounds); ratio = CasADi C / lagrange "
          "(median of the rounds' ratios; > 1: lagrange faster)\n")
    print("| arm | quantity (CasADi C / lagrange) | CasADi C (ns) | lagrange (ns) | ratio |")
    print("|---|---|---:|---:|---:|")
    for robot in ROBOTS:
        for cq, rq, label in ROWS:
            cs = [c[robot, cq] for c, _ in pairs if (robot, cq) in c]
            rs = [r[robot, rq] for _, r in pairs if (robot, rq) in r]
            ratios = [c[robot, cq] / r[robot, rq] for c, r in pairs if (robot, cq) in c and (robot, rq) in r]
            if not ratios:
                continue
            print(f"| {robot} | {label} | {statistics.median(cs):.0f} | {statistics.median(rs):.0f} "
                  f"| {statistics.median(ratios):.2f} |")
    interleaved([pairs_of(t) for t in r_runs])
    sys.exit(0 if ok else 1)


def pairs_of(text):
    """`pair ROBOT QUANTITY C_NS OURS_NS RATIO` lines (casadi_peer --interleave)."""
    out = {}
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 6 and parts[0] == "pair":
            out[parts[1], parts[2]] = tuple(map(float, parts[3:]))
    return out


def interleaved(runs):
    """The table of the rounds' `pair` lines, if there are any: each ratio is
    the median over batches alternated in one process, then over rounds."""
    runs = [r for r in runs if r]
    if not runs:
        return
    print(f"\nInterleaved in one process ({len(runs)} rounds): the C's batches and ours "
          "alternated; ns per call (median over batches, then rounds); ratio = the median "
          "over rounds of the median of the batches' ratios C / lagrange, and its range\n")
    print("| arm | quantity (CasADi C / lagrange) | CasADi C (ns) | lagrange (ns) | ratio | range |")
    print("|---|---|---:|---:|---:|---|")
    for robot in ROBOTS:
        for _, rq, label in ROWS:
            got = [r[robot, rq] for r in runs if (robot, rq) in r]
            if not got or label.startswith("q̈: CRBA + NLE + SX QR"):
                continue
            c, o, ratio = (statistics.median(x) for x in zip(*got))
            lo, hi = min(g[2] for g in got), max(g[2] for g in got)
            print(f"| {robot} | {label} | {c:.0f} | {o:.0f} | {ratio:.2f} | {lo:.2f}–{hi:.2f} |")


if __name__ == "__main__":
    main()
