// The operator as the console window is one: PRINT text and warnings go to the message log,
// and PAUSE, INPUT and MSGBOX become dialogs. The controller's job thread asks and waits; the
// window's thread shows the question and answers it.
#pragma once

#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "gantry/interp/operator_io.hpp"  // OperatorIO, ScriptedIO

namespace gantry::ui {

struct Question {
  enum class Kind { Pause, Input, MsgBox } kind = Kind::Pause;
  std::string where;                    // "part.sbp:12" or "console"
  std::string title;                    // MSGBOX's title
  std::string text;                     // the message, or INPUT's prompt
  std::string variable, default_value;  // INPUT
  std::vector<std::string> buttons;     // MSGBOX
  std::size_t default_button = 0;
  std::uint64_t id = 0;  // a new question has a new id
};

class WindowIO : public OperatorIO {
 public:
  // `yes` and `inputs` answer what they can without asking (as --yes and --input do).
  WindowIO(bool yes, std::map<std::string, std::string> inputs)
      : scripted_(yes, std::move(inputs)) {}

  void print(std::string_view text) override;
  void warn(const Diagnostic& d) override;
  bool confirm(std::string_view message, const SourceLoc& loc) override;
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override;
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     std::size_t default_button, std::string_view title,
                     const SourceLoc& loc) override;
  // SK in a file: the window's keypad takes the keys once the controller waits (Keypad).
  KeypadAnswer keypad(std::string_view message, const SourceLoc& loc) override;

  // ---- the window's side ----
  std::string take_output();                 // PRINT text and warnings since the last call
  std::optional<Question> question() const;  // the one waiting for an answer, if any
  // PAUSE: any answer continues; INPUT: the text; MSGBOX: the caption of a button.
  void answer(std::string a);
  void cancel();  // PAUSE and INPUT cancel the run; MSGBOX presses its last button
  std::string take_keypad_message();  // SK's message, once

 private:
  std::optional<std::string> wait_for(Question q);

  ScriptedIO scripted_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::string output_;
  std::optional<Question> question_;
  std::optional<std::string> answer_;
  std::uint64_t next_id_ = 1;
  std::string keypad_message_;
};

}  // namespace gantry::ui
