// The persistent file's format: strict parsing, and any bytes kept (docs/reliability.md).
#include <fmt/format.h>

#include <cctype>  // isxdigit
#include <string>  // stoi

#include "gantry/core/any_bytes.hpp"  // is_utf8, escaped_bytes, json_text
#include "gantry/interp/persistent_file.hpp"

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

std::optional<json> parse_persistent_file(const std::string& text, std::string* why, int* line) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    *line = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) *line += text[i] == '\n';
    *why = fmt::format("not valid JSON: {}", e.what());
    return std::nullopt;
  } catch (const json::exception& e) {  // a number too large for a double (out_of_range 406)
    *why = fmt::format("not valid JSON: {}", e.what());
    return std::nullopt;
  }
  if (!j.is_object()) {
    *why = "it is not a JSON object";
    return std::nullopt;
  }
  json values = json::object();
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
    // Member by member: "variables" and "registry" themselves stay objects, even one whose
    // only key is "$bytes" (the fuzzer's find: it read back as a text, and saved unreadable).
    json& members = values[it.key()] = json::object();
    for (auto m = it->begin(); m != it->end(); ++m) {
      std::optional<json> value = decoded(*m);
      if (!value) {
        *why = fmt::format("its \"{}\" holds a malformed \"{}\" text", it.key(), kBytes);
        return std::nullopt;
      }
      members[m.key()] = std::move(*value);
    }
  }
  return values;
}

std::string persistent_file_text(const json& values) {
  return json_text(encoded(values), 2) + "\n";
}

}  // namespace gantry
