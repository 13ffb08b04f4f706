// Read-only description of a session: bodies, fingers, effects and world settings. A World is
// built from it; a run can be rebuilt or replayed from the same description.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sim/scene/coupling.hpp"
#include "sim/scene/device.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/patch/patch_settings.hpp"
#include "sim/mesh/tet_pad.hpp"
#include "sim/soft/fem_pad.hpp"

namespace gf::sim {

/// Effects a scene asks for. What is off is neither built nor run.
struct EffectSet {
  bool gravity = true;             ///< world gravity on dynamic bodies
  bool friction = true;            ///< friction on every contact (off: frictionless world)
  bool god_finger = true;          ///< SGOs around each finger contact (off: god-objects)
  bool tangential_stretch = true;  ///< Eq. 2 stretch of the patch
  bool angular_threshold = true;   ///< walk stops at faces beyond tau_a
  bool friction_cone = true;       ///< walk stops at faces outside the friction cone
  bool force_feedback = true;      ///< feedback force to the device is computed and recorded
};

/// Shape of a body. Physics collides with the exact primitive; the walk uses a tessellation.
/// Meshes collide as their convex hull, as convex parts (HACD decomposition, as in the paper's
/// Havok implementation), or as the exact triangles (GImpact when dynamic).
enum class ShapeKind {
  kSphere,
  kBox,
  kCylinder,
  kCapsule,
  kPlane,
  kConvexHull,
  kConvexDecomposition,
  kConcaveMesh,
  kSoftBox,       ///< soft bodies (SoftDesc): generated tetrahedra of a box, a sphere, a cylinder
  kSoftSphere,
  kSoftCylinder,
  kSoftMesh       ///< tetrahedra from a file (TetGen .node/.ele or legacy VTK)
};

/// True for the soft (finite-element) shapes.
inline bool isSoftShape(ShapeKind kind) { return kind >= ShapeKind::kSoftBox; }

/// A box of a soft body's nodes held fixed (in the body's frame, m).
struct PinRegion {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

/// A soft body's material, resolution and fixed nodes (shape soft_*): a deformable body of
/// linear tetrahedra (sim/soft/soft_body.hpp). Its density is its mass over its mesh's volume.
struct SoftDesc {
  double young = 1e5;               ///< Pa: Young's modulus
  double poisson = 0.45;            ///< Poisson's ratio
  double damping = 0.002;           ///< s: Rayleigh stiffness-proportional damping
  double element_size = 0.005;      ///< m: the generated shapes' cells
  double contact_stiffness = 1e5;   ///< N/m: each contact's normal and friction springs
  std::vector<PinRegion> pinned;    ///< nodes inside any of them are held where they start
  std::string tet_path;             ///< soft_mesh: the .node (its .ele beside it) or .vtk file
  /// The mesh's tetrahedra at rest in the body's frame (centred where `position` puts them):
  /// generated or loaded once by the scene reader; null: built where needed (softMesh()).
  std::shared_ptr<const TetMesh> tets;
};

/// One rigid body.
struct BodyDesc {
  std::string name;
  ShapeKind shape = ShapeKind::kBox;
  Vec3 half_extents = Vec3::Constant(0.05);  ///< box half extents (m)
  double radius = 0.05;                      ///< sphere, cylinder, capsule radius (m)
  double half_height = 0.05;                 ///< cylinder / capsule half height along y (m)
  std::string mesh_path;                     ///< hull and concave meshes: file to load
  double mesh_scale = 1.0;                   ///< factor from mesh file units to metres
  /// The file's mesh, welded, times mesh_scale, in the file's frame: loaded once (MeshCache)
  /// and shared by the World and the renderer. Null: loaded from mesh_path where needed.
  std::shared_ptr<const Mesh> mesh;
  int walk_resolution = 0;                   ///< tessellation of the walk mesh; 0: per shape default
  double mass = 0.1;                         ///< kg; 0 makes the body static
  double friction = 0.8;                     ///< Coulomb coefficient against other bodies
  double restitution = 0.0;                  ///< coefficient of restitution
  Vec3 position = Vec3::Zero();              ///< initial position of the centre of mass (m)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vec3 colour = Vec3(0.7, 0.7, 0.7);         ///< linear RGB in 0..1, for rendering
  SoftDesc soft;                             ///< soft shapes only
};

/// The shape of the pad a finger presses soft bodies with (`imprint`): a flat disc across the
/// contact normal at the proxy's lowest point, or the proxy's sphere.
enum class SoftImprint : std::uint8_t { kFlat, kRound };

/// One finger: a god-object proxy coupled to a device, with god-finger settings.
struct FingerDesc {
  std::string name;
  PatchSettings patch;      ///< god-finger settings; patch.n_sgo = 0 is the classic god-object
  CouplingSettings coupling;
  ProxySettings proxy;
  PadSettings pad;          ///< the soft pad of contact_model fem_pad (its skin: the proxy's sphere)
  SoftImprint soft_imprint = SoftImprint::kFlat;  ///< how it presses soft bodies
  /// m; 0: off. On soft bodies, faces reached by points every this far along each walk join the
  /// pad (the paper's SGOs added along the walks, Sec. 4.4).
  double soft_walk_fill = 0.0;
  DeviceTrack device;       ///< where the device is at each time
};

/// A known external load on one dynamic body: a force through its centre of mass and a torque,
/// both fixed in the world frame, switched on at `start`, grown linearly over `ramp` and held
/// until `stop`. Applied with every effect set (it is part of the scene, not an effect).
struct LoadDesc {
  int body = -1;               ///< index into SceneDesc::bodies; the body must be dynamic
  std::string body_name;       ///< the body's name as the scene file gives it (for messages)
  Vec3 force = Vec3::Zero();   ///< N, world frame, through the centre of mass
  Vec3 torque = Vec3::Zero();  ///< N m, world frame
  double start = 0.0;          ///< s: zero before
  double ramp = 0.0;           ///< s: grows linearly from zero over this time; 0: a step
  double stop = std::numeric_limits<double>::infinity();  ///< s: zero at and after; +inf: never
};

/// Fraction of `load` acting at time `t` (s): 0 before start, (t - start) / ramp during the
/// ramp, 1 after it, 0 at and after stop. Pure; any thread; does not allocate.
double loadFactor(const LoadDesc& load, double t);

/// A scripted change of one finger's god-finger settings (the scene file's `[[changes]]`): the
/// World applies it at the first step that starts at or after `time` (to within half a step).
struct PatchChange {
  double time = 0.0;    ///< s, in [0, 1e6]; changes are in time order
  int finger = -1;      ///< index into SceneDesc::fingers
  PatchSettings patch;  ///< the finger's whole god-finger settings from then on (n_sgo 0: god-object)
};

/// What the World does where two fingers' patches on one body overlap (docs/overlap.md).
enum class OverlapMode : std::uint8_t {
  kIgnore,     ///< nothing: each patch on its own, as in the paper (overlap only measured)
  kPushApart,  ///< a force pushes the two proxies apart in the tangent plane (the paper's proposal)
  kMerge,      ///< coinciding points of the two patches carry one point's load, split by the presses
};

/// World-wide physics settings.
struct WorldSettings {
  Vec3 gravity = Vec3(0, -9.81, 0);  ///< m/s^2, y up
  int solver_iterations = 10;        ///< sequential-impulse iterations per step
  /// How god-finger contacts are solved unless a finger chooses (its `contact_solver`).
  ContactSolver contact_solver = ContactSolver::kPoints;
  double haptic_rate_hz = 1000.0;    ///< fixed step rate of the haptic loop
  double linear_damping = 0.0;       ///< Bullet body damping (1/s) on dynamic bodies
  double angular_damping = 0.0;
  OverlapMode overlap = OverlapMode::kIgnore;  ///< two fingers' patches overlapping on one body
  /// N/m: push_apart's force on each proxy per metre of the two patch discs' overlap depth.
  double overlap_stiffness = 2000.0;
};

/// A whole session description.
struct SceneDesc {
  std::string name;
  WorldSettings world;
  EffectSet effects;
  std::vector<BodyDesc> bodies;
  std::vector<FingerDesc> fingers;
  std::vector<LoadDesc> loads;  ///< known external loads, applied at every step
  std::vector<PatchChange> changes;  ///< scripted setting changes, in time order
  double duration = 5.0;  ///< simulated seconds
};

/// The mesh of a mesh-shaped body: `body.mesh`, or the file loaded now when that is null
/// (throws MeshLoadError). Load-time only.
std::shared_ptr<const Mesh> bodyMesh(const BodyDesc& body);

/// A soft body's tetrahedra in its own frame: `body.soft.tets`, or generated (or loaded) now
/// (throws std::invalid_argument or MeshLoadError). Load-time only.
std::shared_ptr<const TetMesh> softMesh(const BodyDesc& body);

/// Each finger's device track, in finger order: what runHapticLoop plays back.
inline std::vector<DeviceTrack> deviceTracks(const SceneDesc& scene) {
  std::vector<DeviceTrack> out;
  for (const FingerDesc& f : scene.fingers) out.push_back(f.device);
  return out;
}

}  // namespace gf::sim
