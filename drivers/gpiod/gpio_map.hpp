// Which GPIO lines the libgpiod card drives and reads, and how it paces them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gantry/hal/limit_filter.hpp"  // LimitFilter

namespace gantry {

// The fastest pacer the GPIO card accepts. Every tick is timed in software by a thread that
// sleeps until an absolute deadline and then makes an ioctl on the GPIO character device;
// wake-up latency (tens of microseconds even on PREEMPT_RT) makes shorter ticks meaningless.
inline constexpr double kGpiodMaxPacerHz = 50'000;

struct OutputLine {
  int bit = 0;          // bit of the card's output word (0-31)
  unsigned offset = 0;  // line offset on the chip
};

struct InputLine {
  unsigned offset = 0;  // line offset on the chip
  int bit = 0;          // bit of the card's input word (0-31) its level sets
};

enum class InputBias { AsIs, PullUp, PullDown, Disabled };

struct GpioMap {
  std::string chip_path = "/dev/gpiochip0";
  double pacer_hz = 20'000;  // the rate the profile's step generator times words for

  // Output-word bits not listed here are ignored. One bit may drive several lines (the two
  // drivers of a ganged axis); a line is driven by one bit only.
  std::vector<OutputLine> outputs;
  std::vector<InputLine> inputs;  // input-word bits not listed here read 0
  InputBias input_bias = InputBias::AsIs;

  // The level every output line is requested with: the profile's idle word, so that opening
  // the card makes no step edge on an active-low step line.
  std::uint32_t initial_word = 0;

  // Input-word bits that stop the card by themselves: an E-stop bit while active
  // (CardFault::EStop), a limit bit as it becomes active (CardFault::Limit); of those, the
  // bits in active_low_bits are active when their line reads low.
  std::uint32_t estop_bits = 0;
  std::uint32_t limit_bits = 0;
  std::uint32_t active_low_bits = 0;
  // When a limit bit trips the card: the profile's [limits] (travel_only, debounce in input
  // samples), the rule every card applies; default: any limit bit as it becomes active.
  LimitFilter limit_rule;
  // The cushioned stop (limits.cushion_steps after a limit trip, and the words' pins and
  // pulse width for limits.esc_steps too); default: a dead stop.
  CushionRule cushion;

  double input_sample_hz = 1'000;     // inputs are read every pacer_hz / input_sample_hz ticks
  double late_tolerance_ticks = 0.5;  // a tick played later than this counts as late

  // The queue between write() and the player: a power of two. A stream starts playing once
  // start_words are queued (or drain() is called), so the producer has a head start.
  std::size_t queue_words = std::size_t{1} << 16;
  std::size_t start_words = std::size_t{1} << 15;

  // Real-time set-up of the player thread: SCHED_FIFO at rt_priority and mlockall() when
  // permitted (the card reports whether it got them), pinned to `cpu` when >= 0.
  bool realtime = true;
  int rt_priority = 80;
  int cpu = -1;
};

// Every problem with `map`, each a complete sentence; empty when it is usable. With
// `chip_lines`, also checks that every offset exists on a chip with that many lines.
std::vector<std::string> validate_gpio_map(const GpioMap& map,
                                           std::optional<unsigned> chip_lines = std::nullopt);

// Why the card cannot pace at `pacer_hz`, or nullopt when it can.
std::optional<std::string> pacer_rate_problem(double pacer_hz);

// The messages joined one per line, for a single error string.
std::string join_lines(const std::vector<std::string>& messages);

}  // namespace gantry
