// `gantry console`: the live machine at a terminal (docs/console.md).
//
// One thread (the caller's) reads the keys, draws the prompt and the status line, and makes
// every request of the Controller; the controller's job thread reaches the operator only
// through the session's OperatorMailbox, which queues PRINT text and hands questions (PAUSE, INPUT, MSGBOX) to
// the console thread. A watcher thread takes the termination signals and E-stops.
#include "console.hpp"

#include <fmt/format.h>  // output
#include <poll.h>        // poll
#include <sys/ioctl.h>   // TIOCGWINSZ
#include <termios.h>     // raw mode
#include <unistd.h>      // read, isatty
#include <CLI/CLI.hpp>   // the subcommand

#include <atomic>
#include <cctype>  // toupper, tolower
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>  // stdout
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "gantry/commands/command_docs.hpp"  // command_help, command_list
#include "gantry/lang/script.hpp"            // Script
#include "gantry/machine/controller.hpp"     // Controller
#include "gantry/lang/scan.hpp"               // upper, trim
#include "gantry/session/console_words.hpp"  // read_typed_line
#include "gantry/session/live_position.hpp"  // LivePosition
#include "gantry/session/operator_io.hpp"   // OperatorMailbox
#include "gantry/session/refusal.hpp"       // refusal_under_line
#include "gantry/session/source_place.hpp"  // kConsoleName, where
#include "line_editor.hpp"                   // KeyDecoder, LineEditor
#include "live_machine.hpp"                  // ValuesKeeper, LiveMachineArgs
#include "machine_profile.hpp"               // load_machine_profile
#include "open_card.hpp"                     // plays_in_real_time
#include "signal_watch.hpp"                  // SignalWatch

