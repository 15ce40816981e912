// Friendly Motion's Alt-F keys: the run's hot-key subroutines and teach mode's position log.
#include "gantry/session/fm_hot_keys.hpp"

#include <fmt/format.h>

#include <cctype>  // toupper
#include <cerrno>
#include <cstring>  // strerror

#include "gantry/interp/fm_executor.hpp"  // kFmStepTitle

namespace gantry::session {

std::optional<int> fm_hot_key(std::string_view name) {
  if (!name.starts_with("Alt+F")) return std::nullopt;
  const std::string_view n = name.substr(5);
  if (n.empty() || n.size() > 2 || n.find_first_not_of("0123456789") != std::string_view::npos)
    return std::nullopt;
  const int k = n.size() == 1 ? n[0] - '0' : (n[0] - '0') * 10 + (n[1] - '0');
  if (k < 1 || k > 10 || n[0] == '0') return std::nullopt;
  return k;
}

HotKeyPress press_fm_hot_key(Controller& c, OperatorMailbox& io, int key) {
  HotKeyPress p;
  p.outcome = c.hot_key(key);
  if (!p.outcome) return p;
  // The run waits at its STEP question: Step lets it go on, and it takes the key first.
  const std::optional<Question> q = io.question();
  if (q && q->kind == Question::Kind::MsgBox && q->title == kFmStepTitle && !q->buttons.empty() &&
      q->buttons.front() == "Step") {
    io.answer("Step");
    p.answered = true;
  }
  return p;
}

std::unique_ptr<TeachLog> TeachLog::open(const std::string& path, Units units, std::string* why) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    if (why) *why = fmt::format("cannot write {}: {}", path, std::strerror(errno));
    return nullptr;
  }
  std::unique_ptr<TeachLog> log(new TeachLog(f, path, units));
  // The taught points are where the table was: absolute, in the units they were read in.
  // The comment first also makes the file Friendly Motion whatever its name.
  if (!log->write("! taught at the Gantry console: Alt-F1 positions, Alt-F7-F10 outputs") ||
      !log->write(units == Units::Millimetres ? "G71 G90" : "G70 G90")) {
    if (why) *why = fmt::format("cannot write {}: {}", path, std::strerror(errno));
    return nullptr;
  }
  log->lines_ = 0;
  return log;
}

TeachLog::~TeachLog() {
  if (f_) close();
}

bool TeachLog::write(const std::string& line) {
  // CR/LF, as the manual's data files end their lines.
  const bool ok = std::fputs((line + "\r\n").c_str(), f_) >= 0 && std::fflush(f_) == 0;
  if (ok) ++lines_;
  return ok;
}

std::optional<TeachLog::Entry> TeachLog::key(int key, const Vec6& position,
                                             const FriendlyMotionSettings& fm, std::string* why) {
  auto fail = [&](std::string m) -> std::optional<Entry> {
    if (why) *why = std::move(m);
    return std::nullopt;
  };
  if (!f_) return fail("the teach log is closed");
  Entry e;
  switch (key) {
    case 1: {
      const int decimals = units_ == Units::Millimetres ? 3 : 4;
      // -0.0000 reads as 0: a value that rounds to zero is written without its sign.
      auto number = [&](double v) {
        std::string t = fmt::format("{:.{}f}", v, decimals);
        if (t.find_first_not_of("-0.") == std::string::npos)
          t = fmt::format("{:.{}f}", 0.0, decimals);
        return t;
      };
      e.line = fmt::format("X{}Y{}", number(position[0]), number(position[1]));
      break;
    }
    case 7:
    case 8:
      if (fm.laser_output == 0)
        return fail(
            fmt::format("Alt-F{} switches the laser, and this profile names no laser "
                        "output (friendly_motion.laser_output = 0)",
                        key));
      e.line = key == 7 ? "M100" : "M101";
      e.output = fm.laser_output;
      e.on = key == 7;
      break;
    case 9:
    case 10:
      e.line = key == 9 ? "M102" : "M103";
      e.output = 2;
      e.on = key == 9;
      break;
    default:
      return fail(
          fmt::format("Alt-F{} does nothing in teach mode: Alt-F1 logs the position, "
                      "Alt-F7/F8 the laser on/off, Alt-F9/F10 the shutter open/closed",
                      key));
  }
  if (!write(e.line)) return fail(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
  return e;
}

int TeachLog::close() {
  if (!f_) return lines_;
  write("M0");  // "All programs should include an M0 or M2"
  --lines_;     // the M0 is not a taught line
  std::fclose(f_);
  f_ = nullptr;
  return lines_;
}

FmKeys::Result FmKeys::teach(const std::string& rest, Units units) {
  Result r;
  auto closed = [&] {
    const std::string path = log_->path();
    const int n = log_->close();
    log_.reset();
    return fmt::format("teach log {} closed: {} line{} taught, then M0", path, n,
                       n == 1 ? "" : "s");
  };
  if (rest.empty()) {
    r.message = log_ ? fmt::format(
                           "teaching into {} ({} lines so far): jog, Alt-F1 logs the "
                           "position, Alt-F7/F8 laser on/off, Alt-F9/F10 shutter "
                           "open/closed; TEACH OFF closes it",
                           log_->path(), log_->lines())
                     : "no teach log is open; TEACH file opens one";
    return r;
  }
  std::string upper = rest;
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (upper == "OFF") {
    if (!log_) {
      r.message = "no teach log is open";
      r.error = true;
      return r;
    }
    r.message = closed();
    return r;
  }
  std::string before;
  if (log_) before = closed() + "\n";
  std::string why;
  log_ = TeachLog::open(rest, units, &why);
  if (!log_) {
    r.message = before + "TEACH: " + why;
    r.error = true;
    return r;
  }
  r.message = before + fmt::format(
                           "teaching into {}: jog, Alt-F1 logs the position, Alt-F7/F8 "
                           "laser on/off, Alt-F9/F10 shutter open/closed; TEACH OFF "
                           "closes it",
                           rest);
  return r;
}

FmKeys::Result FmKeys::key(int key, bool running, Controller& c, OperatorMailbox& io,
                           const Vec6& position, const FriendlyMotionSettings& fm) {
  Result r;
  if (running) {
    const HotKeyPress p = press_fm_hot_key(c, io, key);
    r.answered = p.answered;
    r.error = !p.outcome;
    r.message = p.outcome ? fmt::format(
                                "Alt-F{}: subroutine N{} runs before the next line, then "
                                "STEP",
                                key, 10000 + key)
                          : p.outcome.reason;
    return r;
  }
  if (!log_) {
    r.error = true;
    r.message = fmt::format(
        "Alt-F{}: no Friendly Motion program runs (N{}) and no teach log "
        "is open (TEACH file)",
        key, 10000 + key);
    return r;
  }
  std::string why;
  const std::optional<TeachLog::Entry> e = log_->key(key, position, fm, &why);
  if (!e) {
    r.error = true;
    r.message = why;
    return r;
  }
  r.message = fmt::format("taught {}", e->line);
  if (e->output > 0) r.typed = fmt::format("SO, {}, {}", e->output, e->on ? 1 : 0);
  return r;
}

}  // namespace gantry::session
