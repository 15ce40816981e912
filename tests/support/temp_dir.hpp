// A fresh folder under the system's temporary folder for one test, removed with its contents.
#pragma once

#include <unistd.h>  // getpid

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace gantry {

class TempDir {
 public:
  // The folder is named gantry_<prefix>_<pid>_<count>.
  explicit TempDir(const std::string& prefix) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("gantry_" + prefix + "_" + std::to_string(::getpid()) + "_" +
             std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string path(const std::string& name = "") const {
    return name.empty() ? path_.string() : (path_ / name).string();
  }
  // Writes `text` byte for byte as `name` (sub-folders created); returns its full path.
  std::string write(const std::string& name, std::string_view text) const {
    const std::filesystem::path p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
    return p.string();
  }
  std::string read(const std::string& name) const { return read_path(path_ / name); }
  bool exists(const std::string& name) const { return std::filesystem::exists(path_ / name); }

  static std::string read_path(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

 private:
  std::filesystem::path path_;
};

}  // namespace gantry
