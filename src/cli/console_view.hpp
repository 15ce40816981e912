// The terminal console (`gantry console`): a view over the session. It reads the keys, draws
// the prompt and the status line, and makes every request of the Controller; the session
// (src/session) says what a typed line is, how a refusal reads and where the tool is.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "console.hpp"                        // ConsoleArgs
#include "gantry/machine/controller.hpp"      // Controller
#include "gantry/session/activity_watch.hpp"  // ActivityWatch
#include "gantry/session/console_words.hpp"   // TypedLine
#include "gantry/session/fm_hot_keys.hpp"     // FmKeys
#include "gantry/session/key_bindings.hpp"    // KeyBindings, KeyPendant
#include "gantry/session/live_machine.hpp"    // ValuesKeeper
#include "gantry/session/live_position.hpp"   // LivePosition
#include "gantry/session/machine_memory.hpp"  // MachineMemory
#include "gantry/session/operator_io.hpp"     // OperatorMailbox, Question
#include "gantry/session/pendant_input.hpp"   // PendantInput
#include "key_taps.hpp"                       // KeyTaps
#include "line_editor.hpp"                    // Key, LineEditor

namespace gantry::console {

using Clock = std::chrono::steady_clock;
using session::OperatorMailbox;
using session::Question;

inline constexpr const char* kPrompt = "gantry> ";
inline constexpr const char* kEStopPrompt = "gantry [E-stop: type ack]> ";

inline bool at_rest(MachineState s) {
  return s == MachineState::Idle || s == MachineState::Stopped || s == MachineState::EStop;
}

class Console {
 public:
  Console(Controller& c, OperatorMailbox& io, session::ValuesKeeper& values, const ConsoleArgs& args,
          bool realtime, std::atomic<int>& signal);

  int interactive(const std::string& banner);
  int piped();
  // The machine state kept across sessions, for CONFIRM (none: nothing to confirm).
  void keep_state(session::MachineMemory* memory) { memory_ = memory; }
  // The profile's [pendant] keys, sent to the live machine's pendant input (console_keypad.cpp).
  void bind_keys(const session::KeyBindings& keys, session::PendantInput& input);

 private:
  enum class Mode { Prompt, Job, Keypad };
  enum class WordEnd { NotAWord, Done, Quit, Failed };  // what a console word did

  // Shared.
  void snapshot();  // at rest: the interpreter's exact position, the frame and units
  std::string readout(const ControllerStatus& st) const;
  std::string help(const std::string& arg) const;
  std::string status_report() const;
  std::string confirm();
  std::string refusal(const std::string& prefix, const std::string& line, const Outcome& o,
                      bool echo_first) const;
  std::string ended(const ControllerStatus& st) const;
  WordEnd console_word(const session::TypedLine& t, bool terminal);
  void follow_activity(bool say);  // a motion the console did not start ended: read again

  // Interactive.
  void on_key(const Key& k);
  void prompt_key(const Key& k);
  void job_key(const Key& k);
  void answer_key(const Key& k);
  void answer(const std::string& a);
  void show_question(const std::string& text, const std::string& prompt);
  void keypad_key(const Key& k);
  bool bound_key(const Key& k);  // a [pendant] key: its events sent, true
  void fm_key(int n);            // Alt-F`n`: Friendly Motion's hot key or the teach log's
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
  void step_jog(const JogRequest& j);  // now, or once the jog under way is at rest
  void keypad_tick(Clock::time_point now);
  std::string keypad_text() const;

  Controller& c_;
  OperatorMailbox& io_;
  session::ValuesKeeper& values_;
  session::MachineMemory* memory_ = nullptr;
  std::optional<session::KeyPendant> keys_;  // the [pendant] keys, when any are bound
  session::PendantInput* pendant_ = nullptr;
  const ConsoleArgs& args_;
  bool realtime_;
  std::atomic<int>& signal_;

  session::LivePosition live_;  // the frame and exact position at the last snapshot
  session::ActivityWatch activity_;  // the ends of motions, the pendant's included
  Units units_ = Units::Inches;
  std::string axis_names_ = "XYZABC";  // W for the profile's W axis
  double keypad_step_ = 0.1;

  LineEditor editor_;
  std::string prompt_ = kPrompt;  // the prompt the last line was typed at
  Mode mode_ = Mode::Prompt;
  bool quit_ = false;
  bool asking_ = false;               // a question from the running file has the answer line
  std::uint64_t question_shown_ = 0;  // the id of the last question shown
  Question asked_;                    // ... and the question
  bool single_step_ = false;
  session::FmKeys fm_keys_;  // TEACH's log and the Alt-F keys
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
    std::optional<JogRequest> queued;  // the next press, while a jog is under way
    KeyTaps taps{KeyTaps::ms(150), KeyTaps::ms(600)};  // continuous mode: tap or held
    std::optional<JogRequest> waiting;  // a KeyTaps::Wait: a step unless the key repeats
  } kp_;
};

}  // namespace gantry::console