namespace gantry {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

using session::kConsoleName;
using session::OperatorMailbox;
using session::Question;
using session::where;
const char* const kPrompt = "gantry> ";
const char* const kEStopPrompt = "gantry [E-stop: type ack]> ";

using scan::trim;
using scan::upper;
using session::shown;

void write_out(std::string_view s) {
  std::fwrite(s.data(), 1, s.size(), stdout);
  std::fflush(stdout);
}

int terminal_columns() {
  winsize w{};
  return ioctl(STDOUT_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0 ? w.ws_col : 80;
}

// Raw mode for the keys: no echo, no line buffering, no signals from Ctrl-C (it is the
// console's E-stop key), no flow control. Output processing stays on, so "\n" starts a line.
class RawTerminal {
 public:
  explicit RawTerminal(int fd) : fd_(fd) {
    if (tcgetattr(fd_, &saved_) != 0) return;
    termios raw = saved_;
    raw.c_iflag &= ~static_cast<tcflag_t>(BRKINT | ICRNL | INPCK | ISTRIP | IXON);
    raw.c_lflag &= ~static_cast<tcflag_t>(ECHO | ICANON | IEXTEN | ISIG);
    raw.c_cflag |= CS8;
    raw.c_cc[VMIN] = 1;
    raw.c_cc[VTIME] = 0;
    active_ = tcsetattr(fd_, TCSAFLUSH, &raw) == 0;
  }
  ~RawTerminal() { restore(); }
  RawTerminal(const RawTerminal&) = delete;
  RawTerminal& operator=(const RawTerminal&) = delete;
  void restore() {
    if (active_) tcsetattr(fd_, TCSAFLUSH, &saved_);
    active_ = false;
  }

 private:
  int fd_;
  termios saved_{};
  bool active_ = false;
};

// ---- what the console shows --------------------------------------------------------------

// The position readout: state, X Y Z A B C in working coordinates, units.
std::string readout_text(std::string_view state, const Vec6& p, Units u) {
  return fmt::format("{:<9}X {:.4f}  Y {:.4f}  Z {:.4f}  A {:.4f}  B {:.4f}  C {:.4f}  {}", state,
                     shown(p[0]), shown(p[1]), shown(p[2]), shown(p[3]), shown(p[4]), shown(p[5]),
                     units_name(u));
}

bool at_rest(MachineState s) {
  return s == MachineState::Idle || s == MachineState::Stopped || s == MachineState::EStop;
}

const char* const kConsoleHelp =
    "Type a line and Enter: it runs on the machine, e.g.  MX, 5   J2, 1, 1   VS, 2   &D = 0.5\n"
    "  FP, part.sbp   (a file runs from the current folder).\n"
    "Editing: Left/Right, Home/End (Ctrl-A/Ctrl-E), Backspace/Delete, Ctrl-K/Ctrl-U, Up/Down\n"
    "  recall earlier lines, Tab completes a two-letter code or lists the matches.\n"
    "Words: help [CODE]   help commands   status   ack (after an E-stop)   K (keypad)   quit\n"
    "  step [on|off] (single step: each statement holds once its motion has played)\n"
    "While a line runs: space pauses (then space or Enter resumes, Esc or q quits the file),\n"
    "  Esc stops, ! or Ctrl-C is the E-stop. Other lines wait until the machine is at rest.\n"
    "Keypad (K or SK): arrows X and Y, PageUp/PageDown Z, / and \\ diagonals, Ctrl+key fast;\n"
    "  S (or D) fixed steps or continuous, F fast or slow, space stops a jog, Esc leaves.\n"
    "  SK in a file opens it too: Esc goes on with the file, q stops it.\n"
    "  A continuous jog runs while the key repeats and slows to rest once the repeats stop.\n";

// The console's words and the command table's codes, for Tab.
std::vector<CompletionWord> completion_words() {
  std::vector<CompletionWord> words;
  for (const CommandSpec& s : CommandTable::standard().all())
    words.push_back({std::string(s.code), s.params.empty() ? "" : ", ", std::string(s.name)});
  for (const char* w : {"help", "status", "ack", "quit", "exit"})
    words.push_back({w, "", "console word"});
  return words;
}

// A question from the running file: the text above the answer line, and its prompt.
std::pair<std::string, std::string> question_text(const Question& q) {
  switch (q.kind) {
    case Question::Kind::Pause:
      return {fmt::format("[{}] {}", q.where, q.text),
              "Enter continues, c then Enter cancels (Esc cancels): "};
    case Question::Kind::Input: {
      const bool several = q.variable.find(',') != std::string::npos;
      return {fmt::format("[{}] {}", q.where, q.text),
              fmt::format("{}{}{}: ", q.variable, several ? " (separated by commas)" : "",
                          !several && !q.default_value.empty()
                              ? fmt::format(" [{}]", q.default_value)
                              : "")};
    }
    case Question::Kind::MsgBox: {
      std::string text = fmt::format("[{}] {}: {}", q.where, q.title, q.text);
      for (size_t i = 0; i < q.buttons.size(); ++i)
        text += fmt::format("\n  {}) {}{}", i + 1, q.buttons[i],
                            i == q.default_button ? " (Enter)" : "");
      return {text, "choice: "};
    }
  }
  return {};
}

// ---- the console -------------------------------------------------------------------------

class Console {
 public:
  Console(Controller& c, OperatorMailbox& io, ValuesKeeper& values, const ConsoleArgs& args,
          bool realtime, std::atomic<int>& signal)
      : c_(c),
        io_(io),
        values_(values),
        args_(args),
        realtime_(realtime),
        signal_(signal),
        editor_(write_out, completion_words()) {}

  int interactive(const std::string& banner);
  int piped();

 private:
  enum class Mode { Prompt, Job, Keypad };

  // Shared.
  void snapshot();  // at rest: the interpreter's exact position, the frame and units
  std::string readout(const ControllerStatus& st) const;
  std::string state_text(const ControllerStatus& st) const;
  std::string help(const std::string& arg) const;
  std::string status_report() const;
  std::string refusal(const std::string& prefix, const std::string& line, const Outcome& o,
                      bool echo_first) const;
  std::string ended(const ControllerStatus& st) const;

  // Interactive.
  void on_key(const Key& k);
  void prompt_key(const Key& k);
  void job_key(const Key& k);
  void answer_key(const Key& k);
  void answer(const std::string& a);
  void show_question(const std::string& text, const std::string& prompt);
  void keypad_key(const Key& k);
  void tick();
  void handle_line(const std::string& line);
  void end_job();
  void show_prompt();
  void print_above(std::string_view text);  // clears the current line, prints, redraws
  void draw_status(bool force);
  void flash(std::string text);
  void estop();
  // Keypad.
  void enter_keypad(const std::string& message, bool file = false);
  void leave_keypad();
  void jog_key(const std::array<int, kAxisCount>& dir, bool fast);
  bool start_jog(const JogRequest& j);
  void keypad_tick(Clock::time_point now);
  std::string keypad_text() const;

  Controller& c_;
  OperatorMailbox& io_;
  ValuesKeeper& values_;
  const ConsoleArgs& args_;
  bool realtime_;
  std::atomic<int>& signal_;

  session::LivePosition live_;  // the frame and exact position at the last snapshot
  Units units_ = Units::Inches;
  double keypad_step_ = 0.1;

  LineEditor editor_;
  std::string prompt_ = kPrompt;  // the prompt the last line was typed at
  Mode mode_ = Mode::Prompt;
  bool quit_ = false;
  bool asking_ = false;  // a question from the running file has the answer line
  std::uint64_t question_shown_ = 0;  // the id of the last question shown
  Question asked_;                    // ... and the question
  bool single_step_ = false;
  Vec6 line_start_ = Vec6::Zero();
  bool status_drawn_ = false;
  bool warned_ = false;  // the status line showed SW's warning (its bell rang)
  Clock::time_point last_draw_{};
  std::string flash_;
  Clock::time_point flash_until_{};

  struct Keypad {
    bool step = false, fast = false;
    bool active = false;    // a jog we started has not come to rest yet
    bool released = false;  // ... and its key has been released (or it was stopped)
    bool leaving = false;   // Esc: leave once at rest
    bool file = false;      // a file waits at SK: leaving resumes it
    JogRequest current;
    int repeats = 0;  // key repeats seen for the current jog
    Clock::time_point last_key{};
    std::optional<JogRequest> queued;  // the next press, while a jog is under way
    Clock::time_point queued_at{};
  } kp_;
};

void Console::snapshot() {
  const ModalState m = c_.modal();
  const Settings s = values_.settings();
  live_.snapshot(m, s);
  units_ = s.units;
  keypad_step_ = s.display.keypad_step;
}

std::string Console::state_text(const ControllerStatus& st) const {
  if (st.state == MachineState::Paused && st.step_hold) return "step";
  if (st.warning) return "WARNING: about to move";
  if (st.state == MachineState::Paused && st.phase != FeedPhase::Held) return "pausing";
  return state_name(st.state);
}

std::string Console::readout(const ControllerStatus& st) const {
  // At rest the interpreter's position is exact (a step jog ends on its commanded point);
  // under way, the pulses played say where the tool is.
  const bool rest =
      (at_rest(st.state) || st.state == MachineState::Keypad) && mode_ != Mode::Job && !kp_.active;
  return readout_text(state_text(st), live_.at(st, rest), units_);
}

std::string Console::help(const std::string& arg) const {
  if (arg.empty()) return kConsoleHelp;
  if (upper(arg) == "COMMANDS") return command_list(CommandTable::standard());
  if (const CommandSpec* spec = CommandTable::standard().find(upper(arg)))
    return command_help(*spec);
  return fmt::format("error: unknown command '{}'; help commands lists them all\n", arg);
}

std::string Console::status_report() const {
  const ControllerStatus st = c_.status();
  std::string out = readout(st) + "\n";
  const Vec6 table = live_.table_base();
  out += fmt::format("table base X {:.4f}  Y {:.4f}  Z {:.4f}; keypad step {:.4f} {}\n",
                     shown(table[0]), shown(table[1]), shown(table[2]), keypad_step_,
                     units_name(units_));
  if (!st.message.empty())
    out += fmt::format("last stop: {}{}\n", st.message,
                       st.stopped_at.file ? " at " + where(st.stopped_at) : "");
  if (st.state == MachineState::EStop) out += "E-stop: nothing moves until you type ack\n";
  return out;
}

std::string Console::refusal(const std::string& prefix, const std::string& line, const Outcome& o,
                             bool echo_first) const {
  return session::refusal_under_line(prefix, line, o, echo_first,
                                     c_.state() == MachineState::EStop);
}

// What a line that ran says when it ended other than by running to its end.
std::string Console::ended(const ControllerStatus& st) const {
  if (st.state == MachineState::EStop)
    return fmt::format(
        "E-STOP{}: the pulses stopped at once; the position above is where the tool is.\n"
        "Nothing moves until you type ack.\n",
        st.message.empty() || st.message == "E-stop" ? "" : " (" + st.message + ")");
  if (st.state != MachineState::Stopped) return {};
  // Where the motion came to rest: in a file the line typed ran (FP), that file's line.
  const SourceLoc& at = st.stopped_at;
  return fmt::format("stopped: {}{}\n", st.message.empty() ? "the line did not end" : st.message,
                     at.file && *at.file != kConsoleName ? " (at " + where(at) + ")" : "");
}

// ---- interactive ---------------------------------------------------------------------------

int Console::interactive(const std::string& banner) {
  RawTerminal raw(STDIN_FILENO);
  snapshot();
  write_out(banner);
  write_out(readout(c_.status()) + "\n");
  show_prompt();
  KeyDecoder decoder;
  std::vector<Key> keys;
  Clock::time_point last_byte = Clock::now();
  bool input_open = true;
  while (!quit_ && signal_ == 0) {
    pollfd p{STDIN_FILENO, POLLIN, 0};
    const int ready =
        input_open ? poll(&p, 1, 20) : (std::this_thread::sleep_for(milliseconds(20)), 0);
    if (ready > 0) {
      char buf[256];
      const ssize_t n = read(STDIN_FILENO, buf, sizeof buf);
      if (n > 0) {
        decoder.feed(std::string_view(buf, static_cast<size_t>(n)), keys);
        last_byte = Clock::now();
      } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
        input_open = false;  // the terminal went away: stop what runs, then leave
        if (!at_rest(c_.state())) c_.stop();
        io_.cancel();
      }
    }
    if (decoder.pending() && Clock::now() - last_byte > milliseconds(30)) decoder.flush(keys);
    for (const Key& k : keys) {
      on_key(k);
      if (quit_) break;
    }
    keys.clear();
    tick();
    if (!input_open && mode_ == Mode::Prompt) quit_ = true;
  }
  if (signal_ != 0) {
    io_.cancel();
    c_.wait();
    editor_.erase();
    write_out(fmt::format("signal {}: E-stop; the console ends\n", signal_.load()));
  }
  raw.restore();
  write_out("\n");
  return signal_ != 0 ? 1 : 0;
}

void Console::show_prompt() {
  editor_.set_columns(terminal_columns());
  editor_.remember = true;
  prompt_ = c_.state() == MachineState::EStop ? kEStopPrompt : kPrompt;
  editor_.start(prompt_);
}

void Console::print_above(std::string_view text) {
  editor_.erase();
  std::string t(text);
  if (!t.empty() && t.back() != '\n') t += '\n';
  write_out(t);
  if (mode_ == Mode::Prompt || asking_)
    editor_.redraw();
  else if (status_drawn_)
    draw_status(true);  // otherwise the next tick draws it, if the line runs that long
}

void Console::flash(std::string text) {
  flash_ = std::move(text);
  flash_until_ = Clock::now() + milliseconds(2500);
  draw_status(true);
}

void Console::draw_status(bool force) {
  const Clock::time_point now = Clock::now();
  if (!force && now - last_draw_ < milliseconds(100)) return;
  last_draw_ = now;
  const ControllerStatus st = c_.status();
  std::string text = mode_ == Mode::Keypad ? keypad_text() + readout(st) : readout(st);
  // SW's warning: the terminal's bell once, and the status line says why nothing moves yet.
  if (st.warning && !warned_) write_out("\a");
  warned_ = st.warning;
  if (!flash_.empty() && now < flash_until_) text = flash_;
  const auto width = static_cast<size_t>(std::max(20, terminal_columns() - 1));
  if (text.size() > width) text.resize(width);
  write_out("\r" + text + "\x1b[K");
  status_drawn_ = true;
}

void Console::estop() {
  io_.cancel();  // a question the job thread waits on would keep it from winding down
  const Outcome o = c_.estop();
  if (!o) flash(o.reason);
}

void Console::on_key(const Key& k) {
  if (asking_) return answer_key(k);
  switch (mode_) {
    case Mode::Prompt:
      return prompt_key(k);
    case Mode::Job:
      return job_key(k);
    case Mode::Keypad:
      return keypad_key(k);
  }
}

void Console::prompt_key(const Key& k) {
  switch (editor_.key(k)) {
    case LineEditor::Event::Submit:
      handle_line(editor_.take());
      if (mode_ == Mode::Prompt && !quit_) show_prompt();
      break;
    case LineEditor::Event::EndOfInput:
      quit_ = true;
      break;
    case LineEditor::Event::Interrupt:
      write_out(
          "^C\r\n(Ctrl-C clears the line; while a line runs it is the E-stop. quit or "
          "Ctrl-D leaves.)\r\n");
      show_prompt();
      break;
    case LineEditor::Event::Escape:
    case LineEditor::Event::None:
      break;
  }
}

void Console::job_key(const Key& k) {
  const MachineState s = c_.state();
  Outcome o;
  if (k.code == KeyCode::Interrupt || k.is_char('!')) {
    estop();
    return;
  } else if (k.is_char(' ')) {
    o = s == MachineState::Paused ? c_.resume() : c_.pause();
  } else if (k.code == KeyCode::Enter && s == MachineState::Paused) {
    o = c_.resume();
  } else if (k.code == KeyCode::Escape ||
             (s == MachineState::Paused && (k.is_char('q') || k.is_char('Q')))) {
    o = c_.stop();
  } else {
    flash("a line runs: space pauses, Esc stops, ! or Ctrl-C is the E-stop");
    return;
  }
  if (!o) flash(o.reason);
  draw_status(true);
}

void Console::answer_key(const Key& k) {
  if (k.code == KeyCode::Interrupt) {
    asking_ = false;
    estop();
    return;
  }
  switch (editor_.key(k)) {
    case LineEditor::Event::Submit:
      asking_ = false;
      answer(editor_.take());
      break;
    case LineEditor::Event::Escape:
      asking_ = false;
      editor_.erase();
      write_out("(cancelled)\n");
      io_.cancel();
      break;
    default:
      break;
  }
}

// The line typed at a question, as the mailbox takes it: PAUSE continues unless it starts
// with c; INPUT's empty line is its default (of one variable); MSGBOX's is a button's number
// (Enter: the default button), and any other line asks again.
void Console::answer(const std::string& a) {
  const Question& q = asked_;
  switch (q.kind) {
    case Question::Kind::Pause:
      if (!a.empty() && std::tolower(static_cast<unsigned char>(a[0])) == 'c') return io_.cancel();
      return io_.answer(a);
    case Question::Kind::Input:
      if (a.empty() && q.variable.find(',') == std::string::npos)
        return io_.answer(q.default_value);
      return io_.answer(a);
    case Question::Kind::MsgBox:
      if (a.empty()) return io_.answer(q.buttons[q.default_button]);
      for (size_t i = 0; i < q.buttons.size(); ++i)
        if (trim(a) == std::to_string(i + 1)) return io_.answer(q.buttons[i]);
      return show_question(fmt::format("choose 1 to {}", q.buttons.size()), "choice: ");
  }
}

void Console::show_question(const std::string& text, const std::string& prompt) {
  editor_.erase();
  write_out(text + "\n");
  asking_ = true;
  editor_.remember = false;
  editor_.set_columns(terminal_columns());
  editor_.start(prompt);
}

void Console::handle_line(const std::string& typed) {
  using Word = session::TypedLine::Word;
  const session::TypedLine t = session::read_typed_line(typed, single_step_);
  if (t.line.empty()) return;
  // The line runs as typed (leading blanks too), so that its columns are the screen's.
  const std::string text = typed.substr(0, typed.find_last_not_of(" \t\r\n") + 1);
  switch (t.word) {
    case Word::Quit:
      quit_ = true;
      return;
    case Word::Help:
      return write_out(help(t.rest));
    case Word::Status:
      return write_out(status_report());
    case Word::Ack: {
      const Outcome o = c_.acknowledge();
      if (o) snapshot();
      return write_out(o ? "E-stop acknowledged: the machine is ready\n" : o.reason + "\n");
    }
    case Word::Keypad:
      return enter_keypad(t.message);
    case Word::Step:
      single_step_ = t.step_on;
      c_.set_single_step(single_step_);
      return write_out(single_step_ ? "single step on: each statement holds once its motion has "
                                      "played; space or Enter runs the next, Esc ends the file\n"
                                    : "single step off\n");
    case Word::None:
      break;
  }
  const Outcome o = c_.run_typed(Script::from_text(text, kConsoleName));
  if (!o) {
    // The caret goes under the line on the screen, unless it did not fit there whole.
    const bool scrolled =
        prompt_.size() + text.size() + 1 >= static_cast<size_t>(terminal_columns());
    return write_out(refusal(prompt_, text, o, scrolled));
  }
  line_start_ = live_.exact();
  status_drawn_ = false;
  mode_ = Mode::Job;
}

void Console::tick() {
  if (std::string text = io_.take_output(); !text.empty()) print_above(text);
  if (!asking_) {
    if (std::optional<Question> q = io_.question(); q && q->id != question_shown_) {
      question_shown_ = q->id;
      asked_ = *q;
      const auto [text, prompt] = question_text(*q);
      return show_question(text, prompt);
    }
  }
  if (mode_ == Mode::Job && c_.state() == MachineState::Keypad)
    return enter_keypad(io_.take_keypad_message(), true);
  if (mode_ == Mode::Job && at_rest(c_.state())) return end_job();
  if (mode_ == Mode::Keypad) keypad_tick(Clock::now());
  if (mode_ != Mode::Prompt && !asking_) draw_status(false);
}

void Console::end_job() {
  io_.cancel();
  asking_ = false;
  c_.wait();
  mode_ = Mode::Prompt;  // first: the readout is the snapshot's, exact
  snapshot();
  editor_.erase();
  if (std::string text = io_.take_output(); !text.empty())
    write_out(text.back() == '\n' ? text : text + "\n");
  const ControllerStatus st = c_.status();
  const bool moved = live_.exact() != line_start_;
  if (moved || status_drawn_ || st.state != MachineState::Idle) write_out(readout(st) + "\n");
  write_out(ended(st));
  show_prompt();
}

// ---- keypad --------------------------------------------------------------------------------

void Console::enter_keypad(const std::string& message, bool file) {
  if (c_.state() == MachineState::EStop) {
    write_out("E-stop: type ack before the keypad\n");
    return;
  }
  kp_ = Keypad{};
  kp_.file = file;
  mode_ = Mode::Keypad;
  if (file) snapshot();  // the file's frame, and where its moves left the tool
  editor_.erase();
  if (!message.empty()) write_out(message + "\n");
  write_out(
      fmt::format("keypad: arrows X and Y, PageUp/PageDown Z, / and \\ diagonals, Ctrl+key fast;\n"
                  "  S fixed step or continuous, F fast or slow, space stops a jog, {}\n",
                  file ? "Esc goes on with the file, q stops it" : "Esc leaves"));
  if (!realtime_)
    write_out(
        "  (virtual time: a continuous jog would run to the soft limit at once, so it needs\n"
        "  --realtime; fixed steps work: press S)\n");
  draw_status(true);
}

std::string Console::keypad_text() const {
  return fmt::format("[keypad {} {}] ",
                     kp_.step ? fmt::format("step {:.4f}", keypad_step_) : "continuous",
                     kp_.fast ? "fast" : "slow");
}

void Console::leave_keypad() {
  if (kp_.file) {  // the file goes on from where the tool is (or it was stopped)
    mode_ = Mode::Job;
    if (c_.state() == MachineState::Keypad) {
      const Outcome o = c_.resume();
      if (!o) print_above(o.reason);
    }
    return;
  }
  mode_ = Mode::Prompt;
  editor_.erase();
  const ControllerStatus st = c_.status();
  write_out(readout(st) + "\n");
  write_out(ended(st));
  show_prompt();
}

void Console::keypad_key(const Key& k) {
  std::array<int, kAxisCount> dir{};
  switch (k.code) {
    case KeyCode::Left:
      dir[0] = -1;
      break;
    case KeyCode::Right:
      dir[0] = 1;
      break;
    case KeyCode::Up:
      dir[1] = 1;
      break;
    case KeyCode::Down:
      dir[1] = -1;
      break;
    case KeyCode::PageUp:
      dir[2] = 1;
      break;
    case KeyCode::PageDown:
      dir[2] = -1;
      break;
    default:
      if (k.is_char('/')) dir = {1, 1, 0, 0, 0, 0};
      if (k.is_char('\\')) dir = {-1, 1, 0, 0, 0, 0};
      break;
  }
  if (dir != std::array<int, kAxisCount>{}) return jog_key(dir, kp_.fast || k.ctrl);
  if (k.code == KeyCode::Interrupt || k.is_char('!')) {
    estop();
    kp_.leaving = true;
    return;
  }
  // A jog from a file's SK is released (stop would end the file); at the prompt, stopped.
  auto stop_jog = [&] {
    kp_.queued.reset();
    if (!kp_.active || kp_.released) return;
    if (kp_.file)
      c_.jog_release();
    else
      c_.stop();
    kp_.released = true;
  };
  if (k.code == KeyCode::Escape) {
    kp_.leaving = true;
    return stop_jog();
  }
  if (k.is_char(' ')) return stop_jog();
  if (kp_.file && (k.is_char('q') || k.is_char('Q'))) {
    c_.stop();
    kp_.released = true;
    kp_.leaving = true;
    return;
  }
  if (k.is_char('s') || k.is_char('S') || k.is_char('d') || k.is_char('D')) {
    kp_.step = !kp_.step;
  } else if (k.is_char('f') || k.is_char('F')) {
    kp_.fast = !kp_.fast;
  } else {
    flash("keypad: arrows, PageUp/PageDown, / \\ jog; S step, F fast, space stops, Esc leaves");
    return;
  }
  draw_status(true);
}

void Console::jog_key(const std::array<int, kAxisCount>& dir, bool fast) {
  const Clock::time_point now = Clock::now();
  JogRequest j;
  j.direction = dir;
  j.fast = fast;
  j.step = kp_.step;
  if (j.step) {
    // One step per press; a press while a step is under way waits (one, not a backlog).
    if (kp_.active)
      kp_.queued = j;
    else
      start_jog(j);
    return;
  }
  if (!realtime_) {
    flash("continuous jogs need --realtime on the simulated card; S switches to fixed steps");
    return;
  }
  if (kp_.active && !kp_.released && kp_.current.direction == dir && kp_.current.fast == fast) {
    kp_.last_key = now;  // the key repeats: it is still held
    ++kp_.repeats;
    return;
  }
  if (kp_.active) {  // another key: release this jog, then start that one once at rest
    if (!kp_.released) c_.jog_release();
    kp_.released = true;
    kp_.queued = j;
    kp_.queued_at = now;
    return;
  }
  start_jog(j);
}

bool Console::start_jog(const JogRequest& j) {
  const Outcome o = c_.jog(j);
  if (!o) {
    flash(o.reason);
    return false;
  }
  kp_.active = true;
  kp_.released = false;
  kp_.current = j;
  kp_.repeats = 0;
  kp_.last_key = Clock::now();
  draw_status(true);
  return true;
}

// Key release: a terminal sends key repeats, not key-up. A continuous jog is released once
// no repeat has come for `release_ms`, or, before the first repeat, for `repeat_delay_ms`
// (the terminal waits that long before it starts repeating a held key).
void Console::keypad_tick(Clock::time_point now) {
  if (kp_.active) {
    const MachineState s = c_.state();
    if (!at_rest(s) && s != MachineState::Keypad) {
      if (!kp_.current.step && !kp_.released) {
        const milliseconds window(kp_.repeats == 0 ? args_.repeat_delay_ms : args_.release_ms);
        if (now - kp_.last_key > window) {
          c_.jog_release();
          kp_.released = true;
        }
      }
      return;
    }
    c_.wait();
    kp_.active = false;
    snapshot();
    const ControllerStatus st = c_.status();
    if (st.state == MachineState::EStop) {
      kp_.queued.reset();
      kp_.leaving = true;  // back to the prompt, which says how to go on
    } else if (!st.message.empty() && !kp_.released) {
      kp_.queued.reset();  // a limit switch, say: the operator decides what next
      print_above("jog stopped: " + st.message);
    }
    draw_status(true);
  }
  if (kp_.leaving) return leave_keypad();
  if (kp_.queued) {
    const JogRequest j = *kp_.queued;
    const bool fresh = j.step || now - kp_.queued_at < milliseconds(args_.repeat_delay_ms);
    kp_.queued.reset();
    if (fresh) start_jog(j);
  }
}

// ---- piped ---------------------------------------------------------------------------------

// Lines from a file descriptor, waiting with poll so that a signal is noticed.
class LineReader {
 public:
  explicit LineReader(int fd) : fd_(fd) {}
  bool next(std::string& line, const std::atomic<int>& signal) {
    while (signal == 0) {
      if (const size_t nl = buf_.find('\n'); nl != std::string::npos) {
        line = buf_.substr(0, nl);
        buf_.erase(0, nl + 1);
        return true;
      }
      if (eof_) {
        if (buf_.empty()) return false;
        line = std::exchange(buf_, {});
        return true;
      }
      pollfd p{fd_, POLLIN, 0};
      if (poll(&p, 1, 100) <= 0) continue;
      char buf[4096];
      const ssize_t n = read(fd_, buf, sizeof buf);
      if (n > 0)
        buf_.append(buf, static_cast<size_t>(n));
      else if (n == 0 || (errno != EINTR && errno != EAGAIN))
        eof_ = true;
    }
    return false;
  }

