// The console window's windows (docs/console.md, "Console window").
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>  // InputText on std::string

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "gantry/commands/command_docs.hpp"  // command_help
#include "gantry/lang/scan.hpp"              // trim
#include "gantry/lang/script.hpp"            // Script
#include "gantry/session/console_help.hpp"   // help_answer, window_status, keys_help
#include "gantry/session/console_words.hpp"  // read_typed_line
#include "gantry/session/feed_override.hpp"  // stepped_feed_override
#include "gantry/session/readout_lines.hpp"  // spindle_text
#include "gantry/session/refusal.hpp"        // refusal_entries
#include "gantry/session/run_progress.hpp"   // run_progress
#include "gantry/session/source_place.hpp"   // kConsoleName
#include "gantry/interp/file_system.hpp"     // user_macro_folder
#include "macro_panel.hpp"                   // macro_panel, user_part_files
#include "offsets_panel.hpp"                 // offset_rows, offsets_panel
#include "theme.hpp"                         // digits_font, palette

namespace gantry::ui {
namespace {

using Clock = std::chrono::steady_clock;

// The one-line scripts typed in the window are named like the terminal console's.
using session::kConsoleName;
using session::shown;
const char* const kAxes = "XYZABC";

// The theme's text colours (palette): set at the start of each frame.
ImVec4 kRed, kGreen, kYellow, kGrey, kCyan, kMagenta, kText, kOff;

void use_palette(const Palette& p) {
  kRed = p.red, kGreen = p.green, kYellow = p.yellow, kGrey = p.grey, kCyan = p.cyan;
  kMagenta = p.magenta, kText = p.text, kOff = p.off;
}

bool rest_state(MachineState s) {
  return s == MachineState::Idle || s == MachineState::Stopped || s == MachineState::EStop;
}

// The window's fixed layout: the readout, keypad and job down the left; the preview on the
// right; the console (log and command line) along the bottom. The column's width and the
// console's height follow the window's scale (App::lay_out sets them each frame).
struct Layout {
  ImVec2 pos, size;
};
float kLeft = 370, kConsole = 250;
float kReadout = 300, kKeypad = 215;  // the left column's heights: the job window gets the rest

void place(const Layout& l) {
  ImGui::SetNextWindowPos(l.pos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(l.size, ImGuiCond_Always);
}

constexpr ImGuiWindowFlags kFixed =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;

}  // namespace

App::App(const GuiOptions& options, Machine& machine)
    : opt_(options),
      m_(machine),
      c_(machine.controller),
      table_(CommandTable::standard()),
      menus_(menus(table_)),
      gl_(std::make_unique<PreviewGL>()) {
  snapshot();
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

bool App::can_jog() const {
  return at_rest() || status_.state == MachineState::Keypad;
}

void App::stop_jog() {
  if (status_.state != MachineState::Jogging) return;
  // In a file's SK a stop would end the file: the jog is released instead.
  report(kp_file_ ? c_.jog_release() : c_.stop(), "stop");
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
    kp_continuous_ = false;
    kp_key_ = -1;
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
      const session::HelpAnswer h = session::help_answer(session::FrontEnd::Window, rest);
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
      return log(LogLine::Info, m_.memory ? m_.memory->confirm()
                                          : "nothing to confirm: no machine state is kept");
    case Word::Keypad:
      kp_focus_ = true;
      ImGui::SetWindowFocus("Keypad");
      return log(LogLine::Info, "keypad: arrows X and Y, PageUp/PageDown Z; Esc leaves");
    case Word::Step:  // the window has no single step: the line goes to the machine
    case Word::None:
      break;
  }
  const Outcome o = c_.run_typed(Script::from_text(line, kConsoleName));
  report(o, "refused");
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

void App::load(const std::string& path) {
  file_ = path;
  if (std::error_code ec; std::filesystem::is_regular_file(path, ec))
    if (std::string why; !recent_.add(path, &why))
      log(LogLine::Error, fmt::format("recent files: {}", why));
  cancel_ = true;
  if (loader_.joinable()) loader_.join();
  cancel_ = false;
  loading_ = true;
  loaded_so_far_ = 0;
  load_started_ = Clock::now();
  // On its own thread: a million segments take a while, and the command line must not wait.
  loader_ = std::thread([this, path, settings = settings_] {
    ToolpathOptions o;
    o.job.yes = true;  // a preview answers PAUSE and MSGBOX as --yes does
    o.job.input_defaults = true;  // and INPUT with its default, as `gantry preview` does
    o.cancel = &cancel_;
    o.progress = [this](const Toolpath& so_far) { loaded_so_far_ = so_far.segments.size(); };
    std::shared_ptr<const ListingText> text = ListingText::read(path);
    auto tp = std::make_shared<Toolpath>(load_toolpath(path, settings, o));
    std::lock_guard lock(loaded_m_);
    if (!cancel_) loaded_ = std::move(tp), loaded_text_ = std::move(text);
  });
}

void App::jog(const std::array<int, kAxisCount>& dir) {
  JogRequest j;
  j.direction = dir;
  j.fast = kp_fast_;
  j.step = kp_step_;
  j.step_size = jog_step();
  if (!j.step && !opt_.realtime) {
    log(LogLine::Error, "continuous jogs need --realtime on the simulated card; S: fixed steps");
    return;
  }
  const Outcome o = c_.jog(j);
  report(o, "jog");
  if (o) kp_continuous_ = !j.step;
}

// The keyboard's jogs, while the keypad has the keys.
void App::jog_keys() {
  struct K {
    int key, axis, sign;
  };
  static constexpr K keys[] = {{GLFW_KEY_LEFT, 0, -1},   {GLFW_KEY_RIGHT, 0, 1},
                               {GLFW_KEY_UP, 1, 1},      {GLFW_KEY_DOWN, 1, -1},
                               {GLFW_KEY_PAGE_UP, 2, 1}, {GLFW_KEY_PAGE_DOWN, 2, -1}};
  for (const K& k : keys) {
    std::array<int, kAxisCount> dir{};
    dir[static_cast<std::size_t>(k.axis)] = k.sign;
    if (kp_step_) {
      // A held key repeats: one step per repeat, a press while a step moves is dropped.
      if (ImGui::IsKeyPressed(k.key, true) && can_jog()) jog(dir);
    } else if (ImGui::IsKeyPressed(k.key, false) && can_jog()) {
      jog(dir);
      if (kp_continuous_) kp_key_ = k.key;
    } else if (ImGui::IsKeyReleased(k.key) && kp_key_ == k.key) {
      report(c_.jog_release(), "release");
      kp_key_ = -1;
    }
  }
  if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) kp_step_ = !kp_step_;
  if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) kp_fast_ = !kp_fast_;
  if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) stop_jog();
  if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) {
    stop_jog();
    if (status_.state == MachineState::Keypad) return report(c_.resume(), "go on");
    kp_focus_ = false;
    focus_line_ = true;
  }
}

