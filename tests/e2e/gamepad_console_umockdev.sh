#!/usr/bin/env bash
# `gantry console` with a gamepad emulated by umockdev (run inside umockdev-run with
# drivers/gamepad/tests/data/gamepad.umockdev, gamepad.ioctl and jog_x.events; ctest
# GamepadUmockdev.Console): a profile that turns the gamepad on finds it, the left stick
# pushed right for 0.4 s jogs X+ in real time, and let go the jog ends (the tool comes to
# rest): X between 0.5 and 6 in (the jog speed is 6 in/s, with its ramps).
# With a third argument "quiet" it sends no status, only quit: the piped console follows the
# activity between its lines and prints the readout where the gamepad's jog left the tool
# (ctest GamepadUmockdev.PipedConsoleFollowsTheJog).
# Usage: gamepad_console_umockdev.sh GANTRY PROFILE [quiet]
set -euo pipefail
gantry="$1" profile="$2" quiet="${3:-}"
[[ -n "${UMOCKDEV_DIR:-}" ]] || { echo "run under umockdev-run" >&2; exit 1; }
work="$(mktemp -d)"
trap 'exec 3>&- 2>/dev/null || true; kill "$pid" 2>/dev/null || true; rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; echo "--- console output:" >&2; cat "$work/out" >&2; exit 1; }
cp "$profile" "$work/profile.toml"
printf '\n[pendant]\ngamepad = "auto"\n' >> "$work/profile.toml"
mkfifo "$work/in"
XDG_CONFIG_HOME="$work/config" "$gantry" console --profile "$work/profile.toml" \
  --values "$work/values.toml" --realtime < "$work/in" > "$work/out" 2>&1 &
pid=$!
exec 3> "$work/in"
for _ in $(seq 200); do
  grep -qF "gamepad Gantry Test Gamepad on /dev/input/event7: ready to jog" "$work/out" && break
  sleep 0.05
done
grep -qF "ready to jog" "$work/out" || fail "the gamepad was not found within 10 s"
sleep 2  # the stick is pushed at 0.3 s and let go at 0.7 s; the jog then slows to rest
if [[ "$quiet" != quiet ]]; then echo status >&3; fi
echo quit >&3
exec 3>&-
wait "$pid" || fail "the console ended with an error"
x="$(grep -oE "X +-?[0-9]+\.[0-9]+" "$work/out" | tail -1 | grep -oE -- "-?[0-9]+\.[0-9]+")" \
  || fail "no position in the status"
awk -v x="$x" 'BEGIN { exit !(x > 0.5 && x < 6) }' || fail "X did not jog forward as far as 0.4 s at up to 6 in/s goes: X $x"
grep -qE "Y 0\.0000" "$work/out" || fail "Y moved"
echo "ok: the gamepad found, the stick jogged X to $x and let go it stopped"
