#!/usr/bin/env bash
# Pinocchio traced into CasADi's C against lagrange, on the arms of robots/.
# Installs nothing; needs, from PyPI (the versions that worked):
#   pip install pin==4.0.0 casadi==3.8.2 cmeel-eigen==3.4.1
# and gcc/g++ and cargo. Generates, compiles and checks the C peer
# (casadi_codegen.py), builds examples/casadi_peer/, then runs the C harness
# and the Rust timing alternately, ROUNDS times (default 3), the Rust side
# also timing the C's functions batch for batch beside its own
# (`--interleave` the C harness built as a library), and prints the values'
# check against numeric Pinocchio and the tables (compare.py), at two states
# (compare.py STATE: "small" and "wide").
#   lagrange-bench/peer/casadi/run.sh [ROUNDS]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
rounds="${1:-3}"
out="${TMPDIR:-/tmp}/casadi_peer"

missing=()
python3 -c 'import pinocchio' 2>/dev/null || missing+=("pin==4.0.0")
python3 -c 'import casadi' 2>/dev/null || missing+=("casadi==3.8.2")
prefix="$(python3 -c 'import pinocchio, os; print(os.path.abspath(os.path.join(os.path.dirname(pinocchio.__file__), "../../../..")))' 2>/dev/null || true)"
[ -n "$prefix" ] && [ -d "$prefix/include/eigen3" ] || missing+=("cmeel-eigen==3.4.1")
if [ ${#missing[@]} -gt 0 ]; then
  echo "missing Python packages; install them with: pip install ${missing[*]}" >&2
  exit 1
fi

python3 "$here/casadi_codegen.py" "$out"
# Our side built for this CPU as the C is (-march=native): the emitted
# programs' mul_add then fuse. Its own target directory, so the usual
# build is not invalidated. RUSTFLAGS overrides the flags.
native="${CARGO_TARGET_DIR:-$root/target}/native"
(cd "$root" && RUSTFLAGS="${RUSTFLAGS:--C target-cpu=native}" CARGO_TARGET_DIR="$native" \
  cargo build --release -p lagrange-bench --example casadi_peer)
bin="$native/release/examples/casadi_peer"
rm -f "$out"/casadi_*.txt "$out"/lagrange_*.txt
# Both states: every joint angle within 0.55 rad ("small"), and spread over
# a turn ("wide"), where the C library's sin and cos take their longer path.
for i in $(seq 1 "$rounds"); do
  echo "round $i of $rounds" >&2
  "$out/harness" > "$out/casadi_small_$i.txt"
  "$bin" --interleave "$out/libharness.so" > "$out/lagrange_small_$i.txt"
  "$out/harness" wide > "$out/casadi_wide_$i.txt"
  "$bin" --wide --interleave "$out/libharness.so" > "$out/lagrange_wide_$i.txt"
done
cd "$here"
status=0
for state in small wide; do
  echo "## The $state state"
  python3 compare.py "$out" "$state" || status=1
done
exit $status
