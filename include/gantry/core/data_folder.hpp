// Where Gantry's shipped data (profiles, macros) is: beside an installed program, else in
// the source tree a build runs from.
#pragma once

#include <string>
#include <string_view>

namespace gantry {

// <prefix>/share/gantry/<sub> when the running program is <prefix>/bin/gantry and that folder
// exists (cmake --install, the .deb); otherwise `source_folder` (compiled in by the build).
std::string shipped_data_folder(std::string_view sub, const std::string& source_folder);

}  // namespace gantry
