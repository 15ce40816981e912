// The part-file log: JSON lines (a run's start, then its end), each appended in one write;
// read back for `gantry log`.
#include "gantry/session/run_log.hpp"

#include <fcntl.h>   // open
#include <signal.h>  // kill: is a run's process still there
#include <unistd.h>  // write, fsync, close, getpid
#include <fmt/format.h>

#include <cerrno>
#include <cstring>  // strerror
#include <deque>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "gantry/core/utc_time.hpp"           // utc_timestamp
#include "gantry/session/machine_memory.hpp"  // SavedMachine

namespace gantry::session {

std::string run_log_path(const std::string& values_path) {
  return (std::filesystem::path(values_path).parent_path() / "part_files.log").string();
}

std::string run_record_line(const RunRecord& r) {
  nlohmann::ordered_json j;
  if (!r.id.empty()) j["id"] = r.id;
  if (r.pid) j["pid"] = r.pid;
  j["file"] = r.file;
  j["start"] = r.start;
  j["end"] = r.end;
  j["status"] = r.status;
  j["line"] = r.line;
  j["message"] = r.message;
  j["cycle_s"] = std::round(r.cycle_s * 1000) / 1000;
  nlohmann::ordered_json pos;
  for (int i = 0; i < kAxisCount; ++i)
    pos[std::string(1, kAxisLetters[i])] = std::round(r.position[i] * 1e4) / 1e4;
  j["position"] = pos;
  j["units"] = r.units;
  // Replace: a file name that is not UTF-8 still makes a line.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::optional<RunRecord> parse_run_record(const std::string& line) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (!j.is_object() || !j.contains("file") || !j.contains("status")) return std::nullopt;
  try {
    RunRecord r;
    r.id = j.value("id", "");
    r.pid = j.value("pid", 0);
    r.file = j.at("file").get<std::string>();
    r.status = j.at("status").get<std::string>();
    r.start = j.value("start", "");
    r.end = j.value("end", "");
    r.line = j.value("line", 0);
    r.message = j.value("message", "");
    r.cycle_s = j.value("cycle_s", 0.0);
    r.units = j.value("units", "");
    if (j.contains("position"))
      for (int i = 0; i < kAxisCount; ++i)
        r.position[i] = j["position"].value(std::string(1, kAxisLetters[i]), 0.0);
    return r;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

bool append_run_record(const std::string& path, const RunRecord& r, std::string* why) {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  const std::string line = run_record_line(r) + "\n";
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    *why = std::strerror(errno);
    return false;
  }
  // One write: O_APPEND places it whole at the end, whoever else appends.
  const ssize_t n = ::write(fd, line.data(), line.size());
  const int err = errno;
  const bool ok = n == static_cast<ssize_t>(line.size()) && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) *why = n < 0 ? std::strerror(err) : "the disk took only part of the line";
  return ok;
}

namespace {

// Whether process `pid` is still running (on this machine: the log is local).
bool alive(int pid) {
  return pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM);
}

// Every run in the log, a run's end line in its start line's place.
std::vector<RunRecord> read_runs(const std::string& path, std::size_t* bad) {
  std::vector<RunRecord> runs;
  std::unordered_map<std::string, std::size_t> by_id;
  std::size_t wrong = 0;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::optional<RunRecord> r = parse_run_record(line);
    if (!r) {
      ++wrong;
      continue;
    }
    if (!r->id.empty()) {
      const auto [at, added] = by_id.try_emplace(r->id, runs.size());
      if (!added) {
        const int pid = runs[at->second].pid;
        runs[at->second] = std::move(*r);
        if (!runs[at->second].pid) runs[at->second].pid = pid;
        continue;
      }
    }
    runs.push_back(std::move(*r));
  }
  if (bad) *bad = wrong;
  return runs;
}

}  // namespace

std::vector<RunRecord> read_run_log(const std::string& path, std::size_t last, std::size_t* bad) {
  std::vector<RunRecord> runs = read_runs(path, bad);
  for (RunRecord& r : runs)
    if (r.status == "running" && !alive(r.pid)) {
      r.status = "killed";
      r.message = "killed/unknown end: its process is gone";
    }
  if (last && runs.size() > last) runs.erase(runs.begin(), runs.end() - static_cast<std::ptrdiff_t>(last));
  return runs;
}

