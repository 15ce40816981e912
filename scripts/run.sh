#!/usr/bin/env bash
# Sets up, builds, and runs a part file (default parts/demo.sbp) through the whole pipeline
# on the simulated card, printing progress and the final report.
# Usage: scripts/run.sh [FILE] [gantry run options, e.g. --json --realtime]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
GANTRY_BUILD_TARGETS=gantry "$root/scripts/build.sh" >&2  # the program only, not the tests
file="${1:-$root/parts/demo.sbp}"
shift || true
exec "$root/build/gantry" run "$file" "$@"
