// The shipped data's folder, found from the running program's path.
#include "gantry/core/data_folder.hpp"

#include <filesystem>

namespace gantry {

std::string shipped_data_folder(std::string_view sub, const std::string& source_folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share/gantry" / sub;
    if (fs::is_directory(installed, ec)) return installed.string();
  }
  return source_folder;
}

}  // namespace gantry
