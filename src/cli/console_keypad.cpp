// The terminal console's keypad (K, or SK in a file): the arrows jog, S and F switch fixed
// steps and speed; a terminal sends key repeats, not key-up, so a tap is one step and a
// continuous jog runs while the key repeats (KeyTaps).
#include <fmt/format.h>

#include "console_terminal.hpp"  // write_out
#include "console_view.hpp"      // Console

namespace gantry::console {

void Console::bind_keys(const session::KeyBindings& keys, session::PendantInput& input) {
  if (keys.empty()) return;
  // A terminal repeats a held key after its repeat delay: the same key again within it is a
  // repeat, which only a continuous jog's binding hears.
  keys_.emplace(keys, KeyTaps::ms(args_.repeat_delay_ms));
  pendant_ = &input;
}

bool Console::bound_key(const Key& k) {
  if (!keys_ || !pendant_) return false;
  std::vector<session::PendantEvent> out;
  if (!keys_->key(key_name(k), Clock::now(), out)) return false;
  for (const session::PendantEvent& e : out) pendant_->handle(e);
  return true;
}

void Console::enter_keypad(const std::string& message, bool file) {
  if (c_.state() == MachineState::EStop) {
    write_out("E-stop: type ack before the keypad\n");
    return;
  }
  kp_ = Keypad{};
  kp_.taps = KeyTaps(KeyTaps::ms(args_.release_ms), KeyTaps::ms(args_.repeat_delay_ms));
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
        "  --realtime; here a held key steps, as fixed steps (S) do)\n");
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
    kp_.waiting.reset();
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

namespace {

// The key of a jog (its direction and speed) as KeyTaps names keys.
std::uint32_t key_of(const JogRequest& j) {
  std::uint32_t id = j.fast ? 1 : 0;
  for (int d : j.direction) id = id * 3 + static_cast<std::uint32_t>(d + 1);
  return id;
}

bool same_key(const JogRequest& a, const JogRequest& b) {
  return a.direction == b.direction && a.fast == b.fast;
}

}  // namespace

void Console::step_jog(const JogRequest& j) {
  // One step per press; a press while a step is under way waits (one, not a backlog).
  if (kp_.active)
    kp_.queued = j;
  else
    start_jog(j);
}

// Fixed-step mode: every key event is a step. Continuous mode (docs/console.md, "Taps and
// held keys"): a tap is one step of the keypad step, and a jog runs only while the key
// repeats, as a terminal repeats a held key.
void Console::jog_key(const std::array<int, kAxisCount>& dir, bool fast) {
  const Clock::time_point now = Clock::now();
  JogRequest j;
  j.direction = dir;
  j.fast = fast;
  j.step = true;
  if (kp_.step) return step_jog(j);
  const KeyTaps::Meaning meaning = kp_.taps.key(key_of(j), now);
  kp_.waiting.reset();
  const bool running = kp_.active && !kp_.current.step && !kp_.released;
  if (meaning != KeyTaps::Meaning::Held) {
    if (running) {  // another key, or the same after a pause: this jog is over
      c_.jog_release();
      kp_.released = true;
    }
    if (meaning == KeyTaps::Meaning::Step) return step_jog(j);
    kp_.waiting = j;  // KeyTaps::Wait: keypad_tick steps unless a repeat comes first
    return;
  }
  if (running && same_key(kp_.current, j)) return;  // the key repeats: it is still held
  if (!realtime_) return step_jog(j);  // in virtual time a held key steps, as S does
  j.step = false;
  if (kp_.active) {  // a step (the tap that began the hold) first, then on from there
    if (running) {
      c_.jog_release();
      kp_.released = true;
    }
    kp_.queued = j;
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
  draw_status(true);
  return true;
}

// Key release: a terminal sends key repeats, not key-up. A continuous jog is released once
// its key has not repeated for `release_ms` (KeyTaps::held).
void Console::keypad_tick(Clock::time_point now) {
  if (kp_.waiting && kp_.taps.step_due(now)) {  // no repeat followed: it was a tap
    const JogRequest j = *kp_.waiting;
    kp_.waiting.reset();
    step_jog(j);
  }
  if (kp_.active) {
    ControllerStatus st = c_.status();
    const MachineState s = st.state;
    if (!at_rest(s) && s != MachineState::Keypad) {
      if (!kp_.current.step && !kp_.released && !kp_.taps.held(key_of(kp_.current), now)) {
        c_.jog_release();
        kp_.released = true;
      }
      return;
    }
    // A released jog reads idle while it slows to rest: look again at the next tick. This is
    // the key thread, so it never waits for motion (space, ! and Esc act at once).
    if (!st.settled) return;
    kp_.active = false;
    snapshot();
    st = c_.status();
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
    kp_.queued.reset();
    // A continuous jog waits for the step before it; it starts only if the key still repeats.
    if (j.step || kp_.taps.held(key_of(j), now)) start_jog(j);
  }
}

}  // namespace gantry::console
