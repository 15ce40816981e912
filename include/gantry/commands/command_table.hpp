// The one table of two-letter commands: it drives the parser's checks, dispatch, help and docs.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"    // SourceLoc
#include "gantry/interp/value.hpp"       // Value
#include "gantry/lang/script.hpp"        // IsCommand
#include "gantry/lang/statement.hpp"     // Arg
#include "gantry/settings/settings.hpp"  // Dialect

namespace gantry {

class CommandContext;
struct CommandSpec;

enum class CommandGroup {
  Cuts,
  File,
  Help,
  Jog,
  Move,
  Probe,
  Record,
  Settings,
  Tools,
  Utilities,
  Values,
  Zero
};

enum class ParamKind { Number, Text };

struct ParamSpec {
  std::string_view name;                // as the fill-in sheet shows it
  std::string_view unit;                // "units", "units/s", ""
  bool required = false;                // a blank is an error
  std::optional<double> default_value;  // used when blank (nullopt: the handler decides)
  std::string_view help;
  ParamKind kind = ParamKind::Number;  // Text: a file name, a letter; bare words allowed
  // Checked before the handler runs: a value outside is a located error and nothing happens.
  std::optional<double> min = {}, max = {};  // allowed range, inclusive
  bool whole = false;                        // a whole number
  std::string_view choices = {};             // Text: the allowed words ("O I T"), any case

  ParamSpec range(double lo, double hi) const {
    ParamSpec p = *this;
    p.min = lo;
    p.max = hi;
    return p;
  }
  ParamSpec at_least(double lo) const {
    ParamSpec p = *this;
    p.min = lo;
    return p;
  }
  ParamSpec integer(double lo, double hi) const {
    ParamSpec p = range(lo, hi);
    p.whole = true;
    return p;
  }
  ParamSpec one_of(std::string_view words) const {
    ParamSpec p = *this;
    p.choices = words;
    return p;
  }
};

// The type the fill-in sheet and the docs show: distance, speed, angle, int, flag, choice,
// filename, text or number; derived from the unit, range and kind.
std::string_view param_type(const ParamSpec& p);
// "0 to 1", ">= 0", "O, I or T": the allowed values in words ("" when anything goes).
std::string param_range(const ParamSpec& p);

// A command's parameters after evaluation: one slot per ParamSpec, nullopt when blank.
struct CommandCall {
  const CommandSpec& spec;
  const SourceLoc& loc;                          // the command's own location
  const std::vector<Arg>& args;                  // as written, for locating errors
  std::span<const std::optional<Value>> values;  // one per parameter, nullopt when blank

  // The location of parameter i (or of the command when it was not written).
  SourceLoc param_loc(size_t i) const { return i < args.size() ? args[i].loc : loc; }
  // Parameter i as a number (Number parameters) or text (Text parameters); nullopt if blank.
  std::optional<double> number(size_t i) const {
    return values[i] ? std::optional<double>(values[i]->num()) : std::nullopt;
  }
  std::optional<std::string> text(size_t i) const {
    return values[i] ? std::optional<std::string>(values[i]->to_string()) : std::nullopt;
  }
};

using CommandHandler = void (*)(CommandContext&, const CommandCall&);

struct CommandSpec {
  std::string_view code;  // upper case, two characters
  std::string_view name;
  CommandGroup group;
  std::string_view help;
  std::vector<ParamSpec> params;
  CommandHandler handler;
  // Empty when the command does all the references describe; otherwise what it lacks.
  std::string_view coverage = {};
  // The parameters in FabMo's order when `dialect = "fabmo"` (empty: the same as `params`).
  std::vector<ParamSpec> fabmo_params = {};
  bool immediate = false;      // runs as soon as the code is typed (no parameter line)
  std::string_view sets = {};  // system variables it changes, e.g. "%(1)-%(5)"
  // Parameters past the last are ignored with a warning, as SB3 does; when this says why,
  // they are refused instead (their values would be misread).
  std::string_view extra_params_refused = {};

  // The parameter list in force for `dialect`.
  const std::vector<ParamSpec>& params_for(Dialect d) const {
    return d == Dialect::FabMo && !fabmo_params.empty() ? fabmo_params : params;
  }
};

class CommandTable {
 public:
  explicit CommandTable(std::vector<CommandSpec> specs);
  // The commands Gantry implements.
  static const CommandTable& standard();

  const CommandSpec* find(std::string_view code) const;  // code upper case
  // find() as the predicate a script's load pass reports unknown commands with.
  IsCommand is_command() const {
    return [this](std::string_view code) { return find(code) != nullptr; };
  }
  std::span<const CommandSpec> all() const { return specs_; }

 private:
  std::vector<CommandSpec> specs_;
  std::array<int, 36 * 36> index_{};  // code -> position in specs_, -1 if none
};

const char* group_name(CommandGroup g);

// Registration of each family (one file each in src/commands).
void add_move_commands(std::vector<CommandSpec>& out);
void add_probe_commands(std::vector<CommandSpec>& out);
// C3 when there is no custom file C3.sbp or macro_3.sbp: homing on the proximity switches
// as the profile's [homing] says. `only` (lower-case letters): home just those axes, in the
// profile's order (WinCNC's `G28 Z`); empty: every axis of the order.
void home_on_switches(CommandContext& ctx, const SourceLoc& loc, std::string_view only = {});
void add_mode_commands(std::vector<CommandSpec>& out);
void add_file_commands(std::vector<CommandSpec>& out);
void add_output_commands(std::vector<CommandSpec>& out);
void add_zero_commands(std::vector<CommandSpec>& out);
void add_move_distance(std::vector<CommandSpec>& out);
void add_values_commands(std::vector<CommandSpec>& out);
void add_settings_commands(std::vector<CommandSpec>& out);
void add_help_commands(std::vector<CommandSpec>& out);
void add_tool_commands(std::vector<CommandSpec>& out);
void add_utility_commands(std::vector<CommandSpec>& out);
// The editor FE starts: the machine profile's [machine] editor, else $VISUAL, $EDITOR, vi;
// never a value a part file could set (UN, UR, the values file: docs/security.md). `words`:
// its program and options, split at spaces and run without a shell; `from`: where it is set.
struct EditorChoice {
  std::vector<std::string> words;
  std::string text, from;
};
EditorChoice editor_choice(const CommandContext& ctx);
void add_cut_commands(std::vector<CommandSpec>& out);
void add_record_commands(std::vector<CommandSpec>& out);  // and SI
void add_nudge_commands(std::vector<CommandSpec>& out);   // MN, MI

}  // namespace gantry
