#!/usr/bin/env bash
# The install step and the .deb (issue 25): `cmake --install` to a prefix and the package
# CPack makes each hold the program, the manual page, the desktop entry, the shipped macros and
# profiles, and the installed program finds its macros and profiles beside itself, not in the
# source tree. Usage: install_test.sh BUILD_DIR
set -euo pipefail
build="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

check_tree() {  # $1: the prefix holding bin/gantry
  local p="$1"
  for f in bin/gantry share/man/man1/gantry.1 share/applications/gantry.desktop \
           share/gantry/macros/C2.sbp share/gantry/profiles/handibot.toml \
           share/doc/gantry/LICENSE share/icons/hicolor/scalable/apps/gantry.svg \
           lib/udev/rules.d/70-gantry-pendant.rules; do
    [[ -f "$p/$f" ]] || fail "$p/$f is missing"
  done
  grep -q '^Exec=gantry gui' "$p/share/applications/gantry.desktop" || fail "desktop entry's Exec"
  # The manual page comes from the command and statement tables.
  grep -q '^\.B MX$' "$p/share/man/man1/gantry.1" || fail "MX not in the manual page"
  grep -q '^\.B PAUSE$' "$p/share/man/man1/gantry.1" || fail "PAUSE not in the manual page"
  local out
  out="$(cd "$work" && "$p/bin/gantry" help C2)"
  grep -qF "C2 - custom cut 2: $p/share/gantry/macros/C2.sbp" <<< "$out" \
    || fail "the installed gantry does not find its own macros: $out"
  printf 'MX, 1\n' > "$work/one.sbp"
  out="$(cd "$work" && "$p/bin/gantry" run one.sbp --profile handibot 2>&1)"
  grep -q '^position   X=1\.000' <<< "$out" \
    || fail "the installed gantry does not run a file with a shipped profile: $out"
}

cmake --install "$build" --prefix "$work/prefix" > /dev/null
check_tree "$work/prefix"

(cd "$build" && cpack -G DEB -B "$work/deb" > /dev/null)
deb="$(ls "$work"/deb/gantry_*.deb)"
dpkg-deb -f "$deb" Depends | grep -q libfmt || fail "the package names no dependencies"
dpkg-deb -x "$deb" "$work/root"
check_tree "$work/root/usr"
echo "install and .deb: ok"
