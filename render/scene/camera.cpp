#include "render/scene/camera.hpp"

#include <cmath>
#include <numbers>

namespace gf::render {

Eigen::Matrix4f lookAt(const sim::Vec3& eye, const sim::Vec3& target, const sim::Vec3& up) {
  const sim::Vec3 f = (target - eye).normalized();
  const sim::Vec3 s = f.cross(up).normalized();
  const sim::Vec3 u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m.cast<float>();
}

Eigen::Matrix4f perspective(double fov_deg, double aspect, double near_m, double far_m) {
  const double f = 1.0 / std::tan(0.5 * fov_deg * std::numbers::pi / 180.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far_m + near_m) / (near_m - far_m);
  m(2, 3) = 2.0 * far_m * near_m / (near_m - far_m);
  m(3, 2) = -1.0;
  return m.cast<float>();
}

Eigen::Matrix4f orthographic(double half_width, double half_height, double near_m, double far_m) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 0) = 1.0 / half_width;
  m(1, 1) = 1.0 / half_height;
  m(2, 2) = -2.0 / (far_m - near_m);
  m(2, 3) = -(far_m + near_m) / (far_m - near_m);
  return m.cast<float>();
}

sim::Vec3 upFor(const sim::Vec3& direction) {
  const sim::Vec3 d = direction.normalized();
  return std::abs(d.y()) > 0.99 ? sim::Vec3(0, 0, -1) : sim::Vec3::UnitY();
}

view::Camera closeUpCamera(const sim::Vec3& point, const sim::Vec3& outward_normal, double half_extent) {
  constexpr double kFovDeg = 30.0;
  const double distance = half_extent / std::tan(0.5 * kFovDeg * std::numbers::pi / 180.0);
  view::Camera c;
  c.name = "close-up";
  c.position = point + distance * outward_normal.normalized();
  c.target = point;
  c.fov_deg = kFovDeg;
  return c;
}

}  // namespace gf::render
