// The simulated card: plays pulse words in virtual (or real) time, decodes them back into
// steps, and checks every pulse against the profile's timing rules.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gantry/hal/card.hpp"           // Card
#include "gantry/hal/limit_filter.hpp"   // LimitFilter
#include "gantry/hal/pin_map.hpp"        // PinMap
#include "gantry/settings/settings.hpp"  // Settings
#include "sim/kinematics_monitor.hpp"    // KinematicsMonitor
#include "sim/sim_world.hpp"             // SimWorld

namespace gantry {

// The step rate needs no rule of its own: one word per tick makes two leading edges at
// least two ticks apart (pacer / 2), and the pulse-width rule bounds it by the profile.
enum class TimingRule { PulseWidth, DirSetup, DirDuringPulse };

struct TimingViolation {
  std::uint64_t tick;
  int axis;
  TimingRule rule;
};

// Inputs: the switches of `world` read through the profile's [inputs] bits and polarity.
// A limit switch becoming active or an active E-stop (set_trips) stops the card, as the
// driver of a real card stops its pacer on them, after the word that tripped it; a producer
// stall while words are still due is an underrun. Either way ticks_played() and steps() say
// exactly what was played.
// With a trace path, every change of the output word is written as `tick hex-word`.
class SimCard : public Card {
 public:
  // Checks pulses against the profile's step_pulse_us and dir_setup_us.
  explicit SimCard(const Settings& settings, bool realtime = false, SimWorld world = {},
                   const std::string& trace_path = "");

  void start(double pacer_hz) override;
  void write(std::span<const std::uint32_t> words) override;
  // Virtual time: every word has played when write returns; real time: it waits for them.
  void drain() override;
  // At rest: the card may run dry now (a stream still waiting for its start threshold starts).
  void end_stream() override;
  void stop(std::uint32_t idle_word) override;
  std::uint64_t ticks_played() const override { return tick_; }
  // Real time: words queue ahead of the wall clock, and the step generator bounds its lead
  // over clock_tick(), the tick the wall clock has reached (a word is decoded, and counted
  // played, when written). Virtual time: words play as they are written.
  bool queues_words() const override { return realtime_; }
  std::uint64_t clock_tick() const override;
  // Real time: a stretch of output that begins on an empty queue starts playing once this
  // many words are queued (or at drain() or end_stream()), as the real cards start a stream
  // with half the lead queued: the producer starts with that head start, not with the one
  // block it wrote first. Virtual time: 0.
  std::uint64_t start_words() const override { return realtime_ ? start_words_ : 0; }
  void set_start_words(std::uint64_t words) { start_words_ = words; }
  std::uint32_t inputs() const override { return inputs_; }
  // A switch worked by hand at any time, the machine at rest or not (a stop button): input
  // `bit` reads `high` from the next word on.
  void set_switch(int bit, bool high) { set_input(bit, high, false); }
  CardFault fault() const override { return fault_; }
  std::string fault_detail() const override;
  // Real time: how far the card's queue may run ahead of the wall clock (a real card's
  // FIFO): at least this, and as much as the step generator's lead may grow to (kMostLeadS,
  // or card.lead_ms when longer), so that the lead bounds it, as it does the real cards'
  // deeper queues. A producer that leaves it empty while a word is due underruns the card,
  // and the fault says how late it was.
  static constexpr double kRealtimeQueueS = 0.05;
  void set_realtime_queue(double seconds) { queue_s_ = seconds; }
  std::optional<double> late_s() const { return late_s_; }  // an underrun's lateness
  // Real time: how the feeder kept up, over the blocks written once a stream had played for
  // card.lead_ms (the start of a stream fills an empty queue). least_queue_s: the least the
  // queue held when a block came (0: an underrun); worst_late_s: how far below the lead's
  // refill point (lead less that block) it had fallen then.
  struct FeedFigures {
    std::uint64_t blocks = 0;
    double least_queue_s = 0, worst_late_s = 0;
  };
  FeedFigures feed_figures() const { return feed_; }
  void calibration_changed(const Settings& s) override;
  void set_trips(const InputTrip& estop, const InputTrip& limits) override;
  void stop_cushioned(std::uint32_t idle_word, int steps) override;
  std::optional<CushionPlayed> cushion_played() const override { return cushion_; }
  // Exact: every word's inputs are compared, and a `stop` bit stops the card at its word.
  void watch(const InputWatch& w) override;
  std::optional<InputEdge> watch_fired() override { return fired_; }
  // Whether an input event still to come sets `bit` to `high` (the tool at rest: nothing
  // else here changes an input).
  bool input_may_change(int bit, bool high) const {
    return world_.can_set(bit, high, input_bits_, time_s(), std::nullopt);
  }

