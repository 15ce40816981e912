// A gamepad read through evdev: open and probe the device, then decode its events.
#include "gamepad/evdev_gamepad.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace gantry {

std::optional<GamepadEvent> EvdevDecoder::decode(const input_event& e) {
  if (e.type == EV_SYN) {
    if (e.code == SYN_DROPPED) {
      dropping_ = true;
      axes_.clear();  // what the sticks read is unknown until they next move
      return GamepadEvent{GamepadEvent::Kind::Lost, 0, 0};
    }
    if (e.code == SYN_REPORT) dropping_ = false;
    return std::nullopt;
  }
  if (dropping_) return std::nullopt;  // the rest of a broken report
  if (e.type == EV_KEY) {
    if (e.value == 2) return std::nullopt;  // auto-repeat: the button is still held
    return GamepadEvent{GamepadEvent::Kind::Button, e.code, e.value ? 1.0 : 0.0};
  }
  if (e.type == EV_ABS) {
    const auto r = ranges_.find(e.code);
    const double v = normalised_axis(e.value, r == ranges_.end() ? AxisRange{} : r->second);
    const auto [it, fresh] = axes_.try_emplace(e.code, v);
    if (!fresh && it->second == v) return std::nullopt;
    it->second = v;
    return GamepadEvent{GamepadEvent::Kind::Axis, e.code, v};
  }
  return std::nullopt;
}

namespace {

constexpr size_t kLong = 8 * sizeof(unsigned long);
template <size_t Bits>
using BitSet = std::array<unsigned long, (Bits + kLong - 1) / kLong>;

template <size_t Bits>
bool has(const BitSet<Bits>& set, int bit) {
  return (set[bit / kLong] >> (bit % kLong)) & 1;
}

struct Probe {
  BitSet<ABS_MAX + 1> axes{};
  bool gamepad = false;  // gamepad or joystick buttons, or a stick
};

// What kind of device `fd` is; false when it is not an input device at all.
bool probe(int fd, Probe& p) {
  BitSet<EV_MAX + 1> types{};
  BitSet<KEY_MAX + 1> keys{};
  if (ioctl(fd, EVIOCGBIT(0, sizeof types), types.data()) < 0) return false;
  if (has<EV_MAX + 1>(types, EV_KEY)) ioctl(fd, EVIOCGBIT(EV_KEY, sizeof keys), keys.data());
  if (has<EV_MAX + 1>(types, EV_ABS)) ioctl(fd, EVIOCGBIT(EV_ABS, sizeof p.axes), p.axes.data());
  const bool buttons = has<KEY_MAX + 1>(keys, BTN_GAMEPAD) || has<KEY_MAX + 1>(keys, BTN_JOYSTICK);
  // A touchpad or tablet has ABS_X too, but also BTN_TOUCH or BTN_TOOL_*; those are not sticks.
  const bool pointer = has<KEY_MAX + 1>(keys, BTN_TOUCH) || has<KEY_MAX + 1>(keys, BTN_TOOL_PEN) ||
                       has<KEY_MAX + 1>(keys, BTN_TOOL_FINGER);
  const bool stick = !pointer && (has<ABS_MAX + 1>(p.axes, ABS_X) ||
                                  has<ABS_MAX + 1>(p.axes, ABS_HAT0X));
  p.gamepad = buttons || stick;
  return true;
}

}  // namespace

std::unique_ptr<EvdevGamepad> EvdevGamepad::open(const std::string& path, std::string* error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == EACCES || err == EPERM)
      *error = "cannot open the gamepad " + path + ": " + std::strerror(err) +
               ". Add your user to the 'input' group (sudo usermod -aG input $USER, then log in "
               "again), or install Gantry's udev rule (docs/hardware.md, \"A gamepad as a pendant\")";
    else
      *error = "cannot open the gamepad " + path + ": " + std::strerror(err) +
               ". Check that it is plugged in (ls -l /dev/input/by-id)";
    return nullptr;
  }
  Probe p;
  if (!probe(fd, p) || !p.gamepad) {
    ::close(fd);
    *error = path + " is not a gamepad or joystick (it has no stick and no gamepad buttons)";
    return nullptr;
  }
  std::array<char, 256> name{};
  if (ioctl(fd, EVIOCGNAME(name.size() - 1), name.data()) < 0) name[0] = 0;
  std::unique_ptr<EvdevGamepad> g(new EvdevGamepad(fd, path, name.data()));
  for (int code = 0; code <= ABS_MAX; ++code) {
    input_absinfo info{};
    if (has<ABS_MAX + 1>(p.axes, code) && ioctl(fd, EVIOCGABS(code), &info) == 0)
      g->decoder_.set_range(code, {info.minimum, info.maximum, info.flat});
  }
  return g;
}

std::vector<std::string> EvdevGamepad::find(const std::string& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const auto path = entry.path().string();
    if (!entry.path().filename().string().starts_with("event")) continue;
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    Probe p;
    if (probe(fd, p) && p.gamepad) found.push_back(path);
    ::close(fd);
  }
  std::sort(found.begin(), found.end());
  return found;
}

EvdevGamepad::EvdevGamepad(int fd, std::string path, std::string name)
    : fd_(fd), path_(std::move(path)), name_(std::move(name)) {}

EvdevGamepad::~EvdevGamepad() { ::close(fd_); }

bool EvdevGamepad::read(std::vector<GamepadEvent>& out) {
  std::array<input_event, 64> buf;
  for (;;) {
    const ssize_t n = ::read(fd_, buf.data(), sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    if (n <= 0) {  // ENODEV: unplugged; end of file: the same for a device node
      out.push_back({GamepadEvent::Kind::Lost, 0, 0});
      return false;
    }
    for (size_t i = 0; i < static_cast<size_t>(n) / sizeof(input_event); ++i)
      if (auto e = decoder_.decode(buf[i])) out.push_back(*e);
  }
}

}  // namespace gantry
