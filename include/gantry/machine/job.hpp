// A part-file job: checks the whole file, then runs it through planner, steps and card.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "gantry/hal/card.hpp"           // Card
#include "gantry/lang/statement.hpp"     // Program
#include "gantry/motion/canon_move.hpp"  // MotionSink
#include "gantry/settings/settings.hpp"  // Settings

namespace gantry {

struct JobOptions {
  std::function<void(std::size_t done, std::size_t total)> progress;  // statements
};

struct JobResult {
  std::vector<Diagnostic> errors;  // empty when the job ran to its end
  std::size_t lines = 0;           // statements executed
  std::size_t moves = 0;           // canonical moves issued
  Steps6 commanded_steps{};        // steps the generator emitted
  double planned_time_s = 0;       // the planner's sum of segment durations
  bool ok() const { return errors.empty(); }
};

// Checks every statement first (collecting all errors); only a clean file reaches the card,
// so a bad file never moves the machine.
JobResult run_job(const Program& program, const Settings& settings, Card& card,
                  const JobOptions& options = {});

// Interprets without motion and returns every error: what `gantry check` reports.
std::vector<Diagnostic> check_program(const Program& program, const Settings& settings);

// Interprets a checked program, handing each canonical move to `sink` (for `gantry moves`).
void interpret(const Program& program, const Settings& settings, MotionSink& sink);

}  // namespace gantry
