// Whole-file reads for part files and profiles; the one atomic writer every save goes through.
#include "gantry/core/text_file.hpp"

#include <dirent.h>  // opendir: the stale temporary files beside a target
#include <fcntl.h>   // open, O_EXCL
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <signal.h>    // kill(pid, 0): is an old temporary file's writer alive
#include <sys/file.h>  // flock: a live writer's temporary file is locked
#include <sys/stat.h>  // stat, fchmod
#include <unistd.h>    // fsync, close, unlink, fchown

#include <cerrno>
#include <cstdint>
#include <cstdio>      // rename
#include <cstdlib>     // getenv
#include <cstring>     // strerror
#include <ctime>       // the damaged file's time stamp
#include <filesystem>  // is_regular_file: a directory opens as an empty stream on Linux
#include <fstream>     // ifstream
#include <random>      // the temporary file's name
#include <sstream>     // slurp

namespace gantry {

namespace {

namespace fs = std::filesystem;

// ".<name>.gantry-save-<16 hex digits>": hidden, and recognisable as ours alone.
constexpr std::string_view kTempMark = ".gantry-save-";
constexpr size_t kTempDigits = 16;

bool is_our_temp(std::string_view entry) {
  const size_t mark = entry.rfind(kTempMark);
  if (entry.empty() || entry[0] != '.' || mark == std::string_view::npos ||
      entry.size() != mark + kTempMark.size() + kTempDigits)
    return false;
  return entry.find_first_not_of("0123456789abcdef", mark + kTempMark.size()) ==
         std::string_view::npos;
}

// "<name>.<pid>.tmp" of a process that is gone: what saves before this writer left.
bool is_old_temp_of(std::string_view entry, std::string_view name) {
  if (entry.size() <= name.size() + 5 || !entry.starts_with(name) || !entry.ends_with(".tmp") ||
      entry[name.size()] != '.')
    return false;
  const std::string_view pid = entry.substr(name.size() + 1, entry.size() - name.size() - 5);
  if (pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != pid.npos)
    return false;
  return ::kill(std::stoi(std::string(pid)), 0) != 0 && errno == ESRCH;
}

// Removes the temporary files killed saves left in `folder`. A save in progress holds a
// lock on its own, so only the files of writers that died are removed.
void remove_stale_temps(const fs::path& folder, const std::string& name) {
  DIR* dir = ::opendir(folder.c_str());
  if (!dir) return;
  while (const dirent* e = ::readdir(dir)) {
    if (is_old_temp_of(e->d_name, name)) ::unlink((folder / e->d_name).c_str());
    if (!is_our_temp(e->d_name)) continue;
    const fs::path p = folder / e->d_name;
    const int fd = ::open(p.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) ::unlink(p.c_str());
    ::close(fd);
  }
  ::closedir(dir);
}

// The file a save replaces: `path`, or the file its symlinks lead to (the link stays a link).
fs::path save_target(const fs::path& path) {
  fs::path p = path;
  std::error_code ec;
  for (int hops = 0; hops < 40 && fs::is_symlink(p, ec); ++hops) {
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p;
}

std::string random_hex() {
  thread_local std::mt19937_64 bits{std::random_device{}() ^
                                    (static_cast<std::uint64_t>(::getpid()) << 32)};
  return fmt::format("{:016x}", bits());
}

bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    text.remove_prefix(static_cast<size_t>(n));
  }
  return true;
}

bool fsync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

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

bool write_file_atomically(const std::string& path, std::string_view text, std::string* why) {
  auto failed = [&](std::string what) {
    if (why) *why = fmt::format("{}: {}", what, std::strerror(errno));
    return false;
  };
  const fs::path target = save_target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(folder, ec);
  remove_stale_temps(folder, target.filename().string());

  struct stat old {};
  const bool existed = ::stat(target.c_str(), &old) == 0;
  fs::path tmp;
  int fd = -1;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    tmp = folder / fmt::format(".{}{}{}", target.filename().string(), kTempMark, random_hex());
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC,
                existed ? old.st_mode & 07777 : 0666);  // a new file: 0666 less the umask
    if (fd < 0 && errno != EEXIST) return failed(fmt::format("cannot create {}", tmp.string()));
  }
  if (fd < 0) return failed(fmt::format("cannot create a temporary file in {}", folder.string()));
  ::flock(fd, LOCK_EX);  // marks it live, so that no other save removes it as stale
  bool ok = true;
  if (existed)  // the old file's owner (only root may give a file away) and exact mode
    ok = (::fchown(fd, old.st_uid, old.st_gid) == 0 || errno == EPERM) &&
         ::fchmod(fd, old.st_mode & 07777) == 0;
  ok = ok && write_all(fd, text) && ::fsync(fd) == 0;
  const int saved_errno = errno;
  ::close(fd);
  errno = saved_errno;
  if (!ok || ::rename(tmp.c_str(), target.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    errno = e;
    return failed(fmt::format("cannot write {}", target.string()));
  }
  if (!fsync_folder(folder))
    return failed(fmt::format("cannot sync the folder {}", folder.string()));
  return true;
}

std::optional<std::string> keep_aside(const std::string& path) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  const std::string stamp = fmt::format("{:%Y%m%dT%H%M%SZ}", utc);
  for (int n = 0; n < 100; ++n) {
    const std::string aside = n == 0 ? fmt::format("{}.damaged-{}", path, stamp)
                                     : fmt::format("{}.damaged-{}-{}", path, stamp, n);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(aside, ec))) continue;
    if (::rename(path.c_str(), aside.c_str()) != 0) return std::nullopt;
    return aside;
  }
  return std::nullopt;
}

std::string user_config_dir() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  const std::string base = xdg && *xdg ? xdg : std::string(home ? home : ".") + "/.config";
  return base + "/gantry";
}

}  // namespace gantry
