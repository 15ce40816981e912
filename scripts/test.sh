#!/usr/bin/env bash
# Sets up, builds, and runs the whole test suite.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
# The language fuzzer first (bounded), so that ctest's summary is the last thing printed.
"$root/scripts/fuzz.sh" "${GANTRY_FUZZ_SECONDS:-60}"
cd "$root/build"
ctest --output-on-failure --parallel "$(nproc)"
