// Where a line is, as the operator is told.
#include "gantry/session/source_place.hpp"

#include <fmt/format.h>

namespace gantry::session {

std::string where(const SourceLoc& loc) {
  return loc.file && *loc.file != kConsoleName ? fmt::format("{}:{}", *loc.file, loc.line)
                                               : std::string(kConsoleName);
}

}  // namespace gantry::session
