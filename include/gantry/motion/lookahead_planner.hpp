// The look-ahead planner: joins moves at the corner speeds of the configured mode and plans
// each move's entry, cruise and exit speeds so that the machine can always stop in time.
#pragma once

#include <deque>
#include <vector>

#include "gantry/canon/canon_move.hpp"       // MotionSink, CanonMove
#include "gantry/motion/planned_segment.hpp"  // SegmentSink

namespace gantry {

// Moves are held until enough path lies ahead of them: at least `planner.lookahead` moves
// and at least the longest stopping distance seen, up to 64 x lookahead moves (tiny moves
// beyond that are planned with less look-ahead, never with less safety: the plan always
// ends at rest after the last move held). The passes run when the front is sent, and only
// over the moves whose speeds the new ones can still raise. docs/planner.md gives the model
// and its derivations.
class LookAheadPlanner : public MotionSink {
 public:
  LookAheadPlanner(const Settings& settings, SegmentSink& out);
  void move(const CanonMove& m) override;
  void flush() override;  // brings the machine to rest after the last move
  void settings_changed(const Settings& s) override;

  // Feed override, 0.1 to 2 (10 % to 200 %) of the commanded speeds, never above an axis's
  // max_speed. It applies at once to every move not yet sent.
  void feed_override(double factor);
  // Feed hold: the machine slows to rest along the path as fast as the accelerations allow
  // from the speed it is at, and waits; moves keep arriving and are held. resume() goes on
  // from that point, from rest, along the same path.
  void feedhold();
  void resume();
  bool holding() const { return held_; }
  // The card needs words and no move has come (the job thread is late): sends the front
  // block as the plan stands, the blocks held after it ending at rest. Every block released
  // is planned so that what follows it can stop, so what the feeder holds always ends at
  // rest (grbl's invariant): a late job thread slows the machine down, and never leaves the
  // card dry mid-motion. False when nothing is held (or in a feed hold).
  bool release_front();
  bool empty() const { return q_.empty(); }
  double override_factor() const { return override_; }

  double planned_time() const { return planned_time_; }  // sum of segment durations, s
  size_t most_held() const { return most_held_; }        // the largest look-ahead used
  // Entry bounds the backward passes computed, in all: the re-planning work.
  size_t replanned() const { return replanned_; }
  // Tests and the benchmark: re-plan every held block a new one changes as soon as it arrives
  // (the planner before issue 27). The plan is the same; only the work differs.
  void set_eager(bool eager) { eager_ = eager; }

 private:
  struct Block {
    Vec6 from, to, unit;
    Vec6 u_in_long;  // SB3: the incoming direction over the minimum distance to check
    double length = 0, accel = 0;
    double v_commanded = 0;   // the file's speed along the path
    double v_machine = 0;     // the axes' limit along the path
    double v_max = 0;         // cruise limit: commanded x override, within the machine's
    bool punctuated = false;  // an MS or JS before it
    bool from_rest = false;   // starts from rest after a feed hold
    double rest = 0;          // the speed it may start or stop at
    double max_entry = 0;     // the corner speed with the previous block (rest after a stop)
    double back = -1;         // entry bound from the backward pass (< 0: not yet planned)
    double entry = 0;         // planned entry speed (forward pass)
    SpeedClass speed_class = SpeedClass::Move;
    unsigned resting_channels = 0;
    SourceLoc loc;
    RunCount count;
  };
  void arc(const CanonMove& m);
  void add(Block b);
  // v_max, rest and the corner speed with `prev` (none: from rest) under the feed override.
  void set_speeds(Block& b, const Block* prev) const;
  void release();  // emits the front blocks beyond which enough path is held
  double reach(double v, const Block& b) const;  // the speed reachable from v over b
  double least_reach(double v, const Block& b) const;  // ... from any speed >= v, at least
  // Backward pass from the tail (which ends at `tail_exit`) over what the new blocks change.
  void backward(double tail_exit);
  // Forward pass: plans the entries up to block k.
  void forward(size_t k);
  // Block k's planned entry, brought up to date with the blocks held (tail ending at rest).
  double entry(size_t k);
  void replan_all();  // both passes over everything they change, at once (eager)
  // Sends the front block to `exit` with ramps of `jerk` (the profile's, unless a hold).
  void emit_front(double exit) { emit_front(exit, settings_.planner.jerk); }
  void emit_front(double exit, double jerk);
  // Plans to rest after the last block and emits everything, ending at the ramp speed (SB3).
  void stop();
  Vec6 incoming_direction(const Vec6& at, const Vec6& fallback) const;

  Settings settings_;  // a copy: VR and VU change it mid-stream (settings_changed)
  SegmentSink& out_;
  std::deque<Block> q_;
  bool punctuated_ = false;          // an MS or JS came since the last block
  bool held_ = false;                // feed hold: nothing is sent until resume()
  std::vector<CanonMove> deferred_;  // a dwell or output during a hold, and what follows it
  double override_ = 1;              // feed override factor
  bool front_locked_ = false;        // the front's entry is the exit of a block already emitted
  double held_length_ = 0;           // path length held after the front block
  double stop_distance_ = 0;         // the longest stopping distance of any block seen
  std::deque<std::pair<Vec6, double>> trail_;  // recent path points and distance travelled
  double travelled_ = 0;
  // The axes' velocities (units/s) as the last block sent ended, and the time rested since
  // (dwells): a start from rest jumps on top of that stop's jump (start_after_stop).
  Vec6 stop_velocity_ = Vec6::Zero();
  double rested_s_ = 0;
  double planned_time_ = 0;
  size_t most_held_ = 0;
  // The front blocks whose backward bound no block added can change (up to the last one
  // settled at its corner speed), and those whose entry the forward pass has planned.
  // planned_: the front blocks the last backward pass covered (the others are new).
  size_t settled_ = 0;
  size_t planned_ = 0;
  size_t forwarded_ = 0;
  size_t replanned_ = 0;
  bool eager_ = false;
};

}  // namespace gantry
