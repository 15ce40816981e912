// The work-offset view.
#include "offsets_panel.hpp"

#include <fmt/format.h>
#include <imgui.h>

namespace gantry::ui {

std::string offsets_panel(const std::vector<OffsetRow>& rows, const char* units, bool can_zero,
                          const std::function<bool(const std::string&, bool)>& button) {
  std::string run;
  if (!ImGui::BeginTable("offsets", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchSame))
    return run;
  for (const char* h : {"axis", "machine", "offset", "work", ""}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  for (const OffsetRow& r : rows) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%c", r.axis);
    for (const double v : {r.table, r.offset, r.work}) {
      ImGui::TableNextColumn();
      ImGui::Text("%.4f", v);
    }
    ImGui::TableNextColumn();
    if (!r.zero_code.empty() && button(fmt::format("Zero {}##{}", r.axis, r.zero_code), can_zero))
      run = r.zero_code;
  }
  ImGui::EndTable();
  ImGui::TextDisabled("%s; machine = work + offset; Zero runs ZX, ZY ... as typed", units);
  return run;
}

}  // namespace gantry::ui
