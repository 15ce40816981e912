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
  # console window, pendants, GPIO (the optional backends)
  libglfw3-dev libimgui-dev libusb-1.0-0-dev libgpiod-dev xvfb
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: run as root or install sudo" >&2; exit 1; }
  SUDO="sudo"
fi
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
