// gantry run's progress line on a terminal.
#include "progress.hpp"

#include <fmt/format.h>  // the line
#include <unistd.h>      // isatty

#include <algorithm>  // clamp
#include <cmath>      // lround

namespace gantry {

StatusLine::StatusLine(std::FILE* stream)
    : stream_(stream), enabled_(isatty(fileno(stream)) != 0) {}

StatusLine::~StatusLine() {
  if (enabled_ && !text_.empty()) std::fputs("\n", stream_);
}

void StatusLine::draw() {
  fmt::print(stream_, "\r{}\033[K", text_);  // \033[K: what a longer line left is erased
  std::fflush(stream_);
}

void StatusLine::show(const std::string& text) {
  if (!enabled_) return;
  std::unique_lock lock(m_, std::try_to_lock);
  if (!lock) return;  // a question holds the terminal
  text_ = text;
  draw();
}

StatusLine::Hold::Hold(StatusLine& l) : l_(l), lock_(l.m_) {
  if (l_.enabled_ && !l_.text_.empty()) {
    std::fputs("\r\033[K", l_.stream_);
    std::fflush(l_.stream_);
  }
}

StatusLine::Hold::~Hold() {
  if (l_.enabled_ && !l_.text_.empty()) {
    std::fflush(stdout);  // what the file printed comes before the line
    l_.draw();
  }
}

std::string progress_line(const session::RunProgress& p) {
  constexpr int kWidth = 20;
  // Rounded as the percent beside it is, so "5 %" never stands beside an empty bar.
  const int filled = std::clamp(static_cast<int>(std::lround(p.fraction * kWidth)), 0, kWidth);
  return fmt::format("[{:#<{}}{:<{}}] {:3.0f} %  line {} of {}  {}", "", filled, "",
                     kWidth - filled, 100 * p.fraction, p.line, p.lines, p.times());
}

void StatusLineIO::print(std::string_view text) {
  StatusLine::Hold h(line_);
  inner_.print(text);
}

bool StatusLineIO::confirm(std::string_view message, const SourceLoc& loc) {
  StatusLine::Hold h(line_);
  return inner_.confirm(message, loc);
}

std::optional<std::string> StatusLineIO::ask(std::string_view prompt, std::string_view variable,
                                             std::string_view default_value,
                                             const SourceLoc& loc) {
  StatusLine::Hold h(line_);
  return inner_.ask(prompt, variable, default_value, loc);
}

std::string StatusLineIO::choose(std::string_view text, const std::vector<std::string>& buttons,
                                 size_t default_button, std::string_view title,
                                 const SourceLoc& loc) {
  StatusLine::Hold h(line_);
  return inner_.choose(text, buttons, default_button, title, loc);
}

void StatusLineIO::warn(const Diagnostic& d) {
  StatusLine::Hold h(line_);
  inner_.warn(d);
}

KeypadAnswer StatusLineIO::keypad(std::string_view message, const SourceLoc& loc) {
  StatusLine::Hold h(line_);
  return inner_.keypad(message, loc);
}

}  // namespace gantry
