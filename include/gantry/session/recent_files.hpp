// The part files opened last, newest first, kept across sessions in the folder where the
// machine's state is kept (values/recent_files.txt), saved atomically.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gantry::session {

// The list's file next to the values file: values/NAME.toml -> values/recent_files.txt.
std::string recent_files_path(const std::string& values_path);

class RecentFiles {
 public:
  // Reads the list; a missing or unreadable file is an empty list, never an error. Empty
  // `path`: nothing is kept.
  explicit RecentFiles(std::string path, std::size_t keep = 10);
  // Newest first, absolute paths.
  const std::vector<std::string>& files() const { return files_; }
  // `file` (made absolute) goes first; the oldest beyond `keep` drop off; the list is saved
  // (temporary file + rename). False, with `why`, when it cannot be written (the list in
  // memory has the file all the same).
  bool add(const std::string& file, std::string* why = nullptr);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::size_t keep_;
  std::vector<std::string> files_;
};

}  // namespace gantry::session
