// One job: the whole file checked, then run by the controller (interpreter -> planner ->
// motion feeder -> step generator -> card).
#include "gantry/machine/job.hpp"

#include <fmt/format.h>  // the warning


#include "gantry/core/text_file.hpp"            // read_text_file
#include "gantry/machine/controller.hpp"        // Controller
#include "gantry/motion/cycle_timer.hpp"        // CycleTimer
#include "gantry/settings/values_file.hpp"      // values_text

namespace gantry {
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
                  OperatorIO& io, PersistentStore& store, const JobOptions& options,
                  RunControl* control,
                  const std::function<void(const ControllerStatus&)>& watch,
                  const std::function<void(Controller&)>& prepare) {
  JobResult result;
  result.settings = settings;
  CycleTimer timer(settings, options.feed_override, options.check_moves);
  JobOptions check = options;
  check.check_moves = &timer;
  if (control) check.stop = &control->stopped();
  DiagnosticLog checked = check_program(script, settings, store, check, false);
  result.estimated_time_s = timer.seconds();
  for (Diagnostic& d : checked.kept())
    (d.severity == Severity::Error ? result.errors : result.warnings).push_back(std::move(d));
  result.error_summary = checked.summary();
  result.check_stopped = checked.stopped_short();
  if (!result.ok()) return result;

  // The live machine runs it: the same controller as the console's, so probes, ON INPUT,
  // limit switches and faults behave alike everywhere.
  InterpreterOptions interp_options = options.interpreter;
  interp_options.operator_present = options.operator_present;  // FM M2 repeats only for one
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
  if (prepare) prepare(machine);
  const std::string name = *script->name();
  Outcome started;
  auto start = [&] { started = machine.run(std::move(script), true, result.estimated_time_s); };
  if (!control) {
    start();
  } else if (!control->start(machine, start)) {
    result.errors.push_back({file_loc(name), Severity::Error,
                             "stopped by the operator before the run started; nothing moved"});
    return result;
  }
  struct Detach {  // the control forgets the machine before it goes
    RunControl* c;
    ~Detach() {
      if (c) c->detach();
    }
  } detach{control};
  if (!started) {
    result.errors.push_back({file_loc(name), Severity::Error, started.reason});
    return result;
  }
  if (watch) {
    while (!machine.wait_for(std::chrono::milliseconds(250))) watch(machine.status());
    watch(machine.status());
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
  result.lead = s.lead;
  result.lead_s = s.lead_s;
  result.starved_releases = s.starved_releases;
  result.feeder_realtime = s.feeder_realtime;
  return result;
}

}  // namespace gantry
