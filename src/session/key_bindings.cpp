// Keys as a pendant: key names, the profile's bindings, and the events keys make.
#include "gantry/session/key_bindings.hpp"

#include <array>

#include <fmt/format.h>

#include "gantry/core/text.hpp"              // ascii::trim, lower, upper
#include "gantry/session/pendant_action.hpp"  // pendant_action_named

namespace gantry::session {
namespace {

constexpr std::array<std::string_view, 15> kNamed = {
    "Space", "Enter", "Tab",  "Backspace", "Delete", "Insert",   "Left",  "Right",
    "Up",    "Down",  "Home", "End",       "PageUp", "PageDown", "Escape"};

struct Alias {
  std::string_view from, to;
};
constexpr Alias kAliases[] = {{"esc", "Escape"}, {"pgup", "PageUp"}, {"pgdn", "PageDown"},
                              {"return", "Enter"}, {"del", "Delete"}, {"ins", "Insert"}};

std::optional<std::string> named_key(std::string_view text) {
  const std::string low = ascii::lower(text);
  for (std::string_view n : kNamed)
    if (low == ascii::lower(n)) return std::string(n);
  for (const Alias& a : kAliases)
    if (low == a.from) return std::string(a.to);
  if (low.size() >= 2 && low.size() <= 3 && low[0] == 'f' &&
      low.find_first_not_of("0123456789", 1) == std::string::npos) {
    const int n = std::stoi(low.substr(1));
    if (n >= 1 && n <= 12) return fmt::format("F{}", n);
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> key_name(std::string_view text, std::string* why) {
  auto fail = [&](std::string m) -> std::optional<std::string> {
    if (why) *why = std::move(m);
    return std::nullopt;
  };
  text = ascii::trim(text);
  std::string_view rest = text;
  bool ctrl = false, alt = false, shift = false;
  // The modifiers, each with its '+' ("Ctrl++" is Ctrl and '+').
  for (;;) {
    const std::size_t plus = rest.find('+');
    if (plus == std::string_view::npos || plus == 0 || plus + 1 >= rest.size()) break;
    const std::string mod = ascii::lower(ascii::trim(rest.substr(0, plus)));
    if (mod == "ctrl" || mod == "control") ctrl = true;
    else if (mod == "alt") alt = true;
    else if (mod == "shift") shift = true;
    else break;
    rest = ascii::trim_front(rest.substr(plus + 1));
  }
  std::string base;
  if (rest.size() == 1 && static_cast<unsigned char>(rest[0]) > 0x20 &&
      static_cast<unsigned char>(rest[0]) < 0x7f) {
    base = std::string(rest);
    if (shift && base[0] >= 'a' && base[0] <= 'z') base = ascii::upper(base), shift = false;
    if (shift) return fail(fmt::format("\"{}\": Shift with a character; write the character it types", text));
    if (ctrl) {  // a terminal sends Ctrl+letter as one control byte: no case
      if (!((base[0] >= 'a' && base[0] <= 'z') || (base[0] >= 'A' && base[0] <= 'Z')))
        return fail(fmt::format("\"{}\": Ctrl goes with a letter or a named key", text));
      base = ascii::upper(base);
    }
  } else if (const auto n = named_key(rest)) {
    base = *n;
  } else {
    return fail(fmt::format(
        "\"{}\" is not a key; write a character (a, A, +), a named key (Space, Enter, Tab, "
        "Backspace, Delete, Insert, Left, Right, Up, Down, Home, End, PageUp, PageDown, Escape, "
        "F1-F12), with Ctrl+, Alt+ or Shift+ before it",
        text));
  }
  std::string name = fmt::format("{}{}{}{}", ctrl ? "Ctrl+" : "", alt ? "Alt+" : "",
                                 shift ? "Shift+" : "", base);
  if (name == "Ctrl+C" || name == "!")
    return fail(fmt::format("\"{}\" is the console's E-stop key; it cannot be bound", text));
  if (name == "F12")
    return fail(fmt::format("\"{}\" is the window's E-stop key; it cannot be bound", text));
  return name;
}

KeyBindings KeyBindings::parse(const std::vector<std::string>& items,
                               std::vector<Problem>* problems) {
  KeyBindings b;
  auto problem = [&](std::size_t i, std::string m) {
    if (problems) problems->push_back({i, std::move(m)});
  };
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string& item = items[i];
    // The '=' that splits: the last one, so that "= = stop" binds '='.
    const std::size_t eq = item.rfind('=');
    if (eq == std::string::npos) {
      problem(i, fmt::format("\"{}\" needs KEY = action", item));
      continue;
    }
    std::string why;
    const auto key = key_name(item.substr(0, eq), &why);
    if (!key) {
      problem(i, why);
      continue;
    }
    const auto action = pendant_action_named(ascii::trim(item.substr(eq + 1)));
    if (!action) {
      problem(i, fmt::format("\"{}\" is not an action; use one of {}",
                             ascii::trim(item.substr(eq + 1)), pendant_action_names()));
      continue;
    }
    if (b.keys_.count(*key) > 0) {
      problem(i, fmt::format("{} is bound twice; the first binding is kept", *key));
      continue;
    }
    b.keys_[*key] = *action;
  }
  return b;
}

const PendantEvent* KeyBindings::find(const std::string& key) const {
  const auto it = keys_.find(key);
  return it == keys_.end() ? nullptr : &it->second;
}

bool KeyPendant::key(const std::string& name, Clock::time_point now,
                     std::vector<PendantEvent>& out) {
  const PendantEvent* e = b_.find(name);
  if (!e) return false;
  const bool repeat = name == last_ && now - last_at_ < gap_;
  last_ = name;
  last_at_ = now;
  if (continuous(*e) || !repeat) out.push_back(*e);
  return true;
}

bool KeyPendant::press(const std::string& name, bool repeat, Clock::time_point now,
                       std::vector<PendantEvent>& out) {
  const PendantEvent* e = b_.find(name);
  if (!e) return false;
  if (repeat) return true;  // a held key: its jog reports come from tick
  out.push_back(*e);
  if (continuous(*e)) {
    held_ = name;
    next_report_ = now + kRepeat;
  }
  return true;
}

bool KeyPendant::release(const std::string& name, std::vector<PendantEvent>& out) {
  if (!b_.find(name)) return false;
  if (name == held_) {
    held_.clear();
    out.push_back({.kind = PendantEvent::Kind::Release});
  }
  return true;
}

void KeyPendant::tick(Clock::time_point now, std::vector<PendantEvent>& out) {
  if (held_.empty() || now < next_report_) return;
  next_report_ = now + kRepeat;
  out.push_back(*b_.find(held_));
}

}  // namespace gantry::session