void App::global_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) {
    m_.io.cancel();
    report(c_.estop(), "E-stop");
  }
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
      set_feed_override(session::stepped_feed_override(status_.feed_override, 1));
    if (ImGui::IsKeyPressed(GLFW_KEY_KP_SUBTRACT, false) ||
        ImGui::IsKeyPressed(GLFW_KEY_MINUS, false))
      set_feed_override(session::stepped_feed_override(status_.feed_override, -1));
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

void App::readout_window() {
  const float top = ImGui::GetFrameHeight();
  place({{0, top}, {kLeft, kReadout}});
  ImGui::Begin("Position", nullptr, kFixed);
  const ControllerStatus& st = status_;
  const bool pausing = st.state == MachineState::Paused && st.phase != FeedPhase::Held;
  // One colour a state: E-stop red, stopped yellow, paused magenta, under way cyan, idle green.
  const ImVec4 colour = st.state == MachineState::EStop     ? kRed
                        : st.state == MachineState::Stopped ? kYellow
                        : st.state == MachineState::Paused  ? kMagenta
                        : at_rest()                         ? kGreen
                                                            : kCyan;
  if (st.warning) {  // SW's warning before a run moves the tool: flashing, the whole line
    ImGui::TextColored(std::fmod(ImGui::GetTime(), 0.5) < 0.25 ? kRed : kYellow,
                       "WARNING: about to move");
  } else {
    ImGui::TextColored(colour, "%s", pausing ? "pausing" : state_name(st.state));
    ImGui::SameLine(120 * scale_);
    if (const std::optional<std::string> why = unconfirmed()) {
      // After an E-stop or a kill the position may be wrong until homed or confirmed.
      ImGui::TextColored(kYellow, "UNCONFIRMED");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s: home (C3) or, if the tool is where the readout says, Confirm",
                          why->c_str());
      ImGui::SameLine();
      if (button("Confirm", at_rest())) {
        log(LogLine::Info, m_.memory->confirm());
      }
    } else {
      ImGui::TextDisabled("card: %s", opt_.card.c_str());
    }
  }
  // SB3's readout: large digits, as large as the window allows (lay_out).
  const Vec6 p = position(st);
  ImFont* digits = digits_font();
  if (digits) ImGui::PushFont(digits);
  ImGui::SetWindowFontScale(digits ? digits_px_ / digits_font_size()
                                   : digits_px_ / ImGui::GetFontSize());
  const int axes = std::clamp(settings_.display.axes, 3, kAxisCount);
  const float number_x = ImGui::CalcTextSize("X ").x;
  for (int i = 0; i < axes; ++i) {
    ImGui::TextColored(kGrey, "%c", kAxes[i]);
    ImGui::SameLine(number_x);
    ImGui::Text("%11.4f", shown(p[i]));
  }
  ImGui::SetWindowFontScale(1.0f);
  if (digits) ImGui::PopFont();
  ImGui::Text("%s   %s   %s", units_name(settings_.units),
              modal_.absolute ? "absolute (SA)" : "relative (SR)",
              modal_.preview ? "preview mode (SP)" : "move mode");
  ImGui::TextUnformatted(
      session::speeds_text(modal_.speeds, settings_.units, status_.feed_override).c_str());
  const float led_x = 70 * scale_;
  auto leds = [led_x](const char* label, auto on) {
    ImGui::TextDisabled("%s", label);
    for (int i = 0; i < 12; ++i) {
      ImGui::SameLine(i == 0 ? led_x : 0.0f, 3);
      ImGui::TextColored(on(i) ? kGreen : kOff, "%d", i + 1);
    }
  };
  leds("inputs", [&](int i) { return st.inputs[static_cast<std::size_t>(i)]; });
  leds("outputs", [&](int i) { return ((status_.outputs >> i) & 1u) != 0; });  // as played
  ImGui::TextUnformatted(session::spindle_text(status_, modal_.spindle_rpm).c_str());
  if (!st.message.empty() && at_rest()) ImGui::TextWrapped("last stop: %s", st.message.c_str());
  ImGui::End();
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
  if (!show_macros_was_) macro_files_ = user_part_files(folder);  // listed again at each opening
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

