// Validation of the GPIO line map: every problem found, each named precisely.
#include "gpiod/gpio_map.hpp"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <map>

namespace gantry {
namespace {

// libgpiod v1 requests at most this many lines at once (GPIOD_LINE_BULK_MAX_LINES); outputs
// and inputs are one request each.
constexpr std::size_t kMaxLinesPerRequest = 64;
constexpr std::size_t kMinQueueWords = 16;
constexpr std::size_t kMaxQueueWords = std::size_t{1} << 24;
constexpr double kMinInputSampleHz = 10;

bool bit_in_range(int bit) {
  return bit >= 0 && bit < 32;
}

std::string bits_text(std::uint32_t bits) {
  std::string s;
  for (int b = 0; b < 32; ++b)
    if (bits & (1u << b)) s += fmt::format("{}{}", s.empty() ? "" : ", ", b);
  return s;
}

}  // namespace

std::optional<std::string> pacer_rate_problem(double pacer_hz) {
  if (!std::isfinite(pacer_hz) || pacer_hz <= 0)
    return fmt::format("gpiod: pacer rate {} Hz is not a positive rate", pacer_hz);
  if (pacer_hz > kGpiodMaxPacerHz)
    return fmt::format(
        "gpiod: pacer rate {:g} Hz is above the GPIO card's maximum of {:g} Hz: ticks are "
        "timed in software through the GPIO character device, which cannot keep ticks that "
        "short; set the profile's [card] clock_hz / pacer_divisor to {:g} Hz or less "
        "(see drivers/gpiod/README.md)",
        pacer_hz, kGpiodMaxPacerHz, kGpiodMaxPacerHz);
  return std::nullopt;
}

std::vector<std::string> validate_gpio_map(const GpioMap& map, std::optional<unsigned> chip_lines) {
  std::vector<std::string> errors;
  auto error = [&](std::string message) { errors.push_back("gpiod: " + std::move(message)); };

  if (map.chip_path.empty()) error("no chip path (such as /dev/gpiochip0)");
  if (auto problem = pacer_rate_problem(map.pacer_hz)) errors.push_back(*problem);

  // Each line offset has one user; the first one named is kept for the message.
  std::map<unsigned, std::string> line_users;
  auto use_line = [&](unsigned offset, const std::string& user) {
    auto [it, inserted] = line_users.emplace(offset, user);
    if (!inserted)
      error(fmt::format("line {} is used twice ({} and {})", offset, it->second, user));
    if (chip_lines && offset >= *chip_lines)
      error(fmt::format("line {} ({}) is not on {}: it has {} lines, 0-{}", offset, user,
                        map.chip_path, *chip_lines, *chip_lines == 0 ? 0 : *chip_lines - 1));
  };

  if (map.outputs.empty())
    error("no output lines: map at least each axis's step and direction bits");
  if (map.outputs.size() > kMaxLinesPerRequest)
    error(fmt::format("{} output lines; libgpiod drives at most {} at once", map.outputs.size(),
                      kMaxLinesPerRequest));
  for (const OutputLine& out : map.outputs) {
    if (!bit_in_range(out.bit))
      error(fmt::format("output bit {} (line {}) is out of range 0-31", out.bit, out.offset));
    use_line(out.offset, fmt::format("output bit {}", out.bit));
  }

  std::uint32_t input_bits = 0;
  for (const InputLine& in : map.inputs) {
    if (!bit_in_range(in.bit)) {
      error(fmt::format("input bit {} (line {}) is out of range 0-31", in.bit, in.offset));
    } else {
      if (input_bits & (1u << in.bit))
        error(fmt::format("input bit {} is set by two lines; each input bit has one line", in.bit));
      input_bits |= 1u << in.bit;
    }
    use_line(in.offset, fmt::format("input bit {}", in.bit));
  }

  if (std::uint32_t unread = (map.estop_bits | map.limit_bits) & ~input_bits)
    error(fmt::format(
        "E-stop/limit input bit(s) {} have no input line; map a line to each, or set the "
        "profile's bit to -1 (not wired)",
        bits_text(unread)));
  if (std::uint32_t both = map.estop_bits & map.limit_bits)
    error(fmt::format("input bit(s) {} are both E-stop and limit bits", bits_text(both)));
  if (std::uint32_t stray = map.active_low_bits & ~(map.estop_bits | map.limit_bits))
    error(fmt::format(
        "active-low bit(s) {} are neither E-stop nor limit bits (polarity of other inputs is "
        "the profile's business)",
        bits_text(stray)));

  if (!(map.input_sample_hz >= kMinInputSampleHz && map.input_sample_hz <= map.pacer_hz))
    error(fmt::format("input sample rate {:g} Hz is outside {:g} Hz to the pacer rate {:g} Hz",
                      map.input_sample_hz, kMinInputSampleHz, map.pacer_hz));
  if (!(map.late_tolerance_ticks >= 0 && std::isfinite(map.late_tolerance_ticks)))
    error(fmt::format("late tolerance {} ticks is not a non-negative number",
                      map.late_tolerance_ticks));
  if (!std::has_single_bit(map.queue_words) || map.queue_words < kMinQueueWords ||
      map.queue_words > kMaxQueueWords)
    error(fmt::format("queue of {} words is not a power of two from {} to {}", map.queue_words,
                      kMinQueueWords, kMaxQueueWords));
  if (map.start_words < 1 || map.start_words > map.queue_words)
    error(fmt::format("start threshold of {} words is outside 1 to the queue size {}",
                      map.start_words, map.queue_words));
  if (map.rt_priority < 1 || map.rt_priority > 99)
    error(fmt::format("real-time priority {} is outside 1-99", map.rt_priority));
  if (map.cpu < -1) error(fmt::format("cpu {} is not a CPU number (or -1 for any)", map.cpu));
  return errors;
}

std::string join_lines(const std::vector<std::string>& messages) {
  std::string out;
  for (const std::string& m : messages) {
    if (!out.empty()) out += '\n';
    out += m;
  }
  return out;
}

}  // namespace gantry
