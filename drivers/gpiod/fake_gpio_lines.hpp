// GPIO lines in memory, for tests: records every output change with the tick it happened
// at, and reads inputs the test sets (now, or from a given tick on).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <vector>

#include "gpiod/gpio_lines.hpp"
#include "gpiod/gpio_map.hpp"

namespace gantry {

struct LineChange {
  std::uint64_t tick;
  unsigned offset;
  int level;
  bool operator==(const LineChange&) const = default;
};

class FakeGpioLines : public GpioLines {
 public:
  // Lines as the map requests them: outputs at the levels of map.initial_word, inputs low.
  explicit FakeGpioLines(const GpioMap& map);

  bool set_outputs(std::uint64_t changed, std::uint64_t levels) override;
  bool read_inputs(std::uint64_t& levels) override;

  // Where recorded changes and scheduled inputs take the current tick from (the card's
  // ticks_played(), which is the tick being played while its lines are written).
  void set_tick_source(std::function<std::uint64_t()> tick);
  // Sets an input line's level from tick `from_tick` on.
  void set_input(unsigned offset, int level, std::uint64_t from_tick = 0);
  // The next set_outputs / read_inputs fails with `error` (an errno value).
  void fail_next_write(int error);
  void fail_next_read(int error);

  std::vector<LineChange> changes() const;
  int level(unsigned offset) const;   // an output line's current level
  std::uint64_t write_calls() const;  // set_outputs calls, whether or not they failed
  std::uint64_t read_calls() const;

 private:
  std::uint64_t now() const { return tick_ ? tick_() : 0; }

  mutable std::mutex mutex_;  // the player thread writes, the test reads
  std::vector<unsigned> output_offsets_, input_offsets_;
  std::vector<int> output_levels_;
  // Per input offset: level changes keyed by the tick they take effect.
  std::map<unsigned, std::map<std::uint64_t, int>> input_schedule_;
  std::function<std::uint64_t()> tick_;
  std::vector<LineChange> changes_;
  std::uint64_t write_calls_ = 0, read_calls_ = 0;
  int write_error_ = 0, read_error_ = 0;
};

}  // namespace gantry
