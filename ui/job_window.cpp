// The Job window: the part file, its start line, the run controls, the progress and the
// program listing.
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>  // InputText on std::string

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "gantry/lang/script.hpp"            // Script
#include "gantry/session/feed_override.hpp"  // clamped_feed_override
#include "gantry/session/run_progress.hpp"   // run_progress
#include "gantry/session/source_place.hpp"   // kConsoleName
#include "window_common.hpp"                 // kFixed, place, the palette colours

namespace gantry::ui {

using session::kConsoleName;

void App::start_file(int from_line) {
  if (file_.empty()) return log(LogLine::Error, "no part file: type its name above and Load it");
  if (from_line > 1) {
    // FG runs a file from a line: its sheet's last parameter.
    const CommandSpec* fg = table_.find("FG");
    std::string l = fmt::format("FG, \"{}\"", std::filesystem::absolute(file_).string());
    for (std::size_t i = 1; fg && i + 1 < fg->params.size(); ++i) l += ", ";
    l += fmt::format(", {}", from_line);
    log(LogLine::Typed, "> " + l);
    const Outcome o = c_.run_typed(Script::from_text(l, kConsoleName));
    report(o, "refused");
    job_running_ = o.accepted;
    return;
  }
  try {
    log(LogLine::Typed, "> start " + file_);
    const Outcome o = c_.run(Script::load(file_));
    report(o, "refused");
    job_running_ = o.accepted;
  } catch (const GantryError& e) {
    log(LogLine::Error, e.what());
  }
}

void App::job_window() {
  const float top = ImGui::GetFrameHeight() + kReadout + kKeypad;
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  place({{0, top}, {kLeft, std::max(size.y - top, 100.0f)}});
  ImGui::Begin("Job", nullptr, kFixed);
  const ImGuiStyle& style = ImGui::GetStyle();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("LoadOpen...").x -
                          4 * style.FramePadding.x - 2 * style.ItemSpacing.x);
  ImGui::InputTextWithHint("##file", "part file (.sbp)", &file_);
  ImGui::SameLine();
  if (button("Load")) load(file_);
  ImGui::SameLine();
  const bool ctrl_o = ImGui::GetIO().KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_O, false) &&
                      !file_dialog_.showing() && !sheet_open_ && !dialog_shown_;
  if (button("Open...") || ctrl_o) file_dialog_.open_beside(file_);
  const bool rest = at_rest(), paused = status_.state == MachineState::Paused ||
                                        status_.state == MachineState::Keypad;
  if (button("Start", rest && !file_.empty())) start_file(1);
  ImGui::SameLine();
  if (paused ? button("Resume") : button("Pause", !rest && status_.state != MachineState::Jogging))
    report(paused ? c_.resume() : c_.pause(), paused ? "resume" : "pause");
  ImGui::SameLine();
  if (button("Stop", !rest)) report(c_.stop(), "stop");
  ImGui::SameLine();
  push_estop_colours();
  if (button("E-STOP")) {
    m_.io.cancel();
    report(c_.estop(), "E-stop");
  }
  ImGui::PopStyleColor(kEStopColours);
  if (status_.state == MachineState::EStop) {
    ImGui::SameLine();
    if (button("Ack")) run_line("ack");
  }
  // The live feed override, within the profile's bounds (+ and - while a file runs).
  const session::FeedOverrideBounds bounds = session::feed_override_bounds(settings_);
  int percent = static_cast<int>(std::lround(status_.feed_override * 100));
  ImGui::SetNextItemWidth(200);
  if (ImGui::SliderInt("feed %", &percent, settings_.feed_override.min, settings_.feed_override.max,
                       "%d %%"))
    set_feed_override(session::clamped_feed_override(percent / 100.0, bounds));
  ImGui::SameLine();
  if (button("100 %")) set_feed_override(session::clamped_feed_override(1.0, bounds));
  ImGui::SetNextItemWidth(110);
  ImGui::InputInt("##from", &start_line_);
  start_line_ = std::max(start_line_, 1);
  ImGui::SameLine();
  if (button("Start at line", rest && !file_.empty())) start_file(start_line_);
  ImGui::SameLine();
  if (button("Single step")) {
    single_step_ = !single_step_;
    c_.set_single_step(single_step_);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "On: each statement's motion plays, then the file holds; Resume runs the "
        "next statement, Stop ends the file there");
  ImGui::SameLine();
  ImGui::TextUnformatted(single_step_ ? "on" : "off");
  // Progress of the file running, or of the last one, as `gantry run` and the console show it.
  const session::RunProgress progress = session::run_progress(status_);
  ImGui::ProgressBar(static_cast<float>(progress.fraction), ImVec2(-1, 0),
                     progress.label().c_str());
  ImGui::TextUnformatted(progress.times().c_str());
  // The listing: the line the card plays while the file runs, else where the last run ended;
  // a click at rest chooses the line "Start at line" starts at.
  const std::size_t chosen = listing_.draw(job_running_ ? progress.file_line : listing_line_,
                                           job_running_ ? progress.file : listing_file_,
                                           job_running_ && !rest, rest, start_line_, pending_click_);
  if (chosen > 0) start_line_ = static_cast<int>(chosen);
  ImGui::End();
  if (const std::optional<std::string> f = file_dialog_.draw(
          recent_.files(), [this](const std::string& name) { return clicked(name.c_str()); })) {
    load(*f);
    focus_line_ = true;
  }
}

}  // namespace gantry::ui
