// A Linux gamepad or joystick read through the kernel's evdev interface (/dev/input/event*),
// with no library beyond linux/input.h: its buttons and sticks as GamepadEvents.
#pragma once

#include <linux/input.h>  // input_event

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gamepad/gamepad_event.hpp"

namespace gantry {

// input_event -> GamepadEvent, apart from the device so that it is tested with made-up
// events. A dropped-events marker (SYN_DROPPED: the kernel's buffer overflowed) reads as
// Lost, since whatever was held may have been let go unseen: the bindings end every jog.
class EvdevDecoder {
 public:
  void set_range(int abs_code, const AxisRange& range) { ranges_[abs_code] = range; }
  // The event an input_event makes, if any (auto-repeat, sync and unchanged axes make none).
  std::optional<GamepadEvent> decode(const input_event& e);

 private:
  std::map<int, AxisRange> ranges_;
  std::map<int, double> axes_;  // last value sent per axis: a stick's jitter inside its dead zone says nothing
  bool dropping_ = false;       // after SYN_DROPPED, until the next SYN_REPORT
};

class EvdevGamepad {
 public:
  // Opens `path` non-blocking and reads its sticks' ranges. Null with `error` set (naming the
  // device and the fix) when it cannot be opened or is not a gamepad or joystick.
  static std::unique_ptr<EvdevGamepad> open(const std::string& path, std::string* error);
  // The event devices under `dir` that have a stick or gamepad buttons, sorted.
  static std::vector<std::string> find(const std::string& dir = "/dev/input");

  ~EvdevGamepad();
  EvdevGamepad(const EvdevGamepad&) = delete;
  EvdevGamepad& operator=(const EvdevGamepad&) = delete;

  const std::string& name() const { return name_; }
  const std::string& path() const { return path_; }
  int fd() const { return fd_; }  // for poll()
  // Appends what is waiting, without blocking. False once the device is gone (unplugged):
  // `out` then ends with a Lost event.
  bool read(std::vector<GamepadEvent>& out);

 private:
  EvdevGamepad(int fd, std::string path, std::string name);
  int fd_;
  std::string path_, name_;
  EvdevDecoder decoder_;
};

}  // namespace gantry
