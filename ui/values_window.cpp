// The Values window: the settings in force.
#include "app.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include "window_common.hpp"  // kFixed, place, the palette colours

namespace gantry::ui {

void App::values_window() {
  ImGui::SetNextWindowSize(ImVec2(460, 420), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImVec2(kLeft + 40, 60), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Values", &show_values_)) return ImGui::End();
  const char* u = units_name(settings_.units);
  ImGui::Text("units %s; keypad step %.4f; cutter %.4f; safe Z %.4f", u,
              settings_.display.keypad_step, settings_.cutter.diameter, settings_.cutter.safe_z);
  ImGui::Text("move speeds XY %.3f  Z %.3f; jog XY %.3f  Z %.3f %s/s", modal_.speeds.move.xy,
              modal_.speeds.move.z, modal_.speeds.jog.xy, modal_.speeds.jog.z, u);
  ImGui::Text("table limits X %.2f to %.2f, Y %.2f to %.2f, Z %.2f to %.2f", settings_.axes[0].min,
              settings_.axes[0].max, settings_.axes[1].min, settings_.axes[1].max,
              settings_.axes[2].min, settings_.axes[2].max);
  ImGui::Separator();
  ImGui::TextWrapped(
      "Each editor is the command's fill-in sheet: a blank keeps the value, the ranges are the "
      "command table's, and Run runs the V command, which saves the values.");
  for (const CommandSpec& s : table_.all()) {
    if (s.group != CommandGroup::Values || s.immediate || !s.coverage.empty()) continue;
    if (button(fmt::format("{}##edit", s.code).c_str())) open_sheet(s, "");
    ImGui::SameLine();
    ImGui::Text("%s", std::string(s.name).c_str());
  }
  ImGui::End();
}

}  // namespace gantry::ui
