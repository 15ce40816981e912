#!/bin/sh
# The real-time soak (issue 26): `gantry run --realtime` of a dense file on the simulated card
# for about ten minutes while another process loads every core, under SCHED_FIFO where allowed.
# Prints the underruns (target 0) and the feeder's worst lateness. Not for CI: it takes minutes.
#
#   bench/soak.sh [minutes] [gantry binary] [lead ms]   (defaults: 10, build/gantry, 20)
set -eu
minutes=${1:-10}
gantry=${2:-build/gantry}
lead=${3:-20}
here=$(cd "$(dirname "$0")/.." && pwd)
[ -x "$gantry" ] || { echo "soak: no $gantry; build the gantry target first" >&2; exit 2; }
work=$(mktemp -d)
hogs=""
cleanup() {
  for p in $hogs; do kill "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT INT TERM
# The run keeps its machine state and log beside the values file: in a home of its own.
export HOME="$work/home" XDG_CONFIG_HOME="$work/home/.config"
mkdir -p "$HOME"

# A dense file: circles of 2 in radius as 720 chords each (0.017 in, about 9 ms each at
# 2 in/s), as many as make the minutes asked for.
circles=$(awk -v m="$minutes" 'BEGIN { printf "%d", m * 60 * 2 / (2 * 3.14159265 * 2) + 1 }')
awk -v n="$circles" 'BEGIN {
  print "MS, 2, 0.5"
  print "J2, 7, 5"
  print "MZ, -0.1"
  for (c = 0; c < n; c++)
    for (i = 1; i <= 720; i++) {
      a = i * 2 * 3.14159265358979 / 720
      printf "M2, %.5f, %.5f\n", 5 + 2 * cos(a), 5 + 2 * sin(a)
    }
  print "JZ, 0.5"
}' >"$work/dense.sbp"
moves=$(grep -c '^M2' "$work/dense.sbp")
# The default profile with the lead asked for.
sed "s/^lead_ms = .*/lead_ms = $lead/" "$here/settings/default.toml" >"$work/profile.toml"


# A busy loop per core, by another process, at the normal priority.
cores=$(nproc)
i=0
while [ "$i" -lt "$cores" ]; do
  sh -c 'while :; do :; done' &
  hogs="$hogs $!"
  i=$((i + 1))
done

fifo=""
if chrt -f 10 true 2>/dev/null; then fifo="chrt -f 50"; fi
echo "soak: lead $lead ms, $moves moves ($circles circles), $cores CPU hogs, ${fifo:-SCHED_OTHER (SCHED_FIFO not allowed)}; $(date +%T)"
start=$(date +%s)
set +e
$fifo "$gantry" run --realtime --yes --profile "$work/profile.toml" "$work/dense.sbp" >"$work/out.txt" 2>"$work/err.txt"
code=$?
set -e
end=$(date +%s)
for p in $hogs; do kill "$p" 2>/dev/null || true; done
hogs=""

fault=$(sed -n 's/^ *fault: *//p' "$work/out.txt" | head -n 1)
underruns=0
if grep -qi underrun "$work/out.txt" "$work/err.txt"; then underruns=1; fi
echo "soak: ran $((end - start)) s (wall), exit $code, fault: ${fault:-?}"
grep -e "real time:" -e "the lead grows" "$work/err.txt" | sed 's/^gantry: /soak: /' || true
echo "soak: underruns: $underruns (target 0)"
if [ "$code" -ne 0 ]; then
  echo "soak: the run's report:"
  cat "$work/out.txt" "$work/err.txt" | tail -n 20
fi
[ "$underruns" -eq 0 ]
