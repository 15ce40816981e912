// The scripted actions' parser.
#include "test_script.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key and modifier codes only
#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <sstream>
#include <utility>

namespace gantry::ui {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool number(const std::string& s, double& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc{} && r.ptr == s.data() + s.size();
}

}  // namespace

int key_code(const std::string& name) {
  static const std::pair<const char*, int> named[] = {{"enter", GLFW_KEY_ENTER},
                                                      {"escape", GLFW_KEY_ESCAPE},
                                                      {"esc", GLFW_KEY_ESCAPE},
                                                      {"tab", GLFW_KEY_TAB},
                                                      {"space", GLFW_KEY_SPACE},
                                                      {"backspace", GLFW_KEY_BACKSPACE},
                                                      {"delete", GLFW_KEY_DELETE},
                                                      {"up", GLFW_KEY_UP},
                                                      {"down", GLFW_KEY_DOWN},
                                                      {"left", GLFW_KEY_LEFT},
                                                      {"right", GLFW_KEY_RIGHT},
                                                      {"pageup", GLFW_KEY_PAGE_UP},
                                                      {"pagedown", GLFW_KEY_PAGE_DOWN},
                                                      {"home", GLFW_KEY_HOME},
                                                      {"end", GLFW_KEY_END},
                                                      {"minus", GLFW_KEY_MINUS},
                                                      {"equal", GLFW_KEY_EQUAL}};
  const std::string n = lower(name);
  for (const auto& [k, code] : named)
    if (n == k) return code;
  if (n.size() == 1 && std::isalpha(static_cast<unsigned char>(n[0])))
    return GLFW_KEY_A + (n[0] - 'a');
  if (n.size() == 1 && std::isdigit(static_cast<unsigned char>(n[0])))
    return GLFW_KEY_0 + (n[0] - '0');
  double f = 0;
  if (n.size() >= 2 && n[0] == 'f' && number(n.substr(1), f) && f >= 1 && f <= 12)
    return GLFW_KEY_F1 + static_cast<int>(f) - 1;
  return -1;
}

bool parse_script(const std::string& text, const std::string& name, std::vector<Action>& out,
                  std::string& error) {
  std::istringstream in(text);
  std::string raw;
  int line = 0;
  auto fail = [&](const std::string& what) {
    error = fmt::format("{}:{}: {}", name, line, what);
    return false;
  };
  while (std::getline(in, raw)) {
    ++line;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    const std::size_t b = raw.find_first_not_of(" \t");
    if (b == std::string::npos || raw[b] == '#') continue;
    const std::size_t sp = raw.find(' ', b);
    const std::string verb = lower(raw.substr(b, sp == std::string::npos ? sp : sp - b));
    // The argument: for `type`, exactly what follows the one blank after the verb.
    const std::string arg = sp == std::string::npos ? "" : raw.substr(sp + 1);
    std::istringstream words(arg);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    Action a{Action::Kind::Quit, {}, 0, 0, 0, 0, line};
    if (verb == "type") {
      a.kind = Action::Kind::Type;
      a.text = arg;
    } else if (verb == "key" || verb == "hold" || verb == "tap") {
      if (w.empty()) return fail(fmt::format("{} needs a key name, e.g. {} Enter", verb, verb));
      std::string k = w[0];
      if (verb == "key") {
        for (std::size_t plus; (plus = k.find('+')) != std::string::npos && plus + 1 < k.size();) {
          const std::string m = lower(k.substr(0, plus));
          if (m == "ctrl")
            a.mods |= GLFW_MOD_CONTROL;
          else if (m == "alt")
            a.mods |= GLFW_MOD_ALT;
          else if (m == "shift")
            a.mods |= GLFW_MOD_SHIFT;
          else
            return fail(fmt::format("unknown modifier '{}': use ctrl+, alt+ or shift+", m));
          k = k.substr(plus + 1);
        }
      }
      a.key = key_code(k);
      if (a.key < 0)
        return fail(
            fmt::format("unknown key '{}': Enter, Escape, Tab, Space, Up, PageUp, F1, "
                        "a letter or a digit ...",
                        k));
      a.kind = verb == "key"   ? Action::Kind::Key
               : verb == "tap" ? Action::Kind::Tap
                               : Action::Kind::Hold;
      if (verb == "hold" && (w.size() != 2 || !number(w[1], a.a) || a.a <= 0 || a.a > 60))
        return fail("hold needs a key and seconds (0 to 60), e.g. hold Right 0.5");
    } else if (verb == "click") {
      if (arg.empty()) return fail("click needs a button's name, e.g. click Start");
      a.kind = Action::Kind::Click;
      a.text = arg;
    } else if (verb == "wait") {
      if (w.size() == 1 && w[0] == "idle") {
        a.kind = Action::Kind::WaitIdle;
      } else if (w.size() == 1 && w[0] == "dialog") {
        a.kind = Action::Kind::WaitDialog;
      } else if (w.size() == 2 && w[0] == "frames" && number(w[1], a.a) && a.a >= 1) {
        a.kind = Action::Kind::WaitFrames;
      } else {
        return fail("wait takes idle, dialog or frames N");
      }
    } else if (verb == "hover") {
      if (w.size() != 2 || !number(w[0], a.a) || !number(w[1], a.b) || a.a < 0 || a.a > 1 ||
          a.b < 0 || a.b > 1)
        return fail(
            "hover needs two fractions of the preview's width and height, e.g. hover 0.5 0.5");
      a.kind = Action::Kind::Hover;
    } else if (verb == "screenshot" || verb == "dump") {
      if (w.size() != 1) return fail(fmt::format("{} needs one file name", verb));
      a.kind = verb == "dump" ? Action::Kind::Dump : Action::Kind::Screenshot;
      a.text = w[0];
    } else if (verb == "quit") {
      a.kind = Action::Kind::Quit;
    } else {
      return fail(
          fmt::format("unknown action '{}': type, key, tap, hold, click, wait, hover, "
                      "screenshot, dump or quit",
                      verb));
    }
    out.push_back(std::move(a));
  }
  return true;
}

}  // namespace gantry::ui
