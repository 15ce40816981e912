// A pendant's events on the live machine: jogs, buttons and the dead-man rule.
#include "gantry/session/pendant_input.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "gantry/lang/script.hpp"              // Script
#include "gantry/session/feed_override.hpp"  // stepped_feed_override

namespace gantry::session {

std::string_view button_name(PendantButton b) {
  switch (b) {
    case PendantButton::Reset: return "reset";
    case PendantButton::Stop: return "stop";
    case PendantButton::StartPause: return "start/pause";
    case PendantButton::FeedPlus: return "feed +";
    case PendantButton::FeedMinus: return "feed -";
    case PendantButton::SpindlePlus: return "spindle +";
    case PendantButton::SpindleMinus: return "spindle -";
    case PendantButton::MachineHome: return "machine home";
    case PendantButton::SafeZ: return "safe Z";
    case PendantButton::WorkHome: return "work home";
    case PendantButton::SpindleOnOff: return "spindle on/off";
    case PendantButton::ProbeZ: return "probe Z";
    case PendantButton::Macro: return "macro";
  }
  return "?";
}

PendantInput::PendantInput(Controller& c, const Settings& settings, PendantBindings bindings,
                           std::function<Clock::time_point()> now,
                           std::function<void(const std::string&)> tell)
    : c_(c),
      settings_(settings),
      bindings_(std::move(bindings)),
      now_(std::move(now)),
      tell_(std::move(tell)) {}

void PendantInput::say(const std::string& text) {
  if (tell_) tell_(text);
}

void PendantInput::refuse(std::string_view why) {
  // Told once a second at most: a wheel turned sends a report each detent.
  const Clock::time_point now = now_();
  if (why == refused_ && now - refused_at_ < std::chrono::seconds(1)) return;
  refused_ = why;
  refused_at_ = now;
  say(fmt::format("jog: refused, {}", why));
}

bool PendantInput::at_rest(const ControllerStatus& s) const {
  return s.settled && (s.state == MachineState::Idle || s.state == MachineState::Stopped ||
                       s.state == MachineState::Keypad);
}

bool PendantInput::jogging() const {
  std::lock_guard lock(m_);
  return stepping_ || continuous_;
}

void PendantInput::handle(const PendantEvent& e) {
  switch (e.kind) {
    case PendantEvent::Kind::Lost:
    case PendantEvent::Kind::Release: {
      std::lock_guard lock(m_);
      steps_.clear();
      if (stepping_ || continuous_) release("the pendant's link was lost, or its control let go");
      return;
    }
    case PendantEvent::Kind::Wheel: return wheel(e);
    case PendantEvent::Kind::Button: return button(e);
    case PendantEvent::Kind::Lead: return lead(e);
  }
}

// The controller has no live spindle override (TR sets the speed a file's next cuts use, and
// the spindle's output follows at once only at rest): Lead changes TR by 10 % a detent, at
// rest only, as Spindle+ and Spindle- do.
void PendantInput::lead(const PendantEvent& e) {
  if (e.delta == 0) return;
  const ControllerStatus st = c_.status();
  if (!at_rest(st)) {
    std::lock_guard lock(m_);
    const Clock::time_point now = now_();
    if (refused_ == "lead" && now - refused_at_ < std::chrono::seconds(1)) return;
    refused_ = "lead";
    refused_at_ = now;
    return say("Lead: this controller has no live spindle override; the spindle speed changes "
               "at rest (TR), 10 % a detent");
  }
  const double rpm = spindle_speed(st);
  if (rpm <= 0) return say("Lead: no spindle speed is set (TR)");
  const double f = std::max(0.1, 1 + 0.1 * e.delta);
  run_line(fmt::format("TR, {}", std::lround(rpm * f)), "Lead");
}

// The spindle's speed: as played (the spindle runs), else TR's in force (a profile with no
// speed output plays none).
double PendantInput::spindle_speed(const ControllerStatus& st) const {
  return st.spindle_rpm > 0 ? st.spindle_rpm : c_.modal().spindle_rpm;
}

void PendantInput::release(const char* why) {
  (void)why;
  c_.jog_release();  // refused when the jog ended by itself: nothing to do then
  stepping_ = continuous_ = false;
}

void PendantInput::wheel(const PendantEvent& e) {
  if (e.axis < 0 || e.axis >= kAxisCount || e.delta == 0) return;
  std::lock_guard lock(m_);
  const int dir = e.delta > 0 ? 1 : -1;
  const ControllerStatus st = c_.status();
  if (!stepping_ && !continuous_ && !at_rest(st)) {
    // A file runs or holds (a jog slowing to rest: the next detent tries again): the detents
    // are dropped, not kept for when it ends.
    if (const Verdict v = decide(st.state, Request::Jog); !v.next) refuse(v.refusal);
    return;
  }
  // A step bound without its size: VD's keypad step.
  const double step = e.step < 0 ? settings_.display.keypad_step : e.step;
  if (step > 0) {  // step mode: the detents queue, each jog waits for the last at rest
    if (continuous_) release("step mode");
    if (!steps_.empty() && steps_.back().axis == e.axis && steps_.back().step == step)
      steps_.back().detents += e.delta;
    else
      steps_.push_back({e.axis, step, e.delta});
    next_step();
    return;
  }
  last_wheel_ = now_();
  if (continuous_ && cont_axis_ == e.axis && cont_dir_ == dir) return;  // kept alive
  steps_.clear();
  if (continuous_) {
    release("another axis or way");  // the next report starts the new jog once at rest
    return;
  }
  if (stepping_ || !at_rest(st)) return;  // the next report tries again
  JogRequest j;
  j.direction[static_cast<std::size_t>(e.axis)] = dir;
  j.fast = true;
  j.speed_fraction = std::clamp(e.percent, 0.0, 100.0) / 100;
  if (j.speed_fraction <= 0) return;
  if (const Outcome o = c_.jog(j); !o) {
    say(o.reason);
    return;
  }
  continuous_ = true;
  cont_axis_ = e.axis;
  cont_dir_ = dir;
}

void PendantInput::next_step() {
  while (!stepping_ && !continuous_ && !steps_.empty()) {
    if (!at_rest(c_.status())) return;
    const StepJog s = steps_.front();
    steps_.pop_front();
    if (s.detents == 0) continue;
    JogRequest j;
    j.direction[static_cast<std::size_t>(s.axis)] = s.detents > 0 ? 1 : -1;
    j.fast = true;
    j.step = true;
    j.step_size = s.step * std::abs(s.detents);
    if (const Outcome o = c_.jog(j); !o) {
      steps_.clear();
      say(o.reason);
      return;
    }
    stepping_ = true;
  }
}

void PendantInput::tick() {
  std::lock_guard lock(m_);
  if (continuous_) {
    if (c_.status().state != MachineState::Jogging)
      continuous_ = false;  // it ended by itself (a soft limit, a stop)
    else if (now_() - last_wheel_ >= kDeadMan)
      release("no wheel report for 100 ms");
  }
  if (stepping_ && at_rest(c_.status())) stepping_ = false;
  next_step();
}

void PendantInput::run_line(const std::string& line, std::string_view what) {
  const Outcome o = c_.run_typed(Script::from_text(line, "pendant"));
  if (o) return;
  say(fmt::format("{} ({}): {}", what, line,
                  !o.reason.empty()      ? o.reason
                  : !o.errors.empty() ? o.errors.front().message
                                         : std::string("refused")));
}

void PendantInput::button(const PendantEvent& e) {
  const ControllerStatus st = c_.status();
  const std::string_view name = button_name(e.button);
  auto outcome = [&](const Outcome& o) {
    if (!o) say(fmt::format("{}: {}", name, o.reason));
  };
  switch (e.button) {
    case PendantButton::Reset: return outcome(c_.acknowledge());
    case PendantButton::Stop: {
      {
        std::lock_guard lock(m_);
        steps_.clear();
      }
      return outcome(c_.stop());
    }
    case PendantButton::StartPause:
      switch (st.state) {
        case MachineState::Running:
        case MachineState::Homing:
        case MachineState::Probing: return outcome(c_.pause());
        case MachineState::Paused:
        case MachineState::Keypad: return outcome(c_.resume());
        default: return say("start/pause: nothing is running (start a file at the console)");
      }
    case PendantButton::FeedPlus:
    case PendantButton::FeedMinus: {
      c_.set_feed_override(stepped_feed_override(st.feed_override,
                                                 e.button == PendantButton::FeedPlus ? 1 : -1,
                                                 feed_override_bounds(settings_)));
      return;
    }
    case PendantButton::SpindlePlus:
    case PendantButton::SpindleMinus: {
      const double rpm = spindle_speed(st);
      if (rpm <= 0) return say(fmt::format("{}: no spindle speed is set (TR)", name));
      const double f = e.button == PendantButton::SpindlePlus ? 1.1 : 0.9;
      return run_line(fmt::format("TR, {}", std::lround(rpm * f)), name);
    }
    case PendantButton::MachineHome: return run_line(bindings_.machine_home, name);
    case PendantButton::SafeZ: return run_line(fmt::format("JZ, {}", settings_.cutter.safe_z), name);
    case PendantButton::WorkHome: return run_line(bindings_.work_home, name);
    case PendantButton::SpindleOnOff:
      return run_line((st.outputs & 1u) != 0 ? "SO, 1, 0" : "SO, 1, 1", name);
    case PendantButton::ProbeZ: return run_line(bindings_.probe_z, name);
    case PendantButton::Macro: {
      if (e.macro < 1 || e.macro > 10 || bindings_.macros[static_cast<std::size_t>(e.macro - 1)].empty())
        return say(fmt::format("macro {} is not bound (the profile's [pendant] section)", e.macro));
      return run_line(bindings_.macros[static_cast<std::size_t>(e.macro - 1)],
                      fmt::format("macro {}", e.macro));
    }
  }
}

}  // namespace gantry::session
