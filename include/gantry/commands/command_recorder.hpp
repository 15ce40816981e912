// The console's command record (RA, RI, RP, RR, RS, RZ): the lines the operator typed, kept
// in order so that they can be played again or saved as a part file.
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace gantry {

// Lines typed at the console, oldest first, at most kCapacity of them (the oldest goes).
// Recording is on from the start (RA); RI pauses it without losing what is kept; RZ empties
// it. Lines run from a part file, or played back from the record, are never recorded: only
// the console front end calls record(), through Interpreter::record_typed().
class CommandRecorder {
 public:
  static constexpr std::size_t kCapacity = 100;

  // Keeps `line` (its trailing blanks and line terminator dropped) when recording is on and
  // the line can be played again: it parses as a statement, and it is not a label or a
  // Record command (playing RP back would play the record inside itself; RZ would erase it).
  // Blank and comment lines are not kept. Returns whether the line was kept.
  bool record(std::string_view line);

  void set_active(bool on) { active_ = on; }
  bool active() const { return active_; }
  void clear() { lines_.clear(); }  // RZ
  std::size_t size() const { return lines_.size(); }
  // The last `n` lines kept, oldest first; all of them when `n` is larger than size().
  std::vector<std::string> last(std::size_t n) const;

 private:
  std::deque<std::string> lines_;
  bool active_ = true;  // SB3: recording is on by default
};

}  // namespace gantry
