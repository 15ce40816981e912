// The operator at a terminal: PAUSE, INPUT and MSGBOX answered on stdin.
#pragma once

#include <map>

#include "gantry/interp/operator_io.hpp"  // OperatorIO

namespace gantry {

class TerminalIO : public OperatorIO {
 public:
  // `inputs` (--input) answer INPUT without asking.
  explicit TerminalIO(std::map<std::string, std::string> inputs) : inputs_(std::move(inputs)) {}
  void print(std::string_view text) override;
  bool confirm(std::string_view message, const SourceLoc& loc) override;
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override;
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     size_t default_button, std::string_view title, const SourceLoc& loc) override;
  void warn(const Diagnostic& d) override;

 private:
  std::map<std::string, std::string> inputs_;
};

}  // namespace gantry
