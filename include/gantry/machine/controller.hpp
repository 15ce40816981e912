// The live machine: runs part files and keypad jogs on the card, and obeys pause, resume,
// stop and E-stop at any moment, always knowing where the tool is from the pulses played.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "gantry/core/spsc_queue.hpp"           // SpscQueue
#include "gantry/hal/card.hpp"                  // Card
#include "gantry/interp/interpreter.hpp"        // Interpreter, ModalState
#include "gantry/machine/machine_state.hpp"     // MachineState, Request
#include "gantry/motion/lookahead_planner.hpp"  // LookAheadPlanner
#include "gantry/step/motion_feeder.hpp"        // MotionFeeder

namespace gantry {

struct ControllerStatus {
  MachineState state = MachineState::Idle;
  FeedPhase phase = FeedPhase::Playing;
  Steps6 steps{};               // played by the card: where the tool is
  Vec6 machine = Vec6::Zero();  // the same in units (machine frame)
  std::string message;          // why the last activity stopped, if it did not end
  SourceLoc stopped_at;         // the line the motion came to rest in (Stopped, Paused)
};

// A keypad jog: each axis -1, 0 or +1 (several: a diagonal). Continuous: runs towards the
// soft limits until released. Step: exactly the VD keypad step along the direction.
struct JogRequest {
  std::array<int, kAxisCount> direction{};
  bool fast = false;  // jog speed; otherwise move speed
  bool step = false;
};

struct Outcome {
  bool accepted = true;
  std::string reason;              // why it was refused
  std::vector<Diagnostic> errors;  // a file refused by its check
  explicit operator bool() const { return accepted; }
};

// Threads: the caller's (requests, status), the job thread (interpreter and planner), and the
// feeder (motion feeder, step generator, card). Planned segments pass from job to feeder
// through a bounded lock-free queue; the feeder neither locks nor allocates while it plays.
// docs/controller.md has the states, the transition table and the behaviours.
class Controller {
 public:
  Controller(const Settings& settings, Card& card, OperatorIO& io, PersistentStore& store,
             InterpreterOptions options = {});
  ~Controller();
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  // Checks the file from the live state (every error, soft limits included); a clean file runs.
  Outcome run(std::shared_ptr<const Script> script);
  Outcome pause();
  Outcome resume();
  Outcome stop();
  Outcome estop();
  Outcome acknowledge();
  Outcome jog(const JogRequest& j);
  Outcome jog_release();
  // Virtual time (tests, previews of operator timing): the next activity's Pause, Stop,
  // EStop or JogRelease happens at machine time `at_s` after it starts, as if the key were
  // pressed then.
  void schedule(Request r, double at_s);

  // Returns once nothing is under way: the activity ended, or it is held at rest (paused),
  // or halted (E-stop).
  void wait();
  ControllerStatus status() const;
  MachineState state() const;
  ModalState modal() const;  // the interpreter's state (meaningful while idle)

 private:
  struct FeedItem {
    enum Kind { kSegment, kSettings, kFlush } kind = kSegment;
    PlannedSegment seg;
    std::shared_ptr<const Settings> settings;
  };
  class QueueSink;
  class ForwardSink;
  enum class OnHold { Wait, Discard };

  Outcome refuse_or(Request r, const std::function<void()>& accept);
  void start_activity(std::function<void()> work);
  void job_main();
  void feeder_main();
  void feed(FeedItem& item);
  void wait_for_motion();  // job thread: every flush pushed has played (or was dropped)
  void publish();          // feeder thread: position and phase for status()
  void on_feeder_event();  // feeder thread: a hold or halt took effect
  CanonMove keypad_move(const JogRequest& j) const;
  Vec6 played_machine(const Steps6& steps) const;
  Vec6 played_machine() const;  // the played counts now, in units

  Settings settings_;
  Card& card_;
  OperatorIO& io_;
  PersistentStore& store_;

  // Feeder side.
  StepGenerator steps_;
  MotionFeeder feeder_;
  SpscQueue<FeedItem> queue_;
  std::atomic<unsigned> wake_{0};
  std::atomic<bool> quit_{false}, dropping_{false}, cmd_resume_{false}, cmd_halt_{false},
      cmd_acknowledge_{false};
  std::atomic<OnHold> on_hold_{OnHold::Wait};
  std::atomic<std::uint64_t> flushes_done_{0};
  std::uint64_t flushes_dropped_ = 0;
  std::array<std::atomic<std::int64_t>, kAxisCount> played_{};
  std::atomic<std::int64_t> tick_{0};
  FeedPhase last_phase_ = FeedPhase::Playing;

  // Job side.
  std::unique_ptr<QueueSink> qsink_;
  std::unique_ptr<ForwardSink> forward_;
  std::unique_ptr<LookAheadPlanner> planner_;
  std::unique_ptr<Interpreter> interp_;
  std::uint64_t flushes_pushed_ = 0;
  std::atomic<bool> abort_{false};
  std::atomic<bool> interrupted_{false};  // a stop, release, halt or fault cut the motion
  std::optional<Vec6> jog_target_;        // the jog's commanded end (machine frame)

  mutable std::mutex m_;
  std::condition_variable cv_;
  MachineState state_ = MachineState::Idle;
  bool busy_ = false;  // an activity is under way on the job thread
  std::function<void()> work_;
  std::vector<std::pair<Request, double>> scheduled_;
  std::optional<MachineState> effect_state_;  // entered when a scheduled hold takes effect
  std::string message_;
  SourceLoc stopped_at_;

  std::thread feeder_thread_, job_thread_;  // last: they start once everything exists
};

}  // namespace gantry
