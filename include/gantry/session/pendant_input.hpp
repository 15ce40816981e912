// A pendant's events on the live machine: the wheel jogs (only at rest or at SK's keypad), the
// buttons pause, stop, change the override or run a line; the dead-man rule ends a continuous
// jog when the reports stop.
#pragma once

#include <array>
#include <chrono>
#include <deque>
#include <functional>
#include <mutex>
#include <string>

#include "gantry/machine/controller.hpp"      // Controller
#include "gantry/session/pendant_event.hpp"  // PendantEvent

namespace gantry::session {

// What the buttons run: the lines typed for them (the profile's [pendant] section may change
// them; a macro's empty line: not bound).
struct PendantBindings {
  std::string machine_home = "C3";
  std::string work_home = "JH";
  std::string probe_z = "C2";
  std::array<std::string, 10> macros{};  // "C6", "FP, corner.sbp"
};

class PendantInput {
 public:
  using Clock = std::chrono::steady_clock;
  // No wheel report for this long ends a continuous jog (the dead-man rule).
  static constexpr auto kDeadMan = std::chrono::milliseconds(100);

  // `now`: the clock (a fake one in tests). `tell`: a refusal or a note for the operator.
  PendantInput(Controller& c, const Settings& settings, PendantBindings bindings,
               std::function<Clock::time_point()> now = Clock::now,
               std::function<void(const std::string&)> tell = {});

  // Any thread (the driver's).
  void handle(const PendantEvent& e);
  // Every few milliseconds, on any thread: the dead-man rule, and the next queued step jog
  // once the last is at rest.
  void tick();

  bool jogging() const;  // a jog this pendant started is under way

 private:
  struct StepJog {
    int axis = 0;
    double step = 0;
    int detents = 0;
  };
  void wheel(const PendantEvent& e);
  void button(const PendantEvent& e);
  void lead(const PendantEvent& e);
  void release(const char* why);  // under m_
  void next_step();               // under m_
  bool at_rest(const ControllerStatus& s) const;
  double spindle_speed(const ControllerStatus& s) const;
  void run_line(const std::string& line, std::string_view what);
  void say(const std::string& text);
  void refuse(std::string_view why);  // under m_

  Controller& c_;
  Settings settings_;
  PendantBindings bindings_;
  std::function<Clock::time_point()> now_;
  std::function<void(const std::string&)> tell_;

  mutable std::mutex m_;
  std::deque<StepJog> steps_;  // detents waiting for the last step jog to come to rest
  bool stepping_ = false;      // a step jog of ours plays
  bool continuous_ = false;    // a continuous jog of ours plays
  int cont_axis_ = 0, cont_dir_ = 0;
  Clock::time_point last_wheel_{};
  std::string refused_;  // the last refusal told, and when
  Clock::time_point refused_at_{};
};

}  // namespace gantry::session
