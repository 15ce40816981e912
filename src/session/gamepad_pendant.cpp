// A gamepad's events as the pendant's: bindings, and the held stick's repeated reports.
#include "gantry/session/gamepad_pendant.hpp"

#include <linux/input-event-codes.h>

#include <cmath>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "gantry/core/text.hpp"              // ascii::trim, upper, lower
#include "gantry/session/pendant_action.hpp"  // pendant_action_named

namespace gantry::session {

namespace {

PendantEvent button(PendantButton b) {
  PendantEvent e;
  e.kind = PendantEvent::Kind::Button;
  e.button = b;
  return e;
}

std::vector<std::string> items(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (auto t = std::string(ascii::trim(item)); !t.empty()) out.push_back(t);
  return out;
}

}  // namespace

GamepadBindings GamepadBindings::usual() {
  GamepadBindings b;
  b.jog[0] = {{ABS_X, false}, {ABS_HAT0X, false}};
  b.jog[1] = {{ABS_Y, true}, {ABS_HAT0Y, true}};
  b.jog[2] = {{ABS_RY, true}};
  b.buttons[BTN_SOUTH] = button(PendantButton::StartPause);
  b.buttons[BTN_EAST] = button(PendantButton::Stop);
  b.buttons[BTN_TL] = button(PendantButton::FeedMinus);
  b.buttons[BTN_TR] = button(PendantButton::FeedPlus);
  b.buttons[BTN_SELECT] = button(PendantButton::Reset);
  return b;
}

std::optional<GamepadBindings> GamepadBindings::parse(const std::array<std::string, 6>& jog,
                                                      const std::string& buttons,
                                                      std::string* error) {
  static constexpr std::string_view kAxes = "xyzabc";
  GamepadBindings b = usual();
  for (size_t i = 0; i < jog.size(); ++i) {
    if (jog[i].empty()) continue;
    b.jog[i].clear();
    if (jog[i] == "none") continue;
    for (const auto& item : items(jog[i])) {
      const bool invert = item.front() == '-';
      const auto code = axis_code(ascii::upper(invert ? std::string_view(item).substr(1) : item));
      if (!code) {
        *error = fmt::format(
            "pendant.gamepad_{}: \"{}\" is not a stick axis; write the kernel's name (ABS_X, "
            "ABS_Y, ABS_RX, ABS_RY, ABS_HAT0X ...), with a minus to reverse it, or none",
            kAxes[i], item);
        return std::nullopt;
      }
      b.jog[i].push_back({*code, invert});
    }
  }
  if (!buttons.empty()) {
    b.buttons.clear();
    std::set<int> hats_bound;
    for (const auto& item : items(buttons)) {
      const auto eq = item.find('=');
      const auto name = eq == std::string::npos ? item : std::string(ascii::trim(item.substr(0, eq)));
      // A button, or a hat's way ("ABS_HAT0X+", a D-pad that reports as a hat) pressed as one.
      const std::string up = ascii::upper(name);
      std::optional<int> code = button_code(up);
      int hat_way = 0;
      if (!code && up.size() > 1 && (up.back() == '+' || up.back() == '-')) {
        const auto axis = axis_code(std::string_view(up).substr(0, up.size() - 1));
        if (axis && *axis >= ABS_HAT0X && *axis <= ABS_HAT3Y) {
          code = *axis;
          hat_way = up.back() == '+' ? 1 : -1;
        }
      }
      if (!code) {
        *error = fmt::format(
            "pendant.gamepad_buttons: \"{}\" is not a button; write the kernel's name (BTN_SOUTH, "
            "BTN_EAST, BTN_TL, BTN_DPAD_UP ..., or a hat's way: ABS_HAT0X+, ABS_HAT0Y-) = an action",
            name);
        return std::nullopt;
      }
      const auto action = eq == std::string::npos ? std::nullopt
                                                  : pendant_action_named(ascii::trim(item.substr(eq + 1)));
      if (!action) {
        *error = fmt::format("pendant.gamepad_buttons: \"{}\" needs an action: one of {}", item,
                             pendant_action_names());
        return std::nullopt;
      }
      if (hat_way != 0) {
        b.hats[{*code, hat_way}] = *action;
        hats_bound.insert(*code);
      } else {
        b.buttons[*code] = *action;
      }
    }
    // A hat bound as buttons steps (or presses); it no longer jogs as a stick too.
    for (auto& sticks : b.jog)
      std::erase_if(sticks, [&](const Stick& s) { return hats_bound.count(s.code) > 0; });
  }
  return b;
}

GamepadPendant::Jog GamepadPendant::chosen() const {
  Jog best;
  double most = 0;
  for (int axis = 0; axis < 6; ++axis)
    for (const auto& s : b_.jog[static_cast<size_t>(axis)]) {
      const auto it = sticks_.find(s.code);
      if (it == sticks_.end()) continue;
      const double v = s.invert ? -it->second : it->second;
      if (std::abs(v) > most) {
        most = std::abs(v);
        best = {axis, v > 0 ? 1 : -1, std::max(1.0, std::round(most * 100))};
      }
    }
  return best;
}

void GamepadPendant::event(const GamepadEvent& e, std::vector<PendantEvent>& out) {
  switch (e.kind) {
    case GamepadEvent::Kind::Lost:
      sticks_.clear();
      hat_way_.clear();
      held_ = -1;
      jog_ = {};
      out.push_back({.kind = PendantEvent::Kind::Lost});
      return;
    case GamepadEvent::Kind::Button:
      if (const auto it = b_.buttons.find(e.code); it != b_.buttons.end())
        press(e.code, e.value > 0, it->second, out);
      return;
    case GamepadEvent::Kind::Axis: {
      if (const auto h = hat_way_.find(e.code); h != hat_way_.end() ||
                                                 b_.hats.count({e.code, 1}) + b_.hats.count({e.code, -1}) > 0) {
        const int way = e.value > 0.5 ? 1 : e.value < -0.5 ? -1 : 0;
        int& was = hat_way_[e.code];
        if (way == was) return;
        if (const auto it = b_.hats.find({e.code, was}); was != 0 && it != b_.hats.end())
          press(e.code, false, it->second, out);
        was = way;
        if (const auto it = b_.hats.find({e.code, way}); way != 0 && it != b_.hats.end())
          press(e.code, true, it->second, out);
        return;
      }
      sticks_[e.code] = e.value;
      const Jog now = chosen();
      if (now.axis == jog_.axis && now.dir == jog_.dir) {
        jog_.percent = now.percent;  // the same jog: its speed was set when it started
        return;
      }
      if (jog_.axis >= 0) out.push_back({.kind = PendantEvent::Kind::Release});
      jog_ = now;
      tick(out);
      return;
    }
  }
}

void GamepadPendant::press(int code, bool down, const PendantEvent& action,
                           std::vector<PendantEvent>& out) {
  const bool continuous = action.kind == PendantEvent::Kind::Wheel && action.step == 0;
  if (!down) {
    if (continuous && held_ == code) {
      held_ = -1;
      out.push_back({.kind = PendantEvent::Kind::Release});
    }
    return;
  }
  out.push_back(action);  // a button, a step, or a continuous jog's first report
  if (continuous) {
    held_ = code;
    held_jog_ = action;
  }
}

void GamepadPendant::tick(std::vector<PendantEvent>& out) {
  if (held_ >= 0 && jog_.axis < 0) out.push_back(held_jog_);
  if (jog_.axis < 0) return;
  PendantEvent e;
  e.kind = PendantEvent::Kind::Wheel;
  e.axis = jog_.axis;
  e.delta = jog_.dir;
  e.step = 0;
  e.percent = jog_.percent;
  out.push_back(e);
}

}  // namespace gantry::session
