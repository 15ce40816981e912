// Key and character events to Dear ImGui, one frame at a time.
#include "input_queue.hpp"

#include <backends/imgui_impl_glfw.h>

#include <algorithm>
#include <vector>

namespace gantry::ui {
namespace {

constexpr int kMostHeld = 3;  // frames: a field that does not take the keys by then never will

InputQueue* queue_of(GLFWwindow* w) {
  return static_cast<InputQueue*>(glfwGetWindowUserPointer(w));
}

}  // namespace

InputQueue::InputQueue(GLFWwindow* window) : window_(window) {
  glfwSetWindowUserPointer(window, this);
  previous_key_ = glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    queue_of(w)->key(key, action, mods);
  });
  previous_char_ =
      glfwSetCharCallback(window, [](GLFWwindow* w, unsigned c) { queue_of(w)->character(c); });
}

InputQueue::~InputQueue() {
  glfwSetKeyCallback(window_, previous_key_);
  glfwSetCharCallback(window_, previous_char_);
  glfwSetWindowUserPointer(window_, nullptr);
}

void InputQueue::key(int key, int action, int mods) {
  events_.push_back({true, key, action, mods, 0});
}

void InputQueue::character(unsigned c) {
  events_.push_back({false, 0, 0, 0, c});
}

void InputQueue::deliver(bool hold) {
  if (events_.empty()) return;
  if (hold && held_ < kMostHeld) {
    ++held_;
    return;
  }
  held_ = 0;
  std::vector<int> pressed;  // in this frame: their releases wait for the next
  while (!events_.empty()) {
    const Event e = events_.front();
    if (e.is_key && e.action == GLFW_RELEASE &&
        std::find(pressed.begin(), pressed.end(), e.key) != pressed.end())
      break;
    if (e.is_key && e.action == GLFW_PRESS) pressed.push_back(e.key);
    events_.pop_front();
    if (e.is_key)
      ImGui_ImplGlfw_KeyCallback(window_, e.key, 0, e.action, e.mods);
    else
      ImGui_ImplGlfw_CharCallback(window_, e.c);
  }
}

}  // namespace gantry::ui