 private:
  int fd_;
  std::string buf_;
  bool eof_ = false;
};

int Console::piped() {
  snapshot();
  const std::string prefix = "> ";
  LineReader in(STDIN_FILENO);
  std::string typed;
  while (in.next(typed, signal_)) {
    using Word = session::TypedLine::Word;
    const session::TypedLine t = session::read_typed_line(typed);
    const std::string& line = t.line;
    if (line.empty()) continue;
    write_out(prefix + line + "\n");
    if (t.word == Word::Quit) return 0;
    if (t.word == Word::Help) {
      write_out(help(t.rest));
      continue;
    }
    if (t.word == Word::Status) {
      write_out(status_report());
      continue;
    }
    if (t.word == Word::Ack) {
      const Outcome o = c_.acknowledge();
      if (!o) return write_out(o.reason + "\n"), 1;
      snapshot();
      write_out("E-stop acknowledged: the machine is ready\n");
      continue;
    }
    if (t.word == Word::Keypad) {
      write_out("error: the keypad needs a terminal (standard input is not one)\n");
      return 1;
    }
    if (t.first == "STEP") {
      write_out("error: single step needs a terminal (standard input is not one)\n");
      return 1;
    }
    const Outcome o = c_.run_typed(Script::from_text(line, kConsoleName));
    if (!o) return write_out(refusal(prefix, line, o, false)), 1;
    c_.wait();
    snapshot();
    const ControllerStatus st = c_.status();
    write_out(readout(st) + "\n");
    if (signal_ != 0) break;
    if (st.state != MachineState::Idle) return write_out(ended(st)), 1;
  }
  if (signal_ != 0) {
    c_.wait();
    write_out(fmt::format("signal {}: E-stop; the console ends\n", signal_.load()));
    return 1;
  }
  return 0;
}

}  // namespace

