// `gantry run`'s progress line on a terminal (line, percent, elapsed, remaining), and the
// operator's questions and the file's PRINT text written around it without breaking it.
#pragma once

#include <cstdio>  // FILE
#include <mutex>
#include <string>

#include "gantry/interp/operator_io.hpp"  // OperatorIO
#include "gantry/session/run_progress.hpp"  // RunProgress

namespace gantry {

// One line at the bottom of a terminal, redrawn in place; off when the stream is no terminal.
class StatusLine {
 public:
  explicit StatusLine(std::FILE* stream);
  ~StatusLine();  // ends the line
  bool enabled() const { return enabled_; }
  // Redraws the line with `text` (skipped while held: the next call draws it).
  void show(const std::string& text);
  // While the returned guard lives the line is cleared, and the terminal is the caller's.
  class Hold {
   public:
    explicit Hold(StatusLine& l);
    ~Hold();
    Hold(const Hold&) = delete;
    Hold& operator=(const Hold&) = delete;

   private:
    StatusLine& l_;
    std::unique_lock<std::mutex> lock_;
  };

 private:
  void draw();  // under m_

  std::FILE* stream_;
  bool enabled_;
  std::mutex m_;
  std::string text_;  // what the line shows ("" nothing yet)
};

// The text of the line: "[#####     ]  41 %  line 24 of 58  elapsed 0:00:12  remaining 0:00:17".
std::string progress_line(const session::RunProgress& p);

// An operator that clears the status line while the file prints or asks, then redraws it.
class StatusLineIO : public OperatorIO {
 public:
  StatusLineIO(OperatorIO& inner, StatusLine& line) : inner_(inner), line_(line) {}
  void print(std::string_view text) override;
  bool confirm(std::string_view message, const SourceLoc& loc) override;
  std::optional<std::string> ask(std::string_view prompt, std::string_view variable,
                                 std::string_view default_value, const SourceLoc& loc) override;
  std::string choose(std::string_view text, const std::vector<std::string>& buttons,
                     size_t default_button, std::string_view title, const SourceLoc& loc) override;
  void warn(const Diagnostic& d) override;
  KeypadAnswer keypad(std::string_view message, const SourceLoc& loc) override;

 private:
  OperatorIO& inner_;
  StatusLine& line_;
};

}  // namespace gantry
