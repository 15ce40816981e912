// Runs part files: variables, control flow, nested files, and commands through the table.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>
#include <vector>

#include "gantry/commands/command_recorder.hpp"  // CommandRecorder
#include "gantry/commands/command_table.hpp"     // CommandTable, CommandCall
#include "gantry/core/text_file.hpp"             // user_config_dir
#include "gantry/interp/evaluator.hpp"           // EvalEnv
#include "gantry/interp/file_reach.hpp"          // FileAccess
#include "gantry/interp/file_system.hpp"         // FileSystem
#include "gantry/interp/machine_link.hpp"        // MachineLink, MotionReport
#include "gantry/interp/gcode_state.hpp"         // GcodeOffsets
#include "gantry/interp/operator_io.hpp"         // OperatorIO
#include "gantry/interp/persistent_store.hpp"    // PersistentStore
#include "gantry/interp/system_variables.hpp"    // MachineSnapshot
#include "gantry/lang/script.hpp"                // Script, Cursor
#include "gantry/canon/canon_move.hpp"          // CanonMove, MotionSink
#include "gantry/settings/settings.hpp"          // Settings

namespace gantry {

class DiagnosticLog;

// Where the tool was when SP started a preview: SM returns there.
struct PreviewReturn {
  Vec6 position, zero, machine_origin, applied_offset, tool_offset;
};

// The state the language defines and commands change.
struct ModalState {
  Vec6 position = Vec6::Zero();  // commanded position: working coordinates, machine units
  Vec6 zero = Vec6::Zero();      // where working 0 is in table base coordinates (Z commands)
  bool absolute = true;          // SA (true) or SR (false)
  SpeedSettings speeds;          // MS / JS / VS
  std::uint32_t outputs = 0;     // SO: bit n-1 set while output switch n is on
  double spindle_rpm = 0;        // TR: the speed asked for; the spindle (output 1) runs at it
  std::optional<std::array<double, 2>> last_xy_move;  // its X, Y displacement (for MD)
  // Where table base 0 is in the machine's own frame, the one the step counts are in: ZT,
  // UZ and VA's table base fields move table base coordinates without moving the tool.
  Vec6 machine_origin = Vec6::Zero();
  // VO: the offset the next move adds (zero while off), the one the tool is at now, and the
  // values last entered (turning VO on again uses them).
  Vec6 tool_offset = Vec6::Zero(), applied_offset = Vec6::Zero(), tool_offset_values = Vec6::Zero();
  // VB's in-file tab control, for the cut commands: on, how many tabs, where the first is.
  bool tabs_on = false;
  int tab_count = 0;
  double first_tab = 0;
  // Tabs on plain moves (VB on, FP's tab feature): how far the tool has gone along the path
  // since it last came down from Safe-Z, how far above the file's Z a tab holds it now, and
  // how many tabs of this path it has passed.
  double tab_travel = 0;
  double tab_lift = 0;
  int tabs_passed = 0;
  std::optional<PreviewReturn> preview;  // SP: moves reach no motor until SM
  // CG's centre offsets I and J: modal, as in G-code; a blank one keeps the last given.
  std::array<double, 2> cg_center_offset{0, 0};
  // SC 0 (table base system): the user system's offsets (`zero` when SC 1), set aside.
  std::optional<Vec6> user_zero;
  GcodeOffsets gcode;  // G54..G59.3, G92, G28/G30 positions, the tool table (docs/gcode.md)
  // MI: the axis moving on its own (no move of the file may move it meanwhile; its location
  // here is where it started, until it stops), and the line that started it.
  std::optional<IndependentMotion> independent;
  SourceLoc independent_loc;
};

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
  // Set: these lines run instead of a file, as if typed at the console (RP, RR, SI): not
  // scaled or offset, and the values they change stay when they end.
  std::shared_ptr<const Script> lines;
};

