// The persistent store's file: JSON, loaded strictly, saved by the atomic writer. A text
// value that is not UTF-8 (JSON cannot hold it) is saved as {"$bytes": "caf\\xE9"} and
// read back byte for byte.
#include "gantry/interp/persistent_store.hpp"

#include <fmt/format.h>

#include <cctype>      // isxdigit
#include <filesystem>  // exists
#include <string>      // stoi

#include "gantry/core/any_bytes.hpp"  // is_utf8, escaped_bytes, json_text
#include "gantry/core/text_file.hpp"  // read_text_file, write_file_atomically, keep_aside

namespace gantry {

namespace {

using nlohmann::json;

constexpr const char* kBytes = "$bytes";  // no variable or field name starts with $

// Text that is not UTF-8: every byte that is not part of UTF-8 as \xNN, and \ as \\, so that
// decoded() gives the exact bytes back.
json encoded(const json& j) {
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    if (is_utf8(s)) return j;
    std::string out;
    for (size_t i = 0, from = 0; i <= s.size(); ++i)  // backslashes doubled, then escaped
      if (i == s.size() || s[i] == '\\') {
        out += escaped_bytes(std::string_view(s).substr(from, i - from));
        if (i < s.size()) out += "\\\\";
        from = i + 1;
      }
    return json{{kBytes, out}};
  }
  if (!j.is_structured()) return j;
  json out = j.is_array() ? json::array() : json::object();
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (j.is_array())
      out.push_back(encoded(*it));
    else
      out[it.key()] = encoded(*it);
  }
  return out;
}

// The inverse of encoded(); nullopt when a "$bytes" text is malformed.
std::optional<json> decoded(const json& j) {
  if (j.is_object() && j.size() == 1 && j.contains(kBytes) && j[kBytes].is_string()) {
    const std::string& s = j[kBytes].get_ref<const std::string&>();
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
      if (s[i] != '\\') {
        out += s[i];
      } else if (i + 1 < s.size() && s[i + 1] == '\\') {
        out += '\\';
        ++i;
      } else if (i + 3 < s.size() && s[i + 1] == 'x' &&
                 std::isxdigit(static_cast<unsigned char>(s[i + 2])) &&
                 std::isxdigit(static_cast<unsigned char>(s[i + 3]))) {
        out += static_cast<char>(std::stoi(s.substr(i + 2, 2), nullptr, 16));
        i += 3;
      } else {
        return std::nullopt;
      }
    }
    return json(out);
  }
  if (!j.is_structured()) return j;
  json out = j.is_array() ? json::array() : json::object();
  for (auto it = j.begin(); it != j.end(); ++it) {
    std::optional<json> e = decoded(*it);
    if (!e) return std::nullopt;
    if (j.is_array())
      out.push_back(std::move(*e));
    else
      out[it.key()] = std::move(*e);
  }
  return out;
}

}  // namespace

std::optional<PersistentStore> PersistentStore::parse(const std::string& text, std::string* why,
                                                      int* line) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    *line = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) *line += text[i] == '\n';
    *why = fmt::format("not valid JSON: {}", e.what());
    return std::nullopt;
  }
  if (!j.is_object()) {
    *why = "it is not a JSON object";
    return std::nullopt;
  }
  PersistentStore store;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() != "variables" && it.key() != "registry") {
      *why = fmt::format("it has a key \"{}\"; only \"variables\" and \"registry\" belong there",
                         escaped_bytes(it.key()));
      return std::nullopt;
    }
    if (!it->is_object()) {
      *why = fmt::format("its \"{}\" is not an object", it.key());
      return std::nullopt;
    }
    std::optional<json> values = decoded(*it);
    if (!values) {
      *why = fmt::format("its \"{}\" holds a malformed \"{}\" text", it.key(), kBytes);
      return std::nullopt;
    }
    store.data_[it.key()] = std::move(*values);
  }
  return store;
}

std::string PersistentStore::text() const {
  return json_text(encoded(data_), 2) + "\n";
}

PersistentStore::PersistentStore(std::string path) : path_(std::move(path)) {
  if (!std::filesystem::exists(path_)) return;
  std::optional<std::string> text = read_text_file(path_);
  if (!text) fail(file_loc(path_), "cannot read the persistent variables file");
  std::string why;
  int line = 0;
  if (std::optional<PersistentStore> loaded = parse(*text, &why, &line)) {
    data_ = std::move(loaded->data_);
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
  if (std::string why; !write_file_atomically(path_, text(), &why))
    fail(file_loc(path_), fmt::format("cannot save the persistent variables ({}); the previous "
                                      "file is kept",
                                      why));
  dirty_ = false;
}

}  // namespace gantry
