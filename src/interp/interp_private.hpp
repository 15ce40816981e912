// Interpreter internals shared by its two source files.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "gantry/interp/interpreter.hpp"
#include "gantry/interp/machine_link.hpp"  // MachineLink, MotionReport

namespace gantry {

// One running file: where it is, its GOSUB returns, how its coordinates map to the machine.
struct Interpreter::Frame {
  std::shared_ptr<const Script> script;
  Cursor pc;                   // the next line to execute
  std::vector<Cursor> gosubs;  // return points
  SourceLoc called_from;       // the FP or C# line in the caller (no file for the top level)
  Transform transform;
  FileCall call;
  int repetition = 0;
  double plunge_start_z = 0;        // machine Z when FP was called, for the plunge of each pass
  SpeedSettings saved_speeds;       // at the file's start
  std::array<bool, 10> vs_owned{};  // speeds (move xy..c, jog xy..c) VS set last here
  std::optional<Settings> saved_values;  // before this file's first file-scoped change
  std::optional<Units> saved_units;      // before this file's SU
};

// The motion stream, and the machine's answers (machine_link.hpp), while the lines before a
// start line run: closed, it passes nothing but the end of the stream and the inputs' state;
// it notes that the values changed and which inputs to watch, for open() to send.
// Without a machine (`machine` null: a check, a preview, a list of moves) sync flushes the
// moves and reports nothing, and so does the keypad; no input is watched or read.
class Interpreter::GatedSink : public MotionSink {
 public:
  GatedSink(MotionSink& out, MachineLink* machine) : out_(out), machine_(machine) {}
  void move(const CanonMove& m) override {
    touched.reset();
    if (!closed) out_.move(m);
  }
  void flush() override { out_.flush(); }
  // Without a machine (a check) a probe is taken to reach its target and to touch there: its
  // input reads as the probe asked (closed, or open for G38.4) until the next move, so a file
  // follows the path of a probe that found its switch.
  std::optional<std::pair<int, bool>> touched;
  void drawing_changed(const DrawingState& d) override { out_.drawing_changed(d); }
  void settings_changed(const Settings& s) override {
    if (closed)
      changed = true;
    else
      out_.settings_changed(s);
  }
  // Closed, the machine is not asked: a probe is taken to reach its target, no input fires.
  std::optional<MotionReport> sync() {
    if (closed) return std::nullopt;
    if (!machine_) {
      out_.flush();
      return std::nullopt;
    }
    return machine_->sync();
  }
  void watch_inputs(std::span<const InputTrigger> t, MachineLink::Watching w) {
    if (!closed) {
      if (machine_) machine_->watch_inputs(t, w);
      return;
    }
    watched_.emplace(std::vector<InputTrigger>(t.begin(), t.end()), w);
  }
  std::optional<std::array<bool, 12>> input_switches() const {
    if (!machine_) return std::nullopt;
    return machine_->input_switches();
  }
  std::uint32_t axes_to_home() const { return machine_ ? machine_->axes_to_home() : 0; }
  void homed(int axis) {
    if (machine_) machine_->homed(axis);
  }
  std::optional<MotionReport> keypad(const SourceLoc& loc) {
    if (closed) return std::nullopt;
    if (!machine_) return sync();
    return machine_->keypad(loc);
  }
  // Opens the stream; the inputs the lines before last asked to watch are watched from here.
  void open() {
    closed = false;
    if (watched_ && machine_) machine_->watch_inputs(watched_->first, watched_->second);
    watched_.reset();
  }
  bool closed = false;
  bool changed = false;

