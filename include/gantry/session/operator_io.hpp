// The operator as a console (terminal or window) is one: PRINT text and warnings are queued
// for the front end's thread, and PAUSE, INPUT and MSGBOX become questions. The controller's
// job thread asks and waits; the front end's thread shows the question and answers it.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/interp/operator_io.hpp"  // OperatorIO, ScriptedIO

namespace gantry::session {

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

// One mailbox between the job thread and the front end's thread. `yes` and `inputs` answer
// what they can without asking (as --yes and --input do). With no operator to ask
// (`direct` set: the console reads piped lines), PRINT text goes straight to `direct` (the
// front end waits for the line then) and a question nobody answers fails (NeedsOperator,
// saying which option would answer it).
class OperatorMailbox : public OperatorIO {
 public:
  OperatorMailbox(bool yes, std::map<std::string, std::string> inputs,
                  std::function<void(std::string_view)> direct = {})
      : scripted_(yes, std::move(inputs)), direct_(std::move(direct)) {}

  void print(std::string_view text) override;
  void warn(const Diagnostic& d) override;
  // PAUSE: an answer (any) continues, a cancel cancels the run.
  bool confirm(std::string_view message, const SourceLoc& loc) override;
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override;
  // MSGBOX: the answer is a button's caption; a cancel presses the last button.
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     std::size_t default_button, std::string_view title,
                     const SourceLoc& loc) override;
  // SK in a file: the front end's keypad takes the keys once the controller waits (Keypad).
  KeypadAnswer keypad(std::string_view message, const SourceLoc& loc) override;

  // ---- the front end's side ----
  std::string take_output();                 // PRINT text and warnings since the last call
  std::optional<Question> question() const;  // the one waiting for an answer, if any
  // PAUSE: any answer continues; INPUT: the text; MSGBOX: the caption of a button.
  void answer(std::string a);
  // Cancels the question being asked, if any (Esc, a stop, the E-stop): PAUSE and INPUT
  // cancel the run, MSGBOX presses its last button.
  void cancel();
  std::string take_keypad_message();  // SK's message (as the file gave it), once

 private:
  std::optional<std::string> wait_for(Question q);
  bool has_operator() const { return !direct_; }

  ScriptedIO scripted_;
  std::function<void(std::string_view)> direct_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::string output_;
  std::optional<Question> question_;
  std::optional<std::string> answer_;
  std::uint64_t next_id_ = 1;
  std::string keypad_message_;
};

}  // namespace gantry::session
