// Source locations and located messages: every error an operator sees says where and what.
#pragma once

#include <memory>     // shared_ptr for the file name shared by all locations of a file
#include <stdexcept>  // runtime_error base for GantryError
#include <string>
#include <vector>

namespace gantry {

struct SourceLoc {
  std::shared_ptr<const std::string> file;  // null for locations outside any file
  int line = 0;                             // 1-based; 0 = unknown
  int column = 0;                           // 1-based; 0 = whole line
  // Only on a move of a file the run called (FP, C#): the run's top-level line that called
  // it, which the progress shows while the card plays the move (the reader is ahead by then).
  int caller_line = 0;
};

enum class Severity { Error, Warning };

struct Diagnostic {
  Diagnostic() = default;
  Diagnostic(SourceLoc l, Severity s, std::string m, std::vector<SourceLoc> v = {})
      : loc(std::move(l)), severity(s), message(std::move(m)), via(std::move(v)) {}

  SourceLoc loc;
  Severity severity = Severity::Error;
  std::string message;
  std::vector<SourceLoc> via;  // the calling lines of nested files, outermost first
};

// "FILE:LINE:COL: error: MESSAGE", omitting the parts that are unknown; a diagnostic in a
// nested file starts with its callers: "outer.sbp:12 -> inner.sbp:4:9: error: ...".
std::string format(const Diagnostic& d);

// Thrown by every layer for an operator-facing error; carries its location.
class GantryError : public std::runtime_error {
 public:
  explicit GantryError(Diagnostic d);
  const Diagnostic& diagnostic() const { return diag_; }

 private:
  Diagnostic diag_;
};

// Appends `d` unless the same message at the same place is already there (a statement in a
// loop fails on every pass; a check says it once).
void append_once(std::vector<Diagnostic>& list, Diagnostic d);

// Convenience: throw a located error.
[[noreturn]] void fail(const SourceLoc& loc, std::string message);

// A location naming only a file (for files that cannot be read, say).
SourceLoc file_loc(const std::string& file, int line = 0, int column = 0);

}  // namespace gantry
