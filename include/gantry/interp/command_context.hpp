// What a command handler may touch: the modal state, the profile, the move stream, the files.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gantry/canon/canon_move.hpp"      // CanonMove, MotionSink
#include "gantry/core/vec6.hpp"             // Vec6
#include "gantry/core/diagnostic.hpp"       // SourceLoc
#include "gantry/interp/machine_link.hpp"   // MachineLink::Watching, MotionReport
#include "gantry/interp/modal_state.hpp"    // ModalState
#include "gantry/interp/value.hpp"          // Value
#include "gantry/settings/settings.hpp"     // Settings, Units

namespace gantry {

class CommandRecorder;      // gantry/commands/command_recorder.hpp
class Interpreter;          // gantry/interp/interpreter.hpp
class Script;               // gantry/lang/script.hpp
struct InterpreterOptions;  // gantry/interp/interpreter_options.hpp
class FileSystem;           // gantry/interp/file_system.hpp
enum class FileAccess;      // gantry/interp/file_reach.hpp

// How long a value command's change lasts: for good, or (VS, VU, VI, VL, SF in a part
// file) until that file ends, unless SV makes it permanent.
enum class ValueScope { Permanent, File };

// How a nested file's coordinates map to the machine's: machine = origin + scale * file.
struct Transform {
  Vec6 origin = Vec6::Zero();
  Vec6 scale = Vec6::Ones();
  Vec6 to_machine(const Vec6& file) const { return origin + scale.cwiseProduct(file); }
  Vec6 to_file(const Vec6& machine) const { return (machine - origin).cwiseQuotient(scale); }
};

// FP's parameters, for running a file as a subroutine.
struct FileCall {
  std::string path;
  Vec6 proportion = Vec6::Ones();
  int repetitions = 1;
  int offset = 0;  // 0 none, 1 3D (X, Y, Z from here), 2 2D (X, Y from here)
  double plunge = 0;
  bool tabs = false;       // tabs (VB's sizes) on the cutting moves of the last repetition
  bool from_zero = false;  // Z goes to 0 first; the plunges are measured from there
  // FG, --from-line: the first line to run (0 or 1: all); the lines before it run without
  // motion, then the tool approaches where they leave it (docs/language.md, start line).
  int start_line = 0;
  SourceLoc start_loc;    // where the start line was given, for its errors
  bool resolved = false;  // `path` is final (C<n> found it), not relative to the parts folder
  bool homing = false;    // C3's macro: it may move axes homing.require holds (it homes them)
  // Set: these lines run instead of a file, as if typed at the console (RP, RR, SI): not
  // scaled or offset, and the values they change stay when they end.
  std::shared_ptr<const Script> lines;
};

// What a command handler may touch: the modal state, the profile, and the move stream.
class CommandContext {
 public:
  CommandContext(ModalState& state, Settings& settings, MotionSink& sink)
      : state_(state), settings_(settings), sink_(sink) {}

  ModalState& state() { return state_; }
  const Settings& settings() const { return settings_; }
  // The settings, to change (the V commands). With ValueScope::File, inside a part file,
  // what they were is kept so the file's end restores it (unless SV).
  Settings& change_values(ValueScope scope);
  // Values the planner or the step generator use changed (VR, VU, VI): the machine comes to
  // rest, then the new values travel down the motion stream.
  void values_reach_motion(const SourceLoc& loc);
  // SV: every value changed so far, in every running file, is kept when the files end.
  void make_values_permanent();
  // VD, SU: every value, the location and the speeds change to `to`; the tool stays put.
  // ValueScope::File (SU in a part file): the file's end changes them back.
  void change_units(Units to, ValueScope scope, const SourceLoc& loc);
  // CN, C<n>: runs macro file number n (C<n>.sbp or macro_<n>.sbp) once this command returns.
  void call_macro(int number, const SourceLoc& loc);
  // G-code's G20/G21 (nullopt: a new file, VD's units again): the units the file's numbers
  // are in, for a preview to draw them in (DrawingState::file_units).
  void set_file_units(std::optional<Units> u) { file_units_ = u; }
  // SM (and the end of a run): back from SP's preview to where the tool is.
  void end_preview();
  // SL: every &variable is deleted.
  void clear_variables();
  // Whether a part file is running (false: a command typed at the console, or lines played
  // as typed: RP, RR, SI).
  bool in_file() const;
  // Sets the table base location of the current position for `axes` (bits 0 X .. 5 C)
  // without moving: working locations keep their values.
  void set_table_base(unsigned axes, const Vec6& location);

