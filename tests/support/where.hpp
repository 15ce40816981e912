// A location as tests compare it: "FILE:LINE:COLUMN" ("<none>" for no file).
#pragma once

#include <string>

#include "gantry/core/diagnostic.hpp"  // SourceLoc

namespace gantry {

inline std::string where(const SourceLoc& loc) {
  return (loc.file ? *loc.file : std::string("<none>")) + ":" + std::to_string(loc.line) + ":" +
         std::to_string(loc.column);
}

}  // namespace gantry
