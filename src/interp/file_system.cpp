// Disk and sandboxed file access for the interpreter.
#include "gantry/interp/file_system.hpp"

#include <fmt/format.h>  // find_part_file's refusal

#include <algorithm>   // sort, equal
#include <cctype>      // tolower
#include <filesystem>  // is_regular_file, directory_iterator
#include <fstream>     // ifstream, ofstream

#include "gantry/core/data_folder.hpp"   // shipped_data_folder
#include "gantry/core/file_problem.hpp"  // read_problem, write_problem
#include "gantry/core/text_file.hpp"     // user_config_dir

namespace gantry {

std::string FileSystem::read_problem(const std::string& path) {
  return is_file(path) ? "" : kNoSuchFile;
}

std::shared_ptr<const Script> DiskFileSystem::load_script(const std::string& path,
                                                          const IsCommand& is_command) {
  return Script::load(path, is_command);
}

bool DiskFileSystem::is_file(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::string DiskFileSystem::read_problem(const std::string& path) {
  return gantry::read_problem(path);
}

std::string DiskFileSystem::write_problem(const std::string& path) {
  return gantry::write_problem(path);
}

// Neither opens what is not a regular file: opening a FIFO would wait for its other end.
std::shared_ptr<std::istream> DiskFileSystem::open_read(const std::string& path) {
  if (!gantry::read_problem(path).empty()) return nullptr;
  auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
  return *in ? in : nullptr;
}

std::shared_ptr<std::ostream> DiskFileSystem::open_write(const std::string& path, bool append) {
  if (!gantry::write_problem(path).empty()) return nullptr;
  auto out = std::make_shared<std::ofstream>(path, append ? std::ios::app : std::ios::trunc);
  return *out ? out : nullptr;
}

std::vector<std::string> DiskFileSystem::list(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(folder.empty() ? "." : folder, ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec))
    names.push_back(it->path().filename().string());
  return names;
}

std::shared_ptr<const Script> SandboxFileSystem::load_script(const std::string& path,
                                                             const IsCommand& is_command) {
  auto it = written_.find(path);  // a part file the run wrote itself
  if (it != written_.end()) return Script::from_text(it->second->str(), path, is_command);
  return base_->load_script(path, is_command);
}

bool SandboxFileSystem::is_file(const std::string& path) {
  return written_.count(path) || base_->is_file(path);
}

std::shared_ptr<std::istream> SandboxFileSystem::open_read(const std::string& path) {
  auto it = written_.find(path);
  if (it != written_.end()) return std::make_shared<std::istringstream>(it->second->str());
  return base_->open_read(path);
}

std::string SandboxFileSystem::read_problem(const std::string& path) {
  return written_.count(path) ? "" : base_->read_problem(path);
}

std::string SandboxFileSystem::write_problem(const std::string& path) {
  return written_.count(path) ? "" : base_->write_problem(path);
}

std::vector<std::string> SandboxFileSystem::list(const std::string& folder) {
  std::vector<std::string> names = base_->list(folder);
  for (const auto& [path, text] : written_) {
    const std::filesystem::path p(path);
    if (p.parent_path() == std::filesystem::path(folder)) names.push_back(p.filename().string());
  }
  return names;
}

std::shared_ptr<std::ostream> SandboxFileSystem::open_write(const std::string& path, bool append) {
  auto buffer = std::make_shared<std::stringstream>();
  if (append) {
    if (auto old = open_read(path)) *buffer << old->rdbuf();
  }
  written_[path] = buffer;
  return buffer;
}

namespace {

bool same_ignoring_case(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

// Part by part from the first one missing, so `Sub/Part.SBP` finds `sub/part.sbp` too.
PartFileLookup find_part_file(FileSystem& files, const std::string& path) {
  if (files.is_file(path)) return {path, ""};
  const std::filesystem::path wanted(path);
  std::filesystem::path found = wanted.root_path();
  for (const std::filesystem::path& part : wanted.relative_path()) {
    const std::filesystem::path exact = found / part;
    std::error_code ec;
    if (part == "." || part == ".." || files.is_file(exact.string()) ||
        std::filesystem::exists(exact, ec)) {
      found = exact;
      continue;
    }
    std::vector<std::string> matches;
    for (const std::string& name : files.list(found.string()))
      if (same_ignoring_case(name, part.string())) matches.push_back(name);
    if (matches.empty()) return {path, ""};
    std::sort(matches.begin(), matches.end());
    if (matches.size() > 1) {
      std::string names = matches.front();
      for (size_t i = 1; i < matches.size(); ++i) names += " and " + matches[i];
      return {path, fmt::format("there is no {} but {} in {}, which differ only in case; name "
                                "the one to use exactly",
                                part.string(), names,
                                found.empty() ? "the working directory" : found.string())};
    }
    found /= matches.front();
  }
  return {found.string(), ""};
}

std::string user_macro_folder() {
  return user_config_dir() + "/macros";
}

// An installed gantry (<prefix>/bin/gantry) finds <prefix>/share/gantry/macros beside it;
// one run from its build tree finds the source tree's folder, compiled in.
std::string shipped_macro_folder() {
  return shipped_data_folder("macros", GANTRY_SOURCE_MACROS_DIR);
}

}  // namespace gantry
