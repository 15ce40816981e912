// Run-time values of the part-file language: a number or a string.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "gantry/core/diagnostic.hpp"  // SourceLoc for conversion errors

namespace gantry {

class Value {
 public:
  Value() : v_(0.0) {}
  static Value number(double d) { return Value(d); }
  static Value string(std::string s) { return Value(std::move(s)); }

  bool is_number() const { return std::holds_alternative<double>(v_); }
  bool is_string() const { return !is_number(); }

  // The number; a string converts when its trimmed text is a number literal (handbook §1.7),
  // otherwise it is an error at `loc` naming `what` (e.g. "&COUNT").
  double to_number(const SourceLoc& loc, std::string_view what = "value") const;
  // The text: strings as they are, numbers formatted as the language prints them.
  std::string to_string() const;

  const std::string& str() const { return std::get<std::string>(v_); }  // is_string() only
  double num() const { return std::get<double>(v_); }                   // is_number() only

 private:
  explicit Value(double d) : v_(d) {}
  explicit Value(std::string s) : v_(std::move(s)) {}
  std::variant<double, std::string> v_;
};

// How the language prints a number (PRINT, WRITE, string joins): see docs/language.md.
std::string format_number(double d);

}  // namespace gantry
