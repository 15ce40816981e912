// Pulse decoding and timing checks of the simulated card.
#include "sim/sim_card.hpp"

#include <limits>  // numeric_limits
#include <thread>  // sleep_until for --realtime

namespace gantry {
namespace {

constexpr std::int64_t kLongAgo = std::numeric_limits<std::int64_t>::min() / 2;

std::array<AxisLimits, kAxisCount> limits_of(const Settings& s) {
  std::array<AxisLimits, kAxisCount> out{};
  for (int i = 0; i < kAxisCount; ++i)
    out[i] = {s.axes[i].steps_per_unit, s.axes[i].max_speed, s.axes[i].max_accel,
              s.planner.corner_jump * s.axes[i].max_speed};
  return out;
}

}  // namespace

SimCard::SimCard(const Settings& settings, bool realtime)
    : pins_(PinMap::from(settings.pins)),
      step_pulse_us_(settings.card.step_pulse_us),
      dir_setup_us_(settings.card.dir_setup_us),
      realtime_(realtime),
      tick_s_(1.0 / settings.card.pacer_hz()),
      limits_(limits_of(settings)),
      monitor_(limits_, tick_s_) {
  prev_ = pins_.idle_word();  // the lines rest idle, pointing positive, before the first word
  last_dir_change_.fill(kLongAgo);
}

void SimCard::start(double pacer_hz) {
  stopped_ = false;
  fault_ = CardFault::None;
  tick_s_ = 1.0 / pacer_hz;
  monitor_ = KinematicsMonitor(limits_, tick_s_);
  wall_start_ = std::chrono::steady_clock::now();
}

void SimCard::stop(std::uint32_t idle_word) {
  stopped_ = true;
  if (idle_word != prev_) decode(idle_word);
}

void SimCard::write(std::span<const std::uint32_t> words) {
  if (stopped_ || fault_ != CardFault::None) return;
  for (std::uint32_t w : words) {
    if (w != prev_) decode(w);
    ++tick_;
  }
  if (realtime_) {
    std::this_thread::sleep_until(wall_start_ +
                                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(time_s())));
  }
}

void SimCard::decode(std::uint32_t w) {
  const std::uint32_t diff = w ^ prev_;
  const auto t = static_cast<std::int64_t>(tick_);
  const double tick_us = tick_s_ * 1e6;
  constexpr double eps = 1e-6;  // microseconds: tolerance for the tick arithmetic only
  for (int i = 0; i < kAxisCount; ++i) {
    const AxisPins& ap = pins_.axes[i];
    const bool step_changed = (diff & ap.step_mask) != 0;
    const bool active = ((w & ap.step_mask) != 0) != ap.step_active_low;
    // Order within one word: a trailing edge ends the pulse, then a direction change is
    // judged, then a leading edge is a step. A direction change in the very word where the
    // pulse ends is after the pulse, not during it.
    if (step_changed && !active) {
      if (static_cast<double>(t - pulse_start_[i]) * tick_us < step_pulse_us_ - eps)
        violation(i, TimingRule::PulseWidth);
      pulse_active_[i] = false;
    }
    if (diff & ap.dir_mask) {
      if (pulse_active_[i]) violation(i, TimingRule::DirDuringPulse);
      last_dir_change_[i] = t;
    }
    if (step_changed && active) {
      if (static_cast<double>(t - last_dir_change_[i]) * tick_us < dir_setup_us_ - eps)
        violation(i, TimingRule::DirSetup);
      const bool positive = pins_.positive(i, w);
      steps_[i] += positive ? 1 : -1;
      monitor_.on_step(i, t, positive);
      pulse_start_[i] = t;
      pulse_active_[i] = true;
    }
  }
  prev_ = w;
}

void SimCard::violation(int axis, TimingRule rule) {
  ++violation_count_;
  if (violations_.size() < 16) violations_.push_back({tick_, axis, rule});
}

const KinematicsMonitor& SimCard::kinematics() {
  if (!monitor_finished_) monitor_.finish();
  monitor_finished_ = true;
  return monitor_;
}

const char* rule_name(TimingRule r) {
  switch (r) {
    case TimingRule::PulseWidth:
      return "step pulse shorter than step_pulse_us";
    case TimingRule::DirSetup:
      return "step less than dir_setup_us after a direction change";
    case TimingRule::DirDuringPulse:
      return "direction changed during a step pulse";
  }
  return "?";
}

}  // namespace gantry
