// The part-file log (VD's "write part file log"): a line when a part file run starts and one
// when it ends, appended atomically, and its reading for `gantry log` (docs/machine_state.md).
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "gantry/core/axes.hpp"           // Vec6
#include "gantry/machine/controller.hpp"  // Controller::Activity

namespace gantry::session {
struct SavedMachine;  // machine_memory.hpp
}

namespace gantry::session {

// One run of a part file.
struct RunRecord {
  // The run's start and end lines share it ("<start>-<pid>-<n>"); empty in older logs.
  std::string id;
  int pid = 0;  // the process that ran it (its start line)
  std::string file;
  std::string start, end;  // UTC, ISO 8601
  // "completed", "stopped" (by the operator), "E-stop", "fault" (the card's), "error";
  // "running" (the start line, no end yet), "killed" (no end line: killed or crashed).
  std::string status;
  int line = 0;             // where it stopped (top-level file's line; 0: completed)
  std::string message;      // why it stopped
  double cycle_s = 0;       // machine time from start to rest
  Vec6 position = Vec6::Zero();  // where it left the tool, table base coordinates
  std::string units;
};

// The log next to the values file: values/NAME.toml -> values/part_files.log.
std::string run_log_path(const std::string& values_path);
// One line of JSON (no newline), and back (nullopt: not a record).
std::string run_record_line(const RunRecord& r);
std::optional<RunRecord> parse_run_record(const std::string& line);
// Appends one line in one write (O_APPEND, then fsync): runs of several processes never mix
// their lines. False with `why` when it cannot.
bool append_run_record(const std::string& path, const RunRecord& r, std::string* why);
// The last `last` runs (0: all), oldest first: a run's end line takes its start line's
// place; a start line with no end whose process is gone reads as "killed" (an end unknown).
// Lines that are not records are counted in `bad` (a line cut by a full disk, say) and
// skipped.
std::vector<RunRecord> read_run_log(const std::string& path, std::size_t last,
                                    std::size_t* bad = nullptr);
// A record as the operator reads it: "2026-11-27 01:50:03  0:00:12.3  completed  FILE".
std::string run_record_text(const RunRecord& r);

// Writes the log from the controller's activities: a "running" line when a part file run
// starts, and its end line (same id) when it comes to rest.
class RunLogger {
 public:
  explicit RunLogger(std::string path) : path_(std::move(path)) {}
  // At start: every run left "running" by a process that is gone (killed, crashed, powered
  // off) gets its end line, status "killed", with where the machine state file last knew the
  // tool (`last`, when loaded). How many it closed.
  std::size_t close_unfinished(const SavedMachine* last = nullptr);
  // Tell it every activity (MachineMemory::attach's `also`, or Controller::on_activity).
  void activity(const Controller::Activity& a);
  const std::string& path() const { return path_; }
  // Why the last append failed (empty: it did not).
  std::string failure() const;

 private:
  std::string path_;
  mutable std::mutex m_;
  std::string start_;  // the running file's start
  std::string id_;     // ... and its id
  int runs_ = 0;
  std::string failure_;
};

}  // namespace gantry::session
