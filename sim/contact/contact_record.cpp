#include "sim/contact/contact_record.hpp"

#include <array>

#include "sim/assert.hpp"
#include "sim/patch/warm_walk.hpp"

namespace gf::sim {

namespace {

PointLoad toWorld(const PointLoad& local, const Pose& body_frame) {
  return {local.normal, body_frame.orientation * local.tangential, local.slipping};
}

}  // namespace

void toSnapshotLoads(const ContactLoads& loads, const Pose& body_frame, ContactSnapshot& out) {
  out.force = body_frame.orientation * loads.force;
  out.point_load = toWorld(loads.point, body_frame);
  out.loads.clear();
  for (const PointLoad& l : loads.points) out.loads.push_back(toWorld(l, body_frame));
  out.rolling_moment = body_frame.orientation * loads.rolling_moment;
  out.torsion_moment = body_frame.orientation * loads.torsion_moment;
  out.sliding = loads.sliding;
}

void toContactSnapshot(const ContactRecord& record, const Pose& body_frame, ContactSnapshot& out,
                       const WalkCache* walks) {
  const Patch& p = record.patch;
  out.body = record.body;
  out.point_world = body_frame.toWorld(record.contact.point_local);
  out.outward_normal_world = body_frame.orientation * record.contact.outward_normal_local;
  out.separation = record.contact.separation;
  out.press_depth = record.press_depth;
  out.radius = p.valid ? p.radius : 0.0;
  out.feature = p.hit.feature;
  toSnapshotLoads({}, body_frame, out);
  out.sgos_world.clear();
  out.path_points_world.clear();
  out.path_offsets.clear();
  if (p.sgos.empty()) return;
  for (const Sgo& s : p.sgos) out.sgos_world.push_back(body_frame.toWorld(s.position));
  for (const Sgo& s : p.inner) out.sgos_world.push_back(body_frame.toWorld(s.position));
  GF_ASSERT((walks || !p.crossings_pending) && "a patch with pending crossings needs its walk cache");
  for (std::size_t k = 0; k < p.sgos.size(); ++k) {
    // A carried walk's crossings left pending are placed from the walk cache.
    std::array<Vec3, kWarmCrossingsPerSgo> pending;
    const bool placed = p.crossings_pending && pendingCrossings(*walks, p.sgos[k].radial, pending.data());
    const std::int32_t first = p.path_offsets[k], last = p.path_offsets[k + 1];
    for (std::int32_t j = first; j < last; ++j) {
      const bool crossing = placed && j > first && j + 1 < last;
      out.path_points_world.push_back(body_frame.toWorld(crossing ? pending[static_cast<std::size_t>(j - first - 1)]
                                                                  : p.path_points[static_cast<std::size_t>(j)]));
    }
  }
  out.path_offsets.assign(p.path_offsets.begin(), p.path_offsets.end());
}

}  // namespace gf::sim
