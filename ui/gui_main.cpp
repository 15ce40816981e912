// The console window's main loop: GLFW window, Dear ImGui frames, scripted actions, and the
// benchmark's timings.
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <stb_image_write.h>  // PNG screenshots

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>

#include "app.hpp"
#include "input_queue.hpp"  // keys a frame at a time
#include "gantry/core/any_bytes.hpp"  // json_text
#include "gui.hpp"
#include "test_script.hpp"
#include "theme.hpp"        // fonts and colours at the window's scale
#include "window_size.hpp"  // window_scale

namespace gantry::ui {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The window's pixels as they were drawn (the back buffer, before the swap), top row first.
bool screenshot(GLFWwindow* window, const std::string& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window, &w, &h);
  std::vector<unsigned char> rgb(static_cast<std::size_t>(w * h * 3));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  stbi_flip_vertically_on_write(1);
  return stbi_write_png(path.c_str(), w, h, 3, rgb.data(), w * 3) != 0;
}

long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096;
}

// Plays the scripted actions, one (or a part of one) per frame.
class ScriptRunner {
 public:
  ScriptRunner(std::vector<Action> actions, GLFWwindow* w, App& app, InputQueue& input)
      : actions_(std::move(actions)), window_(w), app_(app), input_(input) {}

  bool done() const { return next_ >= actions_.size() || failed_; }
  bool failed() const { return failed_; }

  // Before the frame: the input this frame gets.
  void before_frame() {
    // From the first frame, as a fast typist: the input queue holds the keys for the command
    // line until it has them.
    if (done()) return;
    ++frame_;
    const Action& a = actions_[next_];
    if (!started_) {
      started_ = true;
      since_ = Clock::now();
      frames_ = 0;
      switch (a.kind) {
        case Action::Kind::Type:
          for (unsigned char c : a.text) input_.character(c);
          break;
        case Action::Kind::Key:
        case Action::Kind::Hold:
          modifiers(a.mods, GLFW_PRESS);
          input_.key(a.key, GLFW_PRESS, a.mods);
          break;
        case Action::Kind::Tap:  // both between two frames, as a quick finger does
          input_.key(a.key, GLFW_PRESS, 0);
          input_.key(a.key, GLFW_RELEASE, 0);
          released_ = true;
          break;
        case Action::Kind::Click:
          app_.click(a.text);
          break;
        case Action::Kind::Hover:
          app_.hover(static_cast<float>(a.a), static_cast<float>(a.b));
          break;
        default:
          break;
      }
      return;
    }
    if (!released_ && ((a.kind == Action::Kind::Key && frames_ >= 1) ||
                       (a.kind == Action::Kind::Hold && seconds_since(since_) >= a.a))) {
      input_.key(a.key, GLFW_RELEASE, a.mods);
      modifiers(a.mods, GLFW_RELEASE);
      released_ = true;
    }
  }

  // After the frame is drawn (before the swap): screenshots, dumps, and whether the action
  // is over.
  void after_frame() {
    if (done() || frame_ == 0) return;
    const Action& a = actions_[next_];
    ++frames_;
    bool over = false;
    switch (a.kind) {
      case Action::Kind::Type:
      case Action::Kind::Hover:
        over = frames_ >= 2;  // one frame to take it, one to show it
        break;
      case Action::Kind::Key:
      case Action::Kind::Hold:
      case Action::Kind::Tap:
        over = released_ && !input_.pending() && frames_ >= 2;
        break;
      case Action::Kind::Click:
        if (const std::optional<std::string> missed = app_.missed_click())
          return fail(fmt::format("no button named '{}' was on the screen", *missed));
        over = true;
        break;
      case Action::Kind::WaitIdle:
        idle_frames_ = app_.idle() ? idle_frames_ + 1 : 0;
        over = idle_frames_ >= 3;
        break;
      case Action::Kind::WaitDialog:
        over = app_.dialog_showing() && frames_ >= 2;
        break;
      case Action::Kind::WaitFrames:
        over = frames_ >= static_cast<int>(a.a);
        break;
      case Action::Kind::Screenshot:
        if (!screenshot(window_, a.text)) return fail("cannot write " + a.text);
        over = true;
        break;
      case Action::Kind::Dump: {
        std::ofstream out(a.text);
        out << json_text(app_.state(), 2) << "\n";  // any bytes a file showed, escaped
        if (!out) return fail("cannot write " + a.text);
        over = true;
        break;
      }
      case Action::Kind::Quit:
        next_ = actions_.size();
        return;
    }
    if (!over && seconds_since(since_) > 60)
      return fail("waited 60 s and the window is still not there");
    if (over) {
      ++next_;
      started_ = released_ = false;
      idle_frames_ = 0;
    }
  }