// Why the position is unconfirmed (the machine memory's mark), or nullopt when it is not.
std::optional<std::string> App::unconfirmed() const {
  if (!m_.memory) return std::nullopt;
  const session::SavedMachine m = m_.memory->state();
  if (m.confirmed) return std::nullopt;
  return m.why.empty() ? std::string("the position is unconfirmed") : m.why;
}

// The keypad's rows of jog buttons, at the window's scale (tighter in a low window, where the
// readout's digits need the height).
float App::pad_row() const {
  return (ImGui::GetIO().DisplaySize.y < 700 * scale_ ? 28.0f : 34.0f) * scale_;
}

void App::keypad_window() {
  const float top = ImGui::GetFrameHeight() + kReadout;
  place({{0, top}, {kLeft, kKeypad}});
  ImGui::Begin("Keypad", nullptr, kFixed);
  if (ImGui::IsWindowFocused() && ImGui::IsMouseClicked(0)) kp_focus_ = true;
  ImGui::TextColored(kp_focus_ ? kGreen : kGrey, "%s",
                     kp_focus_ ? "keys jog (Esc leaves)" : "click here or type K for the keys");
  // The pad: the buttons make the same requests as the keys.
  struct B {
    const char* label;
    int axis, sign;
    float x, y;
  };
  static constexpr B pad[] = {{"Y+", 1, 1, 60, 0},  {"X-", 0, -1, 0, 1},  {"X+", 0, 1, 120, 1},
                              {"Y-", 1, -1, 60, 2}, {"Z+", 2, 1, 200, 0}, {"Z-", 2, -1, 200, 2}};
  const ImVec2 origin = ImGui::GetCursorPos();
  const float row = pad_row();
  for (const B& b : pad) {
    ImGui::SetCursorPos(ImVec2(origin.x + b.x * scale_, origin.y + b.y * row));
    std::array<int, kAxisCount> dir{};
    dir[static_cast<std::size_t>(b.axis)] = b.sign;
    const bool press = ImGui::Button(b.label, ImVec2(52 * scale_, row - 4 * scale_));
    const bool whole = note_button(b.label);
    if (kp_step_ ? (press || (whole && clicked(b.label))) && can_jog()
                 : ImGui::IsItemActivated() && can_jog()) {
      jog(dir);
      if (!kp_step_ && kp_continuous_) kp_key_ = 1000 + b.axis * 2 + (b.sign > 0);
    }
    if (!kp_step_ && ImGui::IsItemDeactivated() && kp_key_ == 1000 + b.axis * 2 + (b.sign > 0)) {
      report(c_.jog_release(), "release");
      kp_key_ = -1;
    }
  }
  ImGui::SetCursorPos(ImVec2(origin.x, origin.y + 3 * row + 4 * scale_));
  if (button(kp_step_ ? "Fixed step##mode" : "Continuous##mode")) kp_step_ = !kp_step_;
  ImGui::SameLine();
  if (button(kp_fast_ ? "Fast##speed" : "Slow##speed")) kp_fast_ = !kp_fast_;
  ImGui::SameLine();
  if (button("Stop jog", status_.state == MachineState::Jogging)) stop_jog();
  // The step: a preset, or VD's keypad step.
  ImGui::TextDisabled("step");
  const std::array<double, 4> presets = jog_presets();
  for (int i = 0; i <= static_cast<int>(presets.size()); ++i) {
    const bool vd = i == static_cast<int>(presets.size());
    ImGui::SameLine();
    const bool chosen = kp_preset_ == (vd ? -1 : i);
    if (chosen)
      ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    const std::string label =
        vd ? "VD##step" : fmt::format("{:g}##step", presets[static_cast<std::size_t>(i)]);
    if (button(label.c_str())) kp_preset_ = vd ? -1 : i;
    if (chosen) ImGui::PopStyleColor();
    if (vd && ImGui::IsItemHovered())
      ImGui::SetTooltip("VD's keypad step: %.4f %s", settings_.display.keypad_step,
                        units_name(settings_.units));
  }
  ImGui::SameLine();
  ImGui::TextDisabled("%s, %s speed", units_name(settings_.units), kp_fast_ ? "jog" : "move");
  ImGui::End();
}

