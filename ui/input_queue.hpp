// The keys and characters typed, handed to Dear ImGui a frame at a time. Dear ImGui 1.86 reads
// the keys as down or up once a frame, so a key pressed and released between two frames (a
// quick tap) was never seen, and what was typed before a field had the keys was dropped (the
// first line typed in a new window). Here each event waits its turn: a release goes in the
// frame after its press, and nothing goes while the window is moving the keys to a field.
#pragma once

#include <deque>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace gantry::ui {

class InputQueue {
 public:
  // Takes the window's key and character callbacks (after Dear ImGui's backend installed its
  // own, which this one feeds).
  explicit InputQueue(GLFWwindow* window);
  ~InputQueue();
  InputQueue(const InputQueue&) = delete;
  InputQueue& operator=(const InputQueue&) = delete;

  // As GLFW reports them (the callbacks), or as a script types them.
  void key(int key, int action, int mods);
  void character(unsigned c);

  // Before a frame: hands Dear ImGui what it can take in this frame. `hold`: a field is about
  // to take the keys (the events wait for it, a few frames at most).
  void deliver(bool hold);
  bool pending() const { return !events_.empty(); }

 private:
  struct Event {
    bool is_key;
    int key, action, mods;
    unsigned c;
  };
  GLFWwindow* window_;
  GLFWkeyfun previous_key_ = nullptr;
  GLFWcharfun previous_char_ = nullptr;
  std::deque<Event> events_;
  int held_ = 0;  // frames the events have waited for a field
};

}  // namespace gantry::ui
