// The pendant's USB seam over libusb-1.0 (Debian's libusb-1.0-0-dev).
#include "pendant/usb_port.hpp"

#ifdef GANTRY_HAVE_LIBUSB
#include <libusb.h>

#include <fmt/format.h>

namespace gantry::pendant {
namespace {

UsbPort::Status status_of(int r) {
  switch (r) {
    case LIBUSB_SUCCESS: return UsbPort::Status::Ok;
    case LIBUSB_ERROR_TIMEOUT: return UsbPort::Status::Timeout;
    case LIBUSB_ERROR_NO_DEVICE:
    case LIBUSB_ERROR_NOT_FOUND: return UsbPort::Status::NoDevice;
    case LIBUSB_ERROR_ACCESS: return UsbPort::Status::Denied;
    default: return UsbPort::Status::Error;
  }
}

class LibusbPort final : public UsbPort {
 public:
  explicit LibusbPort(libusb_context* ctx) : ctx_(ctx) {}
  ~LibusbPort() override {
    close();
    libusb_exit(ctx_);
  }

  Status open(std::uint16_t vendor, std::uint16_t product, std::string* why) override {
    close();
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx_, &list);
    if (n < 0) {
      if (why) *why = libusb_strerror(static_cast<int>(n));
      return Status::Error;
    }
    Status st = Status::NoDevice;
    for (ssize_t i = 0; i < n && st == Status::NoDevice; ++i) {
      libusb_device_descriptor d{};
      if (libusb_get_device_descriptor(list[i], &d) != 0 || d.idVendor != vendor ||
          d.idProduct != product)
        continue;
      const int r = libusb_open(list[i], &handle_);
      if (r != 0) {
        handle_ = nullptr;
        st = status_of(r);
        if (why)
          *why = fmt::format("/dev/bus/usb/{:03}/{:03}: {}", libusb_get_bus_number(list[i]),
                             libusb_get_device_address(list[i]), libusb_strerror(r));
        break;
      }
      st = Status::Ok;
    }
    libusb_free_device_list(list, 1);
    if (st != Status::Ok) return st;
    libusb_set_auto_detach_kernel_driver(handle_, 1);  // usbhid holds it as a keyboard
    const int r = libusb_claim_interface(handle_, 0);
    claimed_ = r == 0;
    // Held by another program, gone, or not ours to take: no pendant. Any other refusal (an
    // emulated device, umockdev's, answers none): usbfs claims the interface at the first
    // transfer, which says soon enough whether it can be had.
    if (r == LIBUSB_ERROR_BUSY || r == LIBUSB_ERROR_NO_DEVICE || r == LIBUSB_ERROR_ACCESS) {
      if (why) *why = fmt::format("cannot claim its interface: {}", libusb_strerror(r));
      close();
      return r == LIBUSB_ERROR_BUSY ? Status::Error : status_of(r);
    }
    return Status::Ok;
  }

  Status read(std::span<std::uint8_t> buf, int* got, int timeout_ms) override {
    if (!handle_) return Status::NoDevice;
    *got = 0;
    return status_of(libusb_interrupt_transfer(handle_, 0x81, buf.data(),
                                               static_cast<int>(buf.size()), got,
                                               static_cast<unsigned>(timeout_ms)));
  }

  Status write(std::span<const std::uint8_t> block) override {
    if (!handle_) return Status::NoDevice;
    // HID SET_REPORT (class request to the interface), output report 0x06.
    const int r = libusb_control_transfer(
        handle_, 0x21,  // class request, to the interface, host to device
        0x09, 0x0306, 0, const_cast<std::uint8_t*>(block.data()),
        static_cast<std::uint16_t>(block.size()), 100);
    return r < 0 ? status_of(r) : Status::Ok;
  }

  void close() override {
    if (!handle_) return;
    if (claimed_) libusb_release_interface(handle_, 0);
    claimed_ = false;
    libusb_close(handle_);
    handle_ = nullptr;
  }

 private:
  libusb_context* ctx_;
  libusb_device_handle* handle_ = nullptr;
  bool claimed_ = false;
};

}  // namespace

std::unique_ptr<UsbPort> open_libusb_port(std::string* why) {
  libusb_context* ctx = nullptr;
  if (const int r = libusb_init(&ctx); r != 0) {
    if (why) *why = fmt::format("libusb cannot start: {}", libusb_strerror(r));
    return nullptr;
  }
  return std::make_unique<LibusbPort>(ctx);
}

}  // namespace gantry::pendant

#else

namespace gantry::pendant {

std::unique_ptr<UsbPort> open_libusb_port(std::string* why) {
  if (why) *why = "this Gantry was built without libusb (GANTRY_USB=OFF)";
  return nullptr;
}

}  // namespace gantry::pendant

#endif
