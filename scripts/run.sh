#!/usr/bin/env bash
# Sets up, builds, and runs a part file (default parts/demo.sbp) through the whole pipeline
# on the simulated card, printing progress and the final report.
# Usage: scripts/run.sh [FILE] [gantry run options, e.g. --json --realtime]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >&2
file="${1:-$root/parts/demo.sbp}"
shift || true
exec "$root/build/gantry" run "$file" "$@"
