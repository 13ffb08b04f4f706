// One finger's contact with one body, as the World keeps it during a step: everything in the
// body's own frame, computed once; and the one function that puts it into a Snapshot, in the
// world frame at one pose. `godfinger run`, `live` and `patch` all go through it.
#pragma once

#include "sim/patch/god_finger.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::sim {

/// The forces the solver put on the touched body at a contact's points in one step, in the
/// body's frame (N): see ContactSnapshot::force, point_load, loads and rolling_moment.
struct ContactLoads {
  Vec3 force = Vec3::Zero();      ///< the contact's: the sum of its points'
  PointLoad point;                ///< the true contact's
  std::vector<PointLoad> points;  ///< the patch's points (its SGOs, then its inner points)
  Vec3 rolling_moment = Vec3::Zero();  ///< ContactSnapshot::rolling_moment (N m)
  Vec3 torsion_moment = Vec3::Zero();  ///< ContactSnapshot::torsion_moment (N m)
  bool sliding = false;           ///< the friction block is at its limit
};

/// A contact and its god-finger patch, in the frame of the touched body's walk mesh.
struct ContactRecord {
  int body = -1;             ///< index into SceneDesc::bodies
  PatchContact contact;      ///< c_p, outward normal (body frame) and separation c_d
  double press_depth = 0.0;  ///< v . c_n (m), Eq. 1's input: > 0 while pressing
  Patch patch;               ///< radius, SGOs and walked paths (body frame); none for a god-object
};

/// `loads` (body frame) into `out`'s force, point_load, loads, rolling_moment, torsion_moment and sliding, in
/// the world frame at `body_frame`. Reuses the storage of `out`. Any thread.
void toSnapshotLoads(const ContactLoads& loads, const Pose& body_frame, ContactSnapshot& out);

/// `record` at `body_frame`, the pose of the frame it is local to: point, normal, SGOs and paths
/// transformed to the world frame with that one pose. Reuses the storage of `out`; does not
/// allocate once it has held as many SGOs and path points. A patch whose crossings are pending
/// (Patch::crossings_pending) takes them from `walks`, the cache it was computed with. Any thread.
void toContactSnapshot(const ContactRecord& record, const Pose& body_frame, ContactSnapshot& out,
                       const WalkCache* walks = nullptr);

}  // namespace gf::sim
