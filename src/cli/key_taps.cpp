// The terminal keypad's tap-or-hold rule (docs/console.md, "Taps and held keys").
#include "key_taps.hpp"

namespace gantry::console {

KeyTaps::Meaning KeyTaps::key(std::uint32_t key, Clock::time_point now) {
  const std::optional<Event> before = last_;
  last_ = Event{key, now};
  if (!before || before->key != key || now - before->at > repeat_delay_) {
    waiting_ = false;  // another key, or a pause longer than any repeat delay: a press
    return Meaning::Step;
  }
  if (now - before->at <= release_) {
    waiting_ = false;  // a repeat: nobody taps this fast
    return Meaning::Held;
  }
  // Within the repeat delay but slower than repeats: a second tap, or the terminal's first
  // repeat of a key held since the last press. The next event, or its absence, tells.
  waiting_ = true;
  return Meaning::Wait;
}

bool KeyTaps::step_due(Clock::time_point now) {
  if (!waiting_ || !last_ || now - last_->at <= release_) return false;
  waiting_ = false;
  return true;
}

bool KeyTaps::held(std::uint32_t key, Clock::time_point now) const {
  return last_ && last_->key == key && now - last_->at <= release_;
}

}  // namespace gantry::console
