// GPIO lines of a real chip through libgpiod v1 (the GPIO character device): the map's output
// lines requested as one bulk, its input lines as another, with consumer name "gantry".
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "gpiod/gpio_lines.hpp"
#include "gpiod/gpio_map.hpp"

namespace gantry {

class LibgpiodLines : public GpioLines {
 public:
  // Opens map.chip_path and requests its lines; nullptr with a message naming the fix in
  // `error` when the chip is missing or not accessible, an offset is not on it, or a line is
  // in use. Checks the map first (validate_gpio_map with the chip's line count).
  static std::unique_ptr<LibgpiodLines> open(const GpioMap& map, std::string* error);
  ~LibgpiodLines() override;

  // The kernel's v1 uAPI sets every line of a request in one ioctl, so the unchanged lines
  // are sent at their current level (which changes nothing on the pin); nothing is sent when
  // no line changed.
  bool set_outputs(std::uint64_t changed, std::uint64_t levels) override;
  bool read_inputs(std::uint64_t& levels) override;

  unsigned chip_lines() const;

 private:
  struct Handles;
  explicit LibgpiodLines(std::unique_ptr<Handles> handles);
  std::unique_ptr<Handles> h_;
};

struct ChipInfo {
  unsigned lines = 0;
  std::string label;  // the kernel's name for the chip, such as "pinctrl-bcm2711"
};
// Opens the chip at `path` only to describe it; nullopt with the reason (worded as open()
// words it) in `error`.
std::optional<ChipInfo> probe_gpio_chip(const std::string& path, std::string* error);

// The message for failing to open chip `path` with errno `err`, naming the fix.
std::string chip_open_error(const std::string& path, int err);

}  // namespace gantry