class Interpreter;
struct InterpreterOptions;
class GcodeExecutor;

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
  // output ([spindle]); without one it is only recorded, with one warning a run.
  void set_spindle_speed(double rpm, const SourceLoc& loc);
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
  // SW and SO 4,-1..-3: before the run's first motion, switch 4 comes on and the machine
  // waits the warning time. end_motion_warning, at the run's end, switches it off again.
  void warn_before_motion(const SourceLoc& loc);
  void end_motion_warning();
  friend class Interpreter;
  ModalState& state_;
  Settings& settings_;
  MotionSink& sink_;
  Interpreter* interp_ = nullptr;
  Transform transform_;
  std::size_t moves_ = 0;
  bool file_tabs_ = false;
  bool own_tabs_ = false;
  bool independent_resting_ = false;   // the machine came to rest under MI: restart it
  bool warned_ = false;                // this run's first motion was warned of
  bool checking_ = false;              // a check: a refused move still changes the location
  bool switch4_auto_ = false;          // ... and switch 4 came on with the warning
  bool spindle_speed_warned_ = false;  // TR with no speed output: this run was told once
};

struct InterpreterOptions {
  bool trig_in_degrees = false;  // dialect "fabmo"
  bool plus_joins_text = false;  // dialect "fabmo": "Offset: " + &z is text
  bool allow_shell = false;      // SHELL runs programs only when allowed
  bool dry_run = false;          // check: no programs started; files (unless `files`
                                 // is given) in a sandbox, so nothing is written
  FileSystem* files = nullptr;   // where files are read and written; null: the disk
  bool operator_present = true;  // check: someone will answer PAUSE/INPUT in the run
  // SW's warning before a run's first motion (the wait, and switch 4 in its automatic modes):
  // where someone may stand at the machine (a real card, the simulated one in real time).
  // Virtual time has nobody to warn, and its cycle times leave the wait out.
  bool warn_before_motion = false;
  // 0: unlimited. A check runs at most this many statements more than the file has lines;
  // past them the file loops (an error).
  std::size_t statement_budget = 0;
  // Set from another thread (a signal, the operator's stop): a check or a run stops before
  // its next statement, so even a loop that moves nothing ends.
  const std::atomic<bool>* stop_check = nullptr;
  // Where C<n> finds its files (docs/language.md, "Custom cuts"): `macro_dir` (--macros),
  // else the parts folder and then `user_macro_dir`; last `shipped_macro_dir`, Gantry's own
  // C6, C7, C9... ("" leaves a folder out).
  std::string macro_dir;
  std::string user_macro_dir = user_macro_folder();
  std::string shipped_macro_dir = shipped_macro_folder();
  // A part file's reach (docs/security.md): besides its job's folder, it reads and writes in
  // `data_dir` (Gantry's data folder) and `allowed_folders` (the profile's [files] allow and
  // --allow-path), and reads the macro folders above.
  std::string data_dir = user_config_dir();
  std::vector<std::string> allowed_folders;
  int max_file_depth = 8;  // FP nesting, the top-level file included
  // The top-level file's first line to run (0 or 1: all of it): the lines before it run
  // without motion, output or questions, then the tool approaches where they leave it
  // (docs/language.md, "Starting at a line").
  int start_line = 0;
  int max_gosub_depth = 256;
  // Where `o<name> call` finds name.ngc when the calling file does not define the subroutine:
  // the calling file's folder, then these (--subroutines), then the profile's `subroutines`;
  // a part file reads them as it reads the macro folders (docs/security.md).
  std::vector<std::string> subroutine_dirs;
  // Called when a run ends (not in a dry run) with the settings as the run leaves them:
  // file-scoped values undone, the speeds MS/JS left in force. The job saves the values.
  std::function<void(const Settings&)> save_values;
  // What UV and UD show and UR loads: the machine profile without the operator's values
  // (null: the built-in default), the file it came from ("": built in), the values file.
  const Settings* profile = nullptr;
  std::string profile_path;
  std::string values_path;
  // The profile's name, for the soft limits' message, which then also lists the shipped
  // profiles whose table holds the move ("": the message names no profile).
  std::string profile_name;
  // With nobody at the machine (--yes, a check): whether anything but a person brings input
  // switch `n` (1-12) to `closed` while the tool rests: the simulated machine's events, and in
  // a check (`check_at`: where the dry run has the tool, machine coordinates) its switches
  // there. On the live machine (nullopt) only an event still to come. Null: the machine's
  // inputs are unknown (a real card's sensors may change them): PAUSE UNTIL waits.
  std::function<bool(int n, bool closed, const std::optional<Vec6>& check_at)> unattended_inputs;
};

