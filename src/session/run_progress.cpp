// The progress of a run from the controller's status, for the console, the window and `gantry run`.
#include "gantry/session/run_progress.hpp"

#include <fmt/format.h>

#include <algorithm>  // clamp
#include <cmath>      // llround

namespace gantry::session {

std::string clock_text(double seconds) {
  const long long t = std::llround(std::max(0.0, seconds));
  return fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60);
}

std::string RunProgress::label() const {
  return fmt::format("line {} of {} ({:.0f} %)", line, lines, 100 * fraction);
}

std::string RunProgress::times() const {
  return fmt::format("elapsed {}  remaining {}", clock_text(elapsed_s),
                     remaining_s < 0 ? std::string("-") : clock_text(remaining_s));
}

RunProgress run_progress(const ControllerStatus& s) {
  RunProgress p;
  p.lines = s.lines;
  p.elapsed_s = s.elapsed_s;
  const MachineState st = s.state;
  p.over = st == MachineState::Idle || st == MachineState::Stopped || st == MachineState::EStop;
  const bool short_end = p.over && (st != MachineState::Idle || !s.message.empty());
  // The line shown is under way (or where the motion stopped): the lines before it are done.
  auto by_lines = [&] {
    return p.lines > 0 && p.line > 0
               ? std::clamp(static_cast<double>(p.line - 1) / static_cast<double>(p.lines), 0.0,
                            1.0)
               : 0.0;
  };
  auto by_time = [&] { return std::clamp(s.elapsed_s / (s.elapsed_s + s.remaining_s), 0.0, 1.0); };
  // A file the run called (FP, C#): its lines are not the run's, whose count the label gives;
  // the label keeps the top-level file's line that called it: the one the motion carries, not
  // the reader's, which is ahead.
  auto called = [&](const std::shared_ptr<const std::string>& f) {
    return f && s.file && *f != *s.file;
  };
  auto calling_line = [&](int carried) {
    return carried > 0 ? static_cast<std::size_t>(carried) : s.line;
  };
  if (short_end) {  // where the motion came to rest
    p.line = s.stopped_at.line > 0 ? static_cast<std::size_t>(s.stopped_at.line) : s.line;
    if (s.stopped_at.line > 0) p.file = s.stopped_at.file;
    p.file_line = p.line;
    if (called(p.file)) p.line = calling_line(s.stopped_at.caller_line);
    p.fraction = s.remaining_s > 0 ? by_time() : by_lines();
  } else if (p.over) {
    p.line = p.file_line = s.line;
    p.fraction = p.lines > 0 ? 1.0 : 0.0;
  } else {
    p.line = s.playing_line > 0 ? static_cast<std::size_t>(s.playing_line) : s.line;
    if (s.playing_line > 0) p.file = s.playing_file;
    p.file_line = p.line;
    if (called(p.file)) p.line = calling_line(s.playing_caller_line);
    if (p.lines > 0) p.line = std::min(p.line, p.lines);
    if (s.remaining_s > 0) p.remaining_s = s.remaining_s;
    p.fraction = s.remaining_s > 0 ? by_time() : by_lines();
  }
  return p;
}

}  // namespace gantry::session
