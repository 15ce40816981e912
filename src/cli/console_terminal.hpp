// The console's terminal: writing, its width, raw mode for the keys, and lines from a pipe.
#pragma once

#include <termios.h>  // termios

#include <atomic>
#include <string>
#include <string_view>

namespace gantry::console {

// Writes `s` to stdout at once.
void write_out(std::string_view s);
// The terminal's width in columns (80 when stdout is not a terminal).
int terminal_columns();

// Raw mode for the keys: no echo, no line buffering, no signals from Ctrl-C (it is the
// console's E-stop key), no flow control. Output processing stays on, so "\n" starts a line.
class RawTerminal {
 public:
  explicit RawTerminal(int fd);
  ~RawTerminal() { restore(); }
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;
  void restore();

 private:
  int fd_;
  termios saved_{};
  bool active_ = false;
};

// Lines from a file descriptor, waiting with poll so that a signal is noticed.
class LineReader {
 public:
  explicit LineReader(int fd) : fd_(fd) {}
  // The next line (false at the end, or once `signal` is set).
  bool next(std::string& line, const std::atomic<int>& signal);

 private:
  int fd_;
  std::string buf_;
  bool eof_ = false;
};

}  // namespace gantry::console
