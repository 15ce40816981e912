// Formatting of located diagnostics.
#include "gantry/core/diagnostic.hpp"

#include <fmt/format.h>  // message formatting

#include "gantry/core/any_bytes.hpp"  // escaped_bytes: a message may quote any bytes

namespace gantry {

std::string format(const Diagnostic& d) {
  std::string out;
  for (const SourceLoc& c : d.via)
    if (c.file) out += fmt::format("{}:{} -> ", escaped_bytes(*c.file), c.line);
  if (d.loc.file) {
    out += escaped_bytes(*d.loc.file);
    if (d.loc.line > 0) out += fmt::format(":{}", d.loc.line);
    if (d.loc.line > 0 && d.loc.column > 0) out += fmt::format(":{}", d.loc.column);
    out += ": ";
  }
  out += d.severity == Severity::Error ? "error: " : "warning: ";
  out += escaped_bytes(d.message);
  return out;
}

GantryError::GantryError(Diagnostic d) : std::runtime_error(format(d)), diag_(std::move(d)) {}

void append_once(std::vector<Diagnostic>& list, Diagnostic d) {
  const std::string text = format(d);
  for (const Diagnostic& o : list)
    if (format(o) == text) return;
  list.push_back(std::move(d));
}

void fail(const SourceLoc& loc, std::string message) {
  throw GantryError(Diagnostic{loc, Severity::Error, std::move(message)});
}

SourceLoc file_loc(const std::string& file, int line, int column) {
  return SourceLoc{std::make_shared<const std::string>(file), line, column};
}

}  // namespace gantry
