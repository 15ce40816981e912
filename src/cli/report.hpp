// The end-of-run report, as text for people and as one JSON object for scripts.
#pragma once

#include <nlohmann/json.hpp>  // json

#include <optional>
#include <string>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandSpec
#include "gantry/core/vec6.hpp"               // Vec6, Steps6
#include "gantry/core/diagnostic.hpp"         // Diagnostic
#include "gantry/canon/canon_move.hpp"       // CanonMove
#include "gantry/settings/settings.hpp"       // Units

namespace gantry {

class SimCard;

struct RunReport {
  std::vector<Diagnostic> errors;
  std::string error_summary;  // the check's errors beyond its cap, in one line ("" none)
  // Where the check before the run stopped short (an INPUT answered at the terminal, the
  // statement budget): the run went past it unchecked, and the report says so.
  std::optional<Diagnostic> check_stopped;
  Units units = Units::Inches;
  std::string axis_names = "XYZABC";  // the text's letters: W for the profile's W axis
  Vec6 position = Vec6::Zero();  // from the steps the card counted
  Steps6 steps{};                // counted by the card from its pulses
  Steps6 commanded_steps{};      // emitted by the step generator
  Steps6 played_steps{};         // the generator's count of what the card played
  std::string fault = "none";    // why the card stopped by itself
  double time_s = 0;             // machine time on the card
  double planned_time_s = 0;
  double estimated_time_s = 0;  // predicted by the check, before the run
  std::size_t lines = 0, moves = 0;
  bool cut = false;  // the motion was cut short: lines and moves are what reached the card
  std::string stopped_by = "none";  // the operator's "stop" or "E-stop" (Ctrl-C, twice)
  std::uint64_t timing_violations = 0;
  std::uint64_t kinematic_violations = 0;  // speeds or accelerations beyond the axis limits
  std::vector<std::string> violation_notes;
  double max_velocity_ratio = 0, max_accel_ratio = 0;
};

// The simulated card's own checks of what it played: pulse timing, and each axis's velocity
// and acceleration reconstructed from the step times (docs/hardware.md).
void add_card_checks(RunReport& r, SimCard& card);

// "error" (it stopped short), "violation" (it ran to its end, but the card saw a pulse, a
// speed or an acceleration beyond the machine's limits) or "done": never "done" when a limit
// was exceeded.
const char* run_status(const RunReport& r);
int exit_code(const RunReport& r);  // 0 only when "done"

nlohmann::ordered_json to_json(const RunReport& r);
std::string to_text(const RunReport& r);

nlohmann::ordered_json to_json(const Diagnostic& d);
// One canonical move as `gantry moves` prints it.
nlohmann::ordered_json to_json(const CanonMove& m);
// One command of the table, with its parameters, as `gantry commands --json` prints it.
nlohmann::ordered_json to_json(const CommandSpec& s);
std::string to_text(const CanonMove& m);

}  // namespace gantry
