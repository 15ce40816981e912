// Real GPIO lines through the libgpiod v1 C API.
#include "gpiod/libgpiod_lines.hpp"

#include <fmt/format.h>
#include <gpiod.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <vector>

namespace gantry {
namespace {

constexpr const char* kConsumer = "gantry";
constexpr const char* kSeeReadme = "see drivers/gpiod/README.md";

int bias_flags(InputBias bias) {
  switch (bias) {
    case InputBias::AsIs:
      return 0;
    case InputBias::PullUp:
      return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
    case InputBias::PullDown:
      return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
    case InputBias::Disabled:
      return GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
  }
  return 0;
}

struct ChipCloser {
  void operator()(gpiod_chip* chip) const { gpiod_chip_close(chip); }
};
using ChipPtr = std::unique_ptr<gpiod_chip, ChipCloser>;

ChipPtr open_chip(const std::string& path, std::string* error) {
  errno = 0;
  ChipPtr chip(gpiod_chip_open(path.c_str()));
  if (!chip && error) *error = chip_open_error(path, errno);
  return chip;
}

}  // namespace

std::string chip_open_error(const std::string& path, int err) {
  switch (err) {
    case ENOENT:
      return fmt::format(
          "{}: no such GPIO chip; list the chips with `gpiodetect` (Debian package gpiod) and "
          "set the chip path; {}",
          path, kSeeReadme);
    case EACCES:
    case EPERM:
      return fmt::format("{}: permission denied; add the user to the gpio group or a udev rule; {}",
                         path, kSeeReadme);
    case ENOTTY:
    case ENODEV:
    case EISDIR:
      return fmt::format(
          "{}: not a GPIO character device (expected /dev/gpiochipN; see `gpiodetect`); {}", path,
          kSeeReadme);
    default:
      return fmt::format("{}: cannot open the GPIO chip: {}; {}", path, std::strerror(err),
                         kSeeReadme);
  }
}

std::optional<ChipInfo> probe_gpio_chip(const std::string& path, std::string* error) {
  ChipPtr chip = open_chip(path, error);
  if (!chip) return std::nullopt;
  const char* label = gpiod_chip_label(chip.get());
  return ChipInfo{gpiod_chip_num_lines(chip.get()), label ? label : ""};
}

struct LibgpiodLines::Handles {
  ChipPtr chip;
  unsigned chip_lines = 0;
  gpiod_line_bulk outputs = GPIOD_LINE_BULK_INITIALIZER;
  gpiod_line_bulk inputs = GPIOD_LINE_BULK_INITIALIZER;
  bool outputs_requested = false, inputs_requested = false;
  // The levels last sent: the v1 uAPI takes a value for every line of the request.
  std::array<int, GPIOD_LINE_BULK_MAX_LINES> output_values{};
  std::array<int, GPIOD_LINE_BULK_MAX_LINES> input_values{};

