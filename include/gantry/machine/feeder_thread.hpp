// The controller's feeder thread and the one owner of the flags between it, the job thread and the
// callers.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "gantry/canon/canon_move.hpp"          // InputTrigger
#include "gantry/core/spsc_queue.hpp"           // SpscQueue
#include "gantry/hal/card.hpp"                  // Card
#include "gantry/hal/input_roles.hpp"           // InputRoles, InputTrip
#include "gantry/motion/lookahead_planner.hpp"  // LookAheadPlanner
#include "gantry/step/motion_feeder.hpp"        // MotionFeeder
#include "gantry/step/step_generator.hpp"       // StepGenerator

namespace gantry {

// The played step counts in units (machine frame).
Vec6 steps_to_machine(const Settings& settings, const Steps6& steps);

// What the feeder thread tells the controller; every call runs on the feeder thread.
class FeederEvents {
 public:
  virtual ~FeederEvents() = default;
  // The feeder's phase changed (a hold or halt took effect, or the card plays again);
  // `rest` is where it came to rest. Takes the controller's mutex.
  virtual void feeder_phase_changed(FeedPhase phase, const SourceLoc& rest) = 0;
  // The card faulted while an item played (it stopped by itself): `commanded` is what the
  // generator had emitted. Takes the controller's mutex.
  virtual void card_faulted(const GantryError& e, CardFault fault, const Steps6& commanded) = 0;
  // VN changed the inputs' roles (at rest). Takes the controller's mutex.
  virtual void roles_changed(const InputRoles& roles) = 0;
  // A stop switch closed (after the block in which the card read it).
  virtual void stop_switch_pressed(std::uint32_t bits) = 0;

 protected:
  FeederEvents() = default;
  FeederEvents(const FeederEvents&) = default;
  FeederEvents& operator=(const FeederEvents&) = default;
};

// The flag protocol. Three kinds of thread: callers (console, window, tests, the signal
// watch, and the feeder itself for a stop switch), the job thread (interpreter, planner) and
// the feeder thread (this class's thread: MotionFeeder, StepGenerator, the card). Each flag
// has one writer method here; "caller" writes happen under the controller's mutex (in a
// request's accept step), which orders them with the state table. seq_cst unless given.
//
// Requests in (callers -> feeder), each consumed once by the feeder's loop:
//   on_hold_          caller (hold()), feeder (consumed), job (end_activity(), keypad)
//                     What a hold does once at rest: Wait (pause: keep the path) or Discard
//                     (stop, key release). Stored BEFORE MotionFeeder::request_hold so that
//                     the feeder, seeing Held, also sees why.
//   cmd_resume_       caller (request_resume()); feeder exchange()s it when Held. Cleared by
//                     the job at the activity's end (a resume that came too late is spent).
//   cmd_halt_         caller (request_estop()); feeder exchange()s it: halt_now() even when
//                     nothing plays (MotionFeeder::request_halt only acts inside a segment).
//   cmd_acknowledge_  caller (request_acknowledge()); feeder exchange()s it when Halted.
//   wake_             every writer above bumps it (release) and notify()s after its store;
//                     the feeder loads it (acquire) BEFORE reading the flags and waits on
//                     that value, so a request made after the read is never slept through.
//   quit_             the controller's destructor; read by the feeder's loop.
// The hold and halt ticks themselves are MotionFeeder's atomics (request_hold/_halt; any
// thread), read by the step generator before every word.
//
// Activity flags (any thread -> job thread, and the interpreter's stop_check):
//   abort_            callers (stop, E-stop), the feeder (card fault, halt, a scheduled stop
//                     taking effect: abort()), the job (an error ends the run: abort();
//                     end_activity(): cleared), an activity's start (cleared: an E-stop at
//                     rest had none to end). Read by the job's queue pushes (acquire), its
//                     waits (under the controller's mutex) and the interpreter's loops. Set
//                     under the mutex except on a card fault; a push that sees it throws.
//   interrupted_      "the motion was cut" (stop, release, halt, fault). Feeder sets it when
//                     it discards or halts; the job clears it at an activity's start (under
//                     the mutex, feeder idle) and after each SK jog. Read by the job after
//                     wait_for_motion() (ordered by flushes_done_), and by summary().
//   dropping_         feeder sets it on a discard or fault: every queued item up to the
//                     activity's fence is dropped (its flushes counted as done). The job
//                     clears it once the queue is empty (wait_for_motion() returned).
//
// State out (feeder -> everyone), stored by publish() after every block and every item:
//   played_, tick_ (release; read acquire): the card's played counts and clock.
//   inputs_ (release/acquire): the card's input bits.
//   playing_line_, playing_caller_line_, warning_, outputs_, spindle_rpm_ (relaxed): display only,
//   no data depend
//     on them.
//   flushes_done_ (release, then notify_all): flushes played or dropped. The job waits on it
//     (acquire) against flushes_pushed_ (job-only): its acquire makes everything the feeder
//     wrote before (interrupted_, fired_, latched_, the phase) visible to the job.
//   fired_, latched_ (plain): the trigger an input edge fired and where the tool was; written
//     on the feeder thread, read by the job only after wait_for_motion() (the feeder idle).
//
// The look-ahead planner runs on the feeder thread (as grbl plans next to its stepper): the
// queue carries the interpreter's canonical moves, not planned segments, so the feeder holds
// the tail of the path that the plan brings to rest. When the card needs words and no move
// has come (the job thread is late: descheduled, computing, about to ask a question), the
// feeder releases the planner's front block as the plan stands (LookAheadPlanner::
// release_front), and the machine slows towards rest along the path instead of the card
// running dry mid-motion. A card that plays words as written (the simulator in virtual time)
// never needs that: there the plan is the same, segment for segment, as the planner's on the
// job thread was.
class FeederThread {
 public:
  struct Item {
    enum Kind { kMove, kSegment, kSettings, kFlush, kWatch, kPlanner, kOverride } kind = kMove;
    CanonMove move;                            // kMove: to the planner
    PlannedSegment seg;                        // kSegment: past the planner (outputs after a stop)
    std::shared_ptr<const Settings> settings;  // kSettings, kPlanner
    std::shared_ptr<const std::vector<InputTrigger>> triggers;  // kWatch
    double factor = 1;                                          // kOverride, kPlanner
  };

