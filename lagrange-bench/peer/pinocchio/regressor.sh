#!/usr/bin/env bash
# Builds and runs the Pinocchio peer of the `regressor` bench on the arms in
# `robots/` (PyPI `pin` for Pinocchio, Debian's Eigen headers):
#   pip install pin && apt-get install libeigen3-dev
#   lagrange-bench/peer/pinocchio/regressor.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
robots="$here/../../../robots"
prefix="$(python3 -c 'import pinocchio, os; print(os.path.abspath(os.path.join(os.path.dirname(pinocchio.__file__), "../../../..")))')"
out="${TMPDIR:-/tmp}/pinocchio_regressor"
python3 "$here/urdf_model.py" "$robots" "$out.hpp"
g++ -O3 -march=native -DNDEBUG -std=c++17 \
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS \
  -DBOOST_FUSION_INVOKE_MAX_ARITY=12 -DURDF_MODELS="\"$out.hpp\"" "$here/regressor.cpp" -o "$out" \
  -I"$prefix/include" -I"$prefix/include/eigen3" -I/usr/include/eigen3 \
  -L"$prefix/lib" -Wl,-rpath,"$prefix/lib" -lpinocchio_default -w
"$out"
