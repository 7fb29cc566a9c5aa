#!/usr/bin/env bash
# DDP on the UR5's reaching problem, lagrange against Crocoddyl's
# SolverBoxFDDP, in alternation (five rounds each way per step method, so
# that a shared machine slows both alike), then the plans compared.
# Needs: pip install crocoddyl (3.2.1 with pin 4.0.0 worked).
set -euo pipefail
cd "$(dirname "$0")"
root=../../..
RUSTFLAGS="-C target-cpu=native" cargo build --quiet --release -p lagrange-bench \
    --example ur5_reach --target-dir "$root/target/native"
ours="$root/target/native/release/examples/ur5_reach"
out=$(mktemp -d)
for method in euler rk4; do
    for round in 1 2 3 4 5; do
        "$ours" --method "$method" --repeats 20 --out "$out/ours_$method.csv" | sed "s/^/$method $round /"
        python3 ur5_reach.py --urdf "$root/robots/ur5.urdf" --method "$method" --repeats 20 \
            --out "$out/crocoddyl_$method.csv" | sed "s/^/$method $round /"
    done
done | tee "$out/log"
python3 compare.py "$out"
