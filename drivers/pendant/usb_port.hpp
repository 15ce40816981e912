// The seam between the pendant driver and libusb: the few USB operations the driver needs,
// so that tests play recorded report sequences through a fake.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace gantry::pendant {

class UsbPort {
 public:
  enum class Status : std::uint8_t {
    Ok,
    Timeout,   // nothing came in time (the pendant sends only when something changes)
    NoDevice,  // not plugged in, or unplugged
    Denied,    // plugged in, but this user may not open it (the udev rule is missing)
    Error,     // anything else: the report stream is lost
  };
  virtual ~UsbPort() = default;
  // Opens the first device `vendor`:`product` and claims its interface 0 (detaching a kernel
  // driver); `why` says why not (Denied: which device node).
  virtual Status open(std::uint16_t vendor, std::uint16_t product, std::string* why) = 0;
  // One input report from the interrupt IN endpoint 0x81, waiting at most `timeout_ms`.
  virtual Status read(std::span<std::uint8_t> buf, int* got, int timeout_ms) = 0;
  // One output report block (a HID SET_REPORT to interface 0, report 0x06).
  virtual Status write(std::span<const std::uint8_t> block) = 0;
  virtual void close() = 0;
};

// The libusb port; null with the reason when Gantry was built without libusb or libusb cannot
// start.
std::unique_ptr<UsbPort> open_libusb_port(std::string* why);

}  // namespace gantry::pendant
