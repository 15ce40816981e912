// The Console window: the message log and the command line, and what a typed line does.
#include "app.hpp"

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>  // InputText on std::string

#include <cmath>

#include "gantry/lang/scan.hpp"              // trim
#include "gantry/lang/script.hpp"            // Script
#include "gantry/session/console_help.hpp"   // help_answer, window_status, keys_help
#include "gantry/session/console_words.hpp"  // read_typed_line
#include "gantry/session/source_place.hpp"   // kConsoleName
#include "window_common.hpp"                 // kFixed, place, the palette colours

namespace gantry::ui {

using session::kConsoleName;

void App::run_line(const std::string& typed) {
  using Word = session::TypedLine::Word;
  const session::TypedLine t = session::read_typed_line(typed);
  const std::string& line = t.line;
  if (line.empty()) return;
  log(LogLine::Typed, "> " + line);
  const std::string& rest = t.rest;
  switch (t.word) {
    case Word::Quit:
      quit_ = true;
      return;
    case Word::Help: {
      const session::HelpAnswer h = session::help_answer(
          session::FrontEnd::Window, rest, key_pendant_ ? &key_pendant_->bindings() : nullptr);
      return log(h.error ? LogLine::Error : LogLine::Info, h.text);
    }
    case Word::Status:
      return log(LogLine::Info,
                 session::window_status(status_, position(status_), settings_.units));
    case Word::Ack: {
      const Outcome o = c_.acknowledge();
      report(o, "ack");
      if (o) {
        snapshot();
        log(LogLine::Info, "E-stop acknowledged: the machine is ready");
      }
      return;
    }
    case Word::Confirm:
      m_.controller.clear_home_flags();  // homing.require's flags too (WinCNC's L29)
      return log(LogLine::Info, session::confirm_position(m_.memory));
    case Word::Keypad:
      kp_focus_ = true;
      ImGui::SetWindowFocus("Keypad");
      return log(LogLine::Info, "keypad: arrows X and Y, PageUp/PageDown Z; Esc leaves");
    case Word::Teach: {
      const session::FmKeys::Result r = fm_keys_.teach(rest, settings_.units);
      return log(r.error ? LogLine::Error : LogLine::Info, r.message);
    }
    case Word::Step:  // the window has no single step: the line goes to the machine
    case Word::None:
      break;
  }
  const Outcome o = c_.run_typed(Script::from_text(line, kConsoleName));
  report(o, "refused");
}

// Alt-F1...F10: during a run (or at its SK keypad) the file's hot-key subroutine; at rest the
// teach log's (session::FmKeys decides, as in the terminal console).
void App::fm_key(int n) {
  const bool running = !rest_state(status_.state) && status_.state != MachineState::Jogging;
  if (!running && !at_rest())
    return log(LogLine::Error,
               fmt::format("Alt-F{}: the table is moving; teach once it is at rest", n));
  if (!running) snapshot();  // at rest: the exact position
  session::FmKeys::Result r =
      fm_keys_.key(n, running, c_, m_.io, position(status_), settings_.friendly_motion);
  if (!r.typed.empty()) {  // the output a teach key switches, as a typed SO would
    const Outcome o = c_.run_typed(Script::from_text(r.typed, kConsoleName));
    if (!o) r.message += "; the output was not switched: " + o.reason;
  }
  log(r.error ? LogLine::Error : LogLine::Info, r.message);
}

void App::console_window() {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  place({{kLeft, size.y - kConsole}, {size.x - kLeft, kConsole}});
  ImGui::Begin("Console", nullptr, kFixed);
  const float below =
      ImGui::GetFrameHeightWithSpacing() + 2 * ImGui::GetTextLineHeightWithSpacing();
  ImGui::BeginChild("log", ImVec2(0, -below), true);
  ImGui::PushTextWrapPos(0.0f);  // long lines wrap at the log's edge instead of being cut off
  for (const LogLine& l : log_) {
    const ImVec4 c = l.kind == LogLine::Error   ? kRed
                     : l.kind == LogLine::Typed ? kCyan
                     : l.kind == LogLine::Print ? kText
                                                : kGrey;
    ImGui::TextColored(c, "%s", l.text.c_str());
  }
  // The rows the last entry takes, for the state dump (a wrapped line takes several).
  log_last_rows_ =
      log_.empty()
          ? 0
          : static_cast<int>(std::lround(ImGui::GetItemRectSize().y / ImGui::GetTextLineHeight()));
  ImGui::PopTextWrapPos();
  if (scroll_log_) ImGui::SetScrollHereY(1.0f);
  scroll_log_ = false;
  ImGui::EndChild();
  // The parameter line: what the code typed takes, or the codes that match so far.
  if (const CommandSpec* spec = command_of(table_, line_)) {
    const ParamLine pl =
        param_line(*spec, settings_.dialect, line_, static_cast<std::size_t>(cursor_));
    ImGui::TextColored(kYellow, "%s", pl.text.c_str());
    ImGui::TextDisabled("%s", pl.help.c_str());
  } else if (const auto m = completions(table_, line_); !m.empty()) {
    std::string list;
    for (const CommandSpec* s : m) list += fmt::format("{} {}   ", s->code, s->name);
    ImGui::TextColored(kYellow, "%s", list.c_str());
    ImGui::TextDisabled("Tab completes; Enter on a code opens its fill-in sheet");
  } else {
    ImGui::TextDisabled("Type a two-letter command (Tab completes), K for the keypad, help");
    ImGui::TextDisabled("%s", at_rest() ? "" : "Space pauses and resumes, Esc stops, F12 E-stop");
  }
  ImGui::TextColored(kCyan, "%s", status_.state == MachineState::EStop ? "ack>" : "gantry>");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  if (focus_line_ && !kp_focus_ && !sheet_open_ && !dialog_shown_ && !file_dialog_.showing()) {
    ImGui::SetKeyboardFocusHere();
    focus_line_ = false;
  }
  auto callback = [](ImGuiInputTextCallbackData* d) -> int {
    App& app = *static_cast<App*>(d->UserData);
    if (d->EventFlag == ImGuiInputTextFlags_CallbackCompletion) {
      const std::string done =
          complete(app.table_, std::string(d->Buf, static_cast<std::size_t>(d->BufTextLen)));
      d->DeleteChars(0, d->BufTextLen);
      d->InsertChars(0, done.c_str());
    } else if (d->EventFlag == ImGuiInputTextFlags_CallbackHistory) {
      const std::string now(d->Buf, static_cast<std::size_t>(d->BufTextLen));
      const std::optional<std::string> h =
          d->EventKey == ImGuiKey_UpArrow ? app.history_.up(now) : app.history_.down();
      if (h) {
        d->DeleteChars(0, d->BufTextLen);
        d->InsertChars(0, h->c_str());
      }
    }
    app.cursor_ = d->CursorPos;
    return 0;
  };
  const ImGuiInputTextFlags flags =
      ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CallbackCompletion |
      ImGuiInputTextFlags_CallbackHistory | ImGuiInputTextFlags_CallbackAlways |
      (at_rest() ? 0 : ImGuiInputTextFlags_ReadOnly);
  if (ImGui::InputText("##line", &line_, flags, callback, this)) {
    const std::string typed = std::exchange(line_, {});
    history_.add(std::string(scan::trim(typed)));
    if (enter_action(table_, typed) == EnterAction::OpenSheet)
      open_sheet(*command_of(table_, typed), typed);
    else
      run_line(typed);
    focus_line_ = true;
  }
  if (!ImGui::IsItemActive() && !kp_focus_ && !ImGui::IsAnyItemActive() &&
      !ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId))
    focus_line_ = true;
  ImGui::End();
}

}  // namespace gantry::ui
