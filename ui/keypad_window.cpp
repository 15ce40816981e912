// The Keypad window and jogging: the arrows, step or continuous, the step presets, and the
// keys that jog while it has the focus.
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>

#include "window_common.hpp"  // kFixed, place, the palette colours

namespace gantry::ui {

bool App::can_jog() const {
  return at_rest() || status_.state == MachineState::Keypad;
}

void App::stop_jog() {
  if (status_.state != MachineState::Jogging) return;
  // In a file's SK a stop would end the file: the jog is released instead.
  report(kp_file_ ? c_.jog_release() : c_.stop(), "stop");
}

void App::jog(const std::array<int, kAxisCount>& dir) {
  JogRequest j;
  j.direction = dir;
  j.fast = kp_fast_;
  j.step = kp_step_;
  j.step_size = jog_step();
  if (!j.step && !opt_.realtime) {
    log(LogLine::Error, "continuous jogs need --realtime on the simulated card; S: fixed steps");
    return;
  }
  const Outcome o = c_.jog(j);
  report(o, "jog");
  if (o) kp_continuous_ = !j.step;
}

// The keyboard's jogs, while the keypad has the keys.
void App::jog_keys() {
  struct K {
    int key, axis, sign;
  };
  static constexpr K keys[] = {{GLFW_KEY_LEFT, 0, -1},   {GLFW_KEY_RIGHT, 0, 1},
                               {GLFW_KEY_UP, 1, 1},      {GLFW_KEY_DOWN, 1, -1},
                               {GLFW_KEY_PAGE_UP, 2, 1}, {GLFW_KEY_PAGE_DOWN, 2, -1}};
  for (const K& k : keys) {
    std::array<int, kAxisCount> dir{};
    dir[static_cast<std::size_t>(k.axis)] = k.sign;
    if (kp_step_) {
      // A held key repeats: one step per repeat, a press while a step moves is dropped.
      if (ImGui::IsKeyPressed(k.key, true) && can_jog()) jog(dir);
    } else if (ImGui::IsKeyPressed(k.key, false) && can_jog()) {
      jog(dir);
      if (kp_continuous_) kp_key_ = k.key;
    } else if (ImGui::IsKeyReleased(k.key) && kp_key_ == k.key) {
      report(c_.jog_release(), "release");
      kp_key_ = -1;
    }
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) kp_step_ = !kp_step_;
  if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) kp_fast_ = !kp_fast_;
  if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) stop_jog();
  if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) {
    stop_jog();
    if (status_.state == MachineState::Keypad) return report(c_.resume(), "go on");
    kp_focus_ = false;
    focus_line_ = true;
  }
}

// The keypad's rows of jog buttons, at the window's scale (tighter in a low window, where the
// readout's digits need the height).
float App::pad_row() const {
  return (ImGui::GetIO().DisplaySize.y < 700 * scale_ ? 28.0f : 34.0f) * scale_;
}

void App::keypad_window() {
  const float top = ImGui::GetFrameHeight() + kReadout;
  place({{0, top}, {kLeft, kKeypad}});
  ImGui::Begin("Keypad", nullptr, kFixed);
  if (ImGui::IsWindowFocused() && ImGui::IsMouseClicked(0)) kp_focus_ = true;
  ImGui::TextColored(kp_focus_ ? kGreen : kGrey, "%s",
                     kp_focus_ ? "keys jog (Esc leaves)" : "click here or type K for the keys");
  // The pad: the buttons make the same requests as the keys.
  struct B {
    const char* label;
    int axis, sign;
    float x, y;
  };
  static constexpr B pad[] = {{"Y+", 1, 1, 60, 0},  {"X-", 0, -1, 0, 1},  {"X+", 0, 1, 120, 1},
                              {"Y-", 1, -1, 60, 2}, {"Z+", 2, 1, 200, 0}, {"Z-", 2, -1, 200, 2}};
  const ImVec2 origin = ImGui::GetCursorPos();
  const float row = pad_row();
  for (const B& b : pad) {
    ImGui::SetCursorPos(ImVec2(origin.x + b.x * scale_, origin.y + b.y * row));
    std::array<int, kAxisCount> dir{};
    dir[static_cast<std::size_t>(b.axis)] = b.sign;
    const bool press = ImGui::Button(b.label, ImVec2(52 * scale_, row - 4 * scale_));
    const bool whole = note_button(b.label);
    if (kp_step_ ? (press || (whole && clicked(b.label))) && can_jog()
                 : ImGui::IsItemActivated() && can_jog()) {
      jog(dir);
      if (!kp_step_ && kp_continuous_) kp_key_ = 1000 + b.axis * 2 + (b.sign > 0);
    }
    if (!kp_step_ && ImGui::IsItemDeactivated() && kp_key_ == 1000 + b.axis * 2 + (b.sign > 0)) {
      report(c_.jog_release(), "release");
      kp_key_ = -1;
    }
  }
  ImGui::SetCursorPos(ImVec2(origin.x, origin.y + 3 * row + 4 * scale_));
  if (button(kp_step_ ? "Fixed step##mode" : "Continuous##mode")) kp_step_ = !kp_step_;
  ImGui::SameLine();
  if (button(kp_fast_ ? "Fast##speed" : "Slow##speed")) kp_fast_ = !kp_fast_;
  ImGui::SameLine();
  if (button("Stop jog", status_.state == MachineState::Jogging)) stop_jog();
  // The step: a preset, or VD's keypad step.
  ImGui::TextDisabled("step");
  const std::array<double, 4> presets = jog_presets();
  for (int i = 0; i <= static_cast<int>(presets.size()); ++i) {
    const bool vd = i == static_cast<int>(presets.size());
    ImGui::SameLine();
    const bool chosen = kp_preset_ == (vd ? -1 : i);
    if (chosen)
      ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    const std::string label =
        vd ? "VD##step" : fmt::format("{:g}##step", presets[static_cast<std::size_t>(i)]);
    if (button(label.c_str())) kp_preset_ = vd ? -1 : i;
    if (chosen) ImGui::PopStyleColor();
    if (vd && ImGui::IsItemHovered())
      ImGui::SetTooltip("VD's keypad step: %.4f %s", settings_.display.keypad_step,
                        units_name(settings_.units));
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s, %s speed", units_name(settings_.units), kp_fast_ ? "jog" : "move");
  ImGui::End();
}

// The step presets in the units in force: a thousandth to an inch, or a hundredth of a
// millimetre to ten.
std::array<double, 4> App::jog_presets() const {
  if (settings_.units == Units::Millimetres) return {0.01, 0.1, 1, 10};
  return {0.001, 0.01, 0.1, 1};
}

double App::jog_step() const {
  return kp_preset_ < 0 ? settings_.display.keypad_step
                        : jog_presets()[static_cast<std::size_t>(kp_preset_)];
}

}  // namespace gantry::ui
