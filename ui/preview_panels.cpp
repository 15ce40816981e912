// The panels over the preview's top right: the work offsets and the macro buttons.
#include "app.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "gantry/interp/file_system.hpp"  // user_macro_folder
#include "gantry/session/part_files.hpp"  // user_part_files
#include "macro_panel.hpp"                // macro_panel
#include "offsets_panel.hpp"              // offset_rows, offsets_panel
#include "window_common.hpp"              // kFixed, place, the palette colours

namespace gantry::ui {

// The work-offset view: Zero runs ZX, ZY ... as typed at the command line.
void App::offsets_window() {
  const int axes = std::clamp(settings_.display.axes, 3, kAxisCount);
  const float h = ImGui::GetFrameHeight() + 2 * ImGui::GetStyle().WindowPadding.y +
                  static_cast<float>(axes + 1) * ImGui::GetFrameHeightWithSpacing() +
                  2 * ImGui::GetTextLineHeightWithSpacing();
  place_panel(0, h);
  panel_top_[1] = h;
  if (ImGui::Begin("Work offsets", &show_offsets_, kFixed)) {
    const std::string code = offsets_panel(
        session::offset_rows(position(status_), modal_, axes, table_), units_name(settings_.units),
        at_rest(), [this](const std::string& label, bool enabled) {
          return button(label.c_str(), enabled);
        });
    if (!code.empty()) run_line(code);
  }
  ImGui::End();
}

// The macro buttons: each runs the line typing it runs (C2, or FP with the file).
void App::macros_window() {
  const std::string folder = opt_.macros.empty() ? user_macro_folder() : opt_.macros;
  if (!show_macros_was_)
    macro_files_ = session::user_part_files(folder);  // listed again at each opening
  const float row = ImGui::GetFrameHeightWithSpacing();
  const float h = ImGui::GetFrameHeight() + 2 * ImGui::GetStyle().WindowPadding.y + 2 * row +
                  2 * ImGui::GetTextLineHeightWithSpacing() +
                  std::ceil(static_cast<float>(macro_files_.size()) / 4) * row;
  place_panel(panel_top_[1] > 0 ? 1 : 0, h);
  if (ImGui::Begin("Macros", &show_macros_, kFixed)) {
    const std::string line = macro_panel(
        macro_files_, folder, at_rest(),
        [this](const std::string& label, bool enabled) { return button(label.c_str(), enabled); });
    if (!line.empty()) run_line(line);
  }
  ImGui::End();
}

}  // namespace gantry::ui
