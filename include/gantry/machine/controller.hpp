// The live machine: runs part files and keypad jogs on the card, and obeys pause, resume,
// stop and E-stop at any moment, always knowing where the tool is from the pulses played.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "gantry/hal/card.hpp"                  // Card
#include "gantry/hal/input_roles.hpp"           // InputRoles
#include "gantry/interp/interpreter.hpp"        // Interpreter, ModalState
#include "gantry/machine/feeder_thread.hpp"     // FeederThread, FeederEvents
#include "gantry/machine/machine_state.hpp"     // MachineState, Request
#include "gantry/motion/lookahead_planner.hpp"  // LookAheadPlanner
#include "gantry/step/motion_feeder.hpp"        // MotionFeeder

namespace gantry {

struct ControllerStatus {
  MachineState state = MachineState::Idle;
  FeedPhase phase = FeedPhase::Playing;
  Steps6 steps{};                 // played by the card: where the tool is
  Vec6 machine = Vec6::Zero();    // the same in units (machine frame)
  std::string message;            // why the last activity stopped, if it did not end
  SourceLoc stopped_at;           // the line the motion came to rest in (Stopped, Paused)
  std::array<bool, 12> inputs{};  // input switches 1-12: closed
  bool step_hold = false;         // paused by single step, after a statement (at rest)
  bool warning = false;           // SW's warning: the machine is about to move
  // Nothing is under way (what wait() waits for): a front end's key thread polls this and
  // never waits for motion (a released jog reads idle while it still slows to rest).
  bool settled = true;
  // Activities (runs, typed lines, jogs) that have ended, at rest or halted: counts up, so a
  // front end that polls sees an end even between two polls (session::ActivityWatch).
  std::uint64_t activities_ended = 0;
  // The outputs as the card plays them (not as the file last set them): switches bit n-1 is
  // output switch n (1 runs the spindle on ShopBot's wiring), and TR's speed.
  std::uint32_t outputs = 0;
  double spindle_rpm = 0;
  double feed_override = 1;  // the operator's, 0.1 to 2 (set_feed_override)
  // Progress of the file running (or the last one run).
  std::size_t line = 0, lines = 0;  // the top-level file's line the interpreter has reached
  int playing_line = 0;             // the line whose motion the card plays (in its own file)
  int playing_caller_line = 0;      // ... in a file the run called: the run's line that called it
  std::shared_ptr<const std::string> playing_file;  // ... and that file (null: none)
  std::shared_ptr<const std::string> file;          // the top-level file (null: typed, none)
  double elapsed_s = 0;                             // machine time since it started
  double remaining_s = 0;  // the check's cycle-time estimate less elapsed (0: none)
};

// A keypad jog: each axis -1, 0 or +1 (several: a diagonal). Continuous: runs towards the
// soft limits until released. Step: exactly the VD keypad step along the direction.
struct JogRequest {
  std::array<int, kAxisCount> direction{};
  bool fast = false;  // jog speed; otherwise move speed
  bool step = false;
  double step_size = 0;       // a step's length (units); 0: VD's keypad step
  double speed_fraction = 1;  // the share of the speed (a pendant's knob), 0-1
};

struct Outcome {
  bool accepted = true;
  std::string reason;              // why it was refused
  std::vector<Diagnostic> errors;  // a file refused by its check
  explicit operator bool() const { return accepted; }
};

// Threads: the caller's (requests, status), the job thread (interpreter), and the feeder
// (planner, motion feeder, step generator, card: FeederThread). Canonical moves pass from job
// to feeder through a bounded lock-free queue; the feeder never locks while it plays, and the
// planner on it keeps the tail of the path that comes to rest, so a late job thread slows the
// tool instead of starving the card. FeederThread owns the flags between the three and
// documents them.
// docs/controller.md has the states, the transition table and the behaviours.
class Controller : private FeederEvents {
 public:
  // An activity's start (before any motion) and its end (at rest), told on the job thread:
  // what the session keeps across sessions (session/machine_memory) and logs (run_log).
  struct Activity {
    bool at_rest = false;    // false: it is about to move
    bool part_file = false;  // a file run (not a jog, not a typed line)
    std::string file;        // the file's name (part_file)
    ModalState modal;        // the interpreter's state: the position, zero, offsets
    Units units = Units::Inches;
    // At rest only: how it ended.
    bool estop = false;                 // an E-stop or a card fault: the pulses stopped at once
    CardFault fault = CardFault::None;  // the card's, if it stopped by itself
    std::optional<Diagnostic> error;    // why it stopped short (stopped_at: where)
    double elapsed_s = 0;               // machine time it took
  };
  void on_activity(std::function<void(const Activity&)> f);
  // Before anything runs: `edit` changes the interpreter's state, given where the card's
  // counts put the tool (machine frame), e.g. to restore the last session's position.
  void restore(const std::function<void(ModalState&, const Vec6& machine)>& edit);

