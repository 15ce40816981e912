// The preview's camera: an orbit around a target, seen orthographically or in perspective,
// from the preset views (top, front, side, iso) or wherever the operator drags it.
#pragma once

#include <Eigen/Geometry>

namespace gantry::ui {

enum class View { Top, Front, Side, Iso };

struct Camera {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float yaw = 0, pitch = 90;  // degrees; yaw 0 pitch 0 looks along +Y (front), pitch 90 down
  float distance = 10;        // from the target
  bool perspective = false;
  static constexpr float kFovY = 40;  // degrees; orthographic shows what perspective does
                                      // at the target's distance

  void set_view(View v);
  // Frames `box` (the toolpath and the table) with a margin, for a viewport of this aspect.
  void fit(const Eigen::AlignedBox3f& box, float aspect);
  // Mouse drags, in pixels of a viewport `height` pixels high.
  void orbit(float dx, float dy);
  void pan(float dx, float dy, float height);
  void zoom(float factor);  // < 1 closer

  Eigen::Vector3f eye_direction() const;  // from the target towards the eye
  Eigen::Vector3f up() const;
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(float aspect) const;
  float half_height() const;  // of the view at the target's distance

 private:
  float radius_ = 10;  // of the framed box, for the clip planes
};

}  // namespace gantry::ui