  // Job thread -> feeder: pushes canonical moves for the feeder's planner, waiting while the
  // queue is full. Once the activity is aborted (stop, E-stop, fault) the next push throws,
  // which unwinds the interpreter; later pushes are dropped (the run's own clean-up flushes).
  class Sink : public MotionSink {
   public:
    explicit Sink(FeederThread& f) : f_(f) {}
    void move(const CanonMove& m) override;
    void flush() override;
    void settings_changed(const Settings& s) override;
    // An activity's start: a new plan with these values and feed override (nothing held).
    void new_plan(const Settings& s, double feed_override);
    // The feed override for the moves that follow in the stream (virtual time: in order).
    void feed_override(double factor);
    void watch(std::span<const InputTrigger> t);
    // The activity's last item, pushed whatever happened: once it is done the queue is empty.
    void fence();
    // After a stop: output switches 1-12 as `mask` says (bit n-1: switch n), then a fence.
    void outputs(std::uint32_t mask);

   private:
    void push(Item&& item, bool abortable = true);
    FeederThread& f_;
    bool dead_ = false;
  };

  // Starts the card (its pacer); the thread starts with start().
  FeederThread(const Settings& settings, Card& card, const InputTrip& stops, FeederEvents& events);
  FeederThread(const FeederThread&) = delete;
  FeederThread& operator=(const FeederThread&) = delete;
  void start();
  void quit();  // with the controller's quit: the loop ends at its next turn
  void join();  // wakes the loop and waits for it

  Sink& sink() { return sink_; }

  // ---- requests (callers, under the controller's mutex) ----
  // A hold at `tick` (0: now): kept for resume, or discarded at rest.
  void hold(std::int64_t tick, bool discard, bool pause = false, bool every_output = false);
  void halt(std::int64_t tick) {  // a scheduled E-stop: the operator's, cushioned as one
    feeder_.request_halt(tick, settings_.limits.esc_steps);
  }
  void request_resume() { cmd_resume_ = true; }
  void request_stop();  // a hold now, discarded; the activity aborts
  void request_estop();
  void request_acknowledge() { cmd_acknowledge_ = true; }
  void wake();  // after any request: the feeder looks again
  void pause_outputs(std::uint32_t mask) { feeder_.pause_outputs(mask); }
  // The operator's feed override on a card that queues words: at once, out of the queue's
  // order (the moves queued and the planner's held blocks re-plan, and the segment playing
  // re-ramps from the next word not generated: MotionFeeder::live_override).
  void live_override(double factor);

  // ---- the activity (job thread, and callers under the mutex) ----
  void abort() { abort_ = true; }
  void clear_abort() { abort_ = false; }  // an activity's start and end (under the mutex)
  bool aborted() const { return abort_; }
  const std::atomic<bool>& abort_flag() const { return abort_; }  // the interpreter's stop_check
  bool interrupted() const { return interrupted_; }
  void halted() { interrupted_ = true; }  // feeder, from feeder_phase_changed (a halt)
  void new_activity();                    // under the mutex, the feeder idle: nothing cut yet
  // Job, at rest after an SK jog: its requests are spent. Returns whether it was cut.
  bool spent_jog();
  void queue_emptied() { dropping_ = false; }  // job: what was cut is gone
  void end_activity();                         // job, the queue empty and the feeder idle
  void wait_for_motion();  // job: every flush pushed has played (or was dropped)
  // Job, after wait_for_motion() (the feeder idle, its flush done): the trigger an input edge
  // fired, once (later calls give nothing until another fires), and where the tool was then.
  std::optional<InputTrigger> take_fired() { return std::exchange(fired_, std::nullopt); }
  const Vec6& latched() const { return latched_; }