  Controller(const Settings& settings, Card& card, OperatorIO& io, PersistentStore& store,
             InterpreterOptions options = {});
  ~Controller() override;
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  // Checks the file from the live state (every error, soft limits included); a clean file runs.
  // `checked`: the caller has checked it already (run_job, with its operator answers).
  // `estimated_time_s` with `checked`: the caller's cycle-time estimate, for the progress.
  Outcome run(std::shared_ptr<const Script> script, bool checked = false,
              double estimated_time_s = 0);
  // A line the operator typed at the console: checked and run as run() does, but as typed
  // (the values it changes stay, outputs stay on) and recorded for RP, RR, RS.
  Outcome run_typed(std::shared_ptr<const Script> lines);
  Outcome pause();
  Outcome resume();
  Outcome stop();
  Outcome estop();
  Outcome acknowledge();
  // homing.require: the axes that must be homed again before they move (bit i: axis i), and
  // the operator's word that the position is right after all (CONFIRM: WinCNC's L29).
  std::uint32_t axes_to_home() const { return must_home_.load(std::memory_order_acquire); }
  void clear_home_flags() { must_home_.store(0, std::memory_order_release); }
  // Jogs run at rest, and while a file waits at SK (Keypad): a jog from there returns there.
  Outcome jog(const JogRequest& j);
  Outcome jog_release();
  // Virtual time (tests, previews of operator timing): the next activity's Pause, Stop,
  // EStop or JogRelease happens at machine time `at_s` after it starts, as if the key were
  // pressed then.
  void schedule(Request r, double at_s);

  // Returns once nothing is under way: the activity ended, or it is held at rest (paused),
  // or halted (E-stop).
  void wait();
  // wait() for at most `timeout`: true when nothing is under way.
  bool wait_for(std::chrono::milliseconds timeout);
  ControllerStatus status() const;
  // What the last activity did; read once it has ended (wait()).
  struct Summary {
    std::optional<Diagnostic> error;  // why it stopped short, located
    CardFault fault = CardFault::None;
    std::size_t lines = 0, moves = 0;  // statements executed, canonical moves issued
    // The motion was cut (a stop, an E-stop, a card fault): lines and moves count only what reached
    // the card, not what the interpreter had read ahead.
    bool cut = false;
    Steps6 commanded{};         // steps the generator emitted
    double planned_time_s = 0;  // the planner's sum of segment durations
    // How the feeder kept up with a card that queues words (bench/soak.sh): the lead's
    // figures (it may have grown), the blocks released because no move came in time, and
    // whether the feeder thread had SCHED_FIFO and locked memory.
    LeadStats lead;
    double lead_s = 0;
    std::uint64_t starved_releases = 0;
    bool feeder_realtime = false;
  };
  Summary summary() const;
  // The speeds' factor (0.1-2). On a card that queues words (a real one, the simulator with
  // --realtime) it acts at once: the moves queued and the planner's held blocks re-plan, and
  // the segment playing re-ramps from the next word not yet generated, so the step rate
  // changes within the lead. In virtual time it reaches the moves after the statement running.
  void set_feed_override(double factor);
  // Single step: after each statement of a file (its motion played out) the file holds
  // (Paused) until resume runs the next one; stop ends it there. For the runs that follow
  // and the one running.
  void set_single_step(bool on);
  // Friendly Motion's Alt-F1...Alt-F10 (`key` 1-10): the file running calls subroutine
  // N10001...N10010 before its next line, then waits in STEP mode (fm_flow.cpp). Refused when
  // no file runs; a file that is not Friendly Motion warns and calls nothing.
  Outcome hot_key(int key);
  // A call after each statement with (line reached in the top-level file, its line count),
  // on the job thread.
  void on_progress(std::function<void(std::size_t, std::size_t)> f);
  MachineState state() const;
  ModalState modal() const;  // the interpreter's state (meaningful while idle)

 private:
  class ForwardSink;

