// The part files in a folder (the operator's macro folder), for a front end to offer.
#pragma once

#include <string>
#include <vector>

namespace gantry::session {

// The part files (.sbp) in `folder`, sorted by name; none when it is missing.
std::vector<std::string> user_part_files(const std::string& folder);

}  // namespace gantry::session
