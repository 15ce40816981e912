// Text with any bytes in it (a Latin-1 part file, UTF-16, garbage), shown safely: every
// message, report and JSON document that goes out passes through here, so that bytes that
// are not UTF-8 are shown escaped (\xE9) instead of aborting a JSON dump or garbling a
// terminal, and source text echoed in a message is capped.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace gantry {

// True when `text` is well-formed UTF-8 (RFC 3629: no overlongs, surrogates or > U+10FFFF).
bool is_utf8(std::string_view text);

// `text` with each byte that is not part of a well-formed UTF-8 sequence written as \xNN
// (upper-case hex); well-formed text comes back unchanged.
std::string escaped_bytes(std::string_view text);

// Source text quoted in a message: escaped as above, and at most `max` characters (a 10 MB
// number is shown by its first ones and "... (N characters)").
std::string echoed(std::string_view source, std::size_t max = 80);

// A copy of `j` whose every string and key is escaped_bytes.
template <class Json>
Json with_escaped_strings(const Json& j) {
  if (j.is_string()) return escaped_bytes(j.template get_ref<const typename Json::string_t&>());
  Json out = j;
  if (j.is_array()) {
    out = Json::array();
    for (const Json& e : j) out.push_back(with_escaped_strings(e));
  } else if (j.is_object()) {
    out = Json::object();
    for (auto it = j.begin(); it != j.end(); ++it)
      out[escaped_bytes(it.key())] = with_escaped_strings(it.value());
  }
  return out;
}

// `j` as JSON text (dump(indent)); any text in it that is not UTF-8 is shown escaped rather
// than throwing nlohmann's type_error 316.
template <class Json>
std::string json_text(const Json& j, int indent = -1) {
  try {
    return j.dump(indent);
  } catch (const typename Json::type_error& e) {
    if (e.id != 316) throw;  // 316: invalid UTF-8 byte
    return with_escaped_strings(j).dump(indent);
  }
}

}  // namespace gantry
