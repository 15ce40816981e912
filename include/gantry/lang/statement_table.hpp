// The OpenSBP keyword statements (PAUSE, IF, INPUT ...): one table that the parser dispatches
// on and that `help` and the docs test read, as the command table drives the two-letter commands.
#pragma once

#include <span>
#include <string_view>

namespace gantry {

// Which parser handles a keyword. Several keywords may share one (the registry statements).
enum class Keyword {
  Goto, Gosub, Return, End, EndAll, Exit, If, On, Pause, Print, Write, Input, Msgbox, Dialog,
  Fail, Open, Close, Shell, Warning, Play, Registry, DataSend,
};

struct StatementSpec {
  std::string_view word;     // as the parser matches it, upper case: "PAUSE"
  Keyword keyword;
  std::string_view title;    // one line: what it does
  std::string_view forms;    // its forms, one a line: "PAUSE seconds    waits that long"
  std::string_view section;  // where docs/language.md describes it: "4.7"
};

std::span<const StatementSpec> statement_table();
// The statement a line's first word names (any case), or null.
const StatementSpec* find_statement(std::string_view word);

}  // namespace gantry
