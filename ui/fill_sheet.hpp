// A fill-in sheet: one field per parameter of a command, generated from the command table
// (name, unit, type, default, range, help), checked field by field as the operator types, and
// turned back into the command line that runs it. The window draws it; nothing here draws.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandSpec, ParamSpec
#include "gantry/core/diagnostic.hpp"         // Diagnostic

namespace gantry::ui {

struct SheetField {
  const ParamSpec* spec;
  std::string label;  // "X location"
  std::string type;   // distance, speed, angle, int, flag, choice, filename, text, number
  std::string unit;   // "in", "in/s", "deg" or "" (the profile's units replace "units")
  std::string range;  // "0 to 1", ">= 0", "O, I or T", ""
  std::string hint;   // shown in an empty field: the default, or what a blank means
  std::string value;  // as typed
  std::string error;  // why `value` is not allowed ("" when it is, or when unknown here)
};

class FillSheet {
 public:
  FillSheet(const CommandSpec& spec, Dialect dialect, std::string_view units_name);
  // Fills the fields from a typed line ("MX, 5" fills the first), as far as it goes.
  void fill_from(std::string_view line);

  const CommandSpec& spec() const { return *spec_; }
  std::vector<SheetField>& fields() { return fields_; }
  const std::vector<SheetField>& fields() const { return fields_; }

  // Checks every field (sets each one's error); true when none has one. A number field
  // holding an expression (&DEPTH * 2) is left to the check the controller makes.
  bool validate();
  // "MX, 5": the code and the values, blanks kept between them, trailing blanks dropped.
  std::string line() const;
  // Places the controller's errors on the fields they point at (by column in line());
  // returns the ones that point at none (shown under the sheet).
  std::vector<std::string> place_errors(const std::vector<Diagnostic>& errors);

 private:
  const CommandSpec* spec_;
  std::vector<SheetField> fields_;
};

// The error a value has for `p` ("" when it is allowed, or is an expression the controller
// will evaluate).
std::string field_error(const ParamSpec& p, std::string_view value);

}  // namespace gantry::ui
