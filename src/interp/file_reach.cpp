// Whether a path lies inside the folders a part file may reach, after `..` and links.
#include "gantry/interp/file_reach.hpp"

#include <fmt/format.h>  // the refusal

#include <algorithm>  // mismatch

#include "gantry/core/file_problem.hpp"  // shown_path

namespace gantry {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxLinks = 40;  // as the kernel's ELOOP limit: a loop of links resolves to itself

fs::path without_trailing_slash(fs::path p) {
  return p.has_filename() || p == p.root_path() ? p : p.parent_path();
}

bool inside(const fs::path& p, const fs::path& folder) {
  return std::mismatch(folder.begin(), folder.end(), p.begin(), p.end()).first == folder.end();
}

}  // namespace

// weakly_canonical resolves the links of the part that exists; a link whose target is
// missing ends that part, so it is followed here by hand.
fs::path resolved_path(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(path.empty() ? fs::path(".") : fs::path(path), ec);
  fs::path c = p.lexically_normal();
  for (int hop = 0; hop < kMaxLinks; ++hop) {
    c = without_trailing_slash(fs::weakly_canonical(p, ec));
    if (ec) return without_trailing_slash(p.lexically_normal());
    fs::path prefix;
    bool followed = false;
    for (auto it = c.begin(); it != c.end() && !followed; ++it) {
      prefix /= *it;
      if (!fs::is_symlink(fs::symlink_status(prefix, ec))) continue;
      const fs::path target = fs::read_symlink(prefix, ec);
      if (ec) break;
      p = target.is_absolute() ? target : prefix.parent_path() / target;
      for (auto rest = std::next(it); rest != c.end(); ++rest) p /= *rest;
      followed = true;
    }
    if (!followed) return c;
  }
  return c;
}

std::string reach_refusal(const std::string& path, FileAccess access, const std::string& job_folder,
                          const FileReach& reach) {
  const fs::path target = resolved_path(path);
  const fs::path job = resolved_path(job_folder);
  if (inside(target, job)) return "";
  for (const std::string& folder : reach.read_write)
    if (!folder.empty() && inside(target, resolved_path(folder))) return "";
  if (access == FileAccess::Read)
    for (const std::string& folder : reach.read_only)
      if (!folder.empty() && inside(target, resolved_path(folder))) return "";
  const fs::path folder = target.parent_path();
  return fmt::format(
      "{} is outside the job's folder {}{}: a part file {} files only there, in the Gantry "
      "data folder and in the folders the operator allows; to allow it, add \"{}\" to "
      "[files] allow in the machine profile or run with --allow-path {}",
      shown_path(path), job.string(),
      target == fs::path(path) ? "" : fmt::format(" (it leads to {})", shown_path(target.string())),
      access == FileAccess::Read ? "reads" : "writes", shown_path(folder.string()),
      shown_path(folder.string()));
}

}  // namespace gantry