class Interpreter : private EvalEnv {
 public:
  // No machine: a check, a preview, a list of moves.
  Interpreter(const Settings& settings, MotionSink& sink, OperatorIO& io, PersistentStore& store,
              InterpreterOptions options = {},
              const CommandTable& table = CommandTable::standard());
  // The moves go down `sink`; `machine` (null: none) answers where the tool is, the inputs
  // and the keypad (the live machine: Controller).
  Interpreter(const Settings& settings, MotionSink& sink, MachineLink* machine, OperatorIO& io,
              PersistentStore& store, InterpreterOptions options = {},
              const CommandTable& table = CommandTable::standard());
  ~Interpreter() override;

  // Runs the script to its end (or END/ENDALL); throws GantryError at the first error,
  // located through every nested file. The motion sink is flushed either way.
  // `typed`: lines the operator typed at the console: they run as typed lines do (values they
  // change stay, output switches stay on), and each is recorded (RA...) once it ran cleanly.
  void run(std::shared_ptr<const Script> script, bool typed = false);

  // Runs without stopping at errors: each statement that fails is reported into `log` and
  // skipped, and a refused move leaves the location where the file meant it to be, so the
  // lines after it are checked from there. Includes the script's own syntax errors. Stops
  // short (log.stop_short) where the rest of the run depends on an operator answer it does
  // not have, when the budget runs out, or at options().stop_check; and when the log is full.
  void check(std::shared_ptr<const Script> script, DiagnosticLog& log);
  // The same into a log without a cap: what it kept.
  std::vector<Diagnostic> check(std::shared_ptr<const Script> script);

  // Called after each statement with (line reached in the top-level file, its line count).
  void on_progress(std::function<void(std::size_t, std::size_t)> f) { progress_ = std::move(f); }

  const ModalState& state() const { return state_; }
  const Settings& settings() const { return settings_; }
  const InterpreterOptions& options() const { return options_; }
  // The machine controller's: the state a check starts from (the live one), and where the
  // tool really is after a stop or a jog (machine frame, units: the step counts over
  // steps per unit); working and table base locations follow, the zero stays.
  void restore_state(const ModalState& s) { state_ = s; }
  void restore_variables(const std::unordered_map<std::string, Value>& v) { vars_ = v; }
  const std::unordered_map<std::string, Value>& variables() const { return vars_; }
  void set_last_stop(SourceLoc at) { last_stop_ = std::move(at); }
  void set_machine_position(const Vec6& machine);
  std::size_t statements_executed() const { return executed_; }
  std::size_t moves_emitted() const { return ctx_.moves(); }
  const Value* variable(std::string_view upper_name) const { return user_variable(upper_name); }
  MachineSnapshot snapshot() const;

  // For console front ends: call record_typed() with each line the operator typed, once it
  // has run without an error (a line that failed is not worth playing again), including
  // the Record commands themselves (they are left out here). Lines run from part files and
  // lines played back are never passed. Returns whether the line was kept: recording is on
  // (RA, the default; RI pauses it) and the line can be played again (see CommandRecorder).
  // RP and RR play the record as typed lines; RS saves it as a part file. Not thread-safe:
  // call it from the thread that runs the interpreter, between lines.
  bool record_typed(std::string_view line) { return recorder_.record(line); }
  // The record, for a console that shows it (its lines) or shows whether recording is on.
  const CommandRecorder& recorder() const { return recorder_; }
  CommandRecorder& recorder() { return recorder_; }  // a check starts from the live record

 private:
  friend class CommandContext;
  struct Frame;
  struct UserFile;
  class GatedSink;
  class GatedIO;
  struct StartLine;

