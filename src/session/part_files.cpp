// The part files in a folder.
#include "gantry/session/part_files.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace gantry::session {

namespace fs = std::filesystem;

std::vector<std::string> user_part_files(const std::string& folder) {
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::string ext = it->path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == ".sbp" && it->is_regular_file(ec)) files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace gantry::session
