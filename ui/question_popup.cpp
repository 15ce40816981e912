// The question dialog: PAUSE, INPUT and MSGBOX from the running file.
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>  // InputText on std::string

#include <string_view>

#include "window_common.hpp"  // kFixed, place, the palette colours

namespace gantry::ui {

void App::question_popup() {
  const std::optional<session::Question> q = m_.io.question();
  if (!q) {
    dialog_shown_ = 0;
    return;
  }
  const char* title = q->kind == session::Question::Kind::Pause   ? "PAUSE###question"
                      : q->kind == session::Question::Kind::Input ? "INPUT###question"
                                                                  : "MSGBOX###question";
  if (dialog_shown_ != q->id) {
    ImGui::OpenPopup("###question");
    answer_ = q->default_value;
  }
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(size.x / 2, size.y / 2), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  const bool fresh = dialog_shown_ != q->id;
  dialog_shown_ = q->id;
  ImGui::TextDisabled("[%s]", q->where.c_str());
  if (!q->title.empty()) ImGui::TextColored(kYellow, "%s", q->title.c_str());
  ImGui::PushTextWrapPos(480);
  ImGui::TextUnformatted(q->text.c_str());
  ImGui::PopTextWrapPos();
  const bool enter = !fresh && ImGui::IsKeyPressed(GLFW_KEY_ENTER, false);
  const bool esc = !fresh && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false);
  std::optional<std::string> answer;
  bool cancel = esc;
  switch (q->kind) {
    case session::Question::Kind::Pause:
      if (button("Continue") || enter) answer = "";
      ImGui::SameLine();
      cancel = button("Cancel##pause") || cancel;
      break;
    case session::Question::Kind::Input:
      if (fresh) ImGui::SetKeyboardFocusHere();
      ImGui::SetNextItemWidth(220);
      ImGui::InputText(q->variable.c_str(), &answer_);
      if (button("OK") || enter) answer = answer_;
      ImGui::SameLine();
      cancel = button("Cancel##input") || cancel;
      break;
    case session::Question::Kind::MsgBox:
      for (std::size_t i = 0; i < q->buttons.size(); ++i) {
        if (i > 0) ImGui::SameLine();
        if (button(q->buttons[i].c_str())) answer = q->buttons[i];
      }
      if (enter && q->default_button < q->buttons.size()) answer = q->buttons[q->default_button];
      break;
  }
  if (answer || cancel) {
    // The log names the dialog by its kind: the title's ###id is ImGui's, not the operator's.
    const std::string_view kind(title, std::string_view(title).find("###"));
    log(LogLine::Info,
        fmt::format("{}: {}", kind,
                    answer ? (answer->empty() ? "continue" : *answer) : "cancelled"));
    if (answer)
      m_.io.answer(*answer);
    else
      m_.io.cancel();
    dialog_shown_ = 0;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

}  // namespace gantry::ui
