// Whole-file reads for part files and profiles; atomic writes for what Gantry saves.
#include "gantry/core/text_file.hpp"

#include <fcntl.h>  // open
#include <fmt/format.h>
#include <unistd.h>  // fsync, close, getpid

#include <cstdio>      // rename, remove
#include <cstdlib>     // getenv
#include <filesystem>  // is_regular_file: a directory opens as an empty stream on Linux
#include <fstream>     // ifstream
#include <sstream>     // slurp

namespace gantry {

std::optional<std::string> read_text_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return std::move(ss).str();
}

bool write_file_atomically(const std::string& path, const std::string& text) {
  const std::filesystem::path p(path);
  std::error_code ec;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  const std::string tmp = fmt::format("{}.{}.tmp", path, ::getpid());  // one per process
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  bool ok = fd >= 0 && ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ok = fd >= 0 && ::fsync(fd) == 0 && ok;
  if (fd >= 0) ::close(fd);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

std::string user_config_dir() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  const std::string base = xdg && *xdg ? xdg : std::string(home ? home : ".") + "/.config";
  return base + "/gantry";
}

}  // namespace gantry
