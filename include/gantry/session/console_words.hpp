// A line typed at a console (terminal or window): one of the console's words (QUIT, HELP,
// STATUS, ACK, K, SK, STEP, TEACH), or a line for the machine.
#pragma once

#include <string>
#include <string_view>

namespace gantry::session {

struct TypedLine {
  enum class Word {
    None,     // a line for the machine (or an empty line)
    Quit,     // QUIT or EXIT
    Help,     // HELP [argument]
    Status,   // STATUS
    Ack,      // ACK: the E-stop acknowledged
    Keypad,   // K, or SK [, message]
    Step,     // STEP [ON|OFF]: single step
    Confirm,  // CONFIRM: the restored position is right (the machine memory)
    Teach,    // TEACH file | TEACH OFF | TEACH: Friendly Motion's teach log (fm_hot_keys.hpp)
  };
  Word word = Word::None;
  std::string line;      // trimmed (empty: nothing to do)
  std::string first;     // the first word, upper case ("STEP" even when the word is not Step)
  std::string rest;      // after the first word, trimmed: HELP's argument, STEP's ON or OFF,
                         // TEACH's file or OFF
  std::string message;   // SK's message
  bool step_on = false;  // STEP: on (ON, or a bare STEP with single step off)
};

// `single_step`: whether single step is on now (a bare STEP toggles it).
TypedLine read_typed_line(std::string_view typed, bool single_step = false);

}  // namespace gantry::session
