// The console window (docs/console.md, "Console window"): the frame that lays out and draws
// each window once a frame (one file each: readout_window.cpp, keypad_window.cpp, ...), the
// menus, the keys that work everywhere, and what a frame polls from the controller.
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

#include "gantry/session/feed_override.hpp"  // stepped_feed_override
#include "gantry/session/refusal.hpp"        // refusal_entries
#include "gantry/session/run_progress.hpp"   // run_progress
#include "gantry/session/source_place.hpp"   // kConsoleName
#include "theme.hpp"                         // digits_font, palette
#include "window_common.hpp"                 // kLeft, kConsole, place, the palette colours

namespace gantry::ui {
namespace {

using Clock = std::chrono::steady_clock;

// The one-line scripts typed in the window are named like the terminal console's.
using session::kConsoleName;

}  // namespace

App::App(const GuiOptions& options, Machine& machine)
    : opt_(options),
      m_(machine),
      c_(machine.controller),
      table_(CommandTable::standard()),
      menus_(menus(table_)),
      gl_(std::make_unique<PreviewGL>()) {
  snapshot();
  bind_keys();
  camera_.set_view(View::Iso);
  log(LogLine::Info, fmt::format("gantry {}: profile \"{}\" on the {} card. F1 lists the keys.",
                                 GANTRY_VERSION, settings_.name, opt_.card));
  if (!opt_.file.empty()) load(opt_.file);
}

App::~App() {
  cancel_ = true;
  if (loader_.joinable()) loader_.join();
}

// ---- state -----------------------------------------------------------------------------------

void App::snapshot() {
  modal_ = c_.modal();
  settings_ = m_.settings();
  tool_.snapshot(modal_, settings_);
}

bool App::at_rest() const {
  return rest_state(status_.state) && status_.settled;
}

bool App::idle() const {
  return at_rest() && !m_.io.question() && !loading_ && dialog_shown_ == 0;
}

bool App::keys_moving() const {
  return (focus_line_ && !kp_focus_ && !sheet_open_ && !dialog_shown_) || sheet_focus_ >= 0;
}

Vec6 App::position(const ControllerStatus& st) const {
  // At rest the interpreter's position is exact (a step ends on its commanded point); under
  // way the pulses played say where the tool is.
  return tool_.at(st, rest_state(st.state) && st.settled);
}

void App::log(LogLine::Kind kind, std::string text) {
  std::size_t start = 0;
  while (start <= text.size()) {  // one entry per line
    const std::size_t nl = text.find('\n', start);
    std::string piece = text.substr(start, nl == std::string::npos ? nl : nl - start);
    if (!piece.empty() || nl == std::string::npos) log_.push_back({kind, std::move(piece)});
    if (nl == std::string::npos) break;
    start = nl + 1;
  }
  if (log_.size() > 5000) log_.erase(log_.begin(), log_.begin() + 1000);
  scroll_log_ = true;
}

void App::poll() {
  if (std::string out = m_.io.take_output(); !out.empty()) {
    if (out.back() == '\n') out.pop_back();
    log(LogLine::Print, out);
  }
  status_ = c_.status();
  // An activity ended since the last frame (at rest or halted): the window never waits for
  // motion, so a released jog slowing to rest leaves every key working.
  if (activity_.ended(status_)) {
    snapshot();
    if (job_running_) {  // where it ended
      const session::RunProgress p = session::run_progress(status_);
      listing_line_ = p.file_line;
      listing_file_ = p.file;
    }
    job_running_ = false;
    // A continuous jog that ended (released, stopped, at the limit) or anything cut short
    // forgets its key; a tap's step that played out keeps it: held on, it becomes a jog.
    if (kp_press_.continuous() ||
        (status_.state != MachineState::Idle && status_.state != MachineState::Keypad))
      kp_press_.reset();
    if (status_.state == MachineState::EStop)
      log(LogLine::Error, "E-STOP: the pulses stopped at once. Nothing moves until Ack (or ack).");
    else if (status_.state == MachineState::Stopped)
      log(LogLine::Error,
          fmt::format(
              "stopped: {}{}", status_.message.empty() ? "the run did not end" : status_.message,
              status_.stopped_at.file && *status_.stopped_at.file != kConsoleName
                  ? fmt::format(" (at {}:{})", *status_.stopped_at.file, status_.stopped_at.line)
                  : ""));
  }
  // SK in a file: the keypad takes the keys until the operator goes on (Esc) or stops.
  const bool file_keypad =
      status_.state == MachineState::Keypad || (kp_file_ && status_.state == MachineState::Jogging);
  if (file_keypad && !kp_file_) {
    kp_focus_ = true;
    std::string message = m_.io.take_keypad_message();
    if (message.empty()) message = "SK: the file waits while you jog";
    log(LogLine::Info,
        message + "\nkeypad: jog, then Esc (or Resume) goes on with the file; Stop ends it");
  }
  if (!file_keypad && kp_file_) kp_focus_ = false, focus_line_ = true;
  kp_file_ = file_keypad;
  std::shared_ptr<const Toolpath> done;
  std::shared_ptr<const ListingText> text;
  {
    std::lock_guard lock(loaded_m_);
    done = std::move(loaded_);
    text = std::move(loaded_text_);
  }
  if (done) {
    if (loader_.joinable()) loader_.join();
    path_ = std::move(done);
    listing_.set(std::move(text));
    listing_line_ = 0;
    listing_file_.reset();
    gl_->set_path(*path_);
    loading_ = false;
    fit_ = true;
    load_seconds_ = std::chrono::duration<double>(Clock::now() - load_started_).count();
    log(LogLine::Info, fmt::format("preview: {} segments, {} moves in {:.2f} s{}",
                                   path_->segments.size(), path_->moves, load_seconds_,
                                   path_->estimated_time_s > 0
                                       ? fmt::format("; cycle time about {}",
                                                     session::clock_text(path_->estimated_time_s))
                                       : ""));
    int shown_errors = 0;
    for (const Diagnostic& d : path_->violations)
      if (shown_errors++ < 20)
        log(d.severity == Severity::Error ? LogLine::Error : LogLine::Info, format(d));
    if (path_->violations.size() > 20)
      log(LogLine::Error, fmt::format("... and {} more", path_->violations.size() - 20));
  }
}

// ---- actions ---------------------------------------------------------------------------------

bool App::clicked(const char* name) {
  if (pending_click_.empty() || pending_click_ != name) return false;
  pending_click_.clear();
  return true;
}

bool App::button(const char* label, bool enabled) {
  if (!enabled) ImGui::BeginDisabled();
  bool pressed = ImGui::Button(label);
  if (!enabled) ImGui::EndDisabled();
  // A script names the button by its label (without any ##id), and clicks it only when the
  // whole button is on the screen, as a person could.
  const std::string name = std::string(label).substr(0, std::string(label).find("##"));
  const bool whole = note_button(name);
  if (enabled && whole && clicked(name.c_str())) pressed = true;
  return pressed;
}

bool App::note_button(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  const ImDrawList& d = *ImGui::GetWindowDrawList();
  const ImVec2 c0 = d.GetClipRectMin(), c1 = d.GetClipRectMax(), size = ImGui::GetIO().DisplaySize;
  const bool whole = a.x >= std::max(c0.x, 0.0f) - 0.5f && a.y >= std::max(c0.y, 0.0f) - 0.5f &&
                     b.x <= std::min(c1.x, size.x) + 0.5f && b.y <= std::min(c1.y, size.y) + 0.5f;
  buttons_[name] = {a.x, a.y, b.x, b.y, whole ? 1.0f : 0.0f};
  return whole;
}

std::optional<std::string> App::missed_click() {
  if (pending_click_.empty()) return std::nullopt;
  return std::exchange(pending_click_, {});
}

void App::report(const Outcome& o, const std::string& what) {
  if (o) return;
  for (std::string& entry : session::refusal_entries(o, what))
    log(LogLine::Error, std::move(entry));
}

void App::open_sheet(const CommandSpec& spec, const std::string& typed) {
  sheet_.emplace(spec, settings_.dialect, units_name(settings_.units));
  sheet_->fill_from(typed);
  sheet_errors_.clear();
  sheet_open_ = true;
  sheet_fresh_ = true;
  sheet_focus_ = 0;
}

void App::choose(const CommandSpec& spec) {
  if (spec.immediate) return run_line(std::string(spec.code));
  open_sheet(spec, "");
}

void App::global_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) {
    m_.io.cancel();
    report(c_.estop(), "E-stop");
  }
  if (pendant_keys()) return;  // a bound key does only what it is bound to
  if (io.KeyAlt && !io.KeyCtrl && !io.KeyShift)  // Friendly Motion's Alt-F1...F10
    for (int f = 1; f <= 10; ++f)
      if (ImGui::IsKeyPressed(GLFW_KEY_F1 + f - 1, false)) return fm_key(f);
  if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) show_keys_ = !show_keys_;
  if (io.KeyAlt)
    for (std::size_t i = 0; i < menus_.size(); ++i)
      if (menus_[i].key >= 'A' && menus_[i].key <= 'Z' &&
          ImGui::IsKeyPressed(GLFW_KEY_A + (menus_[i].key - 'A'), false))
        group_popup_ = static_cast<int>(i);
  if (sheet_open_ || dialog_shown_ || m_.io.question()) return;
  if (kp_focus_) return jog_keys();
  // A running file: the command line is read-only, so Space and Esc are free for it.
  if (!at_rest() && status_.state != MachineState::Jogging) {
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false))
      report(status_.state == MachineState::Paused ? c_.resume() : c_.pause(), "space");
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) report(c_.stop(), "stop");
    // + and - step the feed override (the command line is read-only while a file runs).
    if (ImGui::IsKeyPressed(GLFW_KEY_KP_ADD, false) || ImGui::IsKeyPressed(GLFW_KEY_EQUAL, false))
      set_feed_override(session::stepped_feed_override(status_.feed_override, 1,
                                                       session::feed_override_bounds(settings_)));
    if (ImGui::IsKeyPressed(GLFW_KEY_KP_SUBTRACT, false) ||
        ImGui::IsKeyPressed(GLFW_KEY_MINUS, false))
      set_feed_override(session::stepped_feed_override(status_.feed_override, -1,
                                                       session::feed_override_bounds(settings_)));
  }
}

