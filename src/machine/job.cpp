// Wiring of one job through the pipeline: interpreter -> planner -> step generator -> card.
#include "gantry/machine/job.hpp"

#include "gantry/interp/interpreter.hpp"        // Interpreter
#include "gantry/motion/trapezoid_planner.hpp"  // TrapezoidPlanner
#include "gantry/step/step_generator.hpp"       // StepGenerator

namespace gantry {
namespace {

class NullSink : public MotionSink {
 public:
  void move(const CanonMove&) override {}
  void flush() override {}
};

}  // namespace

std::vector<Diagnostic> check_program(const Program& program, const Settings& settings) {
  NullSink sink;
  Interpreter interp(settings, sink);
  return interp.check(program);
}

void interpret(const Program& program, const Settings& settings, MotionSink& sink) {
  Interpreter interp(settings, sink);
  interp.run(program);
}

JobResult run_job(const Program& program, const Settings& settings, Card& card,
                  const JobOptions& options) {
  JobResult result;
  result.errors = check_program(program, settings);
  if (!result.ok()) return result;

  card.start(settings.card.pacer_hz());
  StepGenerator steps(settings, card);
  TrapezoidPlanner planner(settings, steps);
  Interpreter interp(settings, planner);
  if (options.progress) interp.on_progress(options.progress);
  try {
    interp.run(program);
  } catch (const GantryError& e) {
    steps.flush();  // let the pulses already planned finish; the position stays known
    result.errors.push_back(e.diagnostic());
  }
  card.drain();
  result.lines = interp.statements_executed();
  result.moves = interp.moves_emitted();
  result.commanded_steps = steps.position();
  result.planned_time_s = planner.planned_time();
  return result;
}

}  // namespace gantry
