// `gantry console`: the live machine at a terminal (docs/console.md): the prompt, the running
// line and the readout (the keypad is console_keypad.cpp, the command console_command.cpp).
//
// One thread (the caller's) reads the keys, draws the prompt and the status line, and makes
// every request of the Controller; the controller's job thread reaches the operator only
// through the session's OperatorMailbox, which queues PRINT text and hands questions (PAUSE,
// INPUT, MSGBOX) to the console thread. A watcher thread takes the termination signals and
// E-stops.
#include <fmt/format.h>  // output
#include <poll.h>        // poll
#include <unistd.h>      // read

#include <cctype>  // tolower
#include <cerrno>
#include <thread>

#include "console_terminal.hpp"              // write_out, terminal_columns, RawTerminal
#include "console_view.hpp"                  // Console
#include "gantry/commands/command_docs.hpp"  // command_help, command_list
#include "gantry/lang/scan.hpp"              // upper, trim
#include "gantry/lang/script.hpp"            // Script
#include "gantry/session/console_help.hpp"   // help_answer, terminal_status
#include "gantry/session/console_words.hpp"  // read_typed_line
#include "gantry/session/feed_override.hpp"  // stepped_feed_override
#include "gantry/session/readout_lines.hpp"  // readout_text, speeds_text, spindle_text
#include "gantry/session/refusal.hpp"        // refusal_under_line
#include "gantry/session/source_place.hpp"   // kConsoleName, where