 private:
  void modifiers(int mods, int action) {
    if (mods & GLFW_MOD_CONTROL) input_.key(GLFW_KEY_LEFT_CONTROL, action, 0);
    if (mods & GLFW_MOD_ALT) input_.key(GLFW_KEY_LEFT_ALT, action, 0);
    if (mods & GLFW_MOD_SHIFT) input_.key(GLFW_KEY_LEFT_SHIFT, action, 0);
  }
  void fail(const std::string& why) {
    std::fprintf(stderr, "script line %d: %s\n", actions_[next_].line, why.c_str());
    failed_ = true;
  }

  std::vector<Action> actions_;
  GLFWwindow* window_;
  App& app_;
  InputQueue& input_;
  std::size_t next_ = 0;
  bool started_ = false, released_ = false, failed_ = false;
  int frames_ = 0, idle_frames_ = 0;
  int frame_ = 0;  // frames drawn
  Clock::time_point since_;
};

// The benchmark: the time to the first frame, to the first frame with the whole path, and the
// steady frame time while the view turns.
class Bench {
 public:
  explicit Bench(App& app) : app_(app), rss0_(resident_bytes()) {}
  // After each frame (finished: glFinish). False once the figures are printed.
  bool after_frame(Clock::time_point t0) {
    glFinish();
    const double now = seconds_since(t0);
    if (first_frame_ < 0) first_frame_ = now;
    if (!app_.preview_loaded()) return true;
    if (first_path_ < 0) {
      first_path_ = now;
      app_.set_always_redraw(true);
      last_ = Clock::now();
      return true;
    }
    frame_times_.push_back(seconds_since(last_));
    last_ = Clock::now();
    // 60 frames with the view turning (drawn each time), then 60 with the view still (the
    // picture kept: what typing at the command line costs with the path loaded).
    if (frame_times_.size() < 60) {
      app_.camera().orbit(2, 0);
      return true;
    }
    app_.set_always_redraw(false);
    if (frame_times_.size() < 120) return true;
    const std::vector<double> still(frame_times_.begin() + 61, frame_times_.end());
    std::vector<double> t(frame_times_.begin(), frame_times_.begin() + 60);
    std::sort(t.begin(), t.end());
    const double mean = std::accumulate(t.begin(), t.end(), 0.0) / static_cast<double>(t.size());
    const std::size_t n = app_.preview_segments();
    fmt::print(
        "segments               {}\n"
        "first frame            {:.3f} s (the window, the command line usable)\n"
        "first frame with path  {:.3f} s (load, upload, draw)\n"
        "steady frame           mean {:.1f} ms, median {:.1f} ms, max {:.1f} ms ({} frames, "
        "the view turning)\n"
        "still frame            mean {:.1f} ms (the view unchanged: the picture is kept)\n"
        "memory                 {:.0f} bytes per segment (resident growth), {} in the path "
        "model\n",
        n, first_frame_, first_path_, 1e3 * mean, 1e3 * t[t.size() / 2], 1e3 * t.back(), t.size(),
        1e3 * std::accumulate(still.begin(), still.end(), 0.0) / static_cast<double>(still.size()),
        n ? static_cast<double>(resident_bytes() - rss0_) / static_cast<double>(n) : 0.0,
        sizeof(ToolpathSegment));
    return false;
  }

