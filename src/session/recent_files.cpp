// The recent part files: one absolute path a line, newest first.
#include "gantry/session/recent_files.hpp"

#include <algorithm>
#include <filesystem>

#include "gantry/core/text_file.hpp"  // read_text_file, write_file_atomically

namespace gantry::session {

std::string recent_files_path(const std::string& values_path) {
  return (std::filesystem::path(values_path).parent_path() / "recent_files.txt").string();
}

RecentFiles::RecentFiles(std::string path, std::size_t keep) : path_(std::move(path)), keep_(keep) {
  if (path_.empty()) return;
  const std::optional<std::string> text = read_text_file(path_);
  if (!text) return;
  std::size_t start = 0;
  while (start < text->size() && files_.size() < keep_) {
    std::size_t end = text->find('\n', start);
    if (end == std::string::npos) end = text->size();
    std::string line = text->substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // A hand-edited list may repeat a file or hold blank lines: each file once.
    if (!line.empty() && std::find(files_.begin(), files_.end(), line) == files_.end())
      files_.push_back(std::move(line));
    start = end + 1;
  }
}

bool RecentFiles::add(const std::string& file, std::string* why) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(file, ec);
  const std::string name = (ec ? std::filesystem::path(file) : p.lexically_normal()).string();
  files_.erase(std::remove(files_.begin(), files_.end(), name), files_.end());
  files_.insert(files_.begin(), name);
  if (files_.size() > keep_) files_.resize(keep_);
  if (path_.empty()) return true;
  std::string text;
  for (const std::string& f : files_) text += f + '\n';
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path(), ec);
  return write_file_atomically(path_, text, why);
}

}  // namespace gantry::session