  // The current position in the running file's coordinates (FP may scale and offset them),
  // where the file has the tool: below the tab (VB) it may be on.
  Vec6 position() const {
    Vec6 p = state_.position;
    p[2] -= state_.tab_lift;
    return transform_.to_file(p);
  }
  // A straight move to `target` (file coordinates). A target outside the soft limits is an
  // error at `loc`, and nothing is emitted; in a check the location still becomes `target`
  // (the check goes on as though the move had been made: no cascade of errors after it).
  void line_to(const Vec6& target, SpeedClass cls, const SourceLoc& loc);
  // An arc in `plane` about (cx, cy) (along the plane's first and second axes) through
  // `sweep` radians (positive counter-clockwise) to `target`, the other axes moving in
  // proportion (file coordinates). Its extreme points are checked against the soft limits
  // too (refused as line_to refuses). When FP scales the plane's axes differently the arc is
  // no longer circular, and tabs follow only XY arcs: such an arc is sent as lines within the
  // chord tolerance.
  void arc_to(const Vec6& target, double cx, double cy, double sweep, SpeedClass cls,
              const SourceLoc& loc, ArcPlane plane = ArcPlane::XY);
  // How the running file's coordinates map to working ones (FP's proportions and offsets).
  const Transform& transform() const { return transform_; }
  // A located error, as line_to gives, if the tool cannot pass through `point` (file
  // coordinates): outside the soft limits, or not a number. Nothing moves.
  void check_reach(const Vec6& point, const SourceLoc& loc) const;
  // A probe (P*, homing): a straight move towards `target` (file coordinates) at `speed`
  // that stops where input switch `input` closes. True: it closed, and the tool is exactly
  // where it closed (it comes to rest a little past it, then goes back). False: the move
  // reached the target; always so without a live machine (a check, a preview). An input
  // closed already is an error, as is an unwired one. Soft limits are checked for probes,
  // not for homing (the table base is what homing finds). `closing` false: the probe stops
  // where the switch opens instead (G38.4, G38.5), and one open already is the error.
  bool probe(const Vec6& target, double speed, int input, const SourceLoc& loc,
             MachineLink::Watching why = MachineLink::Watching::Probe, bool closing = true);
  // Homing: the tool's table base location on `axis` becomes `table_base`; working 0 keeps
  // its place on the table.
  void home_axis(int axis, double table_base);
  // Squaring a slaved axis at homing: the driver channels (bit k: channel k + 1) whose
  // motors rest through the moves that follow while their axis moves on its other channel;
  // 0: every channel steps again. Set and cleared at rest (HomingChannels does both).
  void rest_channels(unsigned channels) { resting_channels_ = channels; }
  // Homing's moves: straight, at `speed`, without the soft-limit check (the table base is
  // not known yet).
  void homing_line(const Vec6& target, double speed, const SourceLoc& loc);
  // The input switches 1-12 once the moves so far have played (closed: true); nullopt
  // without a live machine.
  std::optional<std::array<bool, 12>> input_switches();
  // SK: the moves so far play out, then the operator jogs with the keypad until they close
  // it (or, with no keypad here, confirms to go on); the location is where the tool is then.
  void keypad(std::string_view message, const SourceLoc& loc);
  // A timed wait in the motion stream.
  void dwell(double seconds, const SourceLoc& loc);
  // MI: at rest, `m`'s axis starts moving on its own (one axis at a time). It comes to rest
  // whenever the machine does to wait (a probe, SK, an input read, new values) and starts
  // again with the next move; the file's end, or end_independent, stops it for good.
  void start_independent(const IndependentMotion& m, const SourceLoc& loc);
  // It comes to rest; its axis's location is then where the pulses left it.
  void end_independent(const SourceLoc& loc);
  // The moves sent play out; the live machine reports where the tool is (nullopt: none).
  std::optional<MotionReport> sync();
  // The machine ramps down to rest here before the next move (MS, JS).
  void come_to_rest(const SourceLoc& loc);
  // Output switch n (1-based) on or off, at rest between the moves around it (SO).
  void set_output(int n, bool on, const SourceLoc& loc);
  // TR: the spindle speed, at rest between the moves around it, to the profile's speed
  // output ([spindle]); without one it is only recorded, with one warning a run (`quiet`:
  // G-code's S, recorded without a warning). A change while the spindle runs waits for the
  // at-speed input where the profile has one.
  void set_spindle_speed(double rpm, const SourceLoc& loc, bool quiet = false);
  // The spindle (docs/hardware.md, "Spindle"): M3 (+1, clockwise), M4 (-1), M5 (0), on output
  // switch 1 and spindle.reverse_output as spindle.reverse_wiring says; a reversal stops the
  // spindle first. M4 without a reverse output is an error at `loc`. A start waits the
  // profile's spin_up_s and for its at-speed input, a stop its spin_down_s (set_output does
  // the same when SO or C6/C7 switch the spindle's outputs).
  void spindle(int direction, const SourceLoc& loc);
  // 0 stopped, +1 clockwise, -1 counter-clockwise, from the output switches' levels.
  int spindle_direction() const;
  // Whether output switch n starts or stops the spindle (1, or spindle.reverse_output).
  bool spindle_output(int n) const;
  // Makes the current location of `axes` (bits 0 X .. 5 C) working 0; the table base
  // location stays where it is.
  void zero_axes(unsigned axes);
  // FP: runs a file as a subroutine once this command returns.
  void call_file(const FileCall& call, const SourceLoc& loc);
  // RP, RR, SI: runs `lines` `repetitions` times once this command returns, as if the
  // operator typed them (in_file() is false while they run). A syntax error in any of them
  // is an error before the first runs.
  void run_typed(std::shared_ptr<const Script> lines, int repetitions, const SourceLoc& loc);
  // The console's command record (RA, RI, RZ change it; RP, RR, RS read it).
  CommandRecorder& recorder();
  // Records who set a speed group (0 xy .. 4 c): values set by VS are undone when the file
  // that set them ends; MS and JS values stay.
  void speed_set(SpeedClass cls, int group, bool by_values);
  // Text for the operator (help sheets, listings), as PRINT shows it.
  void print(std::string_view text);
  // A warning located at `loc` (a value accepted but without effect on this machine).
  void warn(const SourceLoc& loc, std::string message);
  // A file a command writes (TD, TU, TH): a relative name is found beside the top-level
  // file, as FP finds it; a check or a preview writes into its sandbox, never the disk. A
  // file that is running, out of the part file's reach (docs/security.md) or that cannot be
  // written (no folder, a folder, too long) is refused. On disk every write is atomic: a
  // crash leaves the old file or the new one. Returns the path.
  std::string write_file(const std::string& name, std::string_view text, const SourceLoc& loc);
  // Whether write_file writes to the disk now (false: a check, a preview, FG's quiet lines).
  bool writes_to_disk() const;
  // The files the interpreter reads and writes now (a check's or a start line's sandbox, or
  // the disk): Friendly Motion's data files open through it.
  FileSystem& file_system();
  // The text of a file found as write_file finds it (a check sees its own writes); nullopt
  // when it cannot be read. `path` receives where it looked.
  std::optional<std::string> read_file(const std::string& name, const SourceLoc& loc,
                                       std::string* path = nullptr);

