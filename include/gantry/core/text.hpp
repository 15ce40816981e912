// The one ASCII upper-case and trim every layer uses (part-file words, answers, DXF values).
#pragma once

#include <string>
#include <string_view>

namespace gantry::ascii {

// The blanks a part-file line may carry around its words (no newline: lines are split on it).
inline constexpr std::string_view kBlanks = " \t\r\f\v";

// ASCII only, whatever the locale: part-file words are ASCII, other bytes stay as they are.
inline char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}
inline char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

inline std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = upper(c);
  return out;
}
inline std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = lower(c);
  return out;
}

// `s` without the leading / trailing characters found in `chars`.
inline std::string_view trim_front(std::string_view s, std::string_view chars = kBlanks) {
  while (!s.empty() && chars.find(s.front()) != std::string_view::npos) s.remove_prefix(1);
  return s;
}
inline std::string_view trim_back(std::string_view s, std::string_view chars = kBlanks) {
  while (!s.empty() && chars.find(s.back()) != std::string_view::npos) s.remove_suffix(1);
  return s;
}
inline std::string_view trim(std::string_view s, std::string_view chars = kBlanks) {
  return trim_back(trim_front(s, chars), chars);
}

}  // namespace gantry::ascii
