// The 3D toolpath preview drawn with OpenGL 3: the path's segments straight from the shared
// toolpath model (one 20-byte vertex each, no copy into another layout), the table, the tool,
// and a pick buffer that says which line is under the pointer.
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <optional>
#include <vector>

#include "camera.hpp"                   // Camera
#include "gantry/preview/toolpath.hpp"  // Toolpath, ToolpathSegment

namespace gantry::ui {

// What is drawn over the path, in the path's frame.
struct Overlay {
  Eigen::Vector2f table{24, 18};  // VP's table size, from 0, 0
  float grid = 6;                 // VP's grid spacing (0: none)
  std::optional<Eigen::Vector3f> tool;
  float tool_size = 0.25f;         // the cross drawn at the tool
  std::uint32_t current_line = 0;  // highlighted (0: none)
  std::uint32_t hover_line = 0;    // highlighted differently
  bool show_jogs = true;
};

class PreviewGL {
 public:
  PreviewGL();  // needs the window's GL context current
  ~PreviewGL();
  PreviewGL(const PreviewGL&) = delete;
  PreviewGL& operator=(const PreviewGL&) = delete;

  void set_path(const Toolpath& path);  // uploads the segments (the caller may free them)

  // Draws into the preview's own texture, w x h pixels; returns its GL name (ImGui::Image).
  unsigned render(int w, int h, const Camera& cam, const Overlay& o);
  // The line drawn nearest pixel (x, y) of the last render, within a few pixels; 0 if none.
  // Draws the pick buffer, so call it only when the pointer moved.
  std::uint32_t pick(int x, int y, const Camera& cam);

 private:
  void ensure_targets(int w, int h);
  void draw(const Eigen::Matrix4f& mvp, const Overlay& o, bool pick);

  unsigned program_ = 0, pick_program_ = 0;
  unsigned path_vao_ = 0, path_vbo_ = 0, over_vao_ = 0, over_vbo_ = 0;
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;
  unsigned pick_fbo_ = 0, pick_tex_ = 0, pick_depth_ = 0;
  int w_ = 0, h_ = 0;
  std::size_t count_ = 0;  // path vertices (segments + the start)
  std::size_t over_count_ = 0;
  Overlay last_;  // the overlay of the last render, for pick()
};

}  // namespace gantry::ui
