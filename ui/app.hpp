// The console window's windows: menus, command line, fill-in sheets, position readout,
// keypad, preview, run controls, dialogs, message log and values. One frame at a time, on the
// window's thread; the controller does the work.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "camera.hpp"
#include "command_line.hpp"
#include "file_dialog.hpp"
#include "fill_sheet.hpp"
#include "gantry/session/activity_watch.hpp"  // ActivityWatch
#include "gantry/session/fm_hot_keys.hpp"     // FmKeys
#include "gantry/session/key_bindings.hpp"    // KeyPendant
#include "gantry/session/live_position.hpp"   // LivePosition
#include "gantry/session/recent_files.hpp"    // RecentFiles
#include "gui.hpp"
#include "jog_press.hpp"  // JogPress
#include "preview_gl.hpp"
#include "program_listing.hpp"

namespace gantry::ui {

class App {
 public:
  App(const GuiOptions& options, Machine& machine);
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  // Builds one frame's windows (between ImGui::NewFrame and ImGui::Render).
  void frame();
  bool quit_requested() const { return quit_; }

  // ---- for scripted runs and the benchmark ----
  void click(const std::string& name) { pending_click_ = name; }
  // The click asked for was not made in the last frame (no button of that name was drawn).
  std::optional<std::string> missed_click();
  void hover(float fx, float fy) { scripted_hover_ = Eigen::Vector2f(fx, fy); }
  bool idle() const;  // at rest, no dialog, no load under way
  bool dialog_showing() const { return dialog_shown_ != 0; }
  // A field is about to take the keys (the command line or a sheet's field asked for them):
  // what is typed waits for it (InputQueue).
  bool keys_moving() const;
  bool preview_loaded() const { return path_ != nullptr && !loading_; }
  std::size_t preview_segments() const { return path_ ? path_->segments.size() : 0; }
  nlohmann::json state() const;
  void load(const std::string& path);
  Camera& camera() { return camera_; }
  // Frames are the benchmark's: the preview redraws every frame even when nothing changed.
  void set_always_redraw(bool on) { always_redraw_ = on; }
  // The layout's and fonts' scale (window_scale), set by the main loop when the fonts change.
  void set_scale(float scale) { scale_ = scale; }
  bool light_theme() const { return light_; }  // View > Light theme

 private:
  struct LogLine {
    enum Kind { Info, Typed, Error, Print } kind;
    std::string text;
  };

  // Each window.
  void lay_out();  // the windows' places and the readout's digit size for this frame
  void menu_bar();
  void readout_window();
  void keypad_window();
  void job_window();
  void preview_window();
  void console_window();
  void values_window();
  void offsets_window();
  void macros_window();
  void place_panel(int row, float height);  // the panels over the preview's top right
  void sheet_popup();
  void question_popup();
  void group_popup();
  void keys_window();

  // Actions.
  bool button(const char* label, bool enabled = true);
  bool clicked(const char* name);  // the script's click for a widget drawn another way
  // Records the last button drawn (its place, for the state); true when it is wholly on the
  // screen, so that a script can click it.
  bool note_button(const std::string& name);
  float pad_row() const;
  std::optional<std::string> unconfirmed() const;  // why the position is suspect
  void run_line(const std::string& line);
  void open_sheet(const CommandSpec& spec, const std::string& typed);
  void choose(const CommandSpec& spec);  // a menu item: run it, or ask for its parameters
  void start_file(int from_line);
  void report(const Outcome& o, const std::string& what);
  bool jog(const std::array<int, kAxisCount>& dir, bool step);  // false: refused (logged)
  bool taps_step() const;  // continuous mode's tap-or-hold rule applies (jog_press.hpp)
  void jog_pressed(const std::array<int, kAxisCount>& dir, int id);
  void jog_released(int id);
  void jog_held();
  void jog_keys();
  void global_keys();
  bool pendant_keys();  // the [pendant] keys (pendant_keys.cpp): true when one acted this frame
  void bind_keys();     // ... made GLFW's keys, once
  void fm_key(int n);   // Alt-F`n`: Friendly Motion's hot key or the teach log's
  void log(LogLine::Kind kind, std::string text);
  void snapshot();  // at rest: the exact position, the frame and the units
  void poll();      // once a frame: output, questions, the end of an activity, a finished load
  Vec6 position(const ControllerStatus& st) const;
  bool at_rest() const;
  void set_feed_override(double factor);  // the controller's, shown and logged
  bool can_jog() const;  // at rest, or a file waits at SK
  std::array<double, 4> jog_presets() const;  // the step presets in the units in force
  double jog_step() const;                     // a step's length: the preset, or VD's
  void stop_jog();

