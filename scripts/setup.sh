#!/usr/bin/env bash
# Installs everything Gantry needs to build and test, from Debian's packages only.
# Idempotent: installs nothing when every package is already present.
set -euo pipefail

PACKAGES=(
  # build
  cmake ninja-build g++ pkg-config
  # core libraries
  libeigen3-dev libfmt-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  # a part file's blocks hashed, so what runs is what was checked
  libxxhash-dev
  # the preview's PNG pictures (stb_image_write)
  libstb-dev
  # tests, benchmarks, fuzzing (clang's libFuzzer and sanitizer runtimes)
  googletest libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev
  # the console's terminal tests drive it under tmux
  tmux
  # the .deb (cpack's dpkg-shlibdeps) and its test
  dpkg-dev
  # console window, pendants, GPIO (the optional backends)
  libglfw3-dev libimgui-dev libusb-1.0-0-dev libgpiod-dev xvfb
  # the pendant's and the gamepad's end-to-end tests emulate them (umockdev-run: usbfs, evdev)
  umockdev libumockdev-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: run as root or install sudo" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
updated=0
apt_update() {
  if [ "$updated" -eq 0 ]; then
    $SUDO apt-get update -qq
    updated=1
  fi
}
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  apt_update
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# LinuxCNC's stand-alone G-code interpreter (rs274), the reference of the differential test
# (tests/differential/, docs/gcode.md "Tested against LinuxCNC"). Its package is unpacked into
# build/linuxcnc/root, not installed: the machine's own libraries stay as they are. The
# libraries rs274 needs that are not on the machine are unpacked beside it the same way.
lcnc="$(cd "$(dirname "$0")/.." && pwd)/build/linuxcnc"
rs274="$lcnc/root/usr/bin/rs274"
lcnc_libs="$lcnc/root/usr/lib:$lcnc/root/usr/lib/x86_64-linux-gnu"
unpack() {  # unpack PACKAGE...: download the package files and unpack them into the root
  apt_update
  mkdir -p "$lcnc/debs"
  (cd "$lcnc/debs" && apt-get download -qq "$@" >/dev/null)
  for p in "$@"; do
    dpkg-deb -x "$(ls "$lcnc/debs/${p}"_*.deb | head -n 1)" "$lcnc/root"
  done
}
# The Debian package of each library rs274 (or a library it loads) may find missing.
lib_package() {
  case "$1" in
    libboost_python3*) echo libboost-python1.74.0 ;;
    libpython3.11.so*) echo libpython3.11 ;;
    libedit.so*) echo libedit2 ;;
    libtirpc.so*) echo libtirpc3 ;;
    libbsd.so*) echo libbsd0 ;;
    libmd.so*) echo libmd0 ;;
    libexpat.so*) echo libexpat1 ;;
    libgssapi_krb5.so*) echo libgssapi-krb5-2 ;;
    libkrb5.so*) echo libkrb5-3 ;;
    libk5crypto.so*) echo libk5crypto3 ;;
    libkrb5support.so*) echo libkrb5support0 ;;
    libkeyutils.so*) echo libkeyutils1 ;;
    libcom_err.so*) echo libcom-err2 ;;
    *) return 1 ;;
  esac
}
if [ ! -x "$rs274" ]; then
  echo "setup: unpacking LinuxCNC's rs274 into $lcnc/root" >&2
  unpack linuxcnc-uspace
fi
for _ in 1 2 3; do
  absent=$(LD_LIBRARY_PATH="$lcnc_libs" ldd "$rs274" | awk '/not found/ {print $1}')
  [ -z "$absent" ] && break
  packages=()
  for lib in $absent; do
    pkg=$(lib_package "$lib") || { echo "setup: rs274 needs $lib: no package known for it" >&2; exit 1; }
    packages+=("$pkg")
  done
  mapfile -t packages < <(printf '%s\n' "${packages[@]}" | sort -u)
  echo "setup: unpacking ${packages[*]} for rs274" >&2
  unpack "${packages[@]}"
done
# rs274 starts Python: without the machine's standard library, unpack one and point
# PYTHONHOME at it (the test does so when the root holds one).
if [ ! -f /usr/lib/python3.11/encodings/__init__.py ] &&
  [ ! -f "$lcnc/root/usr/lib/python3.11/encodings/__init__.py" ]; then
  unpack libpython3.11-minimal libpython3.11-stdlib
fi
