// The persistent store's file: JSON, loaded strictly (a damaged file is kept aside and
// reported), saved by the atomic writer; text that is not UTF-8 kept byte for byte.
#include "gantry/interp/persistent_store.hpp"

#include <fmt/format.h>

#include <filesystem>  // exists

#include "gantry/core/text_file.hpp"          // read_text_file, write_file_atomically, keep_aside
#include "gantry/interp/persistent_file.hpp"  // parse_persistent_file, persistent_file_text

namespace gantry {

using nlohmann::json;

PersistentStore::PersistentStore(std::string path) : path_(std::move(path)) {
  if (!std::filesystem::exists(path_)) return;
  std::optional<std::string> text = read_text_file(path_);
  if (!text) fail(file_loc(path_), "cannot read the persistent variables file");
  std::string why;
  int line = 0;
  if (std::optional<json> values = parse_persistent_file(*text, &why, &line)) {
    for (auto it = values->begin(); it != values->end(); ++it) data_[it.key()] = *it;
    return;
  }
  // Kept, never overwritten: renamed aside, so that no later save can replace it.
  if (const std::optional<std::string> aside = keep_aside(path_))
    fail(file_loc(path_, line),
         fmt::format("the persistent variables file is damaged ({}); nothing ran, and it was "
                     "kept as {}: repair it and move it back, or run again to start with no "
                     "$variables",
                     why, *aside));
  fail(file_loc(path_, line), fmt::format("the persistent variables file is damaged ({}); it "
                                          "was left as it is: repair it or move it away",
                                          why));
}

std::string PersistentStore::default_path() {
  return user_config_dir() + "/persistent.json";
}

const nlohmann::json* PersistentStore::variable(std::string_view name) const {
  const nlohmann::json& vars = data_.at("variables");
  auto it = vars.find(std::string(name));
  return it == vars.end() ? nullptr : &*it;
}

void PersistentStore::save() const {
  if (path_.empty() || !dirty_) return;
  if (std::string why; !write_file_atomically(path_, persistent_file_text(data_), &why))
    fail(file_loc(path_), fmt::format("cannot save the persistent variables ({}); the previous "
                                      "file is kept",
                                      why));
  dirty_ = false;
}

}  // namespace gantry
