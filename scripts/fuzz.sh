#!/usr/bin/env bash
# Builds the libFuzzer targets with clang, ASan and UBSan (every report halts: no recover
# mode), and fuzzes each for a bounded time (default 30 s), two at a time, from seed corpora
# of the repository's own files. Any crash or sanitizer report fails this script and prints
# that target's whole log; every log is kept in build-fuzz/fuzz-logs/ (a CI artifact).
# Usage: scripts/fuzz.sh [SECONDS]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-30}"
cd "$root"
targets=(language_fuzz gcode_file_fuzz settings_fuzz persistent_fuzz)
logs="$root/build-fuzz/fuzz-logs"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DGANTRY_FUZZ=ON -DGANTRY_TESTS=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" >/dev/null
rm -rf "$logs"
mkdir -p "$logs"
# Quiet when it builds; the compiler's messages when it does not.
cmake --build build-fuzz --target "${targets[@]}" --parallel "$(nproc)" >"$logs/build.log" ||
  { cat "$logs/build.log"; exit 1; }

# Seeds: the repository's part files, G-code, profiles and persistent files.
seeds="$(mktemp -d)"
trap 'rm -rf "$seeds"' EXIT
for t in "${targets[@]}"; do mkdir -p "$seeds/$t"; done
cp parts/*.sbp tests/data/*.sbp tests/data/posts/*.sbp "$seeds/language_fuzz"/
[ -d ../shared/corpus ] && cp ../shared/corpus/*.sbp "$seeds/language_fuzz"/ || true
cp parts/*.nc tests/fuzz/seeds/gcode/* "$seeds/gcode_file_fuzz"/
cp settings/*.toml settings/profiles/*.toml tests/data/*.toml "$seeds/settings_fuzz"/
cp tests/data/fabmo/*.json tests/fuzz/seeds/persistent/* "$seeds/persistent_fuzz"/

# Whole G-code files reach deep nesting (a 33,000-deep `[` once overflowed the stack): 64 KiB.
# OpenSBP's nesting limit (200) is past within 4 KiB, which keeps its runs many (about 5,000
# a minute at 64 KiB, where every input is a long file checked whole).
max_len() { case "$1" in gcode_file_fuzz) echo 65536 ;; language_fuzz) echo 4096 ;; *) echo 16384 ;; esac; }
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1
fuzz() {
  local t="$1"
  "build-fuzz/tests/fuzz/$t" "$seeds/$t" -max_total_time="$seconds" -max_len="$(max_len "$t")" \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$logs/$t-" \
    >"$logs/$t.log" 2>&1
}
# A sanitizer report fails the target even if the process somehow exited 0.
reported() {
  grep -qE 'runtime error:|ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)|SUMMARY: [A-Za-z]+Sanitizer' \
    "$logs/$1.log"
}

failed=()
for ((i = 0; i < ${#targets[@]}; i += 2)); do  # two at a time: CI has 2 cores
  pids=()
  for t in "${targets[@]:i:2}"; do
    fuzz "$t" &
    pids+=("$!")
  done
  for j in "${!pids[@]}"; do
    t="${targets[i + j]}"
    if ! wait "${pids[j]}" || reported "$t"; then failed+=("$t"); fi
  done
done

for t in "${targets[@]}"; do
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$logs/$t.log" | tail -n 1)"
  echo "fuzz: $t: ${runs:-?} executions in ${seconds} s"
done
if ((${#failed[@]})); then
  for t in "${failed[@]}"; do
    echo "==== fuzz: $t FAILED; its whole log ($logs/$t.log):"
    cat "$logs/$t.log"
  done
  echo "fuzz: FAILED: ${failed[*]} (logs and crashing inputs in $logs)"
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, no crash and no sanitizer report"
