#!/usr/bin/env bash
# `gantry console` with the XHC pendant emulated by umockdev (run inside umockdev-run with
# tests/data/pendant/whb04b.umockdev and feed_plus_unplug.ioctl; ctest PendantUmockdev.Console):
# the console finds the pendant, its Feed+ press raises the feed override, and pulling the
# cable is told. umockdev-run cannot take the device away (libusb keeps its device list from
# uevents, which only the libumockdev API sends), so the console finds it again half a second
# after each unplug and the replay starts over: each round adds 10 % (up to 200 %).
# Usage: pendant_console_umockdev.sh GANTRY
set -euo pipefail
gantry="$1"
[[ -n "${UMOCKDEV_DIR:-}" ]] || { echo "run under umockdev-run" >&2; exit 1; }
work="$(mktemp -d)"
trap 'exec 3>&- 2>/dev/null || true; kill "$pid" 2>/dev/null || true; rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; echo "--- console output:" >&2; cat "$work/out" >&2; exit 1; }
wait_for() {  # $1: text in the console's output, $2: how many times
  for _ in $(seq 200); do
    [[ "$(grep -cF -- "$1" "$work/out" || true)" -ge "$2" ]] && return 0
    sleep 0.05
  done
  fail "no '$1' (x$2) within 10 s"
}
mkfifo "$work/in"
XDG_CONFIG_HOME="$work/config" "$gantry" console --values "$work/values.toml" \
  < "$work/in" > "$work/out" 2>&1 &
pid=$!
exec 3> "$work/in"
wait_for "pendant: the XHC pendant is connected" 1
wait_for "pendant: the pendant was unplugged" 1
echo status >&3
echo quit >&3
exec 3>&-
wait "$pid" || fail "the console ended with an error"
feed="$(grep -oE "feed [0-9]+ %" "$work/out" | tail -1 | grep -oE "[0-9]+")" \
  || fail "no feed override in the status"
(( feed >= 110 && feed <= 200 && feed % 10 == 0 )) || fail "Feed+ did not reach the override: $feed %"
grep -qE "X 0\.0000 +Y 0\.0000" "$work/out" || fail "something moved"
echo "ok: the pendant found, Feed+ (feed $feed %), the unplug told"
