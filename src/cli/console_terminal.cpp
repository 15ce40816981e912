// The console's terminal: writing, its width, raw mode for the keys, and lines from a pipe.
#include "console_terminal.hpp"

#include <poll.h>       // poll
#include <sys/ioctl.h>  // TIOCGWINSZ
#include <unistd.h>     // read

#include <cerrno>
#include <cstdio>  // stdout
#include <utility>

namespace gantry::console {

void write_out(std::string_view s) {
  std::fwrite(s.data(), 1, s.size(), stdout);
  std::fflush(stdout);
}

int terminal_columns() {
  winsize w{};
  return ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0 ? w.ws_col : 80;
}

RawTerminal::RawTerminal(int fd) : fd_(fd) {
  if (tcgetattr(fd_, &saved_) != 0) return;
  termios raw = saved_;
  raw.c_iflag &= ~static_cast<tcflag_t>(BRKINT | ICRNL | INPCK | ISTRIP | IXON);
  raw.c_lflag &= ~static_cast<tcflag_t>(ECHO | ICANON | IEXTEN | ISIG);
  raw.c_cflag |= CS8;
  raw.c_cc[VMIN] = 1;
  raw.c_cc[VTIME] = 0;
  active_ = tcsetattr(fd_, TCSAFLUSH, &raw) == 0;
}

void RawTerminal::restore() {
  if (active_) tcsetattr(fd_, TCSAFLUSH, &saved_);
  active_ = false;
}

bool LineReader::next(std::string& line, const std::atomic<int>& signal) {
  while (signal == 0) {
    if (const size_t nl = buf_.find('\n'); nl != std::string::npos) {
      line = buf_.substr(0, nl);
      buf_.erase(0, nl + 1);
      return true;
    }
    if (eof_) {
      if (buf_.empty()) return false;
      line = std::exchange(buf_, {});
      return true;
    }
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) continue;
    char buf[4096];
    const ssize_t n = read(fd_, buf, sizeof buf);
    if (n > 0)
      buf_.append(buf, static_cast<size_t>(n));
    else if (n == 0 || (errno != EINTR && errno != EAGAIN))
      eof_ = true;
  }
  return false;
}

}  // namespace gantry::console