// ---- the command ---------------------------------------------------------------------------

CLI::App* add_console_command(CLI::App& app, ConsoleArgs& a) {
  CLI::App* cmd = app.add_subcommand(
      "console", "The live machine at a terminal: type lines, pause, stop, jog (docs/console.md)");
  add_live_machine_options(cmd, a,
                           "Play the simulated card in real time (continuous keypad jogs and "
                           "pausing a move need it)");
  cmd->add_flag("--yes", a.yes, "Continue every PAUSE and press each MSGBOX's default button");
  cmd->add_option("--input", a.inputs, "Answer INPUT for a variable: --input '&DEPTH=0.5'");
  cmd->add_option("--key-release-ms", a.release_ms,
                  "Keypad: a continuous jog stops when its key has not repeated for this long")
      ->check(CLI::Range(30, 2000));
  cmd->add_option("--key-repeat-delay-ms", a.repeat_delay_ms,
                  "Keypad: the terminal's delay before a held key repeats (the first window)")
      ->check(CLI::Range(50, 3000));
  return cmd;
}

int run_console(const ConsoleArgs& a) {
  MachineProfile profile;
  if (!load_machine_profile(a.profile, a.values, profile, a.tool_table)) return 1;
  const Settings& settings = profile.settings;
  std::map<std::string, std::string> inputs;
  for (const std::string& kv : a.inputs) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      fmt::print(stderr, "error: --input {} must be NAME=VALUE, e.g. --input '&DEPTH=0.5'\n", kv);
      return 1;
    }
    std::string name = upper(kv.substr(0, eq));
    if (name[0] != '&' && name[0] != '$') name = "&" + name;
    inputs[name] = kv.substr(eq + 1);
  }
  const bool interactive = isatty(STDIN_FILENO) && isatty(STDOUT_FILENO);

  SignalWatch signals;  // before the controller starts its threads: they inherit the mask
  PersistentStore store(a.persistent.empty() ? PersistentStore::default_path() : a.persistent);
  OperatorMailbox io(a.yes, inputs, interactive ? std::function<void(std::string_view)>{}
                                                : std::function<void(std::string_view)>(write_out));
  ValuesKeeper values(profile, io);

  std::string type;
  const std::unique_ptr<Card> card = open_live_card(a, settings, &type);
  if (!card) return 1;
  const bool sim = type == "sim";
  const bool real_time = plays_in_real_time(type, a.realtime);
  Controller controller(settings, *card, io, store,
                        live_interpreter_options(profile, values, a, real_time));
  std::atomic<int> signal{0};
  signals.start([&](int sig) {
    signal = sig;
    controller.estop();
    io.cancel();
  });
  struct StopFirst {  // the watcher ends before the controller it E-stops
    SignalWatch& w;
    ~StopFirst() { w.stop(); }
  } stop_first{signals};

  Console console(controller, io, values, a, real_time, signal);
  if (!interactive) return console.piped();
  const std::string banner = fmt::format(
      "gantry console: profile \"{}\" on the {}{}\nhelp lists the keys; quit leaves.\n",
      settings.name, sim ? "simulated card" : type + " card",
      !sim         ? ""
      : a.realtime ? " (real time)"
                   : " (virtual time: moves end at once; --realtime plays them in real time)");
  return console.interactive(banner);
}

}  // namespace gantry
