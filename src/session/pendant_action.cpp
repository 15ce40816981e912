// The pendant's actions by name: buttons, continuous jogs and step jogs.
#include "gantry/session/pendant_action.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "gantry/core/text.hpp"  // ascii::trim, lower

namespace gantry::session {
namespace {

// The words of a name, lower case: "jog", "x+", "50%".
std::vector<std::string> words(std::string_view name) {
  std::vector<std::string> out;
  std::string w;
  for (char c : ascii::lower(name)) {
    if (c == ' ' || c == '\t') {
      if (!w.empty()) out.push_back(std::move(w)), w.clear();
    } else {
      w += c;
    }
  }
  if (!w.empty()) out.push_back(std::move(w));
  return out;
}

std::optional<double> number(std::string_view s) {
  double v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// "x+" -> axis 0, +1.
bool axis_way(std::string_view s, int& axis, int& dir) {
  static constexpr std::string_view kAxes = "xyzabc";
  if (s.size() != 2 || kAxes.find(s[0]) == std::string_view::npos) return false;
  if (s[1] != '+' && s[1] != '-') return false;
  axis = static_cast<int>(kAxes.find(s[0]));
  dir = s[1] == '+' ? 1 : -1;
  return true;
}

}  // namespace

std::optional<PendantEvent> pendant_action_named(std::string_view name) {
  const std::vector<std::string> w = words(name);
  if (w.empty()) return std::nullopt;
  std::string joined;
  for (const auto& s : w) joined += (joined.empty() ? "" : " ") + s;
  PendantEvent e;
  e.kind = PendantEvent::Kind::Button;
  for (int b = 0; b < static_cast<int>(PendantButton::Macro); ++b) {
    const auto button = static_cast<PendantButton>(b);
    if (joined == ascii::lower(button_name(button))) {
      e.button = button;
      return e;
    }
  }
  if (w.size() == 2 && w[0] == "macro") {  // "macro 1" .. "macro 10"
    const std::optional<double> n = number(w[1]);
    if (!n || *n != std::floor(*n) || *n < 1 || *n > 10) return std::nullopt;
    e.button = PendantButton::Macro;
    e.macro = static_cast<int>(*n);
    return e;
  }
  if ((w[0] == "jog" || w[0] == "step") && (w.size() == 2 || w.size() == 3)) {
    e.kind = PendantEvent::Kind::Wheel;
    if (!axis_way(w[1], e.axis, e.delta)) return std::nullopt;
    if (w[0] == "jog") {  // "jog x+" or "jog x+ 50%": the share of the jog speed
      e.step = 0;
      e.percent = 100;
      if (w.size() == 3) {
        if (!w[2].ends_with('%')) return std::nullopt;
        const auto p = number(std::string_view(w[2]).substr(0, w[2].size() - 1));
        if (!p || *p <= 0 || *p > 100) return std::nullopt;
        e.percent = *p;
      }
      return e;
    }
    e.step = kKeypadStep;  // "step x+": VD's keypad step; "step x+ 0.01": that length
    if (w.size() == 3) {
      const auto s = number(w[2]);
      if (!s || *s <= 0 || *s > 1000) return std::nullopt;
      e.step = *s;
    }
    return e;
  }
  return std::nullopt;
}

std::string pendant_action_text(const PendantEvent& e) {
  static constexpr std::string_view kAxes = "xyzabc";
  switch (e.kind) {
    case PendantEvent::Kind::Button:
      if (e.button == PendantButton::Macro) return fmt::format("macro {}", e.macro);
      return ascii::lower(button_name(e.button));
    case PendantEvent::Kind::Wheel: {
      if (e.axis < 0 || e.axis >= static_cast<int>(kAxes.size())) return {};
      const std::string way =
          fmt::format("{}{}", kAxes[static_cast<std::size_t>(e.axis)], e.delta < 0 ? '-' : '+');
      if (e.step == 0)
        return e.percent == 100 ? "jog " + way : fmt::format("jog {} {}%", way, e.percent);
      if (e.step < 0) return "step " + way;  // VD's keypad step
      return fmt::format("step {} {}", way, e.step);
    }
    default:
      return {};
  }
}

std::string pendant_action_names() {
  std::string s;
  for (int b = 0; b < static_cast<int>(PendantButton::Macro); ++b)
    s += fmt::format("\"{}\", ", button_name(static_cast<PendantButton>(b)));
  return s +
         "\"macro 1\" to \"macro 10\", \"jog x+\" (\"jog z- 50%\"), \"step x+\" (\"step y- 0.01\")";
}

}  // namespace gantry::session
