// A FileSystem whose part files are texts in memory (by path); other paths are read from disk.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "gantry/interp/file_system.hpp"
#include "gantry/lang/script.hpp"

namespace gantry {

class MemoryFiles : public FileSystem {
 public:
  std::shared_ptr<const Script> load_script(const std::string& path,
                                            const IsCommand& is_command) override {
    const auto it = texts.find(path);
    return it == texts.end() ? Script::load(path, is_command)
                             : Script::from_text(it->second, path, is_command);
  }
  bool is_file(const std::string& path) override { return texts.count(path) > 0; }
  std::shared_ptr<std::istream> open_read(const std::string&) override { return nullptr; }
  std::shared_ptr<std::ostream> open_write(const std::string&, bool) override { return nullptr; }
  std::map<std::string, std::string> texts;
};

}  // namespace gantry
