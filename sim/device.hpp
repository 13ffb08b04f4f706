// Scripted haptic devices: the device position as a function of simulated time.
#pragma once

#include <vector>

#include "sim/mesh.hpp"

namespace gf::sim {

/// How a device moves between two keyframes.
enum class Interpolation {
  kLinear,  ///< constant velocity between keyframes
  kSmooth,  ///< smoothstep: zero velocity at every keyframe
};

/// The device at one time.
struct DeviceSample {
  Vec3 position = Vec3::Zero();  ///< m
  Vec3 velocity = Vec3::Zero();  ///< m/s
};

/// A device path through keyframes (time in s, position in m), held at both ends.
struct DeviceTrack {
  struct Keyframe {
    double time = 0.0;
    Vec3 position = Vec3::Zero();
  };
  std::vector<Keyframe> keyframes;  ///< strictly increasing times
  Interpolation interpolation = Interpolation::kSmooth;

  /// Position and velocity at time t (s). Before the first keyframe, at the first; after the
  /// last, at the last; with no keyframe, at the origin. Any thread; does not allocate.
  DeviceSample sample(double t) const;
};

}  // namespace gf::sim
