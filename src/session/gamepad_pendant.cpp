// A gamepad's events as the pendant's: bindings, and the held stick's repeated reports.
#include "gantry/session/gamepad_pendant.hpp"

#include <linux/input-event-codes.h>

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "gantry/core/text.hpp"  // ascii::trim, upper, lower

namespace gantry::session {

std::optional<PendantEvent> pendant_button_named(std::string_view name) {
  PendantEvent e;
  e.kind = PendantEvent::Kind::Button;
  for (int b = 0; b <= static_cast<int>(PendantButton::Macro); ++b) {
    const auto button = static_cast<PendantButton>(b);
    if (button == PendantButton::Macro) continue;
    if (name == ascii::lower(button_name(button))) {
      e.button = button;
      return e;
    }
  }
  // "macro 1" .. "macro 10"
  if (name.starts_with("macro ")) {
    const std::string n(name.substr(6));
    if (n.find_first_not_of("0123456789") == std::string::npos && !n.empty() && n.size() <= 2) {
      e.button = PendantButton::Macro;
      e.macro = std::stoi(n);
      if (e.macro >= 1 && e.macro <= 10) return e;
    }
  }
  return std::nullopt;
}

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

std::string actions() {
  std::string s;
  for (int b = 0; b < static_cast<int>(PendantButton::Macro); ++b)
    s += fmt::format("\"{}\", ", button_name(static_cast<PendantButton>(b)));
  return s + "\"macro 1\" to \"macro 10\"";
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
    for (const auto& item : items(buttons)) {
      const auto eq = item.find('=');
      const auto name = eq == std::string::npos ? item : std::string(ascii::trim(item.substr(0, eq)));
      const auto code = button_code(ascii::upper(name));
      if (!code) {
        *error = fmt::format(
            "pendant.gamepad_buttons: \"{}\" is not a button; write the kernel's name (BTN_SOUTH, "
            "BTN_EAST, BTN_TL, BTN_START ...) = an action",
            name);
        return std::nullopt;
      }
      const auto action = eq == std::string::npos ? std::nullopt
                                                  : pendant_button_named(ascii::lower(ascii::trim(item.substr(eq + 1))));
      if (!action) {
        *error = fmt::format("pendant.gamepad_buttons: \"{}\" needs an action: one of {}", item,
                             actions());
        return std::nullopt;
      }
      b.buttons[*code] = *action;
    }
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
      jog_ = {};
      out.push_back({.kind = PendantEvent::Kind::Lost});
      return;
    case GamepadEvent::Kind::Button:
      if (const auto it = b_.buttons.find(e.code); it != b_.buttons.end() && e.value > 0)
        out.push_back(it->second);
      return;
    case GamepadEvent::Kind::Axis: {
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

void GamepadPendant::tick(std::vector<PendantEvent>& out) {
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