  // ---- state out (any thread) ----
  FeedPhase phase() const { return feeder_.phase(); }
  Steps6 played() const;
  std::int64_t tick() const { return tick_.load(); }
  std::uint32_t inputs() const { return inputs_.load(std::memory_order_acquire); }
  int playing_line() const { return playing_line_.load(std::memory_order_relaxed); }
  int playing_caller_line() const { return playing_caller_line_.load(std::memory_order_relaxed); }
  // The file of playing_line (a file FP called, say); null: none.
  std::shared_ptr<const std::string> playing_file() const {
    return playing_file_.load(std::memory_order_relaxed);
  }
  bool warning() const { return warning_.load(std::memory_order_relaxed); }
  // The outputs in the words the card has played (StepGenerator::played_levels).
  OutputLevels outputs() const {
    return {outputs_.load(std::memory_order_relaxed), spindle_rpm_.load(std::memory_order_relaxed)};
  }
  StepGenerator& steps() { return steps_; }
  const StepGenerator& steps() const { return steps_; }
  // The planner's sum of segment durations for the activity (read once it has ended).
  double planned_time() const { return planned_time_.load(std::memory_order_relaxed); }
  // Whether the feeder thread got SCHED_FIFO and locked memory (a card that queues words).
  bool realtime() const { return realtime_.load(); }
  static constexpr int kFeederPriority = 70;  // above the job thread, below a card's player
  // Blocks the feeder released from the planner because no move had come in time.
  std::uint64_t starved_releases() const { return starved_.load(std::memory_order_relaxed); }

 private:
  void main();
  void make_realtime();  // SCHED_FIFO and locked memory, where allowed
  void feed(Item& item);
  bool feed_from_plan();  // the queue is empty: see the .cpp
  void release_front();   // the card is due and no move came: the planner's front block goes
  void apply_live_override();
  void card_faulted(const GantryError& e, bool flush_lost);
  void publish();          // position and phase for status()
  void on_feeder_event();  // a hold or halt took effect
  void arm_watch(std::shared_ptr<const std::vector<InputTrigger>> triggers);
  void on_input_edge(const InputEdge& e);      // from the card
  void finish_input_cut(bool consumed_flush);  // at rest
  void watch_stop_switches();                  // after every block: a stop switch pauses

  enum class OnHold { Wait, Discard };

  const Settings& settings_;  // the controller's, as constructed
  Card& card_;
  FeederEvents& events_;
  StepGenerator steps_;
  MotionFeeder feeder_;
  SpscQueue<Item> queue_;
  Sink sink_{*this};
  // The planner's output: to the motion feeder, or nowhere while a stop or an input edge's
  // cut drops the rest of what was queued (the planner still takes every move, so that its
  // state is what the stream made it, as before).
  class PlanOut : public SegmentSink {
   public:
    explicit PlanOut(FeederThread& f) : f_(f) {}
    void segment(const PlannedSegment& s) override;
    void flush() override;
    void settings_changed(const Settings& s) override;
    bool muted = false;

   private:
    FeederThread& f_;
  };
  PlanOut plan_out_{*this};
  std::unique_ptr<LookAheadPlanner> planner_;  // feeder thread only
  std::atomic<double> planned_time_{0};
  std::atomic<std::uint64_t> starved_{0};
  std::atomic<double> live_factor_{0};  // 0: none pending
  std::atomic<bool> realtime_{false};

  // Requests in.
  std::atomic<unsigned> wake_{0};
  std::atomic<bool> quit_{false}, cmd_resume_{false}, cmd_halt_{false}, cmd_acknowledge_{false};
  std::atomic<OnHold> on_hold_{OnHold::Wait};
  // The activity.
  std::atomic<bool> abort_{false}, interrupted_{false}, dropping_{false};
  std::uint64_t flushes_pushed_ = 0;  // job thread only
  // State out.
  std::atomic<std::uint64_t> flushes_done_{0};
  std::array<std::atomic<std::int64_t>, kAxisCount> played_{};
  std::atomic<std::int64_t> tick_{0};
  std::atomic<std::uint32_t> inputs_{0};  // the card's input bits, as last published
  std::atomic<int> playing_line_{0};
  std::atomic<int> playing_caller_line_{0};
  // Stored only when the file changes (published_file_, feeder thread only, tells), so the
  // feeder rarely takes the shared pointer's lock; the pointer it holds keeps the name alive.
  std::atomic<std::shared_ptr<const std::string>> playing_file_;
  const std::string* published_file_ = nullptr;
  std::atomic<bool> warning_{false};
  std::atomic<std::uint32_t> outputs_{0};
  std::atomic<double> spindle_rpm_{0};

  // Feeder thread only.
  std::uint64_t flushes_dropped_ = 0;
  InputTrip stop_trip_;       // the stop switches, as the feeder knows them (VN may change them)
  bool stop_active_ = false;  // one was active at the last block
  FeedPhase last_phase_ = FeedPhase::Playing;
  // The watched edges and what fired (read by the job once the motion has played out,
  // after flushes_done_ says so).
  std::shared_ptr<const std::vector<InputTrigger>> watched_;
  bool input_cut_ = false;  // an edge cut the motion: stopping, then dropping to the flush
  bool drop_to_flush_ = false;
  std::optional<InputTrigger> fired_;
  Vec6 latched_ = Vec6::Zero();

  std::thread thread_;  // last
};

}  // namespace gantry