void App::set_feed_override(double factor) {
  c_.set_feed_override(factor);
  status_.feed_override = factor;  // shown at once; the next poll confirms it
  log(LogLine::Info, session::feed_override_text(factor) + " (moves already planned keep their speed)");
}

// ---- the frame -------------------------------------------------------------------------------

void App::frame() {
  use_palette(palette(light_));
  buttons_.clear();
  panel_top_ = {};
  lay_out();
  poll();
  global_keys();
  menu_bar();
  readout_window();
  keypad_window();
  job_window();
  preview_window();
  console_window();
  if (show_values_) values_window();
  if (show_offsets_) offsets_window();
  if (show_macros_) macros_window();
  show_macros_was_ = show_macros_;
  if (show_keys_) keys_window();
  group_popup();
  sheet_popup();
  question_popup();
}

void App::menu_bar() {
  if (clicked("Values window")) show_values_ = true;  // a script names the menu item
  if (clicked("Offsets")) show_offsets_ = !show_offsets_;
  if (clicked("Macros")) show_macros_ = !show_macros_;
  if (clicked("Light theme")) light_ = !light_;
  if (clicked("File > Open...")) file_dialog_.open_beside(file_);
  if (!ImGui::BeginMainMenuBar()) return;
  for (const Menu& menu : menus_) {
    if (!ImGui::BeginMenu(fmt::format("{}##{}", menu.title, menu.key).c_str())) continue;
    ImGui::TextDisabled("Alt+%c", menu.key);
    for (const CommandSpec* s : menu.commands)
      if (ImGui::MenuItem(fmt::format("{}##m{}", s->name, s->code).c_str(),
                          std::string(s->code).c_str()))
        choose(*s);
    if (menu.title == "Values") {
      ImGui::Separator();
      ImGui::MenuItem("Values window", nullptr, &show_values_);
    }
    if (menu.title == "Help") {
      ImGui::Separator();
      ImGui::MenuItem("Keys", "F1", &show_keys_);
    }
    if (menu.title == "File") {
      ImGui::Separator();
      if (ImGui::MenuItem("Open...##menu", "Ctrl+O")) file_dialog_.open_beside(file_);
      if (ImGui::MenuItem("Quit")) quit_ = true;
    }
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    const std::pair<const char*, View> views[] = {
        {"Top", View::Top}, {"Front", View::Front}, {"Side", View::Side}, {"Iso", View::Iso}};
    for (const auto& [name, v] : views)
      if (ImGui::MenuItem(name)) camera_.set_view(v), fit_ = true;
    ImGui::MenuItem("Perspective", nullptr, &camera_.perspective);
    ImGui::MenuItem("Show jogs", nullptr, &show_jogs_);
    ImGui::Separator();
    ImGui::MenuItem("Light theme", nullptr, &light_);  // dark or light, for a bright shop
    ImGui::EndMenu();
  }
  // The panels over the preview, one click away (and touch-friendly): toggles on the bar.
  ImGui::MenuItem("Offsets", nullptr, &show_offsets_);
  ImGui::MenuItem("Macros", nullptr, &show_macros_);
  ImGui::EndMainMenuBar();
}

