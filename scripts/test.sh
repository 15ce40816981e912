#!/usr/bin/env bash
# Sets up, builds, and runs the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
# The language fuzzer first (bounded), so that ctest's summary is the last thing printed.
"$root/scripts/fuzz.sh" "${GANTRY_FUZZ_SECONDS:-30}"
cd "$root/build"
# The differential test against LinuxCNC's rs274 prints its counts here (ctest shows a passing
# test's output only with -V); ctest runs it again, from its cache of rs274's answers.
tests/gantry_gcode_differential | tail -n 1 || true
ctest --output-on-failure --parallel "$(nproc)"
