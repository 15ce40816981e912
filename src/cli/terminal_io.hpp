// The operator at a terminal: PAUSE, INPUT and MSGBOX answered on stdin.
#pragma once

#include <atomic>
#include <cstdio>  // FILE
#include <map>

#include "gantry/interp/operator_io.hpp"  // OperatorIO

namespace gantry {

class TerminalIO : public OperatorIO {
 public:
  // `inputs` (--input) answer INPUT without asking; PRINT text goes to `stream`.
  explicit TerminalIO(std::map<std::string, std::string> inputs, std::FILE* stream = stdout)
      : inputs_(std::move(inputs)), stream_(stream) {}
  void print(std::string_view text) override;
  bool confirm(std::string_view message, const SourceLoc& loc) override;
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override;
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     size_t default_button, std::string_view title, const SourceLoc& loc) override;
  void warn(const Diagnostic& d) override;
  // From any thread: a question waiting for its answer, or the next one, ends the file
  // (OperatorStop) instead: the operator stopped the run.
  void cancel() { cancelled_ = true; }

 private:
  // A line from stdin (nullopt at its end); throws OperatorStop once cancelled.
  std::optional<std::string> read_line(const SourceLoc& loc);

  std::map<std::string, std::string> inputs_;
  std::FILE* stream_;
  std::atomic<bool> cancelled_{false};
};

}  // namespace gantry
