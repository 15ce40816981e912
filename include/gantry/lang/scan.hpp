// Character-level helpers shared by the line and statement parsers.
#pragma once

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/text.hpp"  // upper, trim

namespace gantry::scan {

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}
inline bool is_letter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}
using ascii::upper;
inline bool is_word(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// Blanks are ascii::kBlanks, the characters is_space accepts.
using ascii::trim;

// Index of the first `'` outside double quotes (the start of an inline comment), or npos.
inline size_t comment_start(std::string_view s) {
  bool quoted = false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '"') quoted = !quoted;
    if (s[i] == '\'' && !quoted) return i;
  }
  return std::string_view::npos;
}

// Index of the first `sep` outside quotes and parentheses/brackets at or after `from`.
inline size_t find_top_level(std::string_view s, char sep, size_t from = 0) {
  bool quoted = false;
  int depth = 0;
  for (size_t i = from; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == '(' || c == '[') ++depth;
    if ((c == ')' || c == ']') && depth > 0) --depth;
    if (c == sep && depth == 0) return i;
  }
  return std::string_view::npos;
}

// Like find_top_level, but only a '(' with its own ')' in `s` hides what it encloses: in bare
// text (a MSGBOX body such as `Remove the clamps (all four` ) a lone '(' is a character.
inline size_t find_top_level_matched(std::string_view s, char sep, size_t from = 0) {
  std::vector<bool> matched(s.size(), false);  // '(' and ')' that pair up
  std::vector<size_t> open;
  bool quoted = false;
  for (size_t i = from; i < s.size(); ++i) {
    if (s[i] == '"') quoted = !quoted;
    if (quoted) continue;
    if (s[i] == '(') open.push_back(i);
    if (s[i] == ')' && !open.empty()) {
      matched[open.back()] = matched[i] = true;
      open.pop_back();
    }
  }
  quoted = false;
  int depth = 0;
  for (size_t i = from; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == '(' && matched[i]) ++depth;
    if (c == ')' && matched[i]) --depth;
    if (c == sep && depth == 0) return i;
  }
  return std::string_view::npos;
}

// Index of keyword `kw` (upper case) as a whole word outside quotes/parentheses, or npos.
inline size_t find_keyword(std::string_view s, std::string_view kw, size_t from = 0) {
  bool quoted = false;
  int depth = 0;
  for (size_t i = from; i + kw.size() <= s.size(); ++i) {
    const char c = s[i];
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == '(' || c == '[') ++depth;
    if ((c == ')' || c == ']') && depth > 0) --depth;
    if (depth != 0) continue;
    if (i > 0 && (is_word(s[i - 1]) || s[i - 1] == '&' || s[i - 1] == '$')) continue;
    if (i + kw.size() < s.size() && is_word(s[i + kw.size()])) continue;
    bool match = true;
    for (size_t k = 0; k < kw.size() && match; ++k)
      match = std::toupper(static_cast<unsigned char>(s[i + k])) == kw[k];
    if (match) return i;
  }
  return std::string_view::npos;
}

// Text that can only be meant as an expression: it starts with a variable, a system
// variable or a parenthesis, or calls a function. `numbers_too` also counts text starting
// like a number (for number parameters, where `1.2.3` is a broken number, not a word);
// an assignment keeps `12 apples` as text, as the handbook allows.
inline bool looks_like_expression(std::string_view t, bool numbers_too) {
  if (t.empty()) return false;
  const std::string_view starts = numbers_too ? "&$%(+-.0123456789" : "&$%(";
  return starts.find(t[0]) != std::string_view::npos || t.find('(') != std::string_view::npos;
}

}  // namespace gantry::scan
