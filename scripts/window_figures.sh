#!/bin/sh
# Regenerates the window's pictures in docs/figures (console_window.png, console_sheet.png)
# from the Xvfb tests that take them, so README.md and docs/console.md show the window as
# tested. Needs a build with the window (scripts/build.sh):
#   scripts/window_figures.sh [build folder]
set -e
cd "$(dirname "$0")/.."
BUILD=${1:-build}
cmake --build "$BUILD" --target gantry gantry_gui_tests
GANTRY_FIGURES="$PWD/docs/figures" "$BUILD/tests/gui/gantry_gui_tests" \
  --gtest_filter='GuiWindow.TheDocumentationsPictureOfTheWindow:GuiWindow.ABareCodeOpensItsFillInSheet'
