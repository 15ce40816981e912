// The one table of two-letter commands: it drives the parser's checks, dispatch, help and docs.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc
#include "gantry/lang/statement.hpp"   // Param

namespace gantry {

class CommandContext;
struct CommandSpec;

enum class CommandGroup { Jog, Move, Settings, Values };

struct ParamSpec {
  std::string_view name;                // as the fill-in sheet shows it
  std::string_view unit;                // "units", "units/s", ""
  bool required = false;                // a blank is an error
  std::optional<double> default_value;  // used when blank (nullopt: the handler decides)
  std::string_view help;
};

// A command's parameters after evaluation: one slot per ParamSpec, nullopt when blank.
struct CommandCall {
  const CommandSpec& spec;
  SourceLoc loc;                     // the command's own location
  const std::vector<Param>& params;  // as written, for locating errors
  std::vector<std::optional<double>> values;

  // The location of parameter i (or of the command when it was not written).
  SourceLoc param_loc(size_t i) const { return i < params.size() ? params[i].loc : loc; }
};

using CommandHandler = void (*)(CommandContext&, const CommandCall&);

struct CommandSpec {
  std::string_view code;  // upper case, two characters
  std::string_view name;
  CommandGroup group;
  std::string_view help;
  std::vector<ParamSpec> params;
  CommandHandler handler;
};

class CommandTable {
 public:
  explicit CommandTable(std::vector<CommandSpec> specs);
  // The commands Gantry implements.
  static const CommandTable& standard();

  const CommandSpec* find(std::string_view code) const;  // code upper case
  std::span<const CommandSpec> all() const { return specs_; }

 private:
  std::vector<CommandSpec> specs_;
};

const char* group_name(CommandGroup g);

// Registration of each family (one file each in src/commands).
void add_move_commands(std::vector<CommandSpec>& out);
void add_mode_commands(std::vector<CommandSpec>& out);

}  // namespace gantry
