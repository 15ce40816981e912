// How far the file running (or the last one run) has got, as every front end shows it.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "gantry/machine/controller.hpp"  // ControllerStatus

namespace gantry::session {

struct RunProgress {
  std::size_t line = 0, lines = 0;  // the line shown: the one the card plays while under way
  // Where the run is in the file that plays (a file the run called, FP or C#, while it plays
  // or where the run stopped in it; null: the top-level file): `line` is kept to the top-level
  // file's lines for the label, `file_line` is not (a program listing highlights it).
  std::shared_ptr<const std::string> file;
  std::size_t file_line = 0;
  double fraction = 0;              // 0 to 1
  double elapsed_s = 0;
  double remaining_s = -1;  // < 0: none to show (no estimate, or the run is over)
  bool over = false;        // the run ended: completed, stopped or E-stopped

  // "line 24 of 58 (41 %)"
  std::string label() const;
  // "elapsed 0:00:12  remaining 0:00:17" (remaining "-" when there is none)
  std::string times() const;
};

// The interpreter runs ahead of the motion, so under way the line is the one the card plays
// and the fraction the time played of the check's estimate (the lines when there is none).
// A run that ended short shows the line it stopped at, not the line the interpreter had read
// ahead to, and a run that is over has nothing remaining.
RunProgress run_progress(const ControllerStatus& s);

// "0:01:05"
std::string clock_text(double seconds);

}  // namespace gantry::session
