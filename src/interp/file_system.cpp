// Disk and sandboxed file access for the interpreter.
#include "gantry/interp/file_system.hpp"

#include <filesystem>  // is_regular_file
#include <fstream>     // ifstream, ofstream

namespace gantry {

std::shared_ptr<const Script> DiskFileSystem::load_script(const std::string& path,
                                                          const IsCommand& is_command) {
  return Script::load(path, is_command);
}

bool DiskFileSystem::is_file(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::shared_ptr<std::istream> DiskFileSystem::open_read(const std::string& path) {
  if (!is_file(path)) return nullptr;
  auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
  return *in ? in : nullptr;
}

std::shared_ptr<std::ostream> DiskFileSystem::open_write(const std::string& path, bool append) {
  auto out = std::make_shared<std::ofstream>(path, append ? std::ios::app : std::ios::trunc);
  return *out ? out : nullptr;
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

std::shared_ptr<std::ostream> SandboxFileSystem::open_write(const std::string& path, bool append) {
  auto buffer = std::make_shared<std::stringstream>();
  if (append) {
    if (auto old = open_read(path)) *buffer << old->rdbuf();
  }
  written_[path] = buffer;
  return buffer;
}

}  // namespace gantry
