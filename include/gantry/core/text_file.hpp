// Reading a whole text file, refusing what is not a readable regular file.
#pragma once

#include <optional>
#include <string>

namespace gantry {

// The file's bytes, or nullopt when it is missing, unreadable, or not a regular file.
std::optional<std::string> read_text_file(const std::string& path);

}  // namespace gantry
