// The name of the lines typed at a console (terminal or window), and where a line is, as the
// operator is told.
#pragma once

#include <string>

#include "gantry/core/diagnostic.hpp"  // SourceLoc

namespace gantry::session {

// The name of the one-line scripts typed at the console: errors located there get a caret.
inline constexpr const char* kConsoleName = "console";

// "part.sbp:12", or "console" for a line typed there (or one with no file).
std::string where(const SourceLoc& loc);

}  // namespace gantry::session
