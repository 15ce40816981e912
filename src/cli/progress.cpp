// Terminal progress bar.
#include "progress.hpp"

#include <fmt/format.h>  // bar text
#include <unistd.h>      // isatty

#include <cstdio>  // stderr

namespace gantry {

ProgressBar::ProgressBar() : enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && last_percent_ >= 0) std::fputs("\n", stderr);
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const int percent = static_cast<int>(done * 100 / total);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  constexpr int kWidth = 40;
  const int filled = percent * kWidth / 100;
  fmt::print(stderr, "\r[{:#<{}}{:<{}}] {:3}%  statement {}/{}", "", filled, "", kWidth - filled,
             percent, done, total);
  std::fflush(stderr);
}

}  // namespace gantry
