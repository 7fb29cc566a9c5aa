"""Reads run.sh's log and plans: per arm, the median over rounds of
Crocoddyl's time over ours (per solve and per iteration, each round's two
runs side by side), and how far apart the two plans' inputs are."""

import statistics
import sys

import numpy as np


def main(folder):
    rows = {}
    for line in open(f"{folder}/log"):
        f = line.split()
        arm, side = f[0], f[2]
        fields = dict(zip(f[3::2], f[4::2]))
        rows.setdefault(arm, {}).setdefault(side, []).append(fields)
    for arm, sides in rows.items():
        ours, theirs = sides["lagrange"], sides["crocoddyl"]
        for what in ["per_solve", "per_iteration"]:
            ratios = [float(t[what]) / float(o[what]) for o, t in zip(ours, theirs)]
            print(
                f"{arm:5} {what:13}: Crocoddyl / lagrange = {statistics.median(ratios):.2f} "
                f"(rounds {min(ratios):.2f}–{max(ratios):.2f}); "
                f"lagrange {float(ours[-1][what]) * 1e3:.3f} ms, {ours[-1]['iterations']} iterations, "
                f"Crocoddyl {float(theirs[-1][what]) * 1e3:.3f} ms, {theirs[-1]['iterations']} iterations"
            )
        a = np.loadtxt(f"{folder}/ours_{arm}.csv", delimiter=",")
        b = np.loadtxt(f"{folder}/crocoddyl_{arm}.csv", delimiter=",")
        print(
            f"{arm:5} costs: lagrange {ours[-1]['cost']}, Crocoddyl {theirs[-1]['cost']}; "
            f"inputs differ by at most {abs(a - b).max():.1e} N·m"
        )


if __name__ == "__main__":
    main(sys.argv[1])
