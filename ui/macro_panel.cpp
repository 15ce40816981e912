// The macro buttons.
#include "macro_panel.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include <filesystem>

namespace gantry::ui {

namespace fs = std::filesystem;

std::string macro_panel(const std::vector<std::string>& files, const std::string& folder,
                        bool can_run, const std::function<bool(const std::string&, bool)>& button) {
  // What the shipped files do (the operator's own C<n>.sbp comes first when there is one).
  static const char* const kWhat[] = {"zero Z with the plate", "home X, Y and Z", "spindle on",
                                      "spindle off", "manual tool change"};
  std::string run;
  ImGui::TextDisabled("custom cuts");
  for (std::size_t i = 0; i < std::size(kMacroCuts); ++i) {
    ImGui::SameLine();
    const std::string code = fmt::format("C{}", kMacroCuts[i]);
    if (button(code, can_run)) run = code;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s: %s (runs C%d.sbp from the macro folders, as typed)", code.c_str(),
                        kWhat[i], kMacroCuts[i]);
  }
  ImGui::TextDisabled("part files in %s", folder.c_str());
  if (files.empty()) ImGui::TextDisabled("(none: put .sbp files there)");
  float x = 0;
  const float right = ImGui::GetContentRegionAvail().x;
  for (const std::string& f : files) {
    const std::string name = fs::path(f).stem().string();
    const float w = ImGui::CalcTextSize(name.c_str()).x + 2 * ImGui::GetStyle().FramePadding.x;
    if (x > 0 && x + w < right)
      ImGui::SameLine();
    else
      x = 0;
    x += w + ImGui::GetStyle().ItemSpacing.x;
    if (button(name + "##part", can_run)) run = fmt::format("FP, \"{}\"", f);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("FP, \"%s\"", f.c_str());
  }
  return run;
}

}  // namespace gantry::ui