 private:
  App& app_;
  long rss0_;
  double first_frame_ = -1, first_path_ = -1;
  std::vector<double> frame_times_;
  Clock::time_point last_;
};

}  // namespace

int run_gui(const GuiOptions& opt, Machine& machine) {
  const Clock::time_point t0 = Clock::now();
  std::vector<Action> actions;
  if (!opt.script.empty()) {
    std::ifstream in(opt.script);
    if (!in) {
      std::fprintf(stderr, "error: cannot read the script %s\n", opt.script.c_str());
      return 2;
    }
    std::stringstream text;
    text << in.rdbuf();
    std::string error;
    if (!parse_script(text.str(), opt.script, actions, error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return 2;
    }
  }
  glfwSetErrorCallback([](int, const char* what) { std::fprintf(stderr, "glfw: %s\n", what); });
  if (!glfwInit()) {
    std::fprintf(stderr,
                 "error: cannot open a window (is DISPLAY set? Without a display, run it under "
                 "xvfb-run)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  GLFWwindow* window = glfwCreateWindow(opt.width, opt.height, "Gantry console", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "error: cannot open an OpenGL 3.3 window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  const bool unattended = !actions.empty() || opt.bench;
  glfwSwapInterval(unattended ? 0 : 1);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed: nothing to remember
  float scale = window_scale(static_cast<float>(opt.width), static_cast<float>(opt.height));
  build_fonts(scale);
  bool light = false;
  apply_style(light, scale);
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  int status = 0;
  {
    App app(opt, machine);
    app.set_scale(scale);
    InputQueue input(window);
    ScriptRunner script(std::move(actions), window, app, input);
    std::optional<Bench> bench;
    if (opt.bench) bench.emplace(app);
    while (!glfwWindowShouldClose(window) && !app.quit_requested()) {
      if (unattended || input.pending())  // held keys go in the next frames, at once
        glfwPollEvents();
      else
        glfwWaitEventsTimeout(0.05);  // the readout updates 20 times a second at least
      script.before_frame();
      input.deliver(app.keys_moving());
      // A resized window: the fonts and sizes at its scale (between frames).
      int ww = 0, wh = 0;
      glfwGetWindowSize(window, &ww, &wh);
      if (const float s = window_scale(static_cast<float>(ww), static_cast<float>(wh));
          s != scale && ww > 0 && wh > 0) {
        scale = s;
        build_fonts(scale);
        ImGui_ImplOpenGL3_DestroyFontsTexture();
        ImGui_ImplOpenGL3_CreateFontsTexture();
        apply_style(light, scale);
        app.set_scale(scale);
      }
      if (app.light_theme() != light) {  // View > Light theme
        light = app.light_theme();
        apply_style(light, scale);
      }
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      app.frame();
      ImGui::Render();
      int w = 0, h = 0;
      glfwGetFramebufferSize(window, &w, &h);
      glViewport(0, 0, w, h);
      const ImVec4 bg = palette(light).background;
      glClearColor(bg.x, bg.y, bg.z, 1);
      glClear(GL_COLOR_BUFFER_BIT);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      if (bench && !bench->after_frame(t0)) break;
      if (!opt.script.empty()) {
        script.after_frame();
        if (script.done()) {
          status = script.failed() ? 2 : 0;
          break;
        }
      }
      glfwSwapBuffers(window);
    }
    // Nothing keeps running once the window is gone.
    machine.io.cancel();
    if (machine.controller.state() != MachineState::Idle &&
        machine.controller.state() != MachineState::Stopped &&
        machine.controller.state() != MachineState::EStop)
      machine.controller.stop();
    machine.controller.wait();
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace gantry::ui
