// In-memory GPIO lines for the card's tests.
#include "gpiod/fake_gpio_lines.hpp"

#include <cerrno>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace gantry {

FakeGpioLines::FakeGpioLines(const GpioMap& map) {
  for (const OutputLine& out : map.outputs) {
    output_offsets_.push_back(out.offset);
    output_levels_.push_back((map.initial_word >> out.bit) & 1u);
  }
  for (const InputLine& in : map.inputs) {
    input_offsets_.push_back(in.offset);
    input_schedule_[in.offset][0] = 0;
  }
}

bool FakeGpioLines::set_outputs(std::uint64_t changed, std::uint64_t levels) {
  std::lock_guard lock(mutex_);
  ++write_calls_;
  if (write_error_) {
    errno = std::exchange(write_error_, 0);
    return false;
  }
  for (std::size_t i = 0; i < output_offsets_.size(); ++i) {
    if (!((changed >> i) & 1u)) continue;
    const int level = static_cast<int>((levels >> i) & 1u);
    output_levels_[i] = level;
    changes_.push_back({now(), output_offsets_[i], level});
  }
  return true;
}

bool FakeGpioLines::read_inputs(std::uint64_t& levels) {
  std::lock_guard lock(mutex_);
  ++read_calls_;
  if (read_error_) {
    errno = std::exchange(read_error_, 0);
    return false;
  }
  const std::uint64_t tick = now();
  levels = 0;
  for (std::size_t i = 0; i < input_offsets_.size(); ++i) {
    const auto& schedule = input_schedule_.at(input_offsets_[i]);
    auto it = schedule.upper_bound(tick);  // the last change at or before `tick`
    if (std::prev(it)->second) levels |= std::uint64_t{1} << i;
  }
  return true;
}

void FakeGpioLines::set_tick_source(std::function<std::uint64_t()> tick) {
  std::lock_guard lock(mutex_);
  tick_ = std::move(tick);
}

void FakeGpioLines::set_input(unsigned offset, int level, std::uint64_t from_tick) {
  std::lock_guard lock(mutex_);
  auto it = input_schedule_.find(offset);
  if (it == input_schedule_.end()) throw std::invalid_argument("not an input line of the map");
  it->second[from_tick] = level ? 1 : 0;
}

void FakeGpioLines::fail_next_write(int error) {
  std::lock_guard lock(mutex_);
  write_error_ = error;
}

void FakeGpioLines::fail_next_read(int error) {
  std::lock_guard lock(mutex_);
  read_error_ = error;
}

std::vector<LineChange> FakeGpioLines::changes() const {
  std::lock_guard lock(mutex_);
  return changes_;
}

int FakeGpioLines::level(unsigned offset) const {
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < output_offsets_.size(); ++i)
    if (output_offsets_[i] == offset) return output_levels_[i];
  throw std::invalid_argument("not an output line of the map");
}

std::uint64_t FakeGpioLines::write_calls() const {
  std::lock_guard lock(mutex_);
  return write_calls_;
}

std::uint64_t FakeGpioLines::read_calls() const {
  std::lock_guard lock(mutex_);
  return read_calls_;
}

}  // namespace gantry
