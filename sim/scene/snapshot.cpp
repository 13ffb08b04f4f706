#include "sim/scene/snapshot.hpp"

#include <algorithm>

namespace gf::sim {

void interpolateSnapshot(const Snapshot& a, const Snapshot& b, double time, Snapshot& out) {
  const double span = b.time - a.time;
  const double w = span > 0.0 ? std::clamp((time - a.time) / span, 0.0, 1.0) : 1.0;
  out = b;
  out.time = time;
  for (std::size_t i = 0; i < out.bodies.size() && i < a.bodies.size(); ++i) {
    Pose& o = out.bodies[i];
    o.position = (1 - w) * a.bodies[i].position + w * b.bodies[i].position;
    o.orientation = a.bodies[i].orientation.slerp(w, b.bodies[i].orientation);
  }
  for (std::size_t i = 0; i < out.body_velocities.size() && i < a.body_velocities.size(); ++i) {
    out.body_velocities[i].first = (1 - w) * a.body_velocities[i].first + w * b.body_velocities[i].first;
    out.body_velocities[i].second = (1 - w) * a.body_velocities[i].second + w * b.body_velocities[i].second;
  }
  for (std::size_t f = 0; f < out.fingers.size() && f < a.fingers.size(); ++f) {
    FingerSnapshot& o = out.fingers[f];
    const FingerSnapshot &fa = a.fingers[f], &fb = b.fingers[f];
    o.device = (1 - w) * fa.device + w * fb.device;
    o.device_orientation = fa.device_orientation.slerp(w, fb.device_orientation);
    o.proxy = (1 - w) * fa.proxy + w * fb.proxy;
    o.coupling_force = (1 - w) * fa.coupling_force + w * fb.coupling_force;
    o.feedback_force = (1 - w) * fa.feedback_force + w * fb.feedback_force;
    // A soft pad's shape is b's, carried with its bone.
    for (Vec3& p : o.pad.nodes) p += o.proxy - fb.proxy;
    // Patch points ride with their body from b's pose to the interpolated one.
    for (ContactSnapshot& c : o.contacts) {
      if (c.body < 0 || static_cast<std::size_t>(c.body) >= out.bodies.size()) continue;
      const Pose &from = b.bodies[c.body], &to = out.bodies[c.body];
      const Eigen::Quaterniond turn = to.orientation * from.orientation.conjugate();
      const auto carry = [&](Vec3& p) { p = turn * (p - from.position) + to.position; };
      carry(c.point_world);
      c.outward_normal_world = turn * c.outward_normal_world;
      for (Vec3& p : c.sgos_world) carry(p);
      for (Vec3& p : c.path_points_world) carry(p);
      c.force = turn * c.force;
      c.rolling_moment = turn * c.rolling_moment;
      c.torsion_moment = turn * c.torsion_moment;
      c.point_load.tangential = turn * c.point_load.tangential;
      for (PointLoad& l : c.loads) l.tangential = turn * l.tangential;
    }
  }
}

}  // namespace gf::sim
