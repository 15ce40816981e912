// A one-line progress bar on stderr, shown only when stderr is a terminal.
#pragma once

#include <cstddef>

namespace gantry {

class ProgressBar {
 public:
  ProgressBar();
  ~ProgressBar();  // ends the line
  void update(std::size_t done, std::size_t total);
  bool enabled() const { return enabled_; }

 private:
  bool enabled_;
  int last_percent_ = -1;
};

}  // namespace gantry
