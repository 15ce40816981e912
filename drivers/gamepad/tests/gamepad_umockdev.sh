#!/bin/sh
# The gamepad reader on the kernel's interface as umockdev emulates it (Debian's umockdev):
# a gamepad at /dev/input/event7 with the capabilities and stick ranges in data/gamepad.ioctl
# (written by hand from linux/input.h: 9 buttons, two sticks of +-32767, two 0-255 triggers, a
# hat) plays data/gamepad.events. Found, probed, named, and every event read as the bindings
# see it: the stick's 100 of 32767 is inside the dead zone and reads as rest.
set -eu
replay=$1 data=$2
command -v umockdev-run >/dev/null || { echo "umockdev-run is missing: run scripts/setup.sh"; exit 1; }
got=$(timeout 30 umockdev-run -d "$data/gamepad.umockdev" \
  -i /dev/input/event7="$data/gamepad.ioctl" -e /dev/input/event7="$data/gamepad.events" \
  -- "$replay" 5)
want="found /dev/input/event7
name Gantry Test Gamepad
BTN_SOUTH 1
BTN_SOUTH 0
ABS_X 1
ABS_X 0
ABS_HAT0X -1"
if [ "$got" != "$want" ]; then
  printf 'expected:\n%s\ngot:\n%s\n' "$want" "$got"
  exit 1
fi
echo "gamepad under umockdev: 5 events as expected"