  const Steps6& steps() const { return steps_; }     // decoded from the step and dir lines
  std::uint32_t last_word() const { return prev_; }  // the output lines now
  double time_s() const { return static_cast<double>(tick_) * tick_s_; }
  std::uint64_t timing_violations() const { return violation_count_; }
  const std::vector<TimingViolation>& first_violations() const { return violations_; }
  // Call once the run has ended, before reading the kinematics.
  const KinematicsMonitor& kinematics();

 private:
  void decode(std::uint32_t word);
  void violation(int axis, TimingRule rule);
  void update_switches(int axis);  // after a step of `axis`
  void trace_word(std::uint32_t w);
  std::uint64_t next_event_tick() const;  // the next E-stop, stall or input event
  std::vector<std::uint64_t> input_ticks_;
  std::size_t next_input_ = 0;
  std::uint32_t axis_bits_ = 0;  // every step and direction bit
  void set_input(int bit, bool active, bool active_low);
  void check_trips(std::uint32_t before);  // the inputs were `before`: did a trip go off?
  InputTrip estop_trip_, limit_trip_;
  void sample_watch(std::uint64_t played);  // the inputs may have changed; `played` words in
  EdgeDetector watcher_;
  std::optional<InputEdge> fired_;
  // The watch's last sample and its inputs; a debounce under way reaches its count at
  // watch_at_ if the inputs stay as they are.
  std::uint64_t watch_tick_ = 0, watch_at_ = UINT64_MAX;
  std::uint32_t watch_bits_ = 0;

  SimWorld world_;
  InputSettings input_bits_;
  std::array<double, kAxisCount> steps_per_unit_{};
  std::uint64_t estop_tick_ = UINT64_MAX, stall_tick_ = UINT64_MAX;
  std::unique_ptr<std::ofstream> trace_;

  PinMap pins_;
  double step_pulse_us_, dir_setup_us_;
  bool realtime_;
  double tick_s_ = 0;
  std::uint64_t tick_ = 0;
  std::uint32_t prev_ = 0;
  std::atomic<std::uint32_t> inputs_{0};  // read by other threads (the controller's checks)
  CardFault fault_ = CardFault::None;
  bool stopped_ = false;
  Steps6 steps_{};
  std::array<std::int64_t, kAxisCount> pulse_start_{};
  std::array<std::int64_t, kAxisCount> last_dir_change_{};
  // The card's limit rule (limits.travel_only, limits.debounce: LimitFilter, shared with
  // the real cards); a limit input still counting trips the card at pending_at_.
  LimitFilter filter_;
  std::uint64_t pending_at_ = UINT64_MAX;
  // Each channel's last two steps and the last one's direction: its speed at a cushioned stop.
  std::array<std::int64_t, kAxisCount> last_step_{}, prev_step_{};
  std::array<bool, kAxisCount> last_step_positive_{};
  int cushion_steps_ = 0;  // limits.cushion_steps: after a limit trip
  int pulse_ticks_ = 1;
  std::optional<CushionPlayed> cushion_;
  void play_cushion(int steps);  // from tick_ on, after prev_
  std::array<bool, kAxisCount> pulse_active_{};
  std::array<AxisLimits, kAxisCount> limits_{};
  KinematicsMonitor monitor_;
  bool monitor_finished_ = false;
  std::uint64_t violation_count_ = 0;
  std::vector<TimingViolation> violations_;  // the first few, for messages
  // Real time: the wall-clock instant of tick 0 while words stream (tick t plays at
  // wall_start_ + t ticks); a new stretch of output (after start or end_stream) begins when
  // its first word is written, or when the words before it have played.
  std::chrono::steady_clock::time_point wall_start_;
  std::chrono::steady_clock::time_point wall_at(std::uint64_t tick) const;
  bool streaming_ = false;
  double queue_s_ = kRealtimeQueueS;
  std::optional<double> late_s_;
  double lead_s_ = 0;               // card.lead_ms
  std::uint64_t stream_first_ = 0;  // the tick the stream began at
  std::uint64_t start_words_ = 0;   // the start threshold (half the lead)
  bool starting_ = false;           // the stream waits for start_words_: its clock stands
  void begin_playing(std::chrono::steady_clock::time_point now);  // stream_first_ plays now
  std::size_t block_seen_ = 0;
  FeedFigures feed_;
};

const char* rule_name(TimingRule r);

}  // namespace gantry