namespace gantry::console {
namespace {

using std::chrono::milliseconds;

using scan::trim;
using scan::upper;
using session::kConsoleName;
using session::where;

// ---- what the console shows --------------------------------------------------------------

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
      return {
          fmt::format("[{}] {}", q.where, q.text),
          fmt::format(
              "{}{}{}: ", q.variable, several ? " (separated by commas)" : "",
              !several && !q.default_value.empty() ? fmt::format(" [{}]", q.default_value) : "")};
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

}  // namespace

Console::Console(Controller& c, OperatorMailbox& io, session::ValuesKeeper& values,
                 const ConsoleArgs& args, bool realtime, std::atomic<int>& signal)
    : c_(c),
      io_(io),
      values_(values),
      args_(args),
      realtime_(realtime),
      signal_(signal),
      editor_(write_out, completion_words()) {}

void Console::snapshot() {
  const ModalState m = c_.modal();
  const Settings s = values_.settings();
  live_.snapshot(m, s);
  units_ = s.units;
  axis_names_ = axis_names(s);
  keypad_step_ = s.display.keypad_step;
}

std::string Console::readout(const ControllerStatus& st) const {
  // At rest the interpreter's position is exact (a step jog ends on its commanded point);
  // under way, the pulses played say where the tool is.
  const bool rest = ((at_rest(st.state) && st.settled) || st.state == MachineState::Keypad) &&
                    mode_ != Mode::Job && !kp_.active;
  return session::readout_text(session::state_word(st), live_.at(st, rest), units_, axis_names_);
}

std::string Console::help(const std::string& arg) const {
  return session::help_answer(session::FrontEnd::Terminal, arg,
                              keys_ ? &keys_->bindings() : nullptr)
      .text;
}

std::string Console::status_report() const {
  const ControllerStatus st = c_.status();
  std::string out = session::terminal_status(readout(st), st, c_.modal(), live_.table_base(),
                                             keypad_step_, units_);
  // The last known position (WinCNC shows it at start until G28): said until homed or
  // confirmed, as the window's readout says UNCONFIRMED.
  if (memory_)
    if (const session::SavedMachine m = memory_->state(); !m.confirmed)
      out += fmt::format(
          "the position is UNCONFIRMED until homed (C3, G28) or confirmed "
          "(confirm): {}\n",
          m.why.empty() ? "the last known position" : m.why);
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
  if (bound_key(k)) return;  // a [pendant] key does only what it is bound to, in every mode
  if (const std::optional<int> n = session::fm_hot_key(key_name(k))) return fm_key(*n);
  if (k.code == KeyCode::Char && k.alt) {  // an Alt+character no binding takes: ESC, then it
    for (const Key& each : escape_and_char(k)) {
      on_key(each);
      if (quit_) return;
    }
    return;
  }
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
  } else if (k.is_char('+') || k.is_char('=') || k.is_char('-') || k.is_char('0')) {
    const double now = c_.status().feed_override;
    const session::FeedOverrideBounds b = session::feed_override_bounds(values_.settings());
    const double next = k.is_char('0')
                            ? session::clamped_feed_override(1.0, b)
                            : session::stepped_feed_override(now, k.is_char('-') ? -1 : 1, b);
    c_.set_feed_override(next);
    flash(session::feed_override_text(next) + " (moves already planned keep their speed)");
    return;
  } else {
    flash("a line runs: space pauses, Esc stops, + and - the feed, ! or Ctrl-C is the E-stop");
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

std::string Console::confirm() {
  return session::confirm_position(memory_) + "\n";
}

// The console's words, typed at the terminal or piped in. Piped, a word that needs a terminal
// (the keypad, STEP) and a refused ACK end the console with exit status 1.
Console::WordEnd Console::console_word(const session::TypedLine& t, bool terminal) {
  using Word = session::TypedLine::Word;
  if (!terminal && t.first == "STEP") {
    write_out("error: single step needs a terminal (standard input is not one)\n");
    return WordEnd::Failed;
  }
  switch (t.word) {
    case Word::Quit:
      return WordEnd::Quit;
    case Word::Help:
      write_out(help(t.rest));
      return WordEnd::Done;
    case Word::Status:
      // A pendant's jog between two lines is an activity the console did not start: what is
      // kept of the machine is read again, so the position is where the jog left the tool.
      if (const ControllerStatus st = c_.status(); at_rest(st.state) && st.settled) snapshot();
      write_out(status_report());
      return WordEnd::Done;
    case Word::Confirm:
      c_.clear_home_flags();  // homing.require's flags too (WinCNC's L29)
      write_out(confirm());
      return WordEnd::Done;
    case Word::Ack: {
      const Outcome o = c_.acknowledge();
      if (o) snapshot();
      write_out(o ? "E-stop acknowledged: the machine is ready\n" : o.reason + "\n");
      return o || terminal ? WordEnd::Done : WordEnd::Failed;
    }
    case Word::Keypad:
      if (!terminal) {
        write_out("error: the keypad needs a terminal (standard input is not one)\n");
        return WordEnd::Failed;
      }
      enter_keypad(t.message);
      return WordEnd::Done;
    case Word::Step:
      single_step_ = t.step_on;
      c_.set_single_step(single_step_);
      write_out(single_step_ ? "single step on: each statement holds once its motion has "
                               "played; space or Enter runs the next, Esc ends the file\n"
                             : "single step off\n");
      return WordEnd::Done;
    case Word::Teach: {
      const session::FmKeys::Result r = fm_keys_.teach(t.rest, units_);
      write_out(r.message + "\n");
      return r.error && !terminal ? WordEnd::Failed : WordEnd::Done;
    }
    case Word::None:
      break;
  }
  return WordEnd::NotAWord;
}

// Alt-F1...F10: during a run (a file running, or waiting at its SK or M3 keypad) the file's
// hot-key subroutine; at rest the teach log's (session::FmKeys decides, as in the window).
void Console::fm_key(int n) {
  const bool running = mode_ == Mode::Job || kp_.file;
  const ControllerStatus st = c_.status();
  if (!running && (!at_rest(st.state) || !st.settled || kp_.active))
    return flash(fmt::format("Alt-F{}: the table is moving; teach once it is at rest", n));
  if (!running) snapshot();  // at rest: the exact position
  session::FmKeys::Result r =
      fm_keys_.key(n, running, c_, io_, live_.exact(), values_.settings().friendly_motion);
  if (r.answered && asking_) {  // the key answered the STEP question: it is gone
    asking_ = false;
    editor_.erase();
  }
  if (!r.typed.empty()) {  // the output a teach key switches, at rest, as a typed SO would
    const Outcome o = c_.run_typed(Script::from_text(r.typed, kConsoleName));
    if (!o)
      r.message += "; the output was not switched: " + o.reason;
    else
      c_.wait_for(milliseconds(2000));
  }
  if (mode_ == Mode::Prompt && !asking_)
    print_above(r.message);
  else
    flash(r.message);
}

void Console::handle_line(const std::string& typed) {
  const session::TypedLine t = session::read_typed_line(typed, single_step_);
  if (t.line.empty()) return;
  // The line runs as typed (leading blanks too), so that its columns are the screen's.
  const std::string text = typed.substr(0, typed.find_last_not_of(" \t\r\n") + 1);
  switch (console_word(t, true)) {
    case WordEnd::Quit:
      quit_ = true;
      return;
    case WordEnd::Done:
    case WordEnd::Failed:
      return;
    case WordEnd::NotAWord:
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
  if (mode_ == Mode::Job) {  // the key thread never waits for motion: end once settled
    const ControllerStatus st = c_.status();
    if (at_rest(st.state) && st.settled) return end_job();
    if (at_rest(st.state)) io_.cancel();  // a question would keep the job from winding down
  }
  if (mode_ == Mode::Prompt && !asking_) follow_activity(false);  // a pendant's jog
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

// ---- piped ---------------------------------------------------------------------------------

// A motion the console did not start (a pendant's jog, a gamepad's) ended since the last
// look: what is kept of the machine is read again, so the readout is where it left the tool,
// and the console says so, as the interactive status line and the window follow it.
void Console::follow_activity(bool say) {
  const ControllerStatus st = c_.status();
  if (!activity_.ended(st)) return;
  snapshot();
  if (!say) return;
  write_out(readout(st) + "\n");
  write_out(ended(st));
}

int Console::piped() {
  snapshot();
  activity_.seen(c_.status());
  const std::string prefix = "> ";
  LineReader in(STDIN_FILENO);
  std::string typed;
  while (in.next(typed, signal_)) {
    follow_activity(true);
    const session::TypedLine t = session::read_typed_line(typed);
    const std::string& line = t.line;
    if (line.empty()) continue;
    write_out(prefix + line + "\n");
    const WordEnd w = console_word(t, false);
    if (w == WordEnd::Quit) return 0;
    if (w == WordEnd::Failed) return 1;
    if (w == WordEnd::Done) continue;
    const Outcome o = c_.run_typed(Script::from_text(line, kConsoleName));
    if (!o) return write_out(refusal(prefix, line, o, false)), 1;
    c_.wait();
    snapshot();
    activity_.seen(c_.status());  // the line's own end is told below
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

}  // namespace gantry::console