std::string run_record_text(const RunRecord& r) {
  std::string when = r.start;
  if (when.size() >= 19) when = when.substr(0, 10) + " " + when.substr(11, 8);
  const long whole = static_cast<long>(r.cycle_s);
  const bool unknown = r.status == "running" || r.status == "killed";  // no end yet, or none
  const std::string cycle =
      unknown ? "        ?"
              : fmt::format("{}:{:02}:{:04.1f}", whole / 3600, whole / 60 % 60,
                            r.cycle_s - static_cast<double>(whole - whole % 60));
  std::string status = r.status;
  if (r.status != "completed" && r.line > 0) status += fmt::format(" at line {}", r.line);
  std::string text = fmt::format("{}  {}  {:<22} {}", when, cycle, status, r.file);
  if (r.status != "completed" && r.status != "stopped" && !r.message.empty())
    text += fmt::format(" ({})", r.message);
  return text;
}

std::size_t RunLogger::close_unfinished(const SavedMachine* last) {
  std::lock_guard lock(m_);
  std::vector<RunRecord> open;
  for (RunRecord& r : read_runs(path_, nullptr))
    if (r.status == "running" && !r.id.empty() && !alive(r.pid)) open.push_back(std::move(r));
  std::size_t closed = 0;
  for (RunRecord& r : open) {
    r.status = "killed";
    r.end.clear();  // unknown
    r.message = "killed/unknown end";
    // The machine state file (saved at every start of motion and every rest) knows where
    // the tool was last: for the latest run, the one its process was running.
    if (last && &r == &open.back() && !last->saved_at.empty()) {
      r.position = last->table;
      r.units = units_name(last->units);
      r.message += fmt::format("; last known at X {:.4f} Y {:.4f} Z {:.4f} ({}, table base; "
                               "saved {}{})",
                               last->table[0], last->table[1], last->table[2], r.units,
                               last->saved_at, last->confirmed ? "" : ", mid-move");
    }
    std::string why;
    if (append_run_record(path_, r, &why))
      ++closed;
    else
      failure_ = why;
  }
  return closed;
}

void RunLogger::activity(const Controller::Activity& a) {
  if (!a.part_file) return;
  std::lock_guard lock(m_);
  if (!a.at_rest) {
    // The start line, at once: a run killed before its end still leaves it.
    start_ = utc_timestamp();
    id_ = fmt::format("{}-{}-{}", start_, ::getpid(), ++runs_);
    RunRecord r;
    r.id = id_;
    r.pid = ::getpid();
    r.file = a.file;
    r.start = start_;
    r.status = "running";
    r.position = a.modal.position + a.modal.zero + a.modal.applied_offset;
    r.units = units_name(a.units);
    std::string why;
    failure_ = append_run_record(path_, r, &why) ? std::string() : why;
    return;
  }
  RunRecord r;
  r.id = id_;
  r.pid = ::getpid();
  r.file = a.file;
  r.start = start_.empty() ? utc_timestamp() : start_;
  r.end = utc_timestamp();
  r.cycle_s = a.elapsed_s;
  r.position = a.modal.position + a.modal.zero + a.modal.applied_offset;
  r.units = units_name(a.units);
  if (a.error) {
    r.message = a.error->message;
    r.line = a.error->via.empty() ? a.error->loc.line : a.error->via.front().line;
    const bool estop = a.fault == CardFault::EStop || (a.fault == CardFault::None && a.estop);
    r.status = estop     ? "E-stop"
               : a.estop ? "fault"
               : r.message == "stopped by the operator" ? "stopped"
                                                         : "error";
  } else {
    r.status = a.estop ? "E-stop" : "completed";
  }
  start_.clear();
  id_.clear();
  std::string why;
  failure_ = append_run_record(path_, r, &why) ? std::string() : why;
}

std::string RunLogger::failure() const {
  std::lock_guard lock(m_);
  return failure_;
}

}  // namespace gantry::session
