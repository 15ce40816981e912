// The console window's command line, without any drawing: two-letter completion, the
// parameter line shown after a code, the history, and the menus by command group. Everything
// comes from the command table, so a new command appears here with no change to the window.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/commands/command_table.hpp"  // CommandTable, CommandSpec, CommandGroup

namespace gantry::ui {

// The commands whose code starts with the first one or two letters of `typed` (any case),
// in table order; empty once the text is longer than a code or is not one.
std::vector<const CommandSpec*> completions(const CommandTable& table, std::string_view typed);

// What Tab makes of `typed`: the one matching code (with ", " when it takes parameters), or
// the longest prefix the matches share; `typed` unchanged when nothing matches.
std::string complete(const CommandTable& table, std::string_view typed);

// The command a line starts with (its first two letters, when they are a code followed by
// nothing, a comma or a blank); null otherwise (an assignment, PRINT, a label ...).
const CommandSpec* command_of(const CommandTable& table, std::string_view line);

// The parameter line shown under the command line once a code is typed: "MX, X location
// [units]" with each parameter's unit and default, the one the cursor is in marked.
struct ParamLine {
  std::string text;  // "MX  Move X: X location (distance, units)"
  std::string help;  // the current parameter's help
  int current = -1;  // the parameter the cursor is in (-1: the code)
};
ParamLine param_line(const CommandSpec& spec, Dialect dialect, std::string_view line,
                     std::size_t cursor);

// What Enter does with a line.
enum class EnterAction {
  Nothing,    // blank
  Run,        // run it as typed
  OpenSheet,  // a bare code whose command takes parameters: ask for them in the sheet
};
EnterAction enter_action(const CommandTable& table, std::string_view line);

// Lines entered, for Up and Down; the line being typed is kept while walking.
class History {
 public:
  explicit History(std::size_t limit = 500) : limit_(limit) {}
  void add(const std::string& line);  // not blank, not a repeat of the last
  // Up (older) and Down (newer) from `current` (the text in the field now); nullopt at an end.
  std::optional<std::string> up(const std::string& current);
  std::optional<std::string> down();
  const std::vector<std::string>& lines() const { return lines_; }

 private:
  std::vector<std::string> lines_;
  std::size_t limit_;
  std::size_t pos_ = 0;  // lines_.size(): not walking
  std::string draft_;
};

// A menu of the command bar: a group, its hot key (the letter its codes start with, where
// they share one) and its commands in table order.
struct Menu {
  std::string title;  // "Move"
  char key = 0;       // 'M': Alt+M opens it
  std::vector<const CommandSpec*> commands;
};
// Cuts, File, Jog, Move, Zero, Values, Settings, Tools, Utilities, Help (as SB3 orders its
// menus), then Probe and Record; groups with no command are left out.
std::vector<Menu> menus(const CommandTable& table);

}  // namespace gantry::ui
