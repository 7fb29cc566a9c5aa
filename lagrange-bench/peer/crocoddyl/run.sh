#!/usr/bin/env bash
# DDP on an arm's reaching problem, lagrange against Crocoddyl's
# SolverBoxFDDP, in alternation (five rounds each way, so that a shared
# machine slows both alike), then the plans compared.
#   lagrange-bench/peer/crocoddyl/run.sh [ARM [METHOD]]
# ARM is ur5 (30 steps) or xarm7 (100 steps), both by default; METHOD is
# euler (the same problem on both sides, the default) or rk4. Our side is
# built for this CPU; BUILD=baseline builds it for the x86-64 baseline, as
# PyPI's Crocoddyl is built (SSE2, no FMA).
# Needs: pip install crocoddyl (3.2.1 with pin 4.0.0 worked).
set -euo pipefail
cd "$(dirname "$0")"
root=../../..
arms="${1:-ur5 xarm7}"
method="${2:-euler}"
build="${BUILD:-native}"
case "$build" in
    native) flags="-C target-cpu=native" ;;
    baseline) flags="" ;;
    *) echo "BUILD is native or baseline, not $build" >&2; exit 2 ;;
esac
RUSTFLAGS="$flags" cargo build --quiet --release -p lagrange-bench \
    --example arm_reach --target-dir "$root/target/$build"
ours="$root/target/$build/release/examples/arm_reach"
out=$(mktemp -d)
for arm in $arms; do
    for round in 1 2 3 4 5; do
        "$ours" --arm "$arm" --method "$method" --repeats 20 --out "$out/ours_$arm.csv" | sed "s/^/$arm $round /"
        python3 arm_reach.py --urdf "$root/robots/$arm.urdf" --arm "$arm" --method "$method" --repeats 20 \
            --out "$out/crocoddyl_$arm.csv" | sed "s/^/$arm $round /"
    done
done | tee "$out/log"
python3 compare.py "$out"
