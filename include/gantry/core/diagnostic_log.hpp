// What a check found: its errors and warnings, each once, up to a cap, the rest counted.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // Diagnostic

namespace gantry {

// What a check found. Each error is kept once per line (a statement in a loop fails on every
// pass; a line refused once may fail again for another reason), each warning once per place
// and text, and at most `max_errors` errors: the check stops there, and the errors found
// beyond it are only counted, by kind, for one summary line. Adding takes constant time, so
// a file with many errors is checked in time linear in their number.
class DiagnosticLog {
 public:
  explicit DiagnosticLog(std::size_t max_errors = 0) : max_errors_(max_errors) {}  // 0: no cap
  // Keeps `d` unless it repeats one kept; an error beyond the cap is counted instead. Returns
  // whether `d` was kept.
  bool add(Diagnostic d);
  // The cap is reached: a check goes no further.
  bool full() const { return max_errors_ > 0 && errors_ >= max_errors_; }
  // The check did not reach the end of the file (an operator answer it does not have, the
  // statement budget, a signal): `why` is kept as well, and the first such reason is given
  // by stopped_short().
  void stop_short(Diagnostic why);
  const std::optional<Diagnostic>& stopped_short() const { return stopped_; }
  // Errors and warnings kept, in the order found.
  std::vector<Diagnostic>& kept() { return kept_; }
  const std::vector<Diagnostic>& kept() const { return kept_; }
  bool has_errors() const { return errors_ > 0; }
  std::size_t omitted() const { return omitted_; }  // errors found beyond the cap
  // The errors beyond the cap in one line, "" when there were none: "stopped after 100
  // errors; 25,641 more not shown: 25,000 'unknown command', 641 'end is not on the circle'".
  std::string summary() const;

 private:
  std::size_t max_errors_;
  std::size_t errors_ = 0, omitted_ = 0;
  std::vector<Diagnostic> kept_;
  std::unordered_set<std::string> seen_;  // the keys of what was kept
  std::unordered_map<std::string, std::size_t> omitted_kinds_;
  std::optional<Diagnostic> stopped_;
};

// The kind of an error, for counting many of one: its message before the first ';' or
// " (", without quoted text, each word with a digit in it as '#' ("unknown command 'QQ'; see
// ..." -> "unknown command").
std::string diagnostic_kind(std::string_view message);

}  // namespace gantry
