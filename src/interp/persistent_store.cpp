// The persistent store's file: JSON, loaded strictly, saved atomically.
#include "gantry/interp/persistent_store.hpp"

#include <fmt/format.h>

#include <filesystem>  // exists

#include "gantry/core/text_file.hpp"  // read_text_file, write_file_atomically, user_config_dir

namespace gantry {

PersistentStore::PersistentStore(std::string path) : path_(std::move(path)) {
  if (!std::filesystem::exists(path_)) return;
  std::optional<std::string> text = read_text_file(path_);
  if (!text) fail(file_loc(path_), "cannot read the persistent variables file");
  try {
    nlohmann::json j = nlohmann::json::parse(*text);
    if (!j.is_object()) throw nlohmann::json::type_error::create(302, "not an object", nullptr);
    for (const char* k : {"variables", "registry"})
      if (j.contains(k) && j[k].is_object()) data_[k] = j[k];
  } catch (const nlohmann::json::exception& e) {
    fail(file_loc(path_), fmt::format("the persistent variables file is damaged ({}); it was "
                                      "left as it is: repair or move it away",
                                      e.what()));
  }
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
  if (!write_file_atomically(path_, data_.dump(2) + "\n"))
    fail(file_loc(path_), "cannot save the persistent variables; the previous file is kept");
  dirty_ = false;
}

}  // namespace gantry
