// The window's state as JSON, for scripts and tests (App::state).
#include "app.hpp"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

#include "gantry/session/readout_lines.hpp"  // spindle_text
#include "gantry/session/run_progress.hpp"   // run_progress
#include "offsets_panel.hpp"                 // offset_rows, offsets_panel
#include "window_common.hpp"                 // kFixed, place, the palette colours

namespace gantry::ui {

using session::shown;

nlohmann::json App::state() const {
  using nlohmann::json;
  const Vec6 p = position(status_);
  json s;
  s["state"] = state_name(status_.state);
  s["warning"] = status_.warning;
  s["position"] = json::array();
  for (int i = 0; i < kAxisCount; ++i) s["position"].push_back(shown(p[i]));
  s["units"] = units_name(settings_.units);
  s["absolute"] = modal_.absolute;
  s["preview_mode"] = modal_.preview.has_value();
  s["speeds"] = {{"move_xy", modal_.speeds.move.xy},
                 {"move_z", modal_.speeds.move.z},
                 {"jog_xy", modal_.speeds.jog.xy},
                 {"jog_z", modal_.speeds.jog.z}};
  s["values_window"] = show_values_;
  s["group_menu"] = group_showing_ ? menus_[static_cast<std::size_t>(group_menu_)].title : "";
  s["card"] = opt_.card;
  s["inputs"] = status_.inputs;
  s["outputs"] = status_.outputs;
  s["spindle"] = session::spindle_text(status_, modal_.spindle_rpm);
  s["feed_override"] = status_.feed_override;
  s["message"] = status_.message;
  s["command_line"] = line_;
  s["history"] = history_.lines();
  s["keypad"] = {{"keys", kp_focus_},
                 {"step", kp_step_},
                 {"fast", kp_fast_},
                 {"step_size", jog_step()},
                 {"preset", kp_preset_}};
  s["confirmed"] = !unconfirmed().has_value();
  s["theme"] = light_ ? "light" : "dark";
  s["offsets_window"] = show_offsets_;
  s["offsets"] = json::array();
  const int axes = std::clamp(settings_.display.axes, 3, kAxisCount);
  for (const OffsetRow& r : session::offset_rows(p, modal_, axes, table_))
    s["offsets"].push_back({{"axis", std::string(1, r.axis)},
                            {"machine", shown(r.table)},
                            {"offset", shown(r.offset)},
                            {"work", shown(r.work)}});
  s["layout"] = {{"scale", scale_},
                 {"font_px", ImGui::GetFontSize()},
                 {"digits_px", digits_px_},
                 {"display", {ImGui::GetIO().DisplaySize.x, ImGui::GetIO().DisplaySize.y}}};
  json buttons = json::object();
  for (const auto& [name, b] : buttons_)
    buttons[name] = {{"rect", {b[0], b[1], b[2], b[3]}}, {"whole", b[4] > 0}};
  s["buttons"] = buttons;
  const session::RunProgress progress = session::run_progress(status_);  // as the bar shows it
  s["progress"] = {{"line", progress.line},
                   {"lines", progress.lines},
                   {"fraction", progress.fraction},
                   {"elapsed_s", progress.elapsed_s},
                   {"remaining_s", progress.remaining_s},
                   {"label", progress.label()},
                   {"times", progress.times()}};
  if (sheet_open_ && sheet_) {
    json fields = json::array();
    for (const SheetField& f : sheet_->fields())
      fields.push_back({{"label", f.label},
                        {"type", f.type},
                        {"unit", f.unit},
                        {"range", f.range},
                        {"hint", f.hint},
                        {"value", f.value},
                        {"error", f.error}});
    s["sheet"] = {{"code", sheet_->spec().code},
                  {"fields", fields},
                  {"line", sheet_->line()},
                  {"errors", sheet_errors_}};
  }
  if (const std::optional<session::Question> q = m_.io.question())
    s["dialog"] = {{"kind", q->kind == session::Question::Kind::Pause   ? "PAUSE"
                            : q->kind == session::Question::Kind::Input ? "INPUT"
                                                                        : "MSGBOX"},
                   {"text", q->text},
                   {"buttons", q->buttons},
                   {"shown", dialog_shown_ == q->id}};
  json preview = {
      {"file", file_},
      {"loading", loading_.load()},
      {"hover_line", hover_line_},
      {"view",
       {{"yaw", camera_.yaw}, {"pitch", camera_.pitch}, {"perspective", camera_.perspective}}}};
  if (path_) {
    preview["segments"] = path_->segments.size();
    preview["moves"] = path_->moves;
    preview["violations"] = path_->violations.size();
    preview["estimated_time_s"] = path_->estimated_time_s;
    if (!path_->bounds.isEmpty())
      preview["bounds"] = {path_->bounds.min().x(), path_->bounds.min().y(),
                           path_->bounds.min().z(), path_->bounds.max().x(),
                           path_->bounds.max().y(), path_->bounds.max().z()};
  }
  s["preview"] = preview;
  s["file_dialog"] = file_dialog_.state();
  s["recent_files"] = recent_.files();
  json listing = listing_.state();
  listing["start_line"] = start_line_;
  s["listing"] = listing;
  json log = json::array();
  for (const LogLine& l : log_)
    log.push_back(fmt::format("{}{}", l.kind == LogLine::Error ? "E " : "  ", l.text));
  s["log"] = log;
  s["log_last_rows"] = log_last_rows_;
  return s;
}

}  // namespace gantry::ui