  std::size_t moves() const { return moves_; }

  // Whether FP's tab feature is on here: in the last repetition of a file run with it, or in
  // a file that one calls.
  bool file_tabs() const { return file_tabs_; }
  // While one lives, the moves sent carry their own tabs (a cut command's path): tabs on
  // plain moves leave them alone, and the tabbed path starts again after them.
  class OwnTabs {
   public:
    explicit OwnTabs(CommandContext& c) : c_(c) { c_.own_tabs_ = true; }
    ~OwnTabs() {
      c_.own_tabs_ = false;
      c_.end_tab_path();
    }
    OwnTabs(const OwnTabs&) = delete;
    OwnTabs& operator=(const OwnTabs&) = delete;

   private:
    CommandContext& c_;
  };

  // ---- for the utility and file commands (UL, VV, FS, FE, UV, UD, UR) ----
  // Every &variable (names upper case, without the &), sorted by name.
  std::vector<std::pair<std::string, Value>> variables() const;
  void set_variable(const std::string& upper_name, Value v);
  // Where a relative file name is found (FS changes it); "" is the working directory.
  const std::string& parts_folder() const;
  const std::string& parts_mask() const;
  // FS: the new parts folder (already resolved) and file mask.
  void set_parts_folder(std::string folder, std::string mask);
  // The folder of the top-level file: FS with a blank folder returns to it.
  std::string top_folder() const;
  // The path a relative `name` stands for (the parts folder's), as write_file finds it.
  std::string file_path(const std::string& name, const SourceLoc& loc) const;
  // file_path's path, refused at `loc` when a part file may not reach it (docs/security.md).
  std::string reachable_path(const std::string& name, const SourceLoc& loc,
                             FileAccess access) const;
  // Whether a part file is running, typed lines aside (SI and RP from a part file count):
  // what only the operator may do (UN) is refused then.
  bool part_file_running() const;
  // The last part file loaded (the run's own, FP's) or opened with FE; "" none.
  const std::string& last_file() const;
  void set_last_file(std::string path);
  const InterpreterOptions& options() const;
  // Where the last run stopped short (a stop, an E-stop, a fault; the controller tells), for
  // FG to resume there once: FG clears it, and so does a part file run to its end.
  SourceLoc& last_stop();

