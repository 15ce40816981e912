// The end-of-run report, as text for people and as one JSON object for scripts.
#pragma once

#include <nlohmann/json.hpp>  // json

#include <optional>
#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandSpec
#include "gantry/core/axes.hpp"               // Vec6, Steps6
#include "gantry/core/diagnostic.hpp"         // Diagnostic
#include "gantry/motion/canon_move.hpp"       // CanonMove
#include "gantry/settings/settings.hpp"       // Units

namespace gantry {

struct RunReport {
  std::vector<Diagnostic> errors;
  std::string error_summary;  // the check's errors beyond its cap, in one line ("" none)
  // Where the check before the run stopped short (an INPUT answered at the terminal, the
  // statement budget): the run went past it unchecked, and the report says so.
  std::optional<Diagnostic> check_stopped;
  Units units = Units::Inches;
  Vec6 position = Vec6::Zero();  // from the steps the card counted
  Steps6 steps{};                // counted by the card from its pulses
  Steps6 commanded_steps{};      // emitted by the step generator
  Steps6 played_steps{};         // the generator's count of what the card played
  std::string fault = "none";    // why the card stopped by itself
  double time_s = 0;             // machine time on the card
  double planned_time_s = 0;
  double estimated_time_s = 0;  // predicted by the check, before the run
  std::size_t lines = 0, moves = 0;
  std::uint64_t timing_violations = 0;
  std::vector<std::string> violation_notes;
  double max_velocity_ratio = 0, max_accel_ratio = 0;
};

nlohmann::ordered_json to_json(const RunReport& r);
std::string to_text(const RunReport& r);

nlohmann::ordered_json to_json(const Diagnostic& d);
// One canonical move as `gantry moves` prints it.
nlohmann::ordered_json to_json(const CanonMove& m);
// One command of the table, with its parameters, as `gantry commands --json` prints it.
nlohmann::ordered_json to_json(const CommandSpec& s);
std::string to_text(const CanonMove& m);

}  // namespace gantry
