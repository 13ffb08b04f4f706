// The math types of godfinger's public API: Eigen's double-precision vector and quaternion, and a
// rigid pose. SI units, y up, right-handed; every position and direction is in metres or unit
// length in the frame its name says (world, body, device).
#pragma once

#include <Eigen/Geometry>

namespace gf::sim {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

/// A rigid pose: a point p of the posed frame is at orientation * p + position in the world.
struct Pose {
  Vec3 position = Vec3::Zero();        ///< origin of the frame (m)
  Quat orientation = Quat::Identity();
  /// A point given in this frame, in the world (m).
  Vec3 toWorld(const Vec3& local) const { return orientation * local + position; }
};

}  // namespace gf::sim