 private:
  // A motion-stream item at the current location, in table base coordinates.
  CanonMove here(MoveKind kind, const SourceLoc& loc) const;
  // check_reach for a point in working coordinates.
  void check_working(const Vec6& target, const SourceLoc& loc) const;
  // A line or an arc to `target` (working coordinates, checked), as it is: no tabs.
  void send_line(const Vec6& target, SpeedClass cls, const SourceLoc& loc);
  void send_arc(const Vec6& target, double cx, double cy, double sweep, SpeedClass cls,
                const SourceLoc& loc, ArcPlane plane = ArcPlane::XY);
  // Tabs on plain moves: sends the move with the tabs that fall on it and returns true, or
  // returns false when it is not tabbed (the caller sends it). `arc`: centre X, Y and sweep
  // (working coordinates), null for a line.
  bool tab_move(const Vec6& target, const std::array<double, 3>* arc, SpeedClass cls,
                const SourceLoc& loc);
  void end_tab_path();
  // arc_to's work (arc_to adds what a check assumes of a refused arc).
  void make_arc(const Vec6& target, double cx, double cy, double sweep, SpeedClass cls,
                const SourceLoc& loc, ArcPlane plane);
  // A check goes on past a refused move to `file_target` as though it had been made.
  void assume_reached(const Vec6& file_target);
  // Every line, arc and dwell goes to the sink through here: a move of the axis MI moves is
  // refused, and an axis MI rested starts again first; the run's first motion is warned of.
  void emit(CanonMove& m);
  // Tells the sink the drawing state when it changed since last told (DrawingState).
  void note_drawing(const SourceLoc& loc);
  // SW and SO 4,-1..-3: before the run's first motion, switch 4 comes on and the machine
  // waits the warning time. end_motion_warning, at the run's end, switches it off again.
  void warn_before_motion(const SourceLoc& loc);
  void end_motion_warning();
  // After the spindle's outputs changed from direction `was`: the spin-up wait and the
  // at-speed input, or the spin-down wait (spindle_control.cpp).
  void spindle_settle(int was, const SourceLoc& loc);
  void wait_at_speed(const SourceLoc& loc);
  friend class Interpreter;
  ModalState& state_;
  Settings& settings_;
  MotionSink& sink_;
  Interpreter* interp_ = nullptr;
  Transform transform_;
  CanonMove line_;  // send_line's move (see there)
  std::size_t moves_ = 0;
  bool file_tabs_ = false;
  bool own_tabs_ = false;
  bool independent_resting_ = false;   // the machine came to rest under MI: restart it
  unsigned resting_channels_ = 0;      // rest_channels()
  bool warned_ = false;                // this run's first motion was warned of
  bool checking_ = false;              // a check: a refused move still changes the location
  bool switch4_auto_ = false;          // ... and switch 4 came on with the warning
  double speed_sent_ = 0;              // the RPM the speed output carries now
  bool spindle_speed_warned_ = false;  // TR with no speed output: this run was told once
  bool spindle_settles_ = true;        // false while a run's end switches everything off
  bool soft_clamp_warned_ = false;     // limits.soft_clamp "all" clamped a move: told once
  // limits.soft_clamp: the axes of `target` (machine coordinates) that move beyond their
  // soft limits, clamped to them where the profile says so (WinCNC's softlim B1, V1).
  void clamp_to_soft_limits(Vec6& target, const SourceLoc& loc);
  std::optional<DrawingState> drawn_;  // the drawing state the sink was last told
  std::optional<Units> file_units_;    // a G-code file's G20/G21 (none: VD's units)
};

}  // namespace gantry
