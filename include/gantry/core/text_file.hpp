// Whole text files: reading one (refusing what is not a readable regular file), writing one
// atomically, and where the operator's own files live.
#pragma once

#include <optional>
#include <string>

namespace gantry {

// The file's bytes, or nullopt when it is missing, unreadable, or not a regular file.
std::optional<std::string> read_text_file(const std::string& path);

// Writes `text` to `path` so that a crash leaves the old file or the new one, never a mix:
// a temporary file beside it, fsync, rename. False (and the old file untouched) on failure.
bool write_file_atomically(const std::string& path, const std::string& text);

// The operator's Gantry folder: $XDG_CONFIG_HOME/gantry, or ~/.config/gantry.
std::string user_config_dir();

}  // namespace gantry
