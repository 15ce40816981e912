// The work-offset view.
#include "offsets_panel.hpp"

#include <fmt/format.h>
#include <imgui.h>

namespace gantry::ui {

std::vector<OffsetRow> offset_rows(const Vec6& work, const ModalState& m, int axes,
                                   const CommandTable& table) {
  static const char kAxes[] = "XYZABC";
  std::vector<OffsetRow> rows;
  for (int i = 0; i < axes && i < kAxisCount; ++i) {
    const double offset = m.zero[i] + m.applied_offset[i];
    const std::string code = fmt::format("Z{}", kAxes[i]);
    rows.push_back(
        {kAxes[i], work[i] + offset, offset, work[i], table.find(code) ? code : std::string()});
  }
  return rows;
}

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
