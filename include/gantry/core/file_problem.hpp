// Why a path cannot be read or written as a file, found without opening it (opening a FIFO
// blocks until a writer comes): the same answer for a check and for a run.
#pragma once

#include <string>

namespace gantry {

// "" when `path` is a regular file this process may read; else why not, as a clause to
// follow "cannot read PATH: ": "there is no such file", "there is no folder F", "it is a
// folder, not a file", "it is a named pipe (FIFO), not a file; ...", "it cannot be read:
// permission denied", "the path is N characters long, ...". A folder, an unreadable and a
// missing file each say so.
std::string read_problem(const std::string& path);
inline constexpr const char* kNoSuchFile = "there is no such file";  // read_problem's, exactly

// "" when `path` can be written: an existing regular file this process may write, or a new
// name in an existing folder it may write in; else why not, as read_problem says it.
std::string write_problem(const std::string& path);

// `path` for a message: whole up to 160 characters, else its first and last characters
// around "...", so that a 6,000-character path does not fill the screen.
std::string shown_path(const std::string& path);

}  // namespace gantry
