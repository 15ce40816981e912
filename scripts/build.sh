#!/usr/bin/env bash
# Configures and builds Gantry into build/ (warnings are errors; the console window too).
# GANTRY_BUILD_TARGETS="gantry" builds only those targets (scripts/run.sh: not the tests).
# The benchmarks are built too (CI builds them, so they keep compiling), never run here.
# Debug information is line tables only (-g1): a backtrace still names file and line, and the
# build takes about 30 % less compile time than with -g (docs/performance.md, "Build time").
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGANTRY_WERROR=ON -DGANTRY_GUI=ON -DGANTRY_BENCH=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" "$@" >/dev/null
targets=()
for t in ${GANTRY_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build build --parallel "$(nproc)" "${targets[@]}"
