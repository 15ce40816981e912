// The window keypad's tap-or-hold rule (jog_press.hpp).
#include "jog_press.hpp"

namespace gantry::ui {

void JogPress::press(int id, Clock::time_point now) {
  id_ = id;
  pressed_at_ = now;
  continuous_ = false;
}

bool JogPress::start_continuous(Clock::time_point now, bool at_rest) {
  if (id_ < 0 || continuous_ || !at_rest || now - pressed_at_ < hold_) return false;
  continuous_ = true;
  return true;
}

bool JogPress::release(int id) {
  if (id != id_) return false;
  const bool was = continuous_;
  reset();
  return was;
}

}  // namespace gantry::ui
