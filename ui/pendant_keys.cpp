// The profile's [pendant] keys in the window: each bound key's name made GLFW's key and
// modifiers, and its presses, repeats and releases sent to the pendant input
// (session::KeyPendant says what they make, as it does for the terminal console).
#include "app.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes
#include <fmt/format.h>
#include <imgui.h>

#include <string_view>

namespace gantry::ui {
namespace {

struct GlfwKey {
  int key = -1;
  bool shift = false;  // the character needs Shift (a US layout's)
};

// A character's key on a US layout: its unshifted character's key, and whether Shift types it.
GlfwKey char_key(char c) {
  if (c >= 'a' && c <= 'z') return {GLFW_KEY_A + (c - 'a'), false};
  if (c >= 'A' && c <= 'Z') return {GLFW_KEY_A + (c - 'A'), true};
  if (c >= '0' && c <= '9') return {GLFW_KEY_0 + (c - '0'), false};
  static constexpr std::string_view kPlain = "-=[]\\;',./`";
  static constexpr std::string_view kShifted = "_+{}|:\"<>?~";
  static constexpr int kKeys[] = {GLFW_KEY_MINUS,      GLFW_KEY_EQUAL,         GLFW_KEY_LEFT_BRACKET,
                                  GLFW_KEY_RIGHT_BRACKET, GLFW_KEY_BACKSLASH,  GLFW_KEY_SEMICOLON,
                                  GLFW_KEY_APOSTROPHE, GLFW_KEY_COMMA,         GLFW_KEY_PERIOD,
                                  GLFW_KEY_SLASH,      GLFW_KEY_GRAVE_ACCENT};
  if (const auto i = kPlain.find(c); i != std::string_view::npos) return {kKeys[i], false};
  if (const auto i = kShifted.find(c); i != std::string_view::npos) return {kKeys[i], true};
  static constexpr std::string_view kDigitsShifted = ")!@#$%^&*(";
  if (const auto i = kDigitsShifted.find(c); i != std::string_view::npos)
    return {GLFW_KEY_0 + static_cast<int>(i), true};
  return {};
}

int named_key(std::string_view n) {
  struct Named {
    std::string_view name;
    int key;
  };
  static constexpr Named kNamed[] = {
      {"Space", GLFW_KEY_SPACE},   {"Enter", GLFW_KEY_ENTER},       {"Tab", GLFW_KEY_TAB},
      {"Backspace", GLFW_KEY_BACKSPACE}, {"Delete", GLFW_KEY_DELETE}, {"Insert", GLFW_KEY_INSERT},
      {"Left", GLFW_KEY_LEFT},     {"Right", GLFW_KEY_RIGHT},       {"Up", GLFW_KEY_UP},
      {"Down", GLFW_KEY_DOWN},     {"Home", GLFW_KEY_HOME},         {"End", GLFW_KEY_END},
      {"PageUp", GLFW_KEY_PAGE_UP}, {"PageDown", GLFW_KEY_PAGE_DOWN}, {"Escape", GLFW_KEY_ESCAPE}};
  for (const Named& k : kNamed)
    if (k.name == n) return k.key;
  if (n.size() >= 2 && n[0] == 'F') {
    const int f = std::stoi(std::string(n.substr(1)));
    if (f >= 1 && f <= 12) return GLFW_KEY_F1 + f - 1;
  }
  return -1;
}

}  // namespace

void App::bind_keys() {
  if (!m_.keys || !m_.pendant || m_.keys->empty()) return;
  for (const auto& [name, action] : m_.keys->all()) {
    (void)action;
    std::string_view rest = name;
    int mods = 0;
    for (const auto& [prefix, bit] : {std::pair<std::string_view, int>{"Ctrl+", GLFW_MOD_CONTROL},
                                      {"Alt+", GLFW_MOD_ALT},
                                      {"Shift+", GLFW_MOD_SHIFT}})
      if (rest.starts_with(prefix) && rest.size() > prefix.size()) {
        mods |= bit;
        rest.remove_prefix(prefix.size());
      }
    GlfwKey k;
    if (rest.size() == 1) {
      k = char_key(rest[0]);
      if ((mods & GLFW_MOD_CONTROL) != 0) k.shift = false;  // Ctrl+A: the letter, no case
    } else {
      k.key = named_key(rest);
    }
    if (k.key < 0) {
      log(LogLine::Error, fmt::format("pendant.keys: the window has no key {}; it is left unbound", name));
      continue;
    }
    bound_keys_.push_back({name, k.key, mods | (k.shift ? GLFW_MOD_SHIFT : 0)});
  }
  key_pendant_.emplace(*m_.keys);
}

bool App::pendant_keys() {
  if (!key_pendant_) return false;
  const ImGuiIO& io = ImGui::GetIO();
  const int mods = (io.KeyCtrl ? GLFW_MOD_CONTROL : 0) | (io.KeyAlt ? GLFW_MOD_ALT : 0) |
                   (io.KeyShift ? GLFW_MOD_SHIFT : 0);
  const auto now = session::KeyPendant::Clock::now();
  std::vector<session::PendantEvent> out;
  bool acted = false;
  for (const BoundKey& k : bound_keys_) {
    if (ImGui::IsKeyReleased(k.key)) key_pendant_->release(k.name, out);
    if (mods != k.mods) continue;
    if (ImGui::IsKeyPressed(k.key, false))
      acted |= key_pendant_->press(k.name, false, now, out);
    else if (ImGui::IsKeyPressed(k.key, true))
      acted |= key_pendant_->press(k.name, true, now, out);
  }
  key_pendant_->tick(now, out);
  for (const session::PendantEvent& e : out) m_.pendant->handle(e);
  return acted;
}

}  // namespace gantry::ui
