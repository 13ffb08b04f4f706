// A 1 kg box on a frictionless table, pressed from above by one finger (about 4.6 N) and loaded
// from kLoadStart on: the scene of the contact-accuracy and allocation tests.
#pragma once

#include "sim/scene/scene_desc.hpp"

namespace gf::sim::pressed_box {

constexpr double kMass = 1.0;                            // kg
constexpr double kHalfWidth = 0.04, kHalfHeight = 0.02;  // m
constexpr double kPress = 0.00575;  // m: device below the resting proxy (800 N/m: 4.6 N)
constexpr double kLoadStart = 0.6;  // s: the press has settled
// Moment of inertia of the box about its vertical axis (kg m^2).
constexpr double kInertiaY = kMass * (2 * kHalfWidth) * (2 * kHalfWidth) * 2 / 12;

/// The pressed box, turned by `yaw` about the vertical, with `load` from kLoadStart on.
inline SceneDesc scene(const PatchSettings& patch, double yaw, const LoadDesc& load) {
  SceneDesc s;
  s.name = "pressed-box";
  BodyDesc ground;
  ground.name = "table";
  ground.shape = ShapeKind::kPlane;
  ground.mass = 0.0;
  ground.friction = 0.0;
  BodyDesc box;
  box.name = "box";
  box.half_extents = Vec3(kHalfWidth, kHalfHeight, kHalfWidth);
  box.mass = kMass;
  box.friction = 0.0;
  box.position = Vec3(0, kHalfHeight, 0);
  box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
  s.bodies = {ground, box};
  FingerDesc f;
  f.name = "index";
  f.patch = patch;
  const double rest = 2 * kHalfHeight + f.proxy.radius;
  f.device.interpolation = Interpolation::kLinear;
  f.device.keyframes = {{0.0, Vec3(0, rest + 0.01, 0)}, {0.3, Vec3(0, rest - kPress, 0)}};
  s.fingers = {f};
  s.loads = {load};
  s.loads[0].body = 1;
  s.loads[0].body_name = "box";
  s.loads[0].start = kLoadStart;
  return s;
}

}  // namespace gf::sim::pressed_box
