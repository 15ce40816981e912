// Friendly Motion's Alt-F keys at a console (terminal or window; docs/friendlymotion.md,
// "Hot keys and teach mode"): during a run they call the program's subroutines N10001-N10010
// (the manual's "Automatic Subroutine Call"); at rest, with a teach log open, Alt-F1 writes the
// position and Alt-F7-F10 the laser's and the shutter's M-functions (the manual's Appendix 1).
// Both front ends send their Alt-F keys here, so they do the same.
#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "gantry/core/vec6.hpp"            // Vec6
#include "gantry/machine/controller.hpp"   // Controller, Outcome
#include "gantry/session/operator_io.hpp"  // OperatorMailbox
#include "gantry/settings/settings.hpp"    // Units, FriendlyMotionSettings

namespace gantry::session {

// "Alt+F1" ... "Alt+F10" (key_name's spelling): 1-10; any other key: nullopt.
std::optional<int> fm_hot_key(std::string_view key_name);

// What a hot key did during a run.
struct HotKeyPress {
  Outcome outcome;        // refused: no file runs (the reason says so)
  bool answered = false;  // it answered the run's STEP question (the front end closes it)
};

// Alt-F`key` during a run: the controller's file calls N(10000 + key) before its next line.
// When the file waits at Friendly Motion's STEP question (STEP, M0), the key answers it with
// Step, so the subroutine runs at once and the line asks again after it.
HotKeyPress press_fm_hot_key(Controller& c, OperatorMailbox& io, int key);

// Teach mode's position log: a Friendly Motion program being written (the manual's Teach.nc).
// It starts with a comment, the units and G90, so that it runs as taught; Alt-F1 appends the
// position as one interpolated move, `X1.2500Y-0.5000`; Alt-F7...F10 append M100, M101 (the
// laser's gate on, off), M102, M103 (the safety shutter open, closed); closing it ends the
// program with M0. Each line is flushed as it is written, so a crash keeps every point.
class TeachLog {
 public:
  // Creates (empties) `path`; nullopt with `why` when it cannot be written.
  static std::unique_ptr<TeachLog> open(const std::string& path, Units units, std::string* why);
  ~TeachLog();
  TeachLog(const TeachLog&) = delete;
  TeachLog& operator=(const TeachLog&) = delete;

  // What a key does: the line it writes, and the output switch it turns on or off (0: none).
  struct Entry {
    std::string line;
    int output = 0;
    bool on = false;
  };
  // Alt-F`key` with the table at `position` (working coordinates, the log's units). nullopt
  // for the keys teach mode does not use (Alt-F2...F6), with `why`; otherwise the line is
  // written. `fm` names the laser's output (Alt-F7/F8); the shutter is output 2.
  std::optional<Entry> key(int key, const Vec6& position, const FriendlyMotionSettings& fm,
                           std::string* why);
  // Writes M0 and closes the file; the number of lines taught.
  int close();
  const std::string& path() const { return path_; }
  int lines() const { return lines_; }

 private:
  TeachLog(std::FILE* f, std::string path, Units units)
      : f_(f), path_(std::move(path)), units_(units) {}
  bool write(const std::string& line);
  std::FILE* f_;
  std::string path_;
  Units units_;
  int lines_ = 0;
};

// What a console does with TEACH and the Alt-F keys, the same in both front ends: the front
// end shows `message`, closes its STEP question when `answered`, and runs `typed` (the output
// a teach key switches, as a typed line: SO, n, 1) when it is not empty.
class FmKeys {
 public:
  struct Result {
    std::string message;
    bool error = false;
    bool answered = false;
    std::string typed;
  };
  // TEACH `rest`: "OFF" closes the log, a file name opens one (closing the last), "" says
  // which is open. `units`: the profile's, which the log is written in.
  Result teach(const std::string& rest, Units units);
  // Alt-F`key`. `running`: a file runs (its hot keys are its own); otherwise, at rest with the
  // table at `position` (working coordinates), the teach log's, when one is open.
  Result key(int key, bool running, Controller& c, OperatorMailbox& io, const Vec6& position,
             const FriendlyMotionSettings& fm);
  bool teaching() const { return log_ != nullptr; }

 private:
  std::unique_ptr<TeachLog> log_;
};

}  // namespace gantry::session
