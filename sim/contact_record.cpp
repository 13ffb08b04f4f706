#include "sim/contact_record.hpp"

namespace gf::sim {

void toContactSnapshot(const ContactRecord& record, const Pose& body_frame, ContactSnapshot& out) {
  const Patch& p = record.patch;
  out.body = record.body;
  out.point_world = body_frame.toWorld(record.contact.point_local);
  out.outward_normal_world = body_frame.orientation * record.contact.outward_normal_local;
  out.separation = record.contact.separation;
  out.press_depth = record.press_depth;
  out.radius = p.valid ? p.radius : 0.0;
  out.feature = p.hit.feature;
  out.sgos_world.clear();
  out.path_points_world.clear();
  out.path_offsets.clear();
  if (p.sgos.empty()) return;
  for (const Sgo& s : p.sgos) out.sgos_world.push_back(body_frame.toWorld(s.position));
  for (const Sgo& s : p.inner) out.sgos_world.push_back(body_frame.toWorld(s.position));
  for (const Vec3& q : p.path_points) out.path_points_world.push_back(body_frame.toWorld(q));
  out.path_offsets.assign(p.path_offsets.begin(), p.path_offsets.end());
}

}  // namespace gf::sim