  // EvalEnv
  const Value* user_variable(std::string_view name) const override;
  const nlohmann::json* persistent_variable(std::string_view name) const override;
  Value system_variable(int n, const SourceLoc& loc) override;
  bool trig_in_degrees() const override { return options_.trig_in_degrees; }
  bool plus_joins_text() const override { return options_.plus_joins_text; }

  void push_file(std::shared_ptr<const Script> script, const FileCall& call, SourceLoc from,
                 bool refuse_broken = true);
  void end_file();
  // FP's tab feature for the frames running now (CommandContext::file_tabs).
  void update_file_tabs();
  // Start at a line: the lines before it run quietly (begin_start), then, when it is reached,
  // the machine catches up and the tool approaches (reach_start); a line never reached is an
  // error (start_missed).
  void begin_start(const Script& script, const FileCall& call, const SourceLoc& from);
  void reach_start(const SourceLoc& at);
  void end_quiet();
  [[noreturn]] void start_missed();
  void restore_file_values(Frame& f);
  void plunge_for_pass(Frame& f);
  void loop(DiagnosticLog* collect);
  void execute(const Statement& st);
  // One overload per statement kind: control flow and commands in interpreter.cpp, operator
  // and file statements in io_statements.cpp.
  void exec(const CommandStmt& s, const SourceLoc& loc);
  void extra_params(const CommandSpec& spec, const CommandStmt& cmd, size_t count,
                    const SourceLoc& loc);
  void exec(const CustomCutStmt& s, const SourceLoc& loc);
  void call_macro(int number, const SourceLoc& loc);
  void exec(const LabelStmt&, const SourceLoc&) {}
  void exec(const AssignStmt& s, const SourceLoc& loc);
  void exec(const JumpStmt& s, const SourceLoc& loc);
  void exec(const ReturnStmt& s, const SourceLoc& loc);
  void exec(const EndStmt& s, const SourceLoc& loc);
  void exec(const IfStmt& s, const SourceLoc& loc);
  void exec(const OnInputStmt& s, const SourceLoc& loc);
  void exec(const PauseStmt& s, const SourceLoc& loc);
  void exec(const PrintStmt& s, const SourceLoc& loc);
  void exec(const InputStmt& s, const SourceLoc& loc);
  void exec(const MsgBoxStmt& s, const SourceLoc& loc);
  void exec(const DialogStmt& s, const SourceLoc& loc);
  void exec(const FailStmt& s, const SourceLoc& loc);
  void exec(const OpenStmt& s, const SourceLoc& loc);
  void exec(const CloseStmt& s, const SourceLoc& loc);
  void exec(const ShellStmt& s, const SourceLoc& loc);
  void exec(const WarningOffStmt& s, const SourceLoc& loc);
  void exec(const PlayStmt& s, const SourceLoc& loc);
  void exec(const RegistryStmt& s, const SourceLoc& loc);
  void exec(const GcodeStmt& s, const SourceLoc& loc);
  // O-words, M98/M99 and WinCNC's M98 file (gcode_control_flow.cpp).
  struct GcodeFlow;
  void gcode_flow(const GcodeBlock& b, const SourceLoc& loc);
  void gcode_call(const GcodeBlock& b, const SourceLoc& loc);
  void gcode_return(const GcodeBlock& b, const SourceLoc& loc);
  void gcode_m98_m99(const GcodeBlock& b, const SourceLoc& loc);
  void gcode_call_file(const GcodeBlock& b, const SourceLoc& loc);
  void gcode_drop_stale_calls();
  std::string gcode_sub_file(const std::string& name, const SourceLoc& loc) const;
  // `restore_g92`: WinCNC's M98 file, whose end restores the caller's G92 (unless L92).
  void push_gcode_frame(std::shared_ptr<const Script> script, Cursor pc, const SourceLoc& from,
                        bool restore_g92);
  UserFile& user_file(const Expr& number, const SourceLoc& loc, bool must_be_open);
  std::string pause_message(const SourceLoc& loc) const;
  Value value_of(const Arg& a);
  void assign(const LValue& target, const Value& v);
  // `$nameUU[].x = v`: FabMo's universal units, stored in inches at [0] and mm at [1].
  void assign_universal_units(nlohmann::json& root, const LValue& target, const Value& v);
  std::string file_path(const std::string& name, const SourceLoc& loc) const;
  // The job writes `path`: a part file it calls from now on is what it wrote.
  void forget_called(const std::string& path) const;
  // file_path's file as it is on the disk (case-insensitive where the exact name is missing).
  std::string existing_file(const std::string& name, const SourceLoc& loc) const;
  // existing_file's, refused at `loc` when it cannot be read (FileSystem::read_problem).
  std::string readable_file(const std::string& name, const SourceLoc& loc) const;
  std::vector<std::string> macro_folders() const;  // where C<n> looks, in order
  // The folder part files reach files from: the outermost running part file's; with only
  // typed lines running, the working directory ("").
  std::string job_folder() const;
  // Refuses (at `loc`) a path a part file may not reach for `access` (file_reach.hpp).
  void check_reach(const std::string& path, FileAccess access, const SourceLoc& loc) const;
  // file_path's path for writing: refused at `loc` when out of reach or when it cannot be
  // written (FileSystem::write_problem), in a check as in a run.
  std::string writable_path(const std::string& name, const SourceLoc& loc) const;
  Diagnostic located(Diagnostic d) const;
  [[noreturn]] void rethrow_located(const GantryError& e) const;
  void unwind_all();

