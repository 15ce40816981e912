// Scripted operator answers: --yes and --input, for runs without a person at the machine.
#include "gantry/interp/operator_io.hpp"

#include <fmt/format.h>  // messages

#include <algorithm>  // any_of
#include <cstdio>     // stdout

namespace gantry {

KeypadAnswer OperatorIO::keypad(std::string_view message, const SourceLoc& loc) {
  const std::string text = fmt::format(
      "{}{}SK hands over the keypad, and there is none here (`gantry console` has "
      "one): the file goes on without jogging",
      message, message.empty() ? "" : " - ");
  if (!confirm(text, loc))
    throw OperatorStop({loc, Severity::Error, "stopped by the operator at SK"});
  return KeypadAnswer::GoOn;
}

void ScriptedIO::print(std::string_view text) {
  if (out_)
    out_->append(text);
  else
    fmt::print(stream_, "{}", text);
}

bool ScriptedIO::confirm(std::string_view message, const SourceLoc& loc) {
  if (yes_) return true;
  throw NeedsOperator({loc, Severity::Error,
                       fmt::format("the file waits for the operator (\"{}\"); run from a "
                                   "terminal, or with --yes to continue every pause",
                                   message)});
}

std::optional<std::string> ScriptedIO::ask(std::string_view, std::string_view variable,
                                           std::string_view default_value, const SourceLoc& loc) {
  std::string answer;
  size_t start = 0;
  const std::string names(variable);
  while (start <= names.size()) {  // one value per variable, joined as the operator types them
    size_t comma = names.find(',', start);
    if (comma == std::string::npos) comma = names.size();
    const std::string name = names.substr(start, comma - start);
    auto it = inputs_.find(name);
    // An INPUT that offers no default has no answer to take: the preview stops there.
    if (it == inputs_.end() && input_defaults_ && !default_value.empty()) {
      // Once a line: an INPUT in a loop says it once.
      const bool said = std::any_of(warnings_.begin(), warnings_.end(), [&](const Diagnostic& w) {
        return w.loc.line == loc.line &&
               (w.loc.file == loc.file || (w.loc.file && loc.file && *w.loc.file == *loc.file));
      });
      if (!said)
        warn({loc, Severity::Warning,
              fmt::format("the preview answered INPUT {} with its default \"{}\" (the run asks "
                          "the operator)",
                          variable, default_value)});
      return std::string(default_value);
    }
    if (it == inputs_.end())
      throw NeedsOperator({loc, Severity::Error,
                           fmt::format("the file asks the operator for {}; run from a "
                                       "terminal, or give it with --input '{}=VALUE'",
                                       name, name)});
    answer += (answer.empty() ? "" : ",") + it->second;
    start = comma + 1;
  }
  return answer;
}

std::string ScriptedIO::choose(std::string_view text, const std::vector<std::string>& buttons,
                               size_t default_button, std::string_view, const SourceLoc& loc) {
  if (yes_ || buttons.size() == 1) return buttons[default_button];
  throw NeedsOperator(
      {loc, Severity::Error,
       fmt::format("MSGBOX asks the operator (\"{}\"); run from a terminal, or with "
                   "--yes to press its default button",
                   text)});
}

KeypadAnswer ScriptedIO::keypad(std::string_view message, const SourceLoc& loc) {
  if (yes_) return KeypadAnswer::GoOn;
  throw NeedsOperator(
      {loc, Severity::Error,
       fmt::format("SK hands the keypad to the operator{}{}{}; run the file from `gantry "
                   "console` to jog, or with --yes to go on without jogging",
                   message.empty() ? "" : " (\"", message, message.empty() ? "" : "\")")});
}

void ScriptedIO::warn(const Diagnostic& d) {
  warnings_.push_back(d);
}

}  // namespace gantry
