// The preview camera's matrices (OpenGL conventions: right-handed eye space, -Z forward).
#include "camera.hpp"

#include <algorithm>
#include <cmath>

namespace gantry::ui {
namespace {

constexpr float kDeg = 3.14159265358979f / 180;

}  // namespace

void Camera::set_view(View v) {
  switch (v) {
    case View::Top:
      yaw = 0, pitch = 90;
      break;
    case View::Front:
      yaw = 0, pitch = 0;
      break;
    case View::Side:
      yaw = 90, pitch = 0;
      break;
    case View::Iso:
      yaw = 45, pitch = 35.264f;  // along (1, -1, 1): the three axes equally foreshortened
      break;
  }
}

Eigen::Vector3f Camera::eye_direction() const {
  const float y = yaw * kDeg, p = pitch * kDeg;
  return {std::cos(p) * std::sin(y), -std::cos(p) * std::cos(y), std::sin(p)};
}

Eigen::Vector3f Camera::up() const {
  // The derivative of the eye direction by pitch: always at right angles to it, and +Y when
  // looking straight down (the table's far edge at the top of the screen).
  const float y = yaw * kDeg, p = pitch * kDeg;
  return {-std::sin(p) * std::sin(y), std::sin(p) * std::cos(y), std::cos(p)};
}

float Camera::half_height() const {
  return distance * std::tan(kFovY * kDeg / 2);
}

void Camera::fit(const Eigen::AlignedBox3f& box, float aspect) {
  if (box.isEmpty()) return;
  target = box.center();
  radius_ = std::max(box.diagonal().norm() / 2, 1e-3f);
  // The box's sphere fits the smaller of the two half-angles, with a 10 % margin.
  const float half = std::tan(kFovY * kDeg / 2) * std::min(aspect, 1.0f);
  distance = 1.1f * radius_ / half;
  if (perspective) distance = 1.1f * radius_ / std::sin(std::atan(half));
}

void Camera::orbit(float dx, float dy) {
  yaw -= dx * 0.3f;
  pitch = std::clamp(pitch + dy * 0.3f, -90.0f, 90.0f);
}

void Camera::pan(float dx, float dy, float height) {
  const Eigen::Vector3f right = up().cross(eye_direction()).normalized();
  const float per_pixel = 2 * half_height() / std::max(height, 1.0f);
  target += (-dx * right + dy * up()) * per_pixel;
}

void Camera::zoom(float factor) {
  distance = std::clamp(distance * factor, 1e-4f, 1e7f);
}

Eigen::Matrix4f Camera::view() const {
  const Eigen::Vector3f f = -eye_direction();  // forward
  const Eigen::Vector3f u = up();
  const Eigen::Vector3f r = f.cross(u).normalized();
  const Eigen::Vector3f eye = target + distance * eye_direction();
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4f Camera::projection(float aspect) const {
  const float reach = std::max(radius_ * 4, distance * 0.01f);
  const float n = perspective ? std::max(distance - reach, distance * 1e-3f) : -reach;
  const float f = distance + reach;
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  const float t = half_height(), r = t * aspect;
  if (perspective) {
    const float tn = std::tan(kFovY * kDeg / 2);
    m(0, 0) = 1 / (tn * aspect);
    m(1, 1) = 1 / tn;
    m(2, 2) = -(f + n) / (f - n);
    m(2, 3) = -2 * f * n / (f - n);
    m(3, 2) = -1;
  } else {
    m(0, 0) = 1 / r;
    m(1, 1) = 1 / t;
    m(2, 2) = -2 / (f - n);
    m(2, 3) = -(f + n) / (f - n);
    m(3, 3) = 1;
  }
  return m;
}

}  // namespace gantry::ui
