// The Position window: the state, the large digits per axis, units, speeds, inputs,
// outputs and spindle, and the last stop.
#include "app.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "gantry/session/readout_lines.hpp"  // spindle_text
#include "theme.hpp"                         // digits_font, palette
#include "window_common.hpp"                 // kFixed, place, the palette colours

namespace gantry::ui {

using session::shown;

void App::readout_window() {
  const float top = ImGui::GetFrameHeight();
  place({{0, top}, {kLeft, kReadout}});
  ImGui::Begin("Position", nullptr, kFixed);
  const ControllerStatus& st = status_;
  const bool pausing = st.state == MachineState::Paused && st.phase != FeedPhase::Held;
  // One colour a state: E-stop red, stopped yellow, paused magenta, under way cyan, idle green.
  const ImVec4 colour = st.state == MachineState::EStop     ? kRed
                        : st.state == MachineState::Stopped ? kYellow
                        : st.state == MachineState::Paused  ? kMagenta
                        : at_rest()                         ? kGreen
                                                            : kCyan;
  if (st.warning) {  // SW's warning before a run moves the tool: flashing, the whole line
    ImGui::TextColored(std::fmod(ImGui::GetTime(), 0.5) < 0.25 ? kRed : kYellow,
                       "WARNING: about to move");
  } else {
    ImGui::TextColored(colour, "%s", pausing ? "pausing" : state_name(st.state));
    ImGui::SameLine(120 * scale_);
    if (const std::optional<std::string> why = unconfirmed()) {
      // After an E-stop or a kill the position may be wrong until homed or confirmed.
      ImGui::TextColored(kYellow, "UNCONFIRMED");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s: home (C3) or, if the tool is where the readout says, Confirm",
                          why->c_str());
      ImGui::SameLine();
      if (button("Confirm", at_rest())) {
        m_.controller.clear_home_flags();  // homing.require's flags too (WinCNC's L29)
        log(LogLine::Info, m_.memory->confirm());
      }
    } else {
      ImGui::TextDisabled("card: %s", opt_.card.c_str());
    }
  }
  // SB3's readout: large digits, as large as the window allows (lay_out).
  const Vec6 p = position(st);
  ImFont* digits = digits_font();
  if (digits) ImGui::PushFont(digits);
  ImGui::SetWindowFontScale(digits ? digits_px_ / digits_font_size()
                                   : digits_px_ / ImGui::GetFontSize());
  const int axes = std::clamp(settings_.display.axes, 3, kAxisCount);
  const float number_x = ImGui::CalcTextSize("X ").x;
  for (int i = 0; i < axes; ++i) {
    ImGui::TextColored(kGrey, "%c", axis_name(settings_, i));  // W: the profile's W axis
    ImGui::SameLine(number_x);
    ImGui::Text("%11.4f", shown(p[i]));
  }
  ImGui::SetWindowFontScale(1.0f);
  if (digits) ImGui::PopFont();
  ImGui::Text("%s   %s   %s", units_name(settings_.units),
              modal_.absolute ? "absolute (SA)" : "relative (SR)",
              modal_.preview ? "preview mode (SP)" : "move mode");
  ImGui::TextUnformatted(
      session::speeds_text(modal_.speeds, settings_.units, status_.feed_override).c_str());
  const float led_x = 70 * scale_;
  auto leds = [led_x](const char* label, auto on) {
    ImGui::TextDisabled("%s", label);
    for (int i = 0; i < 12; ++i) {
      ImGui::SameLine(i == 0 ? led_x : 0.0f, 3);
      ImGui::TextColored(on(i) ? kGreen : kOff, "%d", i + 1);
    }
  };
  leds("inputs", [&](int i) { return st.inputs[static_cast<std::size_t>(i)]; });
  leds("outputs", [&](int i) { return ((status_.outputs >> i) & 1u) != 0; });  // as played
  ImGui::TextUnformatted(session::spindle_text(status_, modal_.spindle_rpm).c_str());
  if (!st.message.empty() && at_rest()) ImGui::TextWrapped("last stop: %s", st.message.c_str());
  ImGui::End();
}

}  // namespace gantry::ui
