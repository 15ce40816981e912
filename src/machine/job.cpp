// One job: the whole file checked, then run by the controller (interpreter -> planner ->
// motion feeder -> step generator -> card).
#include "gantry/machine/job.hpp"

#include <fmt/format.h>  // the warning

#include <algorithm>  // stable_sort
#include <climits>    // INT_MAX

#include "gantry/core/text_file.hpp"            // read_text_file
#include "gantry/machine/controller.hpp"        // Controller
#include "gantry/motion/lookahead_planner.hpp"  // LookAheadPlanner
#include "gantry/settings/values_file.hpp"      // values_text

namespace gantry {
namespace {

class NullSink : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

// The check's moves to the estimating planner (or nowhere) and to an observer.
class TeeSink : public MotionSink {
 public:
  TeeSink(MotionSink& a, MotionSink& b) : a_(a), b_(b) {}
  void move(const CanonMove& m) override { a_.move(m), b_.move(m); }
  void flush() override { a_.flush(), b_.flush(); }
  void settings_changed(const Settings& s) override {
    a_.settings_changed(s), b_.settings_changed(s);
  }

 private:
  MotionSink &a_, &b_;
};

class NullSegments : public SegmentSink {
 public:
  void segment(const PlannedSegment&) override {}
  void flush() override {}
};

}  // namespace

DiagnosticLog check_program(std::shared_ptr<const Script> script, const Settings& settings,
                            const PersistentStore& store, const JobOptions& options,
                            bool runtime_warnings, double* estimated_time_s) {
  NullSink nothing;
  NullSegments segments;
  LookAheadPlanner planner(settings, segments);
  planner.feed_override(options.feed_override);
  MotionSink& planned = estimated_time_s ? static_cast<MotionSink&>(planner) : nothing;
  TeeSink both(planned, options.check_moves ? *options.check_moves : nothing);
  MotionSink& sink = options.check_moves ? static_cast<MotionSink&>(both) : planned;
  std::string printed;  // a check prints nothing
  ScriptedIO io(options.yes || options.operator_present, options.inputs, &printed);
  PersistentStore scratch = store.scratch_copy();  // a check may assign $variables, never saves
  InterpreterOptions opt = options.interpreter;
  opt.dry_run = true;
  opt.statement_budget = options.check_budget;
  opt.operator_present = options.operator_present;
  if (options.control) opt.stop_check = &options.control->stopped();
  Interpreter interp(settings, sink, io, scratch, opt);
  if (options.start_state) interp.restore_state(*options.start_state);
  if (options.start_variables) interp.restore_variables(*options.start_variables);
  if (options.record) interp.recorder() = *options.record;
  DiagnosticLog log(options.max_errors);
  interp.check(std::move(script), log);
  if (estimated_time_s) *estimated_time_s = planner.planned_time();
  if (runtime_warnings)
    for (const Diagnostic& w : io.warnings()) log.add(w);
  // In line order: the script's own pass found the syntax errors, the run the others.
  // Messages from nested files keep their order after those of the top-level file.
  auto key = [](const Diagnostic& d) { return d.via.empty() ? d.loc.line : INT_MAX; };
  std::stable_sort(log.kept().begin(), log.kept().end(),
                   [&](const Diagnostic& a, const Diagnostic& b) { return key(a) < key(b); });
  return log;
}

void interpret(std::shared_ptr<const Script> script, const Settings& settings, MotionSink& sink,
               OperatorIO& io, PersistentStore& store, const JobOptions& options) {
  Interpreter interp(settings, sink, io, store, options.interpreter);
  interp.run(std::move(script));
}

bool RunControl::stop() {
  std::lock_guard lock(m_);
  const bool first = ++stops_ == 1;
  stopped_ = true;
  if (machine_) first ? (void)machine_->stop() : (void)machine_->estop();
  return first;
}

bool RunControl::start(Controller& machine, const std::function<void()>& start) {
  std::lock_guard lock(m_);
  if (stops_ > 0) return false;
  machine_ = &machine;
  start();
  return true;
}

void RunControl::detach() {
  std::lock_guard lock(m_);
  machine_ = nullptr;
}

JobResult run_job(std::shared_ptr<const Script> script, const Settings& settings, Card& card,
                  OperatorIO& io, PersistentStore& store, const JobOptions& options) {
  JobResult result;
  result.settings = settings;
  DiagnosticLog checked =
      check_program(script, settings, store, options, false, &result.estimated_time_s);
  for (Diagnostic& d : checked.kept())
    (d.severity == Severity::Error ? result.errors : result.warnings).push_back(std::move(d));
  result.error_summary = checked.summary();
  result.check_stopped = checked.stopped_short();
  if (!result.ok()) return result;

  // The live machine runs it: the same controller as the console's, so probes, ON INPUT,
  // limit switches and faults behave alike everywhere.
  InterpreterOptions interp_options = options.interpreter;
  interp_options.save_values = [&](const Settings& s) {
    result.settings = s;
    if (options.values_path.empty() || !options.profile) return;
    const std::string text = values_text(s, *options.profile);
    if (read_text_file(options.values_path) == text) return;  // unchanged: no write
    if (std::string why; !write_file_atomically(options.values_path, text, &why))
      result.warnings.push_back(
          {file_loc(options.values_path), Severity::Warning,
           fmt::format("cannot save the values this run changed ({}); the previous values file "
                       "is kept",
                       why)});
  };
  Controller machine(settings, card, io, store, interp_options);
  machine.set_feed_override(options.feed_override);
  if (options.progress) machine.on_progress(options.progress);
  const std::string name = *script->name();
  Outcome started;
  auto start = [&] { started = machine.run(std::move(script), true, result.estimated_time_s); };
  if (!options.control) {
    start();
  } else if (!options.control->start(machine, start)) {
    result.errors.push_back({file_loc(name), Severity::Error,
                             "stopped by the operator before the run started; nothing moved"});
    return result;
  }
  struct Detach {  // the control forgets the machine before it goes
    RunControl* c;
    ~Detach() {
      if (c) c->detach();
    }
  } detach{options.control};
  if (!started) {
    result.errors.push_back({file_loc(name), Severity::Error, started.reason});
    return result;
  }
  machine.wait();
  const Controller::Summary s = machine.summary();
  if (s.error) result.errors.push_back(*s.error);
  result.lines = s.lines;
  result.moves = s.moves;
  result.cut = s.cut;
  result.commanded_steps = s.commanded;
  result.played_steps = machine.status().steps;
  result.fault = s.fault;
  result.planned_time_s = s.planned_time_s;
  return result;
}

}  // namespace gantry
