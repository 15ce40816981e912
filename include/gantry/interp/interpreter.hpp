// Runs part files: variables, control flow, nested files, and commands through the table.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>
#include <vector>

#include "gantry/canon/canon_move.hpp"              // CanonMove, MotionSink
#include "gantry/commands/command_recorder.hpp"     // CommandRecorder
#include "gantry/commands/command_table.hpp"        // CommandTable, CommandCall
#include "gantry/interp/command_context.hpp"        // CommandContext, FileCall, Transform
#include "gantry/interp/evaluator.hpp"              // EvalEnv
#include "gantry/interp/file_reach.hpp"             // FileAccess
#include "gantry/interp/file_system.hpp"            // FileSystem
#include "gantry/interp/interpreter_options.hpp"    // InterpreterOptions
#include "gantry/interp/machine_link.hpp"           // MachineLink, MotionReport
#include "gantry/interp/modal_state.hpp"            // ModalState
#include "gantry/interp/operator_io.hpp"            // OperatorIO
#include "gantry/interp/persistent_store.hpp"       // PersistentStore
#include "gantry/interp/system_variables.hpp"       // MachineSnapshot
#include "gantry/lang/script.hpp"                   // Script, Cursor
#include "gantry/settings/settings.hpp"             // Settings

namespace gantry {

class DiagnosticLog;
class GcodeExecutor;
class FmExecutor;

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
  // The statement running is a Friendly Motion file's (its hot keys are polled there).
  bool in_friendly_motion() const;
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
  void tool_change(const SourceLoc& loc);  // C9: &Tool is in the spindle (tool_into_spindle)
  void exec(const LabelStmt&, const SourceLoc&) {}
  void exec(const AssignStmt& s, const SourceLoc& loc);
  void exec(const JumpStmt& s, const SourceLoc& loc);
  void exec(const ReturnStmt& s, const SourceLoc& loc);
  void exec(const EndStmt& s, const SourceLoc& loc);
  void exec(const IfStmt& s, const SourceLoc& loc);
  void exec(const OnInputStmt& s, const SourceLoc& loc);
  void exec(const PauseStmt& s, const SourceLoc& loc);
  void wait_for_input(int in, bool state, const SourceLoc& loc, std::string_view what);
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
  // A Friendly Motion line (fm_flow.cpp): its commands left to right, the flow (N, J, K, M0,
  // M2, M6, input waits) here, the rest through FmExecutor.
  struct FmFlow;
  void exec(const FmStmt& s, const SourceLoc& loc);
  bool fm_input_active(int code, const SourceLoc& loc);
  void fm_wait_input(int code, const SourceLoc& loc);
  void fm_go_to(int sequence, const SourceLoc& loc);
  // Alt-F`key`: N(10000 + key) as a subroutine before the line at `loc`, which runs after it
  // in STEP mode; false (warned) when the program has no such subroutine.
  bool fm_hot_call(int key, const SourceLoc& loc);
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
  const CommandSpec* last_spec_ = nullptr;            // the last command executed (exec)
  bool warning_off_ = false;
  bool stop_all_ = false;
  std::size_t executed_ = 0;
  std::size_t budget_lines_ = 0;  // the checked file's lines, on top of the statement budget
  std::function<void(std::size_t, std::size_t)> progress_;
  std::unique_ptr<StartLine> start_;       // a start line not reached yet
  std::unique_ptr<GcodeExecutor> gcode_;   // G-code's modes and parameters
  std::unique_ptr<GcodeFlow> gcode_flow_;  // G-code's open calls and repeat counts
  std::unique_ptr<FmExecutor> fm_;         // Friendly Motion's state and commands
  std::unique_ptr<FmFlow> fm_flow_;        // its open subroutine calls, its run mode
};

}  // namespace gantry
