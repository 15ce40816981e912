// The interpreter's core: files and frames, the statement loop, control flow, variables and
// command dispatch. Operator and file statements are in io_statements.cpp.
#include "gantry/interp/interpreter.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>   // all_of, count_if
#include <cmath>       // round, floor
#include <filesystem>  // path joining for FP and C#
#include <utility>     // exchange

#include "gantry/core/diagnostic_log.hpp"    // DiagnosticLog
#include "gantry/core/file_problem.hpp"      // shown_path
#include "gantry/interp/fm_executor.hpp"     // Friendly Motion commands
#include "gantry/interp/gcode_executor.hpp"  // G-code blocks
#include "gantry/interp/tool_table.hpp"      // tool_into_spindle
#include "gantry/interp/tool_changer.hpp"    // C9 on a rack
#include "gantry/lang/scan.hpp"              // looks_like_expression
#include "interp_private.hpp"                // Frame, UserFile
#include "persistent_path.hpp"               // describe_path

namespace gantry {

namespace {

double& speed_field(SpeedSettings& s, int i) {  // 0-4 move xy..c, 5-9 jog xy..c
  GroupSpeeds& g = i < 5 ? s.move : s.jog;
  double* fields[] = {&g.xy, &g.z, &g.a, &g.b, &g.c};
  return *fields[i % 5];
}

}  // namespace

// Undoes what the file's VS, VU, VI, VL and SF changed (SV keeps them). Steps per unit and
// driver channels reach the motion stream again; limits and the checking flag need not.
void Interpreter::restore_file_values(Frame& f) {
  for (int i = 0; i < 10; ++i)
    if (f.vs_owned[i]) speed_field(state_.speeds, i) = speed_field(f.saved_speeds, i);
  f.vs_owned.fill(false);
  if (f.saved_values) {
    const Settings& was = *f.saved_values;
    bool motion = settings_.drivers.channel_axis != was.drivers.channel_axis;
    for (int i = 0; i < kAxisCount; ++i) {
      AxisSettings& ax = settings_.axes[i];
      motion |= ax.steps_per_unit != was.axes[i].steps_per_unit;
      ax.steps_per_unit = was.axes[i].steps_per_unit;
      ax.min = was.axes[i].min;
      ax.max = was.axes[i].max;
    }
    settings_.calibration = was.calibration;
    settings_.drivers = was.drivers;
    settings_.machine.limit_checking = was.machine.limit_checking;
    f.saved_values.reset();
    if (motion) ctx_.values_reach_motion(SourceLoc{});
  }
  if (f.saved_units)  // SU: back to the units the file started in
    ctx_.change_units(*std::exchange(f.saved_units, std::nullopt), ValueScope::Permanent,
                      SourceLoc{});
}

// ---- construction, files and frames ---------------------------------------------------

Interpreter::Interpreter(const Settings& settings, MotionSink& sink, OperatorIO& io,
                         PersistentStore& store, InterpreterOptions options,
                         const CommandTable& table)
    : Interpreter(settings, sink, nullptr, io, store, std::move(options), table) {}

Interpreter::Interpreter(const Settings& settings, MotionSink& sink, MachineLink* machine,
                         OperatorIO& io, PersistentStore& store, InterpreterOptions options,
                         const CommandTable& table)
    : settings_(settings),
      gated_sink_(std::make_unique<GatedSink>(sink, machine)),
      gated_io_(std::make_unique<GatedIO>(io)),
      table_(table),
      sink_(*gated_sink_),
      io_(*gated_io_),
      store_(store),
      options_(std::move(options)),
      ctx_(state_, settings_, sink_),
      gcode_flow_(std::make_unique<GcodeFlow>()),
      fm_flow_(std::make_unique<FmFlow>()) {
  ctx_.interp_ = this;
  gated_io_->before_asking = [this] { ctx_.sync(); };
  // The profile's subroutine folders after --subroutines', for every front end alike.
  options_.subroutine_dirs.insert(options_.subroutine_dirs.end(), settings.subroutine_paths.begin(),
                                  settings.subroutine_paths.end());
  state_.speeds = settings.speeds;
  state_.spindle_rpm = settings.spindle.initial_rpm;
  gcode_ = std::make_unique<GcodeExecutor>(ctx_, io_, [this] {  // M2, M30: the file ends
    // In a subroutine's own file, its callers' file ends too: it is one program.
    size_t from = frames_.size() - 1;
    for (const GcodeFlow::Call& c : gcode_flow_->calls)
      if (c.own_frame && c.frame > 0 && c.frame < frames_.size())
        from = std::min(from, c.frame - 1);
    for (size_t i = from; i < frames_.size(); ++i)
      frames_[i].pc = Cursor{std::string::npos, frames_[i].pc.line};
  });
  fm_ = std::make_unique<FmExecutor>(ctx_, io_);
  if (options_.files) {
    files_system_ = options_.files;
  } else {
    own_files_ = options_.dry_run ? std::unique_ptr<FileSystem>(new SandboxFileSystem())
                                  : std::unique_ptr<FileSystem>(new DiskFileSystem());
    files_system_ = own_files_.get();
  }
}

Interpreter::~Interpreter() = default;

void Interpreter::set_machine_position(const Vec6& machine) {
  state_.position = machine - state_.machine_origin - state_.zero - state_.applied_offset;
}

void Interpreter::forget_called(const std::string& path) const {
  if (!frames_.empty()) frames_.front().script->forget_called(path);
}

std::string Interpreter::file_path(const std::string& name, const SourceLoc& loc) const {
  std::string n = name;
  std::replace(n.begin(), n.end(), '\\', '/');  // part files written on Windows
  if (n.size() >= 2 && std::isalpha(static_cast<unsigned char>(n[0])) && n[1] == ':')
    fail(loc, fmt::format("{} names a Windows drive; give a path on this machine, relative to "
                          "the part file's folder or absolute",
                          name));
  std::filesystem::path p(n);
  if (p.is_relative() && !parts_dir_.empty()) p = std::filesystem::path(parts_dir_) / p;
  return p.string();
}

// Every file name a part file gives goes through file_path and then one of these two, in a
// check as in a run: the reach and the file's state are refused here, located.
std::string Interpreter::existing_file(const std::string& name, const SourceLoc& loc) const {
  const std::string wanted = file_path(name, loc);
  check_reach(wanted, FileAccess::Read, loc);  // before looking: outside, nothing is probed
  const PartFileLookup found = find_part_file(*files_system_, wanted);
  if (!found.error.empty()) fail(loc, found.error);
  check_reach(found.path, FileAccess::Read, loc);  // a name in another case may be a link
  return found.path;
}

std::string Interpreter::readable_file(const std::string& name, const SourceLoc& loc) const {
  const std::string path = existing_file(name, loc);
  if (const std::string why = files_system_->read_problem(path); !why.empty())
    fail(loc, fmt::format("cannot read {}: {}", shown_path(path), why));
  return path;
}

std::string Interpreter::writable_path(const std::string& name, const SourceLoc& loc) const {
  const std::string path = file_path(name, loc);
  check_reach(path, FileAccess::Write, loc);
  if (const std::string why = files_system_->write_problem(path); !why.empty())
    fail(loc, fmt::format("cannot write {}: {}", shown_path(path), why));
  return path;
}

std::string Interpreter::job_folder() const {
  for (const Frame& f : frames_)
    if (!f.call.lines && f.script->name())
      return std::filesystem::path(*f.script->name()).parent_path().string();
  return "";
}

void Interpreter::check_reach(const std::string& path, FileAccess access,
                              const SourceLoc& loc) const {
  FileReach reach;
  reach.read_write = options_.allowed_folders;
  reach.read_write.push_back(options_.data_dir);
  reach.read_only = {options_.macro_dir, options_.user_macro_dir, options_.shipped_macro_dir};
  reach.read_only.insert(reach.read_only.end(), options_.subroutine_dirs.begin(),
                         options_.subroutine_dirs.end());
  if (const std::string why = reach_refusal(path, access, job_folder(), reach); !why.empty())
    fail(loc, why);
}

void Interpreter::push_file(std::shared_ptr<const Script> script, const FileCall& call,
                            SourceLoc from, bool refuse_broken) {
  if (static_cast<int>(frames_.size()) >= options_.max_file_depth)
    fail(from, fmt::format("files are nested {} deep, the most allowed; a file may be calling "
                           "itself",
                           options_.max_file_depth));
  if (refuse_broken && !script->ok()) {  // a missing or broken file, named with its callers
    for (Diagnostic d : script->errors())
      if (d.severity == Severity::Error) {
        d = located(std::move(d));
        if (from.file) d.via.push_back(from);
        throw GantryError(std::move(d));
      }
  }
  if (!call.resolved && script->name()) last_file_ = *script->name();  // FE's blank opens it
  // FG: from here to its start line nothing reaches the machine (the plunges below included).
  if (call.start_line > 1 && !start_) begin_start(*script, call, from);
  if (call.from_zero) {  // FP 9: first Z to the caller's 0, at move speed; plunges count from 0
    Vec6 target = ctx_.position();
    target[2] = 0;
    ctx_.line_to(target, SpeedClass::Move, from);
  }
  if (frames_.empty()) {  // a new run or check: no G-code call is open
    gcode_flow_ = std::make_unique<GcodeFlow>();
    gcode_->reset_calls();
  }
  if (script->gcode()) gcode_->begin_file(call.lines != nullptr);
  if (script->fm()) {
    fm_->begin_file();
    *fm_flow_ = FmFlow{};
    fm_flow_->step = options_.fm_step;  // --step: the operator starts each line
  }
  Frame f;
  f.script = std::move(script);
  f.pc = f.script->start();
  f.called_from = std::move(from);
  f.call = call;
  f.saved_speeds = state_.speeds;
  const Transform parent = frames_.empty() ? Transform{} : frames_.back().transform;
  f.transform.scale = parent.scale.cwiseProduct(call.proportion);
  f.transform.origin = parent.origin;
  // An offset run places the file's 0 at the current position: X, Y (2D) or X, Y, Z (3D).
  for (int i = 0; i < (call.offset == 1 ? 3 : call.offset == 2 ? 2 : 0); ++i)
    f.transform.origin[i] = state_.position[i];
  if (call.lines) f.transform = Transform{};  // typed lines: the console's coordinates
  f.plunge_start_z = state_.position[2];
  frames_.push_back(std::move(f));
  update_file_tabs();
  plunge_for_pass(frames_.back());
}

void Interpreter::update_file_tabs() {
  bool on = false;  // a sub-file of a file in its tabbed repetition is tabbed too
  for (const Frame& f : frames_) on = on || (f.call.tabs && f.repetition == f.call.repetitions - 1);
  ctx_.file_tabs_ = on;
}

// FP's plunge: pass k (from 1) runs k * plunge lower. The file's Z is shifted, and the tool
// moves down first, so that a template with no Z moves of its own cuts deeper each pass.
void Interpreter::plunge_for_pass(Frame& f) {
  if (f.call.plunge == 0) return;
  f.transform.origin[2] += f.call.plunge * f.transform.scale[2];
  Vec6 target = state_.position;
  target[2] = f.plunge_start_z + (f.repetition + 1) * f.call.plunge * f.transform.scale[2];
  ctx_.transform_ = Transform{};
  ctx_.line_to(target, SpeedClass::Move, pending_call_loc_);
}

// Ends the current pass of the innermost file: another repetition, or back to the caller.
void Interpreter::end_file() {
  Frame& f = frames_.back();
  if (f.script->gcode()) gcode_->end_file({f.script->name(), current_.line, 0});
  if (f.script->fm()) fm_->end_file({f.script->name(), current_.line, 0});
  restore_file_values(f);
  if (++f.repetition < f.call.repetitions) {
    f.pc = f.script->start();
    f.gosubs.clear();
    update_file_tabs();
    plunge_for_pass(f);
    return;
  }
  if (start_ && start_->depth + 1 == frames_.size()) start_missed();
  if (f.script->gcode()) gcode_->leave_file();  // WinCNC restores the file's G92 (unless L92)
  const SourceLoc called_from = f.called_from;
  frames_.pop_back();
  update_file_tabs();
  // What the called file changed in the drawing (C9's macro sets VC for the tool) is told at
  // the line that called it, not at the caller's next move.
  if (!frames_.empty()) ctx_.note_drawing(called_from);
}

// Names the calling lines of the running files, outermost first, unless already named.
Diagnostic Interpreter::located(Diagnostic d) const {
  if (d.via.empty())
    for (const Frame& f : frames_)
      if (f.called_from.file) d.via.push_back(f.called_from);
  return d;
}

[[noreturn]] void Interpreter::rethrow_located(const GantryError& e) const {
  Diagnostic d = located(e.diagnostic());
  if (dynamic_cast<const OperatorStop*>(&e)) throw OperatorStop(std::move(d));
  throw GantryError(std::move(d));
}

// Ends every running file at once (ENDALL, the end of a run), innermost first.
void Interpreter::unwind_all() {
  while (!frames_.empty()) {
    restore_file_values(frames_.back());
    frames_.pop_back();
  }
  update_file_tabs();
}

// ---- starting at a line ----------------------------------------------------------------

namespace {

// The top-level file's call: no transform, maybe a start line.
FileCall top_call(const Script& script, int start_line) {
  FileCall call;
  call.start_line = start_line;
  call.start_loc = SourceLoc{script.name(), start_line, 0};
  return call;
}

// The first line at or after `line` that holds a statement other than a label (a line with
// a syntax error counts: the check reports it); 0 when there is none.
int statement_line_from(const Script& script, int line) {
  Cursor c = script.start(), next;
  Statement scratch;
  while (!script.at_end(c)) {
    const std::string_view text = script.line_at(c, &next);
    if (c.line >= line) {
      if (parse_simple_command(text, script.name(), c.line, &scratch)) return c.line;
      const std::shared_ptr<const LineParse> lp = script.parse(c, &next);
      if (lp->error || (lp->statement && !std::holds_alternative<LabelStmt>(lp->statement->body)))
        return c.line;
    }
    c = next;
  }
  return 0;
}

}  // namespace

// The lines before the start line run as a full run would run them (variables, modes,
// values, the location), but nothing reaches the machine, the operator or a file.
void Interpreter::begin_start(const Script& script, const FileCall& call, const SourceLoc& from) {
  const SourceLoc at = call.start_loc.file ? call.start_loc : from;
  const int line = statement_line_from(script, call.start_line);
  if (line == 0)
    fail(at, fmt::format("start line {} is past the end of {}: it has {} lines and no statement "
                         "from line {} on; nothing was moved",
                         call.start_line, script.name() ? *script.name() : "the file",
                         script.line_count(), call.start_line));
  auto s = std::make_unique<StartLine>();
  s->depth = frames_.size();
  s->line = line;
  s->at = at;
  s->machine = state_.machine_origin + state_.zero + state_.position + state_.applied_offset;
  s->outputs = state_.outputs;
  s->moves = ctx_.moves_;
  s->dry_run = options_.dry_run;
  s->files = files_system_;
  s->sandbox = std::make_unique<SandboxFileSystem>(files_system_);
  files_system_ = s->sandbox.get();
  options_.dry_run = true;  // SHELL and FE start nothing
  gated_sink_->closed = true;
  gated_sink_->changed = false;
  gated_io_->closed = true;
  start_ = std::move(s);
}

void Interpreter::end_quiet() {
  if (!start_ || !gated_sink_->closed) return;
  gated_sink_->open();
  gated_io_->closed = false;
  options_.dry_run = start_->dry_run;
  files_system_ = start_->files;
  ctx_.moves_ = start_->moves;  // the moves the machine was sent
}

// The start line is reached: the machine catches up with what the lines before changed (the
// values the planner uses, the output switches), then the tool moves from where it really is
// to where they left it: up to Safe-Z (or higher, when it or the target is above it) at jog
// speed, across at jog speed, and down at move speed.
void Interpreter::reach_start(const SourceLoc& at) {
  if (state_.preview)
    fail(at, fmt::format("line {} is inside a preview (SP before it, and no SM yet): nothing "
                         "reached the machine there, so there is no place to resume from; start "
                         "before the SP or after the SM; nothing was moved",
                         start_->line));
  end_quiet();
  const StartLine s = std::move(*start_);
  start_.reset();
  // The approach, checked before anything is sent.
  const Vec6 target = state_.position;
  const auto last_move = state_.last_xy_move;  // MD turns from the file's last move
  const Vec6 from = s.machine - state_.machine_origin - state_.zero - state_.applied_offset;
  const CutterSettings& c = settings_.cutter;
  auto higher = [&](double a, double b) {
    return c.plunge_negative ? std::max(a, b) : std::min(a, b);
  };
  const double lift = higher(higher(c.safe_z, from[2]), target[2]);
  Vec6 up = from, across = target;
  up[2] = across[2] = lift;
  const std::uint32_t outputs = state_.outputs;
  state_.position = from;  // where the tool and the switches really are
  state_.outputs = s.outputs;
  for (const Vec6& p : {up, across, target}) ctx_.check_working(p, at);
  if (gated_sink_->changed) ctx_.values_reach_motion(at);
  for (int n = 1; n <= 32; ++n) {
    const std::uint32_t bit = 1u << (n - 1);
    if ((outputs ^ s.outputs) & bit) ctx_.set_output(n, (outputs & bit) != 0, at);
  }
  if (from != target) {                       // (a tool already there stays)
    ctx_.send_line(up, SpeedClass::Jog, at);  // no tabs: the tabbed path goes on after
    ctx_.send_line(across, SpeedClass::Jog, at);
    ctx_.send_line(target, SpeedClass::Move, at);
  }
  state_.last_xy_move = last_move;
}

// VN output modes 3, 4 and 5: the switch comes on as a part file starts (one the profile does
// not wire is left off, with a warning: SO would refuse it).
void Interpreter::outputs_on_at_start(const Script& script) {
  const SourceLoc at{script.name(), 1, 0};
  for (int n = 1; n <= 12; ++n) {
    if (settings_.switches.output_modes[n - 1] < 3 || (state_.outputs >> (n - 1) & 1u)) continue;
    const std::vector<int>& wired = settings_.outputs.aux_bits;
    if (n > static_cast<int>(wired.size()) || wired[n - 1] < 0) {
      ctx_.warn(at, fmt::format("output switch {} should come on as the file starts (VN output "
                                "mode {}), but this profile does not wire it (outputs.aux_bits)",
                                n, settings_.switches.output_modes[n - 1]));
      continue;
    }
    ctx_.set_output(n, true, at);
  }
}

void Interpreter::start_missed() {
  const StartLine& s = *start_;
  const std::string file = frames_.size() > s.depth && frames_[s.depth].script->name()
                               ? *frames_[s.depth].script->name()
                               : (s.at.file ? *s.at.file : std::string("the file"));
  fail(s.at, fmt::format("line {} of {} is never reached when the file runs (it is after its "
                         "END, in a subroutine no GOSUB calls, or jumped over); nothing was "
                         "moved",
                         s.line, file));
}

// ---- the statement loop ---------------------------------------------------------------

void Interpreter::run(std::shared_ptr<const Script> script, bool typed) {
  parts_dir_ = std::filesystem::path(*script->name()).parent_path().string();
  auto clear_run_flag = [&] {  // SetUsrValClrd lives for one top-level run
    if (store_.registry_value("uValueClrd")) store_.registry().erase("uValueClrd");
  };
  clear_run_flag();
  frames_.clear();
  extra_params_warned_.clear();
  // Ends the run whatever happened: files closed, VS speeds of every open file undone
  // (innermost first), the moves already issued completed, the store saved.
  auto finish = [&] {
    unwind_all();
    files_.clear();
    if (!on_input_.empty()) {
      on_input_.clear();
      gated_sink_->watch_inputs({}, MachineLink::Watching::Handlers);
    }
    pending_call_.reset();
    ctx_.end_preview();  // first: a preview switches no output
    // Output switches go off when the job ends, however it ends, unless their VN mode keeps
    // them on; VO lasts until the part file is exited. Typed lines are no part file.
    if (!typed) {
      ctx_.spindle_settles_ = false;   // no spin-down wait after the end: nothing follows
      for (int n = 1; n <= 12; ++n) {  // VN output modes 1 and 4 stay on (docs/values.md)
        const int mode = settings_.switches.output_modes[n - 1];
        if (n == 4 && ctx_.switch4_auto_) continue;  // off once the motion has ended, below
        if ((state_.outputs >> (n - 1) & 1u) && mode != 1 && mode != 4)
          ctx_.set_output(n, false, SourceLoc{});
      }
      ctx_.spindle_settles_ = true;
      state_.tool_offset = Vec6::Zero();
      // The speed output goes to 0 with the spindle; TR's RPM stays, as a VFD keeps it.
      if (ctx_.speed_sent_ != 0 && settings_.spindle.speed_output() && !state_.preview) {
        CanonMove m = ctx_.here(MoveKind::SpindleSpeed, SourceLoc{});
        sink_.move(m);
        ctx_.speed_sent_ = 0;
      }
      ctx_.spindle_speed_warned_ = false;
      ctx_.soft_clamp_warned_ = false;
    }
    end_quiet();  // a start line never reached: the machine was never told otherwise
    start_.reset();
    try {  // MI stops with the run: its axis is where the pulses leave it
      ctx_.end_independent(SourceLoc{});
    } catch (const GantryError&) {  // stopped: the controller takes the pulses played
      state_.independent.reset();
    }
    ctx_.end_motion_warning();
    sink_.flush();
    settings_.speeds = state_.speeds;  // MS and JS changes stay; VS ones were undone above
    if (!options_.dry_run && options_.save_values) options_.save_values(settings_);
    clear_run_flag();
    store_.save();
  };
  try {
    FileCall call = top_call(*script, options_.start_line);
    if (typed) call.lines = script;
    push_file(script, call, SourceLoc{});
    if (!typed) outputs_on_at_start(*script);
    loop(nullptr);
    if (start_) start_missed();  // ENDALL before it
  } catch (...) {
    try {
      finish();
    } catch (const GantryError&) {  // stopped: what ended the run is the error to report
    }
    throw;
  }
  finish();
  if (typed)
    for (Cursor c = script->start(), next; !script->at_end(c); c = next)
      recorder_.record(script->line_at(c, &next));
}

namespace {

// A check stopped from another thread (InterpreterOptions::stop_check).
struct CheckInterrupted {
  SourceLoc at;
};

// A check that ran its statement budget out (InterpreterOptions::statement_budget).
struct BudgetSpent {
  SourceLoc at;
};

}  // namespace

std::vector<Diagnostic> Interpreter::check(std::shared_ptr<const Script> script) {
  DiagnosticLog log;
  check(std::move(script), log);
  return std::move(log.kept());
}

void Interpreter::check(std::shared_ptr<const Script> script, DiagnosticLog& log) {
  for (const Diagnostic& d : script->errors()) log.add(d);
  // As a run would: SetUsrValClrd starts empty (the store is a check's own copy).
  if (store_.registry_value("uValueClrd")) store_.registry().erase("uValueClrd");
  parts_dir_ = std::filesystem::path(*script->name()).parent_path().string();
  extra_params_warned_.clear();
  budget_lines_ = static_cast<std::size_t>(script->line_count());  // a long file is no loop
  ctx_.checking_ = true;
  try {
    frames_.clear();
    // A check goes through a file with syntax errors too (they are reported already).
    push_file(script, top_call(*script, options_.start_line), SourceLoc{},
              /*refuse_broken=*/false);
    outputs_on_at_start(*script);
    loop(&log);
    if (start_ && !log.full()) start_missed();  // ENDALL before it
  } catch (const NeedsOperator& e) {
    // The rest depends on an answer. With an operator at the run that is fine (a warning);
    // without one the run would stop here, part-way through the job: an error now.
    Diagnostic d = located(e.diagnostic());
    const bool fine = d.severity == Severity::Warning || options_.operator_present;
    d.message = (fine ? "checking stopped here: " : "the run would stop here: ") + d.message;
    d.severity = fine ? Severity::Warning : Severity::Error;
    log.stop_short(std::move(d));
  } catch (const BudgetSpent& e) {
    // Not "stopped short" with a warning: a run would loop here for ever, or at least far
    // longer than any part file's lines explain.
    log.stop_short(located(
        {e.at, Severity::Error,
         fmt::format("the check ran {} statements and the file had not ended: it loops here "
                     "without end (a GOTO back with no way out?). Nothing ran; if the file is "
                     "meant to run that long, give a larger --budget",
                     options_.statement_budget + budget_lines_)}));
  } catch (const CheckInterrupted& e) {
    log.stop_short(located({e.at, Severity::Error,
                            "the check was stopped here (a signal); the lines from here on were "
                            "not checked, and nothing ran"}));
  } catch (const OperatorStop&) {
    // a DIALOG or FAIL that ends the run ends the check too
  } catch (const GantryError& e) {
    log.add(e.diagnostic());
  }
  ctx_.checking_ = false;
  frames_.clear();  // where a full log, or an error, left the check
  end_quiet();
  start_.reset();
  state_.independent.reset();
  sink_.flush();
}

void Interpreter::loop(DiagnosticLog* collect) {
  while (!frames_.empty() && !(collect && collect->full())) {
    Frame& f = frames_.back();
    if (f.script->at_end(f.pc)) {
      end_file();
      continue;
    }
    Cursor next;
    current_ = f.pc;
    std::shared_ptr<const LineParse> lp;  // only lines that are not simple commands need one
    const Statement* st = &simple_;
    // An O-word loop's lines are parsed once, then taken from the script's cache.
    const bool hot = f.script->gcode() && gcode_flow_->hot;
    const std::string_view text = hot ? std::string_view() : f.script->line_at(f.pc, &next);
    if (hot || f.script->fm() ||
        !(f.script->gcode() ? parse_gcode_statement(text, f.script->name(), f.pc.line, &simple_)
                            : parse_simple_command(text, f.script->name(), f.pc.line, &simple_) ||
                                  f.script->read_common(f.pc, text, next, &simple_))) {
      lp = f.script->parse(f.pc, &next);
      st = lp->statement ? &*lp->statement : nullptr;
    }
    const Diagnostic* error = lp && lp->error ? &*lp->error : nullptr;
    f.pc = next;
    if (start_ && start_->depth + 1 == frames_.size() && current_.line == start_->line)
      reach_start(SourceLoc{f.script->name(), current_.line, 0});
    if (!st && !error) continue;
    if (error && collect) continue;  // already reported by the script's own pass
    ++executed_;
    const SourceLoc& at = st ? st->loc : error->loc;
    // A stop is seen before every statement, so a loop that moves nothing ends too.
    if (options_.stop_check && options_.stop_check->load(std::memory_order_relaxed)) {
      if (collect) throw CheckInterrupted{at};
      throw OperatorStop({at, Severity::Error, "stopped by the operator"});
    }
    if (options_.statement_budget && executed_ > options_.statement_budget + budget_lines_)
      throw BudgetSpent{at};
    try {
      if (error) throw GantryError(*error);
      ctx_.transform_ = f.transform;
      const std::size_t moves_before = ctx_.moves();
      execute(*st);
      service_inputs(moves_before);
      if (pending_call_) {
        FileCall call = *pending_call_;
        pending_call_.reset();
        const std::string path =
            call.resolved ? call.path : readable_file(call.path, pending_call_loc_);
        push_file(
            call.lines
                ? call.lines
                : frames_.front().script->called(
                      path, [&] { return files_system_->load_script(path, table_.is_command()); }),
            call, pending_call_loc_);
      }
    } catch (const NeedsOperator&) {
      throw;
    } catch (const OperatorStop& e) {
      rethrow_located(e);
    } catch (const GantryError& e) {
      pending_call_.reset();
      if (!collect) rethrow_located(e);
      // A check goes on past errors. A variable whose assignment failed stays unset; what
      // fails only because of it has been explained already, so it is not reported again.
      const std::string& m = e.diagnostic().message;
      const bool cascade = m.rfind("undefined variable &", 0) == 0 &&
                           failed_vars_.count(m.substr(20, m.find_first_of(" ;", 20) - 20));
      if (const auto* a = std::get_if<AssignStmt>(&st->body))
        if (!a->target.persistent) failed_vars_.insert(a->target.name);
      if (cascade) continue;
      collect->add(located(e.diagnostic()));
    }
    if (stop_all_) {
      unwind_all();
      stop_all_ = false;
    }
    if (progress_ && !frames_.empty()) {
      // A typed line that calls a file (FG from a line, FP) shows that file's progress, not
      // its own one line's.
      const Frame& top = frames_.size() > 1 && frames_.front().call.lines && !frames_[1].call.lines
                             ? frames_[1]
                             : frames_.front();
      progress_(static_cast<size_t>(top.pc.line - 1),
                static_cast<size_t>(top.script->line_count()));
    }
  }
}

void Interpreter::execute(const Statement& st) {
  std::visit([&](const auto& body) { exec(body, st.loc); }, st.body);
}

// ---- control flow ---------------------------------------------------------------------

void Interpreter::exec(const JumpStmt& s, const SourceLoc& loc) {
  Frame& f = frames_.back();
  const std::optional<Cursor> target = f.script->label(s.label);
  if (!target)
    fail(s.label_loc, fmt::format("no label {}: in this file; labels are written on their own "
                                  "line as NAME:",
                                  s.label));
  if (s.gosub) {
    if (static_cast<int>(f.gosubs.size()) >= options_.max_gosub_depth)
      fail(loc, fmt::format("GOSUB nested {} deep without RETURN; a subroutine may be calling "
                            "itself",
                            options_.max_gosub_depth));
    f.gosubs.push_back(f.pc);
  }
  f.pc = *target;
}

void Interpreter::exec(const ReturnStmt&, const SourceLoc& loc) {
  Frame& f = frames_.back();
  if (f.gosubs.empty())
    fail(loc,
         "RETURN without GOSUB; put END before the subroutines so the file does not run "
         "into them");
  f.pc = f.gosubs.back();
  f.gosubs.pop_back();
}

void Interpreter::exec(const EndStmt& s, const SourceLoc&) {
  if (s.message) io_.print(value_of(*s.message).to_string() + "\n");
  if (s.scope == EndStmt::Scope::File) {
    Frame& f = frames_.back();
    f.pc = Cursor{std::string::npos, f.pc.line};  // at_end: the loop ends this pass
    return;
  }
  stop_all_ = true;
}

void Interpreter::exec(const IfStmt& s, const SourceLoc& loc) {
  if (is_true(evaluate(s.test, *this), loc)) execute(*s.action);
}

void Interpreter::exec(const OnInputStmt& s, const SourceLoc& loc) {
  const double input = evaluate(s.input, *this).to_number(loc, "the input number");
  const double cond = evaluate(s.condition, *this).to_number(loc, "the state");
  if (input != std::round(input) || input < 1 || input > 12)
    fail(loc, fmt::format("input switch {} does not exist; inputs are 1 to 12", input));
  if (cond != std::round(cond) || cond < 0 || cond > 3)
    fail(loc, fmt::format("ON INPUT state {} is not 0 (off), 1 (on), 2 (off, ramped) or 3 (on, "
                          "ramped)",
                          cond));
  const int n = static_cast<int>(input), c = static_cast<int>(cond);
  if (settings_.inputs.switch_bits[n - 1] < 0 && s.action)
    io_.warn({loc, Severity::Warning,
              fmt::format("input switch {} is not wired in this profile (inputs.switch_bits): "
                          "this handler never runs",
                          n)});
  // States 1 and 3 watch the switch closing, 0 and 2 opening; 0 and 1 stop at once.
  const std::pair<int, int> key{n, c % 2};
  if (s.action)
    on_input_[key] = {s.action, c < 2, frames_.size()};
  else
    on_input_.erase(key);
  arm_inputs();
}

// The machine comes to rest first: the new handlers apply from the next move on.
void Interpreter::arm_inputs() {
  std::vector<InputTrigger> triggers;
  for (const auto& [key, h] : on_input_)
    triggers.push_back({key.first, key.second == 1, h.instant});
  ctx_.sync();
  gated_sink_->watch_inputs(triggers, MachineLink::Watching::Handlers);
}

// While handlers are armed, each statement's motion plays out before the next statement
// runs, so the statement an edge cuts is the one just executed and its successor is where
// the file goes on (a GOTO action aside). The price: no look-ahead across moves while a
// handler is armed (docs/language.md).
void Interpreter::service_inputs(std::size_t moves_before) {
  if (on_input_.empty() || ctx_.moves() == moves_before) return;
  const std::optional<MotionReport> r = ctx_.sync();
  if (!r || !r->fired) return;
  set_machine_position(r->machine);  // where it came to rest
  auto it = on_input_.find({r->fired->input, r->fired->closing ? 1 : 0});
  if (it == on_input_.end()) return;
  const InputHandler h = it->second;
  on_input_.erase(it);  // one-shot
  arm_inputs();
  if (const auto* jump = std::get_if<JumpStmt>(&h.action->body); jump && !jump->gosub)
    while (frames_.size() > h.depth && frames_.size() > 1) end_file();
  execute(*h.action);
}

// ---- variables ------------------------------------------------------------------------

const Value* Interpreter::user_variable(std::string_view name) const {
  auto it = vars_.find(std::string(name));
  return it == vars_.end() ? nullptr : &it->second;
}

const nlohmann::json* Interpreter::persistent_variable(std::string_view name) const {
  return store_.variable(name);
}

Value Interpreter::system_variable(int n, const SourceLoc& loc) {
  // An input, and the machine's clock, are read where the motion is: the moves before this
  // line play out first. A check has no machine: its clock reads 0 (docs/system_variables.md).
  std::optional<MotionReport> played;
  if ((n >= 51 && n <= 58) || (n >= 126 && n <= 129) || n == 130) played = ctx_.sync();
  MachineSnapshot m = snapshot();
  if (played) m.elapsed_seconds = played->elapsed_s;
  if (n == 146 || n == 147) m.now = local_date_time();
  if (std::optional<Value> v = read_system_variable(n, m)) return *v;
  fail(loc, fmt::format("unknown system variable %({}); docs/system_variables.md lists them", n));
}

MachineSnapshot Interpreter::snapshot() const {
  MachineSnapshot m;
  const Settings& s = settings_;
  m.location = state_.position + state_.applied_offset;  // VO: the tool's true position
  m.table_base = m.location + state_.zero;
  m.relative = !state_.absolute;
  m.preview = state_.preview.has_value();
  m.indexer_on = state_.independent.has_value();
  m.metric = s.units == Units::Millimetres;
  m.axis_count = s.display.axes;
  m.limit_check_axes = s.machine.limit_checking ? s.display.axes : 0;
  m.cutter_diameter = s.cutter.diameter;
  m.safe_z = s.cutter.safe_z;
  m.safe_a = s.cutter.safe_a;
  m.trigger_on_threshold = s.cutter.trigger_on;
  m.trigger_off_threshold = s.cutter.trigger_off;
  m.warning_delay = s.machine.warning_s;
  m.tab_pull_up = s.tabs.pull_up;
  m.tab_spacing = s.tabs.spacing;
  m.tab_size = s.tabs.size;
  m.tab_lead = s.tabs.leads;
  for (int k = 0; k < 5; ++k)
    m.resolution_multiplier[k] = static_cast<int>(s.calibration.resolution_multiplier[k]);
  m.step_interval_divider = s.calibration.step_divider;
  for (int k = 0; k < kAxisCount; ++k)
    m.driver_channel_axis[k] = static_cast<char>("XYZABC"[s.drivers.channel_axis[k]]);
  m.input_mode = s.switches.input_modes;
  m.output_mode = s.switches.output_modes;
  m.input4_mode = s.switches.stop_normally_open ? 1 : 0;
  for (int k = 0; k < 12; ++k) m.outputs[k] = (state_.outputs >> k & 1u) != 0;  // as set, in order
  m.output4_auto_mode = s.machine.switch4_mode;
  for (int i = 0; i < kAxisCount; ++i) {
    m.limit_min[i] = settings_.axes[i].min;
    m.limit_max[i] = settings_.axes[i].max;
    m.steps_per_unit[i] = settings_.axes[i].steps_per_unit;
  }
  auto groups = [](const GroupSpeeds& g) {
    return MachineSnapshot::Groups{g.xy, g.z, g.a, g.b, g.c};
  };
  m.move_speed = groups(state_.speeds.move);
  m.jog_speed = groups(state_.speeds.jog);
  m.move_ramp = groups(settings_.ramps.move_ramp_speed);
  m.jog_ramp = groups(settings_.ramps.jog_ramp_speed);
  m.spindle_rpm = ctx_.spindle_direction() != 0 ? state_.spindle_rpm : 0;
  if (!frames_.empty()) {
    const Frame& f = frames_.back();
    m.file_path = std::filesystem::absolute(*f.script->name()).string();
    m.file_offset = f.transform.origin;
    m.file_proportion = f.transform.scale;
  }
  if (std::optional<std::array<bool, 12>> in = gated_sink_->input_switches())
    m.inputs = *in;
  else if (const auto& touched = gated_sink_->touched)
    m.inputs[static_cast<size_t>(touched->first - 1)] = touched->second;
  return m;
}

Value Interpreter::value_of(const Arg& a) {
  if (a.number) return Value::number(*a.number);
  if (a.expr) return evaluate(*a.expr, *this);
  return Value::string(a.text);  // a bare word: the text as written
}

namespace {

// FabMo's universal-unit variables (its runtime's UU_README): `$nameUU[].x = v` stores v at
// index 0 in inches and index 1 in mm, whichever units are current, so that a file reads
// `$nameUU[%(25)].x` in its own units. The empty index is that placeholder, once per path.
size_t unit_placeholders(const LValue& t) {
  return std::ranges::count_if(t.path, [](const Accessor& a) { return !a.is_field && !a.index; });
}

}  // namespace

void Interpreter::assign_universal_units(nlohmann::json& root, const LValue& target,
                                         const Value& v) {
  const std::string shown = "$" + target.name;
  if (unit_placeholders(target) > 1)
    fail(target.loc, fmt::format("{} has more than one []; the unit index [] is given once",
                                 describe_path(target.name, target.path, *this)));
  if (!target.name.ends_with("UU"))
    fail(target.loc,
         fmt::format("[] is the unit index of universal-unit variables, whose names end in UU; "
                     "give an index to {}, or rename it {}UU",
                     shown, shown));
  if (v.is_string()) {  // a name or a label: the same in both units
    assign_path(root, target.path, v, *this, target.loc, 0);
    assign_path(root, target.path, v, *this, target.loc, 1);
    return;
  }
  const bool mm = system_variable(25, target.loc).num() == 1;
  const double inches = mm ? v.num() / 25.4 : v.num();
  assign_path(root, target.path, Value::number(inches), *this, target.loc, 0);
  assign_path(root, target.path, Value::number(inches * 25.4), *this, target.loc, 1);
}

void Interpreter::assign(const LValue& target, const Value& v) {
  if (!target.persistent) {
    vars_[target.name] = v;
    return;
  }
  nlohmann::json& root = store_.variables()[target.name];
  if (unit_placeholders(target) > 0) return assign_universal_units(root, target, v);
  if (target.path.empty()) {
    if (v.is_string())
      root = v.str();
    else if (v.num() == std::floor(v.num()) && std::abs(v.num()) < 9e15)
      root = static_cast<std::int64_t>(v.num());  // whole numbers stay whole in the file
    else
      root = v.num();
    return;
  }
  assign_path(root, target.path, v, *this, target.loc);
}

void Interpreter::exec(const AssignStmt& s, const SourceLoc&) {
  if (s.weak) {  // `:=` keeps an existing value (for $x.y, the value at that path)
    bool defined = false;
    if (!s.target.persistent) {
      defined = vars_.count(s.target.name) > 0;
    } else if (const nlohmann::json* root = store_.variable(s.target.name)) {
      defined = true;
      if (!s.target.path.empty()) try {
          read_path(*root, s.target.path, *this, s.target.loc, s.target.name, 0);
        } catch (const GantryError&) {
          defined = false;
        }
    }
    if (defined) return;
  }
  assign(s.target, s.value.blank() ? Value::string("") : value_of(s.value));
}

// ---- commands -------------------------------------------------------------------------

namespace {

std::string param_what(const CommandSpec& spec, const ParamSpec& ps, size_t i) {
  return fmt::format("{} parameter {} ({})", spec.code, i + 1, ps.name);
}

// The table's range for a number; most parameters have none, so this costs a test.
void check_param(const CommandSpec& spec, const ParamSpec& ps, size_t i, double v,
                 const SourceLoc& at) {
  if (!ps.min && !ps.max && !ps.whole) return;
  if ((ps.min && !(v >= *ps.min)) || (ps.max && !(v <= *ps.max)))
    fail(at, fmt::format("{} is {}; allowed: {}", param_what(spec, ps, i), format_number(v),
                         param_range(ps)));
  if (ps.whole && v != std::round(v))
    fail(at, fmt::format("{} must be a whole number, not {}", param_what(spec, ps, i),
                         format_number(v)));
}

void check_choice(const CommandSpec& spec, const ParamSpec& ps, size_t i, const std::string& v,
                  const SourceLoc& at) {
  std::string_view rest = ps.choices;
  while (!rest.empty()) {
    const size_t space = rest.find(' ');
    const std::string_view word = rest.substr(0, space);
    rest = space == std::string_view::npos ? std::string_view{} : rest.substr(space + 1);
    if (scan::upper(v) == scan::upper(word)) return;
  }
  fail(at, fmt::format("{} is '{}'; allowed: {}", param_what(spec, ps, i), v, param_range(ps)));
}

}  // namespace

void Interpreter::exec(const CommandStmt& cmd, const SourceLoc& loc) {
  // A file is mostly one command line after another (M3, M3, ...): the last one's spec is
  // kept, by its code.
  if (!last_spec_ || cmd.code != last_spec_->code) {
    const CommandSpec* spec = table_.find(cmd.code);
    if (!spec) fail(loc, unknown_command_message(cmd.code));
    last_spec_ = spec;
  }
  const CommandSpec* spec = last_spec_;
  const std::vector<ParamSpec>& params = spec->params_for(settings_.dialect);
  if (cmd.args.size() > params.size()) extra_params(*spec, cmd, params.size(), loc);
  // The values' storage is kept from line to line (taken, so a nested call gets its own).
  // The loop below writes every one of them.
  std::vector<std::optional<Value>> values = std::move(values_storage_);
  values.resize(params.size());
  CommandCall call{*spec, loc, cmd.args, values};
  const size_t param_count = params.size(), arg_count = cmd.args.size();
  for (size_t i = 0; i < param_count; ++i) {
    const ParamSpec& ps = params[i];
    const Arg* a = i < arg_count && !cmd.args[i].blank() ? &cmd.args[i] : nullptr;
    if (a && a->number && ps.kind == ParamKind::Number) {  // a plain number: what follows gives
      if (ps.min || ps.max || ps.whole)                    // only this (most lines of a file)
        check_param(*spec, ps, i, *a->number, a->loc);
      values[i].emplace(Value::number(*a->number));
      continue;
    }
    std::optional<Value> v;
    if (a) v = value_of(*a);
    if (v && v->is_string() && v->str().empty()) v.reset();  // "" counts as blank
    if (!v) {
      if (ps.required)
        fail(call.param_loc(i),
             fmt::format("{} needs its parameter {} ({})", spec->code, i + 1, ps.name));
      if (ps.default_value) v = Value::number(*ps.default_value);
    } else if (ps.kind == ParamKind::Number) {
      if (!a->is_expression() && a->expr_error && scan::looks_like_expression(a->text, true))
        throw GantryError(*a->expr_error);  // a broken expression: say where it breaks
      if (!a->is_expression() && a->expr_error && v->is_string())
        fail(a->loc, fmt::format("expected a number for {} ({}), found '{}'", ps.name, spec->code,
                                 a->text));
      if (v->is_string() && a->text.size() > 1 && a->text[0] == '&' &&
          std::all_of(a->text.begin() + 1, a->text.end(), scan::is_word) &&
          !user_variable(scan::upper(a->text.substr(1))))
        fail(a->loc,
             fmt::format("undefined variable {}; set it before this line", scan::upper(a->text)));
      if (v->is_string())  // the message is only built when a conversion is needed
        v = Value::number(v->to_number(a->loc, fmt::format("{} ({})", ps.name, spec->code)));
      check_param(*spec, ps, i, v->num(), a->loc);
    } else if (!ps.choices.empty()) {
      check_choice(*spec, ps, i, v->to_string(), a->loc);
    }
    values[i] = std::move(v);
  }
  spec->handler(ctx_, call);
  values_storage_ = std::move(values);
}

// SB3 ignores parameters past a command's last one, and ShopBot's own sample files write
// some (CR with 10, CP with 15): Gantry ignores them too, with one warning per command and
// file. Moves, jogs and zero commands refuse them: there an extra value is most likely meant
// for another command (M2 for M3, ZX for VA), and ignoring it would put the tool somewhere the
// file did not mean. So does a command whose table gives a reason (VA: another layout's
// values would be misread). Trailing blanks are already gone, so one of them is written.
void Interpreter::extra_params(const CommandSpec& spec, const CommandStmt& cmd, size_t count,
                               const SourceLoc& loc) {
  size_t first = count;
  while (cmd.args[first].blank()) ++first;
  const Arg& extra = cmd.args[first];
  const std::string takes =
      fmt::format("{} takes {} parameter{}", spec.code, count, count == 1 ? "" : "s");
  if (!spec.extra_params_refused.empty())
    fail(extra.loc,
         fmt::format("{}; this is parameter {}: {}", takes, first + 1, spec.extra_params_refused));
  if (spec.group == CommandGroup::Move || spec.group == CommandGroup::Jog ||
      spec.group == CommandGroup::Zero)
    fail(extra.loc, fmt::format("{}; this is parameter {}", takes, first + 1));
  const std::string key = fmt::format("{}\n{}", loc.file ? *loc.file : "", spec.code);
  if (!extra_params_warned_.insert(key).second) return;
  io_.warn({extra.loc, Severity::Warning,
            fmt::format("{}; parameter {} and those after it are ignored, as SB3 ignores them",
                        takes, first + 1)});
}

void Interpreter::exec(const GcodeStmt& s, const SourceLoc& loc) {
  if (s.block.oword.kind != OwordKind::None || !s.block.call_file.empty())
    return gcode_flow(s.block, loc);
  gcode_->execute(s.block, loc);
  if (s.block.flow_m) gcode_m98_m99(s.block, loc);
}

void Interpreter::exec(const CustomCutStmt& s, const SourceLoc& loc) {
  if (!s.computed) return call_macro(s.number, loc);
  const SourceLoc& at = s.computed->loc;
  const double n = value_of(*s.computed).to_number(at, "the custom cut's number (C#)");
  if (n < 0 || n > kMaxCustomCut || n != std::floor(n))
    fail(at, fmt::format("custom cuts are numbered 0 to {}; C# was given {}", kMaxCustomCut,
                         format_number(n)));
  call_macro(static_cast<int>(n), loc);
}

// --macros, else the parts folder ("": the working directory) and the operator's folder;
// then the shipped macros.
std::vector<std::string> Interpreter::macro_folders() const {
  std::vector<std::string> folders;
  if (!options_.macro_dir.empty()) {
    folders.push_back(options_.macro_dir);
  } else {
    folders.push_back(parts_dir_);
    if (!options_.user_macro_dir.empty()) folders.push_back(options_.user_macro_dir);
  }
  if (!options_.shipped_macro_dir.empty()) folders.push_back(options_.shipped_macro_dir);
  return folders;
}

// &Tool = n, then C9 (SB3's tool change, as CAM posts write it): tool n is in the spindle
// from here on, whatever the macro does (the shipped C9 sets no VC), so a preview draws the
// cuts after it with tool n's cutter, and the change is told at the C9 line. A &Tool that
// is not a tool number is left to the macro to refuse.
void Interpreter::tool_change(const SourceLoc& loc) {
  const Value* t = user_variable("TOOL");
  if (!t || !t->is_number()) return;
  const double n = t->num();
  if (n < 1 || n > 1e9 || n != std::floor(n)) return;
  tool_into_spindle(ctx_, static_cast<int>(n), loc);
  ctx_.note_drawing(loc);
}

void Interpreter::call_macro(int number, const SourceLoc& loc) {
  if (number == 9 && settings_.toolchanger.rack()) {  // the rack's change, not a C9.sbp
    const Value* t = user_variable("TOOL");
    const double n = t && t->is_number() ? t->num() : -1;
    if (n < 1 || n > 1e9 || n != std::floor(n))
      fail(loc, "C9 changes the tool on this machine's rack ([toolchanger] in the profile): set "
                "&Tool to the number of the tool to put in first (&Tool = 2, then C9)");
    opensbp_rack_change(ctx_, static_cast<int>(n), loc);
    tool_into_spindle(ctx_, static_cast<int>(n), loc);  // VC's diameter, as after C9.sbp
    ctx_.note_drawing(loc);
    return;
  }
  const std::vector<std::string> folders = macro_folders();
  for (const std::string& dir : folders)
    for (const std::string& name :
         {fmt::format("C{}.sbp", number), fmt::format("macro_{}.sbp", number)}) {
      const PartFileLookup found =
          find_part_file(*files_system_, (std::filesystem::path(dir) / name).string());
      if (!found.error.empty()) fail(loc, found.error);
      if (files_system_->is_file(found.path)) {
        check_reach(found.path, FileAccess::Read, loc);  // a macro may be a link out
        if (number == 9) tool_change(loc);
        FileCall call;
        call.path = found.path;
        call.resolved = true;
        call.homing = number == 3;
        pending_call_ = call;
        pending_call_loc_ = loc;
        return;
      }
    }
  if (number == 3) return home_on_switches(ctx_, loc);  // the built-in homing
  std::string where;
  for (size_t i = 0; i < folders.size(); ++i)
    where += (i == 0                    ? ""
              : i + 1 == folders.size() ? " or "
                                        : ", ") +
             (folders[i].empty() ? std::string("the working directory") : folders[i]);
  fail(loc, fmt::format("C{0} runs custom cut {0}, but there is no C{0}.sbp or macro_{0}.sbp in "
                        "{1}; put the macro in one of them or give its folder with --macros",
                        number, where));
}

}  // namespace gantry
