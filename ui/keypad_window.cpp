// The Keypad window and jogging: the arrows, step or continuous, the step presets, and the
// keys that jog while it has the focus.
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>

#include "window_common.hpp"  // kFixed, place, the palette colours

namespace gantry::ui {
namespace {
constexpr int kButtonIds = 1000;  // the on-screen buttons' ids in JogPress; below: GLFW keys
}  // namespace

bool App::can_jog() const {
  return at_rest() || status_.state == MachineState::Keypad;
}

void App::stop_jog() {
  kp_press_.reset();  // a key still held after Space does not start a jog again
  if (status_.state != MachineState::Jogging) return;
  // In a file's SK a stop would end the file: the jog is released instead.
  report(kp_file_ ? c_.jog_release() : c_.stop(), "stop");
}

bool App::jog(const std::array<int, kAxisCount>& dir, bool step) {
  JogRequest j;
  j.direction = dir;
  j.fast = kp_fast_;
  j.step = step;
  j.step_size = jog_step();
  const Outcome o = c_.jog(j);
  report(o, "jog");
  return static_cast<bool>(o);
}

// Continuous mode's tap-or-hold rule (docs/console.md, "Taps and held keys"), as the terminal
// has it: a press is one step of the keypad step, at once; a key or button still down
// JogPress::kHold after it (and once that step has played) jogs until it is let go. In
// virtual time (the simulated card without --realtime) a continuous jog would reach the soft
// limit at once, so there every press and key repeat is a step, as in fixed-step mode.
bool App::taps_step() const {
  return !kp_step_ && opt_.realtime;
}

void App::jog_pressed(const std::array<int, kAxisCount>& dir, int id) {
  if (!can_jog()) return;
  kp_press_.press(id, JogPress::Clock::now());
  kp_dir_ = dir;
  jog(dir, /*step=*/true);
}

void App::jog_released(int id) {
  if (kp_press_.release(id) && status_.state == MachineState::Jogging)
    report(c_.jog_release(), "release");
}

// Each frame: the key or button held past the threshold starts its continuous jog.
void App::jog_held() {
  // A key let go while the keys went elsewhere, or the mode changed under a held key: the
  // jog must not run on to the soft limit.
  const int id = kp_press_.id();
  if (!taps_step() || (id >= 0 && id < kButtonIds && !ImGui::IsKeyDown(id))) {
    if (kp_press_.continuous() && status_.state == MachineState::Jogging)
      report(c_.jog_release(), "release");
    return kp_press_.reset();
  }
  if (kp_press_.start_continuous(JogPress::Clock::now(), can_jog()) &&
      !jog(kp_dir_, /*step=*/false))
    kp_press_.reset();  // refused (at the soft limit): nothing to release
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
    if (!taps_step()) {
      // A held key repeats: one step per repeat, a press while a step moves is dropped.
      if (ImGui::IsKeyPressed(k.key, true) && can_jog()) jog(dir, /*step=*/true);
    } else if (ImGui::IsKeyPressed(k.key, false)) {
      jog_pressed(dir, k.key);
    } else if (ImGui::IsKeyReleased(k.key)) {
      jog_released(k.key);
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
    const int id = kButtonIds + b.axis * 2 + (b.sign > 0);
    const bool script_click = whole && clicked(b.label);  // a click: pressed and let go at once
    if (!taps_step()) {
      if ((press || script_click) && can_jog()) jog(dir, /*step=*/true);
    } else if (ImGui::IsItemActivated() || script_click) {
      jog_pressed(dir, id);
      if (script_click) jog_released(id);
    } else if (ImGui::IsItemDeactivated()) {
      jog_released(id);
    }
  }
  jog_held();
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
