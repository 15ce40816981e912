// Parameter values substituted into (PRINT,...), (DEBUG,...) and (ABORT,...) texts, in the
// form LinuxCNC's interpreter prints them (docs/gcode.md, "Blocks").
#include <fmt/format.h>

#include <cctype>  // tolower

#include "gantry/lang/gcode.hpp"

namespace gantry {
namespace {

// A parameter's value as `%lf` prints it; a value that rounds to zero prints without a sign,
// as rs274 prints -0.0000004.
std::string six_decimals(double v) {
  std::string s = fmt::format("{:.6f}", v);
  if (s == "-0.000000") s.erase(0, 1);
  return s;
}

constexpr std::string_view kNoValue = "######";
constexpr int kLastNumbered = 5601;  // LinuxCNC's numbered parameters are #0 to #5601

}  // namespace

std::string substitute_gcode_parameters(std::string_view text, const GcodeParameters& params) {
  std::string out;
  out.reserve(text.size());
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c != '#' || i + 1 >= text.size()) {
      out += c;
      ++i;
      continue;
    }
    if (text[i + 1] == '<') {
      const size_t close = text.find('>', i + 2);
      if (close == std::string_view::npos) {
        out += text.substr(i);
        break;
      }
      std::string name;
      for (size_t k = i + 2; k < close; ++k)
        if (text[k] != ' ' && text[k] != '\t')
          name += static_cast<char>(std::tolower(static_cast<unsigned char>(text[k])));
      const double* v = name.empty() ? nullptr : params.named(name);
      out += v ? six_decimals(*v) : std::string(kNoValue);
      i = close + 1;
      continue;
    }
    size_t j = i + 1;
    long n = 0;
    // Digits only: `#1.5` is #1 followed by ".5"; a long run of digits names nothing.
    while (j < text.size() && text[j] >= '0' && text[j] <= '9') {
      if (n <= kLastNumbered) n = n * 10 + (text[j] - '0');
      ++j;
    }
    if (j == i + 1) {  // `#` followed by anything else stays
      out += c;
      ++i;
      continue;
    }
    out += n <= kLastNumbered ? six_decimals(params.numbered(static_cast<int>(n), nullptr))
                              : std::string(kNoValue);
    i = j;
  }
  return out;
}

}  // namespace gantry
