// Values that outlive a run: FabMo's $variables and the SB3 registry statements.
#pragma once

#include <nlohmann/json.hpp>  // the stored values

#include <string>

#include "gantry/core/diagnostic.hpp"  // load errors

namespace gantry {

class PersistentStore {
 public:
  // An in-memory store that is never saved (check, preview, tests).
  PersistentStore() = default;
  // Backed by `path`: loaded now (a missing file is empty; a damaged one is an error, and is
  // kept: renamed aside, docs/reliability.md), saved atomically by save().
  explicit PersistentStore(std::string path);

  static std::string default_path();  // $XDG_CONFIG_HOME/gantry/persistent.json

  // The same values, never saved: for checks and previews.
  PersistentStore scratch_copy() const {
    PersistentStore s;
    s.data_ = data_;
    return s;
  }

  // Mutable access marks the store changed; save() writes only a changed store.
  nlohmann::json& variables() { return dirty_ = true, data_["variables"]; }
  nlohmann::json& registry() { return dirty_ = true, data_["registry"]; }
  const nlohmann::json* variable(std::string_view name) const;
  const nlohmann::json* registry_value(std::string_view key) const {
    const nlohmann::json& r = data_.at("registry");
    auto it = r.find(std::string(key));
    return it == r.end() ? nullptr : &*it;
  }

  // Writes to a temporary file, fsyncs it and renames it over the old one: a crash leaves
  // either the old or the new file, never a torn one. No-op for an in-memory store.
  void save() const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  mutable bool dirty_ = false;
  nlohmann::json data_ = {{"variables", nlohmann::json::object()},
                          {"registry", nlohmann::json::object()}};
};

}  // namespace gantry