// The step presets in the units in force: a thousandth to an inch, or a hundredth of a
// millimetre to ten.
std::array<double, 4> App::jog_presets() const {
  if (settings_.units == Units::Millimetres) return {0.01, 0.1, 1, 10};
  return {0.001, 0.01, 0.1, 1};
}

double App::jog_step() const {
  return kp_preset_ < 0 ? settings_.display.keypad_step
                        : jog_presets()[static_cast<std::size_t>(kp_preset_)];
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
  // The live feed override, 10 % to 200 % (+ and - while a file runs).
  int percent = static_cast<int>(std::lround(status_.feed_override * 100));
  ImGui::SetNextItemWidth(200);
  if (ImGui::SliderInt("feed %", &percent, 10, 200, "%d %%"))
    set_feed_override(session::clamped_feed_override(percent / 100.0));
  ImGui::SameLine();
  if (button("100 %")) set_feed_override(1.0);
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

void App::preview_window() {
  const float top = ImGui::GetFrameHeight();
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  place({{kLeft, top}, {size.x - kLeft, size.y - top - kConsole}});
  ImGui::Begin("Preview", nullptr, kFixed);
  const std::pair<const char*, View> views[] = {
      {"Top", View::Top}, {"Front", View::Front}, {"Side", View::Side}, {"Iso", View::Iso}};
  for (const auto& [name, v] : views) {
    if (button(name)) camera_.set_view(v), fit_ = true;
    ImGui::SameLine();
  }
  if (button(camera_.perspective ? "Perspective" : "Orthographic"))
    camera_.perspective = !camera_.perspective, fit_ = true;
  ImGui::SameLine();
  if (button("Fit")) fit_ = true;
  ImGui::SameLine();
  ImGui::Checkbox("jogs", &show_jogs_);
  ImGui::SameLine();
  if (!loading_ && !path_)
    ImGui::TextDisabled("no part file loaded");
  else if (loading_)
    ImGui::TextColored(kYellow, "loading %s: %zu segments ...", file_.c_str(),
                       loaded_so_far_.load());
  else if (path_)
    ImGui::TextDisabled("%zu segments, %zu moves%s", path_->segments.size(), path_->moves,
                        path_->violations.empty()
                            ? ""
                            : fmt::format(", {} problems (log)", path_->violations.size()).c_str());
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const int w = std::max(static_cast<int>(avail.x), 16),
            h = std::max(static_cast<int>(avail.y), 16);
  const float aspect = static_cast<float>(w) / static_cast<float>(h);
  if (fit_) {
    Eigen::AlignedBox3f box(Eigen::Vector3f::Zero(),
                            Eigen::Vector3f(static_cast<float>(settings_.preview.table_x),
                                            static_cast<float>(settings_.preview.table_y), 0));
    if (path_ && !path_->bounds.isEmpty()) box.extend(path_->bounds);
    camera_.fit(box, aspect);
    fit_ = false;
  }
  Overlay o;
  o.table = {static_cast<float>(settings_.preview.table_x),
             static_cast<float>(settings_.preview.table_y)};
  o.grid = static_cast<float>(settings_.preview.grid);
  o.show_jogs = show_jogs_;
  const Vec6 p = position(status_);
  if (settings_.preview.draw_tool)
    o.tool = Eigen::Vector3f(static_cast<float>(p[0]), static_cast<float>(p[1]),
                             static_cast<float>(p[2]));
  o.tool_size = 0.02f * std::max(o.table.x(), o.table.y());
  if (!at_rest() && status_.playing_line > 0)
    o.current_line = static_cast<std::uint32_t>(status_.playing_line);
  o.hover_line = hover_line_;
  // Drawing a million segments takes a software renderer a tenth of a second: the picture
  // is drawn again only when the view changed, and at 5 Hz for the tool while it moves.
  const ViewKey view{camera_.yaw,
                     camera_.pitch,
                     camera_.distance,
                     camera_.target.x(),
                     camera_.target.y(),
                     camera_.target.z(),
                     camera_.perspective,
                     w,
                     h,
                     path_.get(),
                     show_jogs_,
                     hover_line_,
                     o.table.x(),
                     o.table.y(),
                     o.grid};
  const LiveKey live{o.tool.value_or(Eigen::Vector3f::Zero()), o.current_line};
  const bool stale = !(view == view_) || (!(live == live_) && Clock::now() - drawn_at_ >
                                                                  std::chrono::milliseconds(200));
  if (stale || always_redraw_) {
    tex_ = gl_->render(w, h, camera_, o);
    view_ = view;
    live_ = live;
    drawn_at_ = Clock::now();
  }
  const unsigned tex = tex_;
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(tex)),
               ImVec2(static_cast<float>(w), static_cast<float>(h)), ImVec2(0, 1), ImVec2(1, 0));
  const ImGuiIO& io = ImGui::GetIO();
  std::optional<Eigen::Vector2f> pointer;
  if (scripted_hover_) {
    pointer = Eigen::Vector2f(scripted_hover_->x() * static_cast<float>(w),
                              scripted_hover_->y() * static_cast<float>(h));
  } else if (ImGui::IsItemHovered()) {
    pointer = Eigen::Vector2f(io.MousePos.x - corner.x, io.MousePos.y - corner.y);
    if (ImGui::IsMouseDragging(0)) camera_.orbit(io.MouseDelta.x, io.MouseDelta.y);
    if (ImGui::IsMouseDragging(1) || ImGui::IsMouseDragging(2))
      camera_.pan(io.MouseDelta.x, io.MouseDelta.y, static_cast<float>(h));
    if (io.MouseWheel != 0) camera_.zoom(std::pow(0.85f, io.MouseWheel));
  }
  if (pointer) {
    if (*pointer != last_mouse_) {
      hover_line_ =
          gl_->pick(static_cast<int>(pointer->x()), static_cast<int>(pointer->y()), camera_);
      last_mouse_ = *pointer;
    }
    if (hover_line_ > 0 && !ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId))
      ImGui::SetTooltip("line %u", hover_line_);
  } else {
    hover_line_ = 0;
    last_mouse_ = {-1, -1};
  }
  ImGui::End();
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