  ~Handles() {
    if (outputs_requested) gpiod_line_release_bulk(&outputs);
    if (inputs_requested) gpiod_line_release_bulk(&inputs);
  }
};

namespace {

// Finds the lines at `offsets`, refusing any another consumer holds (naming it).
bool get_free_lines(gpiod_chip* chip, const std::string& path, const std::vector<unsigned>& offsets,
                    gpiod_line_bulk* bulk, std::string* error) {
  gpiod_line_bulk_init(bulk);
  if (offsets.empty()) return true;
  if (gpiod_chip_get_lines(chip, const_cast<unsigned*>(offsets.data()),
                           static_cast<unsigned>(offsets.size()), bulk) != 0) {
    *error =
        fmt::format("{}: cannot look up lines: {}; {}", path, std::strerror(errno), kSeeReadme);
    return false;
  }
  for (unsigned i = 0; i < offsets.size(); ++i) {
    gpiod_line* line = gpiod_line_bulk_get_line(bulk, i);
    if (!gpiod_line_is_used(line)) continue;
    const char* consumer = gpiod_line_consumer(line);
    *error = fmt::format(
        "{}: line {} is in use by \"{}\"; free it (stop that program, or remove the kernel "
        "driver or overlay that claims it; see `gpioinfo`) or map another line",
        path, offsets[i], consumer ? consumer : "the kernel");
    return false;
  }
  return true;
}

std::string request_error(const std::string& path, const char* what, int err) {
  if (err == EBUSY)
    return fmt::format("{}: {} lines are in use by another program (see `gpioinfo`)", path, what);
  if (err == EINVAL && std::strcmp(what, "input") == 0)
    return fmt::format(
        "{}: cannot request the input lines: {} (input bias needs Linux 5.5 or later; try "
        "input_bias as-is)",
        path, std::strerror(err));
  return fmt::format("{}: cannot request the {} lines: {}", path, what, std::strerror(err));
}

}  // namespace

std::unique_ptr<LibgpiodLines> LibgpiodLines::open(const GpioMap& map, std::string* error) {
  std::string message;
  if (!error) error = &message;
  if (auto problems = validate_gpio_map(map); !problems.empty()) {
    *error = join_lines(problems);
    return nullptr;
  }
  auto h = std::make_unique<Handles>();
  h->chip = open_chip(map.chip_path, error);
  if (!h->chip) return nullptr;
  h->chip_lines = gpiod_chip_num_lines(h->chip.get());
  if (auto problems = validate_gpio_map(map, h->chip_lines); !problems.empty()) {
    *error = join_lines(problems);
    return nullptr;
  }

  std::vector<unsigned> out_offsets, in_offsets;
  for (std::size_t i = 0; i < map.outputs.size(); ++i) {
    out_offsets.push_back(map.outputs[i].offset);
    h->output_values[i] = static_cast<int>((map.initial_word >> map.outputs[i].bit) & 1u);
  }
  for (const InputLine& in : map.inputs) in_offsets.push_back(in.offset);
  if (!get_free_lines(h->chip.get(), map.chip_path, out_offsets, &h->outputs, error) ||
      !get_free_lines(h->chip.get(), map.chip_path, in_offsets, &h->inputs, error))
    return nullptr;

  if (gpiod_line_request_bulk_output(&h->outputs, kConsumer, h->output_values.data()) != 0) {
    *error = request_error(map.chip_path, "output", errno);
    return nullptr;
  }
  h->outputs_requested = true;
  if (!in_offsets.empty()) {
    if (gpiod_line_request_bulk_input_flags(&h->inputs, kConsumer, bias_flags(map.input_bias)) !=
        0) {
      *error = request_error(map.chip_path, "input", errno);
      return nullptr;
    }
    h->inputs_requested = true;
  }
  return std::unique_ptr<LibgpiodLines>(new LibgpiodLines(std::move(h)));
}

LibgpiodLines::LibgpiodLines(std::unique_ptr<Handles> handles) : h_(std::move(handles)) {}

LibgpiodLines::~LibgpiodLines() = default;

unsigned LibgpiodLines::chip_lines() const {
  return h_->chip_lines;
}

bool LibgpiodLines::set_outputs(std::uint64_t changed, std::uint64_t levels) {
  if (!changed) return true;
  const unsigned n = gpiod_line_bulk_num_lines(&h_->outputs);
  for (unsigned i = 0; i < n; ++i)
    if ((changed >> i) & 1u) h_->output_values[i] = static_cast<int>((levels >> i) & 1u);
  return gpiod_line_set_value_bulk(&h_->outputs, h_->output_values.data()) == 0;
}

bool LibgpiodLines::read_inputs(std::uint64_t& levels) {
  levels = 0;
  const unsigned n = gpiod_line_bulk_num_lines(&h_->inputs);
  if (n == 0) return true;
  if (gpiod_line_get_value_bulk(&h_->inputs, h_->input_values.data()) != 0) return false;
  for (unsigned i = 0; i < n; ++i)
    if (h_->input_values[i]) levels |= std::uint64_t{1} << i;
  return true;
}

}  // namespace gantry
