// The operator, as the interpreter sees one: messages out, answers in.
#pragma once

#include <cstdio>  // FILE, stdout
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gantry/core/diagnostic.hpp"  // SourceLoc, Diagnostic

namespace gantry {

// SK's answer: the operator jogs with the machine's keypad and the file waits until they
// close it (the console), or there is no keypad here and the file goes on.
enum class KeypadAnswer { Jog, GoOn };

class OperatorIO {
 public:
  virtual ~OperatorIO() = default;
  // PRINT output, exactly as the program formatted it (newline included when it has one).
  virtual void print(std::string_view text) = 0;
  // PAUSE, DIALOG: true continues, false cancels the run.
  virtual bool confirm(std::string_view message, const SourceLoc& loc) = 0;
  // INPUT: the answer typed for `variable` (upper case, with its sigil); nullopt cancels.
  virtual std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                         std::string_view default_value, const SourceLoc& loc) = 0;
  // MSGBOX: the caption of the button pressed, one of `buttons`.
  virtual std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                             size_t default_button, std::string_view title,
                             const SourceLoc& loc) = 0;
  // A warning during the run (PLAY not played, a CLOSE of a closed file, ...).
  virtual void warn(const Diagnostic& d) = 0;
  // SK: the file hands the keypad to the operator. This default is a front end without a
  // keypad: it asks to go on without jogging (confirm), and a refusal ends the run.
  virtual KeypadAnswer keypad(std::string_view message, const SourceLoc& loc);
};

// Answers without a person: `yes` continues every PAUSE and presses a MSGBOX's default
// button; `inputs` answers INPUT by variable name. A question it cannot answer is an error
// naming its line and the option that would answer it. PRINT text goes to `out`, or when
// that is null to `stream`.
class ScriptedIO : public OperatorIO {
 public:
  ScriptedIO(bool yes, std::map<std::string, std::string> inputs, std::string* out = nullptr,
             std::FILE* stream = stdout)
      : yes_(yes), inputs_(std::move(inputs)), out_(out), stream_(stream) {}
  void print(std::string_view text) override;
  bool confirm(std::string_view message, const SourceLoc& loc) override;
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override;
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     size_t default_button, std::string_view title, const SourceLoc& loc) override;
  void warn(const Diagnostic& d) override;
  KeypadAnswer keypad(std::string_view message, const SourceLoc& loc) override;
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  // A preview: an INPUT `inputs` does not answer takes the default it offers (what Enter at
  // the window's dialog gives), with a warning that says so, instead of ending the check.
  void take_input_defaults() { input_defaults_ = true; }

 private:
  bool yes_;
  bool input_defaults_ = false;
  std::map<std::string, std::string> inputs_;  // keys upper case, e.g. "&DEPTH"
  std::string* out_;                           // PRINT text goes here (or to stream_)
  std::FILE* stream_;
  std::vector<Diagnostic> warnings_;
};

// Thrown where the run needs an operator answer that nobody can give (a check, or a run
// without a terminal and without --yes/--input).
class NeedsOperator : public GantryError {
 public:
  using GantryError::GantryError;
};

// Thrown when the operator cancels (PAUSE, INPUT, MSGBOX Cancel): the run ends everywhere.
class OperatorStop : public GantryError {
 public:
  using GantryError::GantryError;
};

}  // namespace gantry