void App::values_window() {
  ImGui::SetNextWindowSize(ImVec2(460, 420), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImVec2(kLeft + 40, 60), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Values", &show_values_)) return ImGui::End();
  const char* u = units_name(settings_.units);
  ImGui::Text("units %s; keypad step %.4f; cutter %.4f; safe Z %.4f", u,
              settings_.display.keypad_step, settings_.cutter.diameter, settings_.cutter.safe_z);
  ImGui::Text("move speeds XY %.3f  Z %.3f; jog XY %.3f  Z %.3f %s/s", modal_.speeds.move.xy,
              modal_.speeds.move.z, modal_.speeds.jog.xy, modal_.speeds.jog.z, u);
  ImGui::Text("table limits X %.2f to %.2f, Y %.2f to %.2f, Z %.2f to %.2f", settings_.axes[0].min,
              settings_.axes[0].max, settings_.axes[1].min, settings_.axes[1].max,
              settings_.axes[2].min, settings_.axes[2].max);
  ImGui::Separator();
  ImGui::TextWrapped(
      "Each editor is the command's fill-in sheet: a blank keeps the value, the ranges are the "
      "command table's, and Run runs the V command, which saves the values.");
  for (const CommandSpec& s : table_.all()) {
    if (s.group != CommandGroup::Values || s.immediate || !s.coverage.empty()) continue;
    if (button(fmt::format("{}##edit", s.code).c_str())) open_sheet(s, "");
    ImGui::SameLine();
    ImGui::Text("%s", std::string(s.name).c_str());
  }
  ImGui::End();
}

void App::keys_window() {
  ImGui::SetNextWindowPos(ImVec2(kLeft + 60, 80), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Keys", &show_keys_, ImGuiWindowFlags_AlwaysAutoResize))
    ImGui::TextUnformatted(session::keys_help(session::FrontEnd::Window));
  ImGui::End();
}

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

// ---- the state, for scripts ----------------------------------------------------------------

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
