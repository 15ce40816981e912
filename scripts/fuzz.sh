#!/usr/bin/env bash
# Builds the libFuzzer target with clang, ASan and UBSan, and fuzzes the language for a
# bounded time (default 60 s) from a seed corpus of every part file in the repository.
# Usage: scripts/fuzz.sh [SECONDS]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
cd "$root"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DGANTRY_FUZZ=ON -DGANTRY_TESTS=OFF >/dev/null
seeds="$(mktemp -d)"
trap 'rm -rf "$seeds"' EXIT
# Quiet when it builds; the compiler's messages when it does not.
cmake --build build-fuzz --target language_fuzz --parallel "$(nproc)" >"$seeds/build.log" ||
  { cat "$seeds/build.log"; exit 1; }
rm "$seeds/build.log"
cp parts/*.sbp tests/data/*.sbp "$seeds"/
[ -d ../shared/corpus ] && cp ../shared/corpus/*.sbp "$seeds"/ || true
# -max_len keeps inputs line-sized; any crash or sanitizer report fails this script.
build-fuzz/tests/fuzz/language_fuzz "$seeds" -max_total_time="$seconds" -max_len=4096 \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 2>&1 | tail -n 12
echo "fuzz: ${seconds} s without a crash"
