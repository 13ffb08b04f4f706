// Immutable plain-data picture of the world at one instant: what crosses from the haptic
// thread to the render thread and the recorders. No Bullet types, no pointers into the World.
// Every position and direction in a Snapshot is in the world frame.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim/math.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/patch/patch_settings.hpp"

namespace gf::sim {

/// The force one point of a contact puts on the touched body in a step (N, world frame): the
/// solver's result, split over the contact's points. A contact's points' loads add up to its
/// `force` (ContactSnapshot).
struct PointLoad {
  double normal = 0.0;             ///< pressing force along -outward_normal (N, >= 0)
  Vec3 tangential = Vec3::Zero();  ///< friction on the body at the point, in the tangent plane (N)
  bool slipping = false;           ///< the body's surface slides under the point, friction at its limit
};

/// One contact of one finger with one body, with its patch, in the world frame.
struct ContactSnapshot {
  int body = -1;                             ///< index into SceneDesc::bodies
  Vec3 point_world = Vec3::Zero();           ///< c_p: the true contact point on the body (m)
  Vec3 outward_normal_world = Vec3::UnitY(); ///< from the body towards the proxy (unit)
  double separation = 0.0;                   ///< c_d: signed, negative when penetrating (m)
  double press_depth = 0.0;                  ///< v . c_n of Eq. 1 (m): > 0 while pressing
  double radius = 0.0;                       ///< r of Eq. 1 (m); 0 without a patch
  Feature feature = Feature::kFace;          ///< where c_p lies on the walk mesh
  std::vector<Vec3> sgos_world;              ///< SGO positions (m), then a filled patch's inner points
  std::vector<Vec3> path_points_world;       ///< walked paths, concatenated (m)
  std::vector<std::int32_t> path_offsets;    ///< SGO k's path: [offsets[k], offsets[k+1])
  /// The contact's force on the body this step (N): the solver's normal and friction forces,
  /// what `point_load` and `loads` add up to. Zero when the solver did not see the contact.
  Vec3 force = Vec3::Zero();
  PointLoad point_load;          ///< the true contact point's share (at point_world)
  /// The contact point is one of the solver's points (point_load is its share); false where the
  /// loads are elsewhere alone (a god-finger's pressed nodes on a soft body).
  bool point_loaded = true;
  std::vector<PointLoad> loads;  ///< one per sgos_world; empty when the solver did not see them
  /// The moment of the patch's rolling rows on the body (N m): what keeps the body from rolling
  /// under the pad beyond what the points' loads do (god-finger patches; zero otherwise). With
  /// it, the points' loads make the contact's whole force and moment.
  Vec3 rolling_moment = Vec3::Zero();
  /// The moment about the normal the points' loads do not carry (N m, along the outward
  /// normal): a soft finger's torsion, which its one point cannot hold; zero where the points'
  /// loads share the torsion out (a god-finger patch).
  Vec3 torsion_moment = Vec3::Zero();
  bool sliding = false;          ///< the contact's friction is at its limit (it slides or spins)
  /// On a soft body: how far the surface at the contact point sank from where the body's rest
  /// shape, carried by its frame, puts it (m); 0 on a rigid body.
  double indentation = 0.0;
};

/// A fem_pad finger's soft pad as it is (empty for the other models).
struct PadSnapshot {
  std::vector<Vec3> nodes;  ///< every node of its tetrahedra (world, m)
  /// Its outer surface (skin and sides, wound outward), indices into `nodes`; shared, immutable.
  std::shared_ptr<const std::vector<std::array<int, 3>>> skin;
  double bone_radius = 0.0;  ///< the bone, a sphere about the proxy centre (m)
  long resets = 0;           ///< times it was put back at rest (turned inside out) so far
};

/// A soft body's shape now (SceneDesc's soft_* bodies).
struct SoftBodySnapshot {
  int body = -1;            ///< index into SceneDesc::bodies
  std::vector<Vec3> nodes;  ///< its tetrahedra's nodes (world, m)
  /// Its surface (wound outward), indices into `nodes`; shared, immutable.
  std::shared_ptr<const std::vector<std::array<int, 3>>> surface;
  long resets = 0;          ///< steps undone so far (turned inside out)
};

/// One finger.
struct FingerSnapshot {
  Vec3 device = Vec3::Zero();          ///< device position (m)
  /// The device's orientation (device frame to world; identity unless its track or transport
  /// gives one): what an oriented pad (PatchSettings::pad_axis) turns with.
  Quat device_orientation = Quat::Identity();
  Vec3 proxy = Vec3::Zero();           ///< proxy centre, the god-object (m)
  Vec3 coupling_force = Vec3::Zero();  ///< force of the coupling on the proxy (N)
  Vec3 feedback_force = Vec3::Zero();  ///< force rendered to the device: -coupling (N)
  int sgo_count = 0;                   ///< SGOs injected this step, over all contacts
  PatchSettings patch;                 ///< the finger's god-finger settings as given (live ones may change)
  /// Its contacts: with fem_pad, the bone's own (through the pad) and then one per body the
  /// pad presses, whose points are the pressed skin nodes with their loads.
  std::vector<ContactSnapshot> contacts;
  PadSnapshot pad;
};

/// Haptic-loop timings as of a snapshot (wall-clock; all zero in offline replays).
struct HapticTimings {
  double step_median_us = 0.0;  ///< over the last second of steps
  double step_p99_us = 0.0;
  long late_steps = 0;          ///< realtime steps started > 0.5 ms past their deadline, so far
};

/// The world at simulated time `time`.
struct Snapshot {
  double time = 0.0;  ///< s
  long step = 0;
  long nan_recoveries = 0;            ///< steps so far whose result was not finite and was rolled back
  std::vector<Pose> bodies;           ///< each body's description frame
  /// Each body's linear (m/s) and angular (rad/s) velocity, in the world frame.
  std::vector<std::pair<Vec3, Vec3>> body_velocities;
  std::vector<FingerSnapshot> fingers;
  std::vector<SoftBodySnapshot> soft_bodies;  ///< one per soft body, in body order
  HapticTimings timings;
  /// The browser view's numbered moves (app/serve, realtime): the newest that, with every
  /// earlier one, this state has taken, and the newest that, with every earlier one, its
  /// device has reached (0: none, and offline).
  long moves_taken = 0, moves_arrived = 0;
};

/// The world at `time` between snapshots a (earlier) and b (later) of the same world: body
/// poses, proxies, devices' poses and forces interpolated (slerp for orientations); contacts
/// and patches taken from b and carried along with their body's interpolated pose. `out`
/// reuses its storage. Any thread.
void interpolateSnapshot(const Snapshot& a, const Snapshot& b, double time, Snapshot& out);

}  // namespace gf::sim