 private:
  MotionSink& out_;
  MachineLink* machine_;  // null: no machine
  std::optional<std::pair<std::vector<InputTrigger>, MachineLink::Watching>> watched_;
};

// The operator while the lines before a start line run: closed, nothing is shown and nobody
// is asked to continue (PAUSE and DIALOG go on, MSGBOX takes its default button); INPUT still
// asks, since the lines after it need the answer. Warnings pass.
// Every question first calls `before_asking` (the moves before it play out: the machine
// waits for the answer at rest, where the file has it, not somewhere before).
class Interpreter::GatedIO : public OperatorIO {
 public:
  explicit GatedIO(OperatorIO& out) : out_(out) {}
  std::function<void()> before_asking;
  void print(std::string_view text) override {
    if (!closed) out_.print(text);
  }
  bool confirm(std::string_view message, const SourceLoc& loc) override {
    if (closed) return true;
    before_asking();
    return out_.confirm(message, loc);
  }
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override {
    before_asking();
    return out_.ask(prompt, variable, default_value, loc);
  }
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     size_t default_button, std::string_view title, const SourceLoc& loc) override {
    if (closed) return buttons.at(default_button);
    before_asking();
    return out_.choose(text, buttons, default_button, title, loc);
  }
  void warn(const Diagnostic& d) override { out_.warn(d); }
  KeypadAnswer keypad(std::string_view message, const SourceLoc& loc) override {
    return closed ? KeypadAnswer::GoOn : out_.keypad(message, loc);
  }
  bool closed = false;

 private:
  OperatorIO& out_;
};

// A start line (FG, --from-line) not reached yet.
struct Interpreter::StartLine {
  size_t depth = 0;  // the frame of the file it is in
  int line = 0;      // the first line that runs (a statement's)
  SourceLoc at;      // where it was given
  // Where the tool really is while the lines before run (the machine frame), and which
  // output switches are really on.
  Vec6 machine = Vec6::Zero();
  std::uint32_t outputs = 0;
  std::size_t moves = 0;  // moves sent before it
  // Put back when the quiet part ends.
  bool dry_run = false;
  FileSystem* files = nullptr;
  std::unique_ptr<SandboxFileSystem> sandbox;  // the quiet part's writes
};

// G-code's open subroutine calls (o-call, M98) and repeat loops, for every running file.
struct Interpreter::GcodeFlow {
  struct Call {
    size_t frame = 0;        // index in frames_ of the frame the subroutine runs in
    Cursor back;             // the line after the call, in the caller's frame
    bool own_frame = false;  // the subroutine's file was pushed for it: returning pops it
    bool fanuc = false;      // M98: ends at M99, shares #1-#30
    long loops_left = 0;     // M98 L: runs still to come
    Cursor body;             // M98: the subprogram's first line, for L
    size_t repeats_base = 0;
  };
  struct Repeat {
    const Script* script;
    size_t offset;  // the repeat line's
    long left;      // passes still to run after the current one
  };
  std::vector<Call> calls;
  std::vector<Repeat> repeats;
  // The branch line a false if or elseif jumped to: it is tested (elseif) or entered (else)
  // rather than ending the branch before it.
  const Script* branch_script = nullptr;
  size_t branch_offset = 0;
  // A loop or a subroutine runs: its lines come round again, so they are parsed once into
  // the script's parse cache rather than on every pass (the interpreter's loop reads it).
  bool hot = false;
};

// Friendly Motion's open K calls (10 deep), the line and command a return or a STEP resumes
// at, and the run mode (AUTO, or STEP after M0).
struct Interpreter::FmFlow {
  struct Call {
    Cursor line;      // the calling line
    size_t next = 0;  // the command after the K on it
    Cursor target;    // the subroutine's first line (for R)
    long left = 0;    // calls still to come (R)
    bool hot = false;  // an Alt-F key's: M6 goes back to the start of `line`, in STEP mode
  };
  std::vector<Call> calls;
  size_t resume_offset = SIZE_MAX;  // the line to resume at (its offset), and its command
  size_t resume_index = 0;
  bool step = false;  // STEP mode: the operator starts each line
};

// A file opened with OPEN ... AS #n.
struct Interpreter::UserFile {
  int number = 0;
  OpenStmt::Mode mode = OpenStmt::Mode::Input;
  std::string path;
  std::shared_ptr<std::istream> in;
  std::shared_ptr<std::ostream> out;
};

}  // namespace gantry
