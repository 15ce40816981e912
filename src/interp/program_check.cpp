// Programs checked and interpreted without a machine (program_check.hpp).
#include "gantry/interp/program_check.hpp"

#include <algorithm>  // stable_sort
#include <climits>    // INT_MAX

#include "gantry/commands/command_recorder.hpp"  // CommandRecorder
#include "gantry/interp/interpreter.hpp"         // Interpreter

namespace gantry {
namespace {

class NullSink : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

}  // namespace

DiagnosticLog check_program(std::shared_ptr<const Script> script, const Settings& settings,
                            const PersistentStore& store, const JobOptions& options,
                            bool runtime_warnings) {
  NullSink nothing;
  MotionSink& sink = options.check_moves ? *options.check_moves : nothing;
  std::string printed;  // a check prints nothing
  ScriptedIO io(options.yes || options.operator_present, options.inputs, &printed);
  if (options.input_defaults) io.take_input_defaults();
  PersistentStore scratch = store.scratch_copy();  // a check may assign $variables, never saves
  InterpreterOptions opt = options.interpreter;
  opt.dry_run = true;
  opt.statement_budget = options.check_budget;
  opt.operator_present = options.operator_present;
  opt.stop_check = options.stop;
  Interpreter interp(settings, sink, io, scratch, opt);
  if (options.start_state) interp.restore_state(*options.start_state);
  if (options.start_variables) interp.restore_variables(*options.start_variables);
  if (options.record) interp.recorder() = *options.record;
  DiagnosticLog log(options.max_errors);
  interp.check(std::move(script), log);
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

}  // namespace gantry