  const GuiOptions& opt_;
  Machine& m_;
  Controller& c_;
  const CommandTable& table_;
  std::vector<Menu> menus_;
  Settings settings_;  // in force at the last snapshot
  ControllerStatus status_;
  ModalState modal_;
  session::LivePosition tool_;  // the frame and exact position at the last snapshot
  session::ActivityWatch activity_;  // a run, line or jog ended since the last frame
  // The [pendant] keys: each bound key's GLFW key and modifiers, and their events.
  struct BoundKey {
    std::string name;
    int key = 0, mods = 0;
  };
  std::vector<BoundKey> bound_keys_;
  std::optional<session::KeyPendant> key_pendant_;
  session::FmKeys fm_keys_;  // TEACH's log and the Alt-F keys, as the terminal console has

  // Command line.
  std::string line_;
  History history_;
  bool focus_line_ = true;
  int cursor_ = 0;

  // Fill-in sheet.
  std::optional<FillSheet> sheet_;
  std::vector<std::string> sheet_errors_;
  bool sheet_open_ = false;
  bool sheet_fresh_ = false;  // opened this frame
  int sheet_focus_ = -1;

  // Questions: the id of the one whose dialog is showing (0: none).
  std::uint64_t dialog_shown_ = 0;
  std::string answer_;

  // Menus opened from the keyboard (Alt + the group's letter).
  int group_popup_ = -1;        // asked for this frame
  int group_menu_ = 0;          // the one showing
  bool group_showing_ = false;  // the Alt+letter menu is open

  // Keypad.
  bool single_step_ = false;  // the controller holds after each statement
  bool kp_step_ = true, kp_fast_ = false;
  bool kp_focus_ = false;       // the keyboard jogs (the keypad window has the focus)
  JogPress kp_press_;           // continuous mode: the key or button held (its jog)
  std::array<int, kAxisCount> kp_dir_{};  // its direction
  bool kp_file_ = false;        // a file waits at SK: the keypad is its
  int kp_preset_ = -1;          // the step preset chosen (-1: VD's keypad step)

  // Layout: the scale, the readout's digit height, the buttons drawn in the last frame
  // (x0, y0, x1, y1, wholly on the screen).
  float scale_ = 1, digits_px_ = 24;
  std::map<std::string, std::array<float, 5>> buttons_;

  // Job.
  std::string file_;
  int start_line_ = 1;
  ProgramListing listing_;
  bool job_running_ = false;      // a file we started has not ended yet
  std::size_t listing_line_ = 0;  // highlighted at rest: where the last run ended or stopped
  std::shared_ptr<const std::string> listing_file_;  // ... in this file (null: the loaded one)
  FileDialog file_dialog_;
  session::RecentFiles recent_{opt_.recent_files};

  // Preview.
  std::unique_ptr<PreviewGL> gl_;
  std::shared_ptr<const Toolpath> path_;
  std::thread loader_;
  std::atomic<bool> cancel_{false}, loading_{false};
  std::atomic<std::size_t> loaded_so_far_{0};
  std::mutex loaded_m_;
  std::shared_ptr<const Toolpath> loaded_;  // handed over by the loader
  std::shared_ptr<const ListingText> loaded_text_;  // and the file's lines, for the listing
  Camera camera_;
  bool fit_ = true;
  std::uint32_t hover_line_ = 0;
  Eigen::Vector2f last_mouse_{-1, -1};
  std::optional<Eigen::Vector2f> scripted_hover_;
  bool always_redraw_ = false;
  // What the last picture of the preview showed.
  struct ViewKey {
    float yaw, pitch, distance, tx, ty, tz;
    bool perspective;
    int w, h;
    const Toolpath* path;
    bool jogs;
    std::uint32_t hover;
    float table_x, table_y, grid;
    bool operator==(const ViewKey&) const = default;
  } view_{};
  struct LiveKey {
    Eigen::Vector3f tool;
    std::uint32_t current_line;
    bool operator==(const LiveKey&) const = default;
  } live_{Eigen::Vector3f::Zero(), 0};
  unsigned tex_ = 0;
  std::chrono::steady_clock::time_point drawn_at_;
  bool show_jogs_ = true;
  std::chrono::steady_clock::time_point load_started_;
  double load_seconds_ = 0;

  // Log.
  std::vector<LogLine> log_;
  bool scroll_log_ = false;
  int log_last_rows_ = 0;  // text rows the last entry was drawn on (wrapped: more than 1)

  bool show_values_ = false, show_keys_ = false;
  bool show_offsets_ = false;
  bool light_ = false;  // the light theme (the main loop applies it between frames)
  bool show_macros_ = false, show_macros_was_ = false;
  std::vector<std::string> macro_files_;  // the operator's part files, listed when opened
  std::array<float, 3> panel_top_{};  // where each panel over the preview starts (below the last)
  bool quit_ = false;
  std::string pending_click_;
};

}  // namespace gantry::ui
