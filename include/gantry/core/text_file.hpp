// Whole text files: reading one (refusing what is not a readable regular file), writing one
// atomically, and where the operator's own files live.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace gantry {

// The file's bytes, or nullopt when it is missing, unreadable, or not a regular file.
std::optional<std::string> read_text_file(const std::string& path);

// Every save goes through here (docs/reliability.md, "Saves"). Writes `text` to `path` so
// that a crash at any moment leaves the old file or the new one, complete: a temporary file
// in the same folder (a unique name per save), fsync, rename over the target, fsync the
// folder. The target keeps its mode and owner; a symlink is written through (it stays a
// link). Temporary files that killed saves left in the folder are removed first. False (the
// old file untouched, `why` says what failed) on failure.
bool write_file_atomically(const std::string& path, std::string_view text,
                           std::string* why = nullptr);

// Renames a damaged file to "<path>.damaged-<UTC time>" so that the next save cannot
// overwrite it: the new name, or nullopt when it could not be renamed.
std::optional<std::string> keep_aside(const std::string& path);

// The operator's Gantry folder: $XDG_CONFIG_HOME/gantry, or ~/.config/gantry.
std::string user_config_dir();

}  // namespace gantry