void App::group_popup() {
  if (group_popup_ >= 0) {
    ImGui::OpenPopup("##group");
    ImGui::SetNextWindowPos(ImVec2(kLeft + 10, ImGui::GetIO().DisplaySize.y - kConsole - 10),
                            ImGuiCond_Always, ImVec2(0, 1));
    group_menu_ = group_popup_;
    group_popup_ = -1;
  }
  group_showing_ = ImGui::BeginPopup("##group");
  if (!group_showing_) return;
  const Menu& menu = menus_[static_cast<std::size_t>(group_menu_)];
  ImGui::TextColored(kCyan, "%s", menu.title.c_str());
  ImGui::Separator();
  for (const CommandSpec* s : menu.commands)
    if (ImGui::Selectable(fmt::format("{}  {}", s->code, s->name).c_str()) ||
        clicked(std::string(s->code).c_str())) {
      ImGui::CloseCurrentPopup();
      choose(*s);
    }
  ImGui::EndPopup();
}

// The layout at this frame's size. The column and the console scale with the fonts; the
// keypad and the job window (the run controls) get the height they need and the readout what
// is left, up to what its digits fill: at 1024 x 600 every run control stays on the screen.
void App::lay_out() {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const ImGuiStyle& style = ImGui::GetStyle();
  kLeft = std::min(370 * scale_, size.x * 0.45f);
  kConsole = std::min(250 * scale_, size.y * 0.4f);
  const float title = ImGui::GetFrameHeight(), pad = 2 * style.WindowPadding.y;
  const float row = ImGui::GetFrameHeightWithSpacing();
  const float text = ImGui::GetTextLineHeightWithSpacing();
  kKeypad = title + pad + text + 3 * pad_row() + 2 * row + style.ItemSpacing.y;
  const float job = title + pad + 5 * row + text + style.ItemSpacing.y;
  const float column = size.y - ImGui::GetFrameHeight();  // below the menu bar
  // The readout: the state line, the digits, then five lines (units, speeds, inputs, outputs,
  // spindle; the last stop scrolls in a low window). The digits as large as the height left
  // and the width allow.
  const float fixed = title + pad + 6 * text;
  const int axes = std::clamp(settings_.display.axes, 3, kAxisCount);
  const float left = column - kKeypad - job;  // for the readout
  const float by_height = (left - fixed) / static_cast<float>(axes) - style.ItemSpacing.y;
  // A digit is about 0.6 of the font's size wide; 11 of them and the axis letter's column.
  const float by_width = (kLeft - 2 * style.WindowPadding.x - 40 * scale_) / (11 * 0.62f);
  const float most = digits_font() ? digits_font_size() : 3 * ImGui::GetFontSize();
  digits_px_ = std::clamp(std::min(by_height, by_width), ImGui::GetFontSize(), most);
  // Too little height: the readout scrolls (its digits first), the run controls stay whole.
  kReadout = std::max(
      std::min(fixed + static_cast<float>(axes) * (digits_px_ + style.ItemSpacing.y), left),
      4 * text);
  // The program listing gets its rows before the digits grow past twice the text's size.
  const float short_of = ProgramListing::kRows * text - (left - kReadout);
  const float smallest =
      fixed + static_cast<float>(axes) * (2 * ImGui::GetFontSize() + style.ItemSpacing.y);
  if (const float give = std::min(short_of, kReadout - smallest); give > 0) {
    kReadout -= give;
    digits_px_ = std::max((kReadout - fixed) / static_cast<float>(axes) - style.ItemSpacing.y,
                          ImGui::GetFontSize());
  }
}

// A panel over the preview's top right corner (offsets, macros), `row` panels down.
void App::place_panel(int row, float height) {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const float w = std::min(440 * scale_, size.x - kLeft);
  // Below the menu bar and the preview's title and tool bar.
  const float y = 3 * ImGui::GetFrameHeight() + 24 * scale_ + static_cast<float>(row) * 10 * scale_;
  ImGui::SetNextWindowPos(ImVec2(size.x - w - 8 * scale_, y + panel_top_[row]), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(w, height), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(1.0f);
}

// Why the position is unconfirmed (the machine memory's mark), or nullopt when it is not.
std::optional<std::string> App::unconfirmed() const {
  if (!m_.memory) return std::nullopt;
  const session::SavedMachine m = m_.memory->state();
  if (m.confirmed) return std::nullopt;
  return m.why.empty() ? std::string("the position is unconfirmed") : m.why;
}

// ---- the state, for scripts ----------------------------------------------------------------

}  // namespace gantry::ui
