#!/bin/sh
# Regenerates the pictures of docs/cuts.md from the part files beside them:
#   scripts/cut_figures.sh [path/to/gantry]
set -e
cd "$(dirname "$0")/.."
GANTRY=${1:-build/gantry}
for f in docs/figures/*.sbp; do
  XDG_CONFIG_HOME=$(mktemp -d) "$GANTRY" moves "$f" --svg "${f%.sbp}.svg"
done
