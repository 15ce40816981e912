// The fill-in sheet: a command's parameters asked for in a dialog.
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>  // InputText on std::string

#include "gantry/lang/script.hpp"           // Script
#include "gantry/session/source_place.hpp"  // kConsoleName
#include "window_common.hpp"                // kFixed, place, the palette colours

namespace gantry::ui {

using session::kConsoleName;

void App::sheet_popup() {
  if (sheet_open_ && !ImGui::IsPopupOpen("Fill-in sheet")) ImGui::OpenPopup("Fill-in sheet");
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(size.x / 2, size.y / 2), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(560, 0), ImVec2(size.x - 40, size.y - 40));
  if (!ImGui::BeginPopupModal("Fill-in sheet", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  if (!sheet_open_ || !sheet_) {
    ImGui::CloseCurrentPopup();
    return ImGui::EndPopup();
  }
  const CommandSpec& spec = sheet_->spec();
  ImGui::TextColored(kYellow, "%s  %s", std::string(spec.code).c_str(),
                     std::string(spec.name).c_str());
  ImGui::PushTextWrapPos(540);
  ImGui::TextDisabled("%s", std::string(spec.help).c_str());
  ImGui::PopTextWrapPos();
  if (ImGui::BeginTable("fields", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    int n = 0;
    for (SheetField& f : sheet_->fields()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%d %s", n + 1, f.label.c_str());
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(f.spec->help).c_str());
      ImGui::TableNextColumn();
      ImGui::SetNextItemWidth(160);
      if (sheet_focus_ == n) {
        ImGui::SetKeyboardFocusHere();
        sheet_focus_ = -1;
      }
      if (ImGui::InputTextWithHint(fmt::format("##f{}", n).c_str(), f.hint.c_str(), &f.value))
        f.error = field_error(*f.spec, f.value);
      ImGui::TableNextColumn();
      ImGui::TextDisabled("%s", f.unit.empty() ? f.type.c_str() : f.unit.c_str());
      ImGui::TableNextColumn();
      if (!f.error.empty())
        ImGui::TextColored(kRed, "%s", f.error.c_str());
      else
        ImGui::TextDisabled("%s", f.range.c_str());
      ++n;
    }
    ImGui::EndTable();
  }
  for (const std::string& e : sheet_errors_) ImGui::TextColored(kRed, "%s", e.c_str());
  ImGui::TextDisabled("%s", sheet_->line().c_str());
  bool run = button("Run");
  ImGui::SameLine();
  bool cancel = button("Cancel");
  // Not the Enter that opened the sheet (it is still down in the frame it opens in).
  const bool keys = !sheet_fresh_;
  sheet_fresh_ = false;
  run = run || (keys && (ImGui::IsKeyPressed(GLFW_KEY_ENTER, false) ||
                         ImGui::IsKeyPressed(GLFW_KEY_KP_ENTER, false)));
  cancel = cancel || (keys && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false));
  // After Enter the field has lost the keys: give them to the first one in error.
  auto focus_error = [&] {
    sheet_focus_ = 0;
    const std::vector<SheetField>& f = sheet_->fields();
    for (std::size_t i = f.size(); i-- > 0;)
      if (!f[i].error.empty()) sheet_focus_ = static_cast<int>(i);
  };
  if (cancel) {
    sheet_open_ = false;
  } else if (run && !sheet_->validate()) {
    focus_error();
  } else if (run) {
    const std::string line = sheet_->line();
    const Outcome o = c_.run_typed(Script::from_text(line, kConsoleName));
    log(LogLine::Typed, "> " + line);
    if (o) {
      history_.add(line);
      sheet_open_ = false;
    } else {
      report(o, "refused");
      sheet_errors_ =
          o.errors.empty() ? std::vector<std::string>{o.reason} : sheet_->place_errors(o.errors);
      focus_error();
    }
  }
  if (!sheet_open_) {
    ImGui::CloseCurrentPopup();
    focus_line_ = true;
  }
  ImGui::EndPopup();
}

}  // namespace gantry::ui