  Settings settings_;  // the profile as the V commands change it
  // The motion stream and the operator, closed while the lines before a start line run.
  std::unique_ptr<GatedSink> gated_sink_;
  std::unique_ptr<GatedIO> gated_io_;
  const CommandTable& table_;
  MotionSink& sink_;     // *gated_sink_
  SourceLoc last_stop_;  // see CommandContext::last_stop
  OperatorIO& io_;       // *gated_io_
  PersistentStore& store_;
  InterpreterOptions options_;
  ModalState state_;
  CommandContext ctx_;
  std::vector<Frame> frames_;
  std::unordered_map<std::string, Value> vars_;
  std::set<std::string> failed_vars_;          // check: assignments that failed
  std::set<std::string> extra_params_warned_;  // "file\ncode": warned of ignored parameters
  std::unique_ptr<FileSystem> own_files_;      // when options_.files is null
  FileSystem* files_system_ = nullptr;
  // ON INPUT handlers by (switch, 1 closing or 0 opening): one-shot, for the run.
  struct InputHandler {
    std::shared_ptr<const Statement> action;
    bool instant = true;    // states 0 and 1 stop at once; 2 and 3 ramp down
    std::size_t depth = 0;  // the file that armed it (a GOTO action continues there)
  };
  std::map<std::pair<int, int>, InputHandler> on_input_;
  void arm_inputs();                               // the machine watches the handlers' edges
  void outputs_on_at_start(const Script& script);  // VN output modes 3-5
  void service_inputs(std::size_t moves_before);   // after a statement: did an edge cut it?
  std::vector<std::unique_ptr<UserFile>> files_;
  std::optional<FileCall> pending_call_;
  SourceLoc pending_call_loc_;
  std::string parts_dir_;
  // FS's file mask, and the last file loaded (FE's blank opens it).
  std::string parts_mask_ = "*.sb?";
  std::string last_file_;
  CommandRecorder recorder_;  // the lines typed at the console (RA ... RZ)
  Cursor current_;            // the line being executed
  Statement simple_;          // the last simple command line, its storage reused line after line
  std::vector<std::optional<Value>> values_storage_;  // a command's values, reused likewise
  bool warning_off_ = false;
  bool stop_all_ = false;
  std::size_t executed_ = 0;
  std::size_t budget_lines_ = 0;  // the checked file's lines, on top of the statement budget
  std::function<void(std::size_t, std::size_t)> progress_;
  std::unique_ptr<StartLine> start_;       // a start line not reached yet
  std::unique_ptr<GcodeExecutor> gcode_;   // G-code's modes and parameters
  std::unique_ptr<GcodeFlow> gcode_flow_;  // G-code's open calls and repeat counts
};

}  // namespace gantry
