// The persistent store's file format (docs/language.md §2.3, docs/reliability.md): a JSON
// object whose only keys are "variables" and "registry", each an object. JSON text must be
// UTF-8, so a text value that is not is written as {"$bytes": "caf\\xE9"} (bytes that are not
// UTF-8 as \xNN, a backslash as \\) and read back byte for byte.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace gantry {

// The file's values ({"variables": {...}, "registry": {...}}, the keys it has), or nullopt
// when it is damaged: what is wrong in `why` and, where JSON places it, the line in `line`.
std::optional<nlohmann::json> parse_persistent_file(const std::string& text, std::string* why,
                                                    int* line);

// The file's text for `values`: what parse_persistent_file reads back as the same values.
std::string persistent_file_text(const nlohmann::json& values);

}  // namespace gantry
