// What app.cpp and the window files (readout_window.cpp, keypad_window.cpp, ...) share: this
// frame's text colours from the theme's palette, the fixed layout's sizes and place(), and
// the flags of a fixed window.
#pragma once

#include <imgui.h>

#include "gantry/machine/controller.hpp"  // MachineState
#include "theme.hpp"                      // Palette

namespace gantry::ui {

inline constexpr const char* kAxes = "XYZABC";

// The theme's text colours (palette): set at the start of each frame.
inline ImVec4 kRed, kGreen, kYellow, kGrey, kCyan, kMagenta, kText, kOff;

inline void use_palette(const Palette& p) {
  kRed = p.red, kGreen = p.green, kYellow = p.yellow, kGrey = p.grey, kCyan = p.cyan;
  kMagenta = p.magenta, kText = p.text, kOff = p.off;
}

inline bool rest_state(MachineState s) {
  return s == MachineState::Idle || s == MachineState::Stopped || s == MachineState::EStop;
}

// The window's fixed layout: the readout, keypad and job down the left; the preview on the
// right; the console (log and command line) along the bottom. The column's width and the
// console's height follow the window's scale (App::lay_out sets them each frame).
struct Layout {
  ImVec2 pos, size;
};
inline float kLeft = 370, kConsole = 250;
// The left column's heights: the job window gets the rest.
inline float kReadout = 300, kKeypad = 215;

inline void place(const Layout& l) {
  ImGui::SetNextWindowPos(l.pos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(l.size, ImGuiCond_Always);
}

inline constexpr ImGuiWindowFlags kFixed =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;

}  // namespace gantry::ui
