// The console's words, read from a typed line.
#include "gantry/session/console_words.hpp"

#include <algorithm>

#include "gantry/lang/scan.hpp"  // upper, trim

namespace gantry::session {

TypedLine read_typed_line(std::string_view typed, bool single_step) {
  TypedLine t;
  t.line = std::string(scan::trim(typed));
  if (t.line.empty()) return t;
  const std::string& line = t.line;
  const size_t space = line.find_first_of(" \t");
  t.first = scan::upper(line.substr(0, space));
  t.rest = space == std::string::npos ? "" : std::string(scan::trim(line.substr(space)));
  const std::string& word = t.first;
  const bool bare = t.rest.empty();
  const std::string code = scan::upper(line.substr(0, std::min<size_t>(2, line.size())));
  if ((word == "QUIT" || word == "EXIT") && bare) {
    t.word = TypedLine::Word::Quit;
  } else if (word == "HELP") {
    t.word = TypedLine::Word::Help;
  } else if (word == "STATUS" && bare) {
    t.word = TypedLine::Word::Status;
  } else if (word == "ACK" && bare) {
    t.word = TypedLine::Word::Ack;
  } else if (word == "CONFIRM" && bare) {
    t.word = TypedLine::Word::Confirm;
  } else if (word == "K" && bare) {
    t.word = TypedLine::Word::Keypad;
  } else if (word == "STEP" &&
             (bare || scan::upper(t.rest) == "ON" || scan::upper(t.rest) == "OFF")) {
    t.word = TypedLine::Word::Step;
    t.step_on = bare ? !single_step : scan::upper(t.rest) == "ON";
  } else if (word == "TEACH") {
    t.word = TypedLine::Word::Teach;
  } else if (code == "SK" && (line.size() == 2 || line[2] == ',' || line[2] == ' ')) {
    t.word = TypedLine::Word::Keypad;
    const size_t comma = line.find(',');
    if (comma != std::string::npos) t.message = std::string(scan::trim(line.substr(comma + 1)));
  }
  return t;
}

}  // namespace gantry::session
