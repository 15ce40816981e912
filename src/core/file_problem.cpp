// Why a path cannot be read or written, from stat and access: nothing is opened.
#include "gantry/core/file_problem.hpp"

#include <fmt/format.h>  // messages
#include <sys/stat.h>    // stat
#include <unistd.h>      // access

#include <cerrno>      // ENOENT, ENOTDIR, EACCES
#include <climits>     // PATH_MAX, NAME_MAX
#include <cstring>     // strerror
#include <filesystem>  // path parts

namespace gantry {
namespace {

// The system's limits: a longer path or name fails in open() with ENAMETOOLONG.
std::string length_problem(const std::string& path) {
  if (path.size() >= PATH_MAX)
    return fmt::format("the path is {} characters long, and this system allows at most {}",
                       path.size(), PATH_MAX - 1);
  for (const std::filesystem::path& part : std::filesystem::path(path)) {
    const std::string name = part.string();
    if (name.size() > NAME_MAX)
      return fmt::format(
          "the name {}... is {} characters long, and a file or folder name may "
          "have at most {}",
          name.substr(0, 24), name.size(), NAME_MAX);
  }
  return "";
}

std::string folder_of(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  return parent.empty() ? "." : parent;
}

// What a stat() failure says about `path`.
std::string missing_problem(const std::string& path, int error, bool for_writing) {
  const std::string folder = folder_of(path);
  struct stat st {};
  if (error == ENOENT || error == ENOTDIR) {
    if (::stat(folder.c_str(), &st) != 0) return fmt::format("there is no folder {}", folder);
    if (!S_ISDIR(st.st_mode)) return fmt::format("{} is not a folder", folder);
    if (for_writing) return "";  // a new file in a folder that is there
    return kNoSuchFile;
  }
  if (error == EACCES) return "a folder on the way to it cannot be entered: permission denied";
  return std::strerror(error);
}

// "" for a regular file; else what it is instead.
std::string kind_problem(const struct stat& st) {
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "it is a folder, not a file";
  const char* kind = S_ISFIFO(st.st_mode)                         ? "a named pipe (FIFO)"
                     : S_ISSOCK(st.st_mode)                       ? "a socket"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                  : "not a regular file";
  return fmt::format("it is {}, not a file; Gantry opens only regular files", kind);
}

}  // namespace

std::string shown_path(const std::string& path) {
  constexpr size_t kHead = 100, kTail = 50;
  if (path.size() <= kHead + kTail + 10) return path;
  return path.substr(0, kHead) + "..." + path.substr(path.size() - kTail);
}

std::string read_problem(const std::string& path) {
  if (std::string why = length_problem(path); !why.empty()) return why;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return missing_problem(path, errno, false);
  if (std::string why = kind_problem(st); !why.empty()) return why;
  if (::access(path.c_str(), R_OK) != 0) return "it cannot be read: permission denied";
  return "";
}

std::string write_problem(const std::string& path) {
  if (std::string why = length_problem(path); !why.empty()) return why;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int error = errno;
    if (std::string why = missing_problem(path, error, true); !why.empty()) return why;
    const std::string folder = folder_of(path);
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
      return fmt::format("no file can be made in {}: permission denied", folder);
    return "";
  }
  if (std::string why = kind_problem(st); !why.empty()) return why;
  if (::access(path.c_str(), W_OK) != 0) return "it cannot be written: permission denied";
  return "";
}

}  // namespace gantry
