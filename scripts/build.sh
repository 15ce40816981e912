#!/usr/bin/env bash
# Configures and builds Gantry into build/ (warnings are errors; the console window too).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGANTRY_WERROR=ON -DGANTRY_GUI=ON "$@" >/dev/null
cmake --build build --parallel "$(nproc)"