  Outcome refuse_or(Request r, const std::function<void()>& accept);
  Outcome pause(bool every_output);  // every_output: a stop switch also stops the spindle
  Outcome start_run(std::shared_ptr<const Script> script, bool checked, double estimated_time_s,
                    bool typed);
  void start_activity(std::function<void()> work);
  void job_main();
  bool settled() const;    // what wait() waits for; under m_
  void wait_for_motion();  // job thread: every flush pushed has played (or was dropped)
  // FeederEvents, on the feeder thread.
  void feeder_phase_changed(FeedPhase phase, const SourceLoc& rest) override;
  void card_faulted(const GantryError& e, CardFault fault, const Steps6& commanded) override;
  void roles_changed(const InputRoles& roles) override;
  void stop_switch_pressed(std::uint32_t bits) override;
  std::array<bool, 12> input_switches(std::uint32_t bits) const;
  // Under m_: the limit and stop switches active in `bits`, named ("X high limit switch
  // (input bit 3)", "the stop switch (input 4)").
  std::string active_limits(std::uint32_t bits) const;
  std::string active_stops(std::uint32_t bits) const;
  // Why nothing may move now: a limit switch towards `direction` (a jog; zero: a run,
  // refused while any is active), a stop switch for anything.
  std::optional<std::string> input_refusal(const Vec6& direction) const;
  CanonMove keypad_move(const JogRequest& j) const;
  Vec6 played_machine(const Steps6& steps) const;
  Vec6 played_machine() const;    // the played counts now, in units
  double elapsed_s() const;       // the card's clock since the activity began; takes m_
  MotionReport keypad_session();  // job thread: SK's wait, playing jogs
  void after_statement();         // job thread: single step, a new feed override
  void say_where_the_card_stopped();
  Activity activity(bool at_rest) const;  // job thread: for on_activity

  Settings settings_;
  Card& card_;
  OperatorIO& io_;
  PersistentStore& store_;

  // The feeder thread (motion feeder, step generator, card) and the flags between it, the
  // job thread and the callers: feeder_thread.hpp documents who writes and reads each.
  FeederThread feed_;

  // Job side.
  FeederThread::Sink* qsink_;  // the feeder's queue (its planner's moves)
  std::unique_ptr<ForwardSink> forward_;
  std::unique_ptr<Interpreter> interp_;
  std::optional<Vec6> jog_target_;  // the jog's commanded end (machine frame)
  // SK: the file waits on the job thread, which plays the operator's jogs (pending_jog_)
  // until resume closes the keypad (keypad_open_ false).
  bool keypad_open_ = false;
  std::optional<CanonMove> pending_jog_;
  bool keypad_jogging_ = false;  // a jog from the keypad state has not come to rest

  mutable std::mutex m_;
  std::condition_variable cv_;
  bool quit_ = false;  // the destructor: the job thread ends (under m_)
  MachineState state_ = MachineState::Idle;
  bool busy_ = false;                   // an activity is under way on the job thread
  std::uint64_t activities_ended_ = 0;  // ControllerStatus::activities_ended
  std::function<void()> work_;
  std::vector<std::pair<Request, double>> scheduled_;
  std::optional<MachineState> effect_state_;  // entered when a scheduled hold takes effect
  std::string message_;
  InputRoles roles_;  // what each input does, with the values in force (VN)
  SourceLoc stopped_at_;
  std::optional<Diagnostic> error_;
  CardFault fault_ = CardFault::None;
  Steps6 fault_commanded_{};  // the steps generated when the card faulted
  // homing.require: the axes that must be homed again (bit i: axis i), after an E-stop or a
  // card fault stopped a motion; cleared by homing each axis, or clear_home_flags().
  std::atomic<std::uint32_t> must_home_{0};
  double feed_override_ = 1;
  // Caller -> job thread, read after each statement: override_changed_ (exchanged by the job,
  // which then reads feed_override_ under m_) and single_step_ (a setting; seq_cst, no data
  // hangs on it). Neither concerns the feeder.
  std::atomic<bool> override_changed_{false}, single_step_{false};
  std::atomic<int> hot_key_{0};  // Alt-F1...F10 pressed, for the interpreter's next FM line
  bool step_waiting_ = false;  // single step: the file holds after a statement
  bool running_file_ = false;  // the activity is a file (not a jog)
  bool typed_ = false;         // ... typed at the console (not a part file of its own)
  std::function<void(std::size_t, std::size_t)> progress_;  // the caller's
  std::function<void(const Activity&)> activity_;           // the caller's (set while idle)
  std::shared_ptr<const std::string> top_file_;             // the file run (null: a typed line)
  std::string activity_file_;                               // the part file the activity runs
  // Job thread -> status() (relaxed: display only). Set by start_run under m_, then by the
  // interpreter's progress call on the job thread.
  std::atomic<std::size_t> line_{0}, lines_{0};
  std::int64_t start_tick_ = 0;  // the activity's first tick
  double estimate_s_ = 0;

  std::thread job_thread_;  // last: it starts (with the feeder's) once everything exists
};

}  // namespace gantry
