// Whole-file reads for part files and profiles.
#include "gantry/core/text_file.hpp"

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

}  // namespace gantry
