// How a refused line or file is shown, at a terminal and in a log.
#include "gantry/session/refusal.hpp"

#include <fmt/format.h>

#include "gantry/session/source_place.hpp"  // kConsoleName

namespace gantry::session {
namespace {

// A diagnostic: under the line typed with a caret at its column, when it is located there;
// otherwise as `FILE:LINE:COL: error: ...`. `echo`: print the line again first.
std::string located(const std::string& prefix, const std::string& line, const Diagnostic& d,
                    bool echo) {
  if (!in_typed_line(d)) return format(d) + "\n";
  const char* what = d.severity == Severity::Error ? "error" : "warning";
  if (d.loc.column <= 0) return fmt::format("{}: {}\n", what, d.message);
  std::string out = echo ? prefix + line + "\n" : "";
  out += std::string(prefix.size() + static_cast<size_t>(d.loc.column) - 1, ' ') + "^\n";
  out += fmt::format("{}: column {}: {}\n", what, d.loc.column, d.message);
  return out;
}

}  // namespace

bool in_typed_line(const Diagnostic& d) {
  return d.loc.file && *d.loc.file == kConsoleName && d.loc.line == 1 && d.via.empty();
}

std::string refusal_under_line(const std::string& prompt, const std::string& line, const Outcome& o,
                               bool echo_first, bool estop) {
  if (o.errors.empty()) return o.reason + (estop ? " (type ack)\n" : "\n");
  std::string out;
  bool echo = echo_first;  // otherwise the line is on the screen just above the first caret
  for (const Diagnostic& d : o.errors) {
    out += located(prompt, line, d, echo);
    echo = true;
  }
  return out;
}

std::vector<std::string> refusal_entries(const Outcome& o, const std::string& what) {
  if (o.errors.empty()) return {fmt::format("{}: {}", what, o.reason)};
  std::vector<std::string> out;
  for (const Diagnostic& d : o.errors)
    out.push_back(in_typed_line(d) ? fmt::format("error: column {}: {}", d.loc.column, d.message)
                                   : format(d));
  return out;
}

}  // namespace gantry::session
