// Test helper: the simulated card's pin trace (`tick hex-word` per change of the output
// word) read back, and one step/direction channel's pulses decoded from it.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace gantry::test {

struct TracePulse {
  std::int64_t tick;  // the step line's active edge
  bool positive;      // the direction line's travel at that edge
};

// The word changes of a trace file, in order.
inline std::vector<std::pair<std::int64_t, std::uint32_t>> read_trace(const std::string& path) {
  std::vector<std::pair<std::int64_t, std::uint32_t>> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t space = line.find(' ');
    out.emplace_back(std::stoll(line.substr(0, space)),
                     static_cast<std::uint32_t>(std::stoul(line.substr(space + 1), nullptr, 16)));
  }
  return out;
}

// The pulses of the channel on `step_bit`/`dir_bit` (step active high; the direction line low
// for positive travel, high with `invert_dir`: docs/hardware.md).
inline std::vector<TracePulse> channel_pulses(
    const std::vector<std::pair<std::int64_t, std::uint32_t>>& trace, int step_bit, int dir_bit,
    bool invert_dir = false) {
  std::vector<TracePulse> out;
  bool active = false;
  for (const auto& [tick, w] : trace) {
    const bool step = (w >> step_bit & 1u) != 0;
    const bool dir_high = (w >> dir_bit & 1u) != 0;
    if (step && !active) out.push_back({tick, dir_high == invert_dir});
    active = step;
  }
  return out;
}

// Runs of one direction: (positive, count) per run.
inline std::vector<std::pair<bool, int>> direction_runs(const std::vector<TracePulse>& pulses) {
  std::vector<std::pair<bool, int>> runs;
  for (const TracePulse& p : pulses)
    if (!runs.empty() && runs.back().first == p.positive)
      ++runs.back().second;
    else
      runs.emplace_back(p.positive, 1);
  return runs;
}

}  // namespace gantry::test
