// World's private state, and its jobs each in a source of its own: world_bullet.cpp (the Bullet
// world: construction, bodies, proxies, a finger's settings, couplings, loads and time),
// world_contacts.cpp (the contact pipeline between collision detection and the solve: proxy
// manifolds gathered, contact records, patches, each contact's rows by its finger's model,
// impulses remembered) and world_safety.cpp (a step that is not finite rolled back, tunnelling
// proxies stopped); world.cpp keeps the public API. Haptic thread only. Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <array>
#include <memory>
#include <span>
#include <thread>
#include <vector>

#include "sim/world/body_factory.hpp"
#include "sim/contact/contact_models.hpp"
#include "sim/contact/contact_algorithms.hpp"
#include "sim/world/world.hpp"
#include "sim/soft/fem_pad.hpp"
#include "sim/soft/soft_body.hpp"
#include "sim/patch/god_finger.hpp"

namespace gf::sim {

/// A resumed device's offset (World::Impl::washOutResume) shrinks by at least this speed (m/s),
/// or by its size over kResumeWashTime (s) when faster, and is zero below kResumeWashDone (m).
inline constexpr double kResumeWashSpeed = 0.02;
inline constexpr double kResumeWashTime = 0.5;
inline constexpr double kResumeWashDone = 1e-9;

/// A finger's proxy touches a soft body this close to its surface (m): its presses whose points
/// are not inside its pad do nothing.
inline constexpr double kSoftTouchMargin = 5e-4;
/// A god-finger's pad on a soft body gathers the faces of at most this many points.
inline constexpr std::size_t kMaxPadFaces = 4096;

/// A finger handles at most this many touched bodies per step; further ones stay god-objects.
inline constexpr int kMaxContactsPerFinger = 4;
/// Bullet's pools sized for `scene` when all its bodies are primitives or convex hulls: manifolds
/// for every contact its fingers can inject in a step and two for every pair of its bodies and
/// proxies (at least 64), four algorithms per pair (at least 256), neither above Bullet's default. Bullet's default, 4096 of each, wrote 7.2 MB
/// per World when it was made, and stays for scenes with convex parts, triangle meshes or soft
/// bodies (each part touching opens its own). Past these sizes Bullet takes from the heap.
btDefaultCollisionConstructionInfo collisionPools(const SceneDesc& scene);

/// Collision group of proxies: they touch bodies, never each other.
inline constexpr int kFingerGroup = 1 << 6;
/// Bullet user index marking a proxy (bodies carry their index, >= 0).
inline constexpr int kProxyTag = -1;

/// A fem_pad's contact with one body, its skin nodes' gathered (world).
struct PadTouch {
  int body = -1;
  int nodes = 0;                  ///< skin nodes pressed into it
  Vec3 force = Vec3::Zero();      ///< on the body (N)
  double load = 0.0;              ///< the force's part into the body (N, >= 0)
  Vec3 point = Vec3::Zero();      ///< the nodes' centre, weighted by their loads (by count without load)
  Vec3 normal = Vec3::UnitY();    ///< outward, the nodes' normals weighted likewise (unit)
  double depth = 0.0;             ///< the deepest node's (m)
  Vec3 deepest_point = Vec3::Zero();    ///< on the surface above the deepest node (world)
  Vec3 deepest_normal = Vec3::UnitY();  ///< the surface's outward normal there
  double area = 0.0;              ///< the pressed nodes' skin (m²)
  bool sliding = false;           ///< every pressed node slips
};

/// A finger's touch of a soft body in one step (world_soft.cpp).
struct SoftTouch {
  int body = -1;
  Vec3 point = Vec3::Zero();      ///< the closest point of the surface to the proxy's centre
  Vec3 normal = Vec3::UnitY();    ///< outward, from the body towards the proxy (unit)
  double separation = 0.0;        ///< negative: how deep the proxy's sphere reaches in (m)
  double press_depth = 0.0;       ///< v . c_n of Eq. 1 (m)
  double radius = 0.0;            ///< Eq. 1's (m); 0 for a god-object
  double indentation = 0.0;       ///< how far the surface at `point` sank from its rest (m)
  Feature feature = Feature::kFace;
  int face = -1;                  ///< the surface's face at `point`
  Vec3 weights = Vec3(1.0, 0.0, 0.0);  ///< `point`'s barycentric coordinates in it
  bool centre_press = false;      ///< a god-object's: its one press is the contact point's
  Patch patch;                    ///< the god-finger's patch on the surface this step
  Vec3 ring_tangent = Vec3::Zero();  ///< the last patch's, so the ring does not turn
  int first_press = 0, press_count = 0;  ///< its presses in the body's step
  std::vector<int> last_nodes;    ///< the nodes its pad pressed (the last step's, until this one's are chosen)
  std::vector<Vec3> sgos;         ///< the pressed points at the step's end (a god-object's: its one)
  std::vector<PointLoad> loads;   ///< their loads on the body
  Vec3 force = Vec3::Zero();      ///< on the body (N)
  bool sliding = false;
};

struct World::Impl final : SolveHooks {
  struct Body {
    BodyShapes shapes;
    std::unique_ptr<btRigidBody> rigid;  // a soft body's collides with nothing
    std::unique_ptr<SoftBody> soft;      // soft shapes only
    Vec3 soft_origin = Vec3::Zero();     // the soft body's centre of mass at rest (world)
  };
  struct Finger {
    std::unique_ptr<btSphereShape> shape;
    std::unique_ptr<btRigidBody> proxy;
    EffectiveSettings settings;          // after the scene's effect switches (applySettings)
    PatchSettings given;                 // as given (applySettings), for snapshots
    const FingerModel* model = nullptr;  // the model of settings.patch.model
    DeviceSample device;
    Vec3 force = Vec3::Zero();  // coupling force on the proxy (N)
    Vec3 sent = Vec3::Zero();   // force the device is to render (N): -force, rate-limited
    Vec3 told = Vec3::Zero();   // force the device was told after the last step (setToldForce)
    // The device held where it was at a resume, less the hand's position (m): washed out to zero
    // no faster than the port's energy pays for (applyCouplings).
    Vec3 resume_offset = Vec3::Zero();
    double resume_spent = 0.0;  // J the washouts put into the coupling (washOutResume)
    Vec3 overlap_push = Vec3::Zero();  // push_apart's force on the proxy from the last step's overlaps (N)
    PortObserver port;          // the energy that came in through the device port
    std::array<FingerContact, kMaxContactsPerFinger> contacts;
    int contact_count = 0;
    std::array<ContactMemory, kMaxContactsPerFinger> memory;
    int memory_count = 0;
    // memory[k]'s walks (warm_walk.hpp), swapped with its contact's during a step.
    std::array<WalkCache, kMaxContactsPerFinger> memory_walks;
    // fem_pad's soft pad on the proxy (its bone), null for every other model (world_pad.cpp).
    std::unique_ptr<FemPad> pad;
    // Its touches of soft bodies this step (world_soft.cpp).
    std::array<SoftTouch, kMaxContactsPerFinger> soft;
    int soft_count = 0;

    const ContactMemory* memoryOf(int body) const {
      for (int k = 0; k < memory_count; ++k) {
        if (memory[k].body == body) return &memory[k];
      }
      return nullptr;
    }
  };
  // Two fingers' patches on one body (world_overlap.cpp): fingers a < b, summed over bodies.
  struct OverlapPair {
    int a = -1, b = -1;
    double area = 0.0;      // m^2 this step
    double peak = 0.0;      // m^2 so far
    double integral = 0.0;  // m^2 s so far
  };
  // Last finite state of a rigid body, for rolling back a step that produced NaN.
  struct SavedState {
    btTransform transform;
    btVector3 linear, angular;
  };

  // The Bullet world (world_bullet.cpp). Construction allocates; the rest does not.
  /// Checks the description (requireValid), builds bodies, proxies and the solver's settings.
  explicit Impl(const SceneDesc& d);
  /// Removes every body from the Bullet world before Bullet's parts are destroyed.
  ~Impl() override;
  void configureSolver();  ///< iterations, warm starting and the randomized row order
  void addBody(int index, const BodyDesc& d);
  void addFinger(int index, const FingerDesc& d);
  /// The finger's settings from now on: effectiveSettings and its model, once per change.
  void applySettings(Finger& f, const PatchSettings& patch) const;
  void applyChangesDue(double dt);  ///< scripted changes due at this step's start
  void applyCouplings(std::span<const DeviceSample> devices, double dt);  ///< device samples, coupling forces
  void washOutResume(Finger& f, double dt);
  void applyLoads();                ///< the scene's loads at time (N, N m)
  void slewSentForces(double dt);   ///< the forces sent after the step (max_force_rate)
  void countStep(double dt);        ///< time after a step of dt seconds, and the step counter
  Pose bodyFrame(int body) const;   ///< body i's frame: that of its walk mesh (world)
  std::vector<btRigidBody*> allRigidBodies() const;  ///< bodies, then proxies (allocates)
  bool ownedHere() const { return std::this_thread::get_id() == owner; }

  // The contact pipeline (world_contacts.cpp): between collision detection and the solve.
  void beforeSolve() override;  ///< gathers each proxy's contacts, adds their rows
  void afterSolve() override;   ///< remembers the impulses, releases injected manifolds
  /// Keeps the deepest point of a proxy's manifold as its finger's contact with that body.
  void gatherProxyManifold(btPersistentManifold& m, const btCollisionObject* proxy);
  /// Every walk cache of f sized for n_sgo radial vectors (allocates when they grow).
  static void sizeWalks(Finger& f, int n_sgo);
  /// One contact: its record and its patch if the finger's model wants one (rows: beforeSolve).
  void handleContact(Finger& f, FingerContact& c);
  void recordContact(const Finger& f, const ContactMemory* mem, FingerContact& c) const;
  void computeContactPatch(const Finger& f, FingerContact& c, const ContactMemory* mem);
  void placePatchPoints(FingerContact& c, const ContactMemory* mem);  ///< world points, depths
  void checkWalks(const Mesh& mesh, const Finger& f, FingerContact& c);  ///< checkWarmWalks
  void rememberImpulses(Finger& f);  ///< each contact's ContactMemory for the next step

  // Overlapping patches (world_overlap.cpp), between the patches and the rows of a step.
  void makeOverlapPairs();  ///< one OverlapPair per two fingers (construction; allocates)
  /// Each pair's overlap this step; push_apart's forces for the next step; merge's shares.
  void handleOverlaps();
  /// merge: coinciding points of a's and b's patches share one point's load, split by `share_a`.
  void mergeCoinciding(FingerContact& a, FingerContact& b, double share_a) const;

  // The fem_pad fingers' pads (world_pad.cpp): stepped before Bullet's step, their contacts'
  // forces put on the bodies for it, the bones' velocities given to the proxies.
  class PadBodies;
  void addPad(Finger& f, const FingerDesc& d);
  void stepPads(double dt);
  /// Pad `f`'s contacts as snapshots (one per touched body) after `out`'s own, and its shape.
  void padSnapshot(const Finger& f, FingerSnapshot& out) const;
  /// Pad `f`'s last step's contacts gathered by body, the first kMaxContactsPerFinger bodies
  /// touched, into `out`; returns how many. Does not allocate.
  int padTouches(const Finger& f, std::array<PadTouch, kMaxContactsPerFinger>& out) const;

  // Soft bodies (world_soft.cpp): stepped before Bullet's step, after the pads.
  void addSoftBody(int index, const BodyDesc& d);
  Pose softPose(int body) const;  ///< the description frame of soft body `body` now
  void touchSoft(Finger& f, int fi, int body);
  void padNodes(const SoftTouch& t, const SoftBody& s, double walk_fill);
  void stepSoftBodies(double dt);
  void readSoftStep(int body, SoftBody& s, double dt);
  void softSnapshot(const Finger& f, FingerSnapshot& out) const;
  void softBodySnapshot(Snapshot& out) const;
  std::vector<int> soft_bodies;  // the soft bodies' indices
  std::vector<SoftPress> soft_presses;
  std::vector<SoftFinger> soft_fingers;
  std::vector<char> soft_given;
  std::vector<int> soft_faces, soft_nodes;                  // padNodes' scratch
  std::vector<std::pair<double, double>> soft_outline;      // padNodes' scratch: (angle, reach) per SGO

  // Step safety (world_safety.cpp).
  void saveStates();   ///< every body's and proxy's state before the step
  void checkStep();    ///< rolls a step that is not finite back, else stops tunnelling proxies
  bool statesFinite() const;
  void restoreStates();  ///< the saved states, at rest
  void stopTunnelling();  ///< puts a proxy whose step's path entered a body back on its surface

  SceneDesc desc;
  std::thread::id owner = std::this_thread::get_id();
  // Bullet's parts, each declared after what it points to: the world is destroyed first, and
  // ~Impl removes every body from it before that.
  btDefaultCollisionConfiguration config{collisionPools(desc)};
  ContactAlgorithms contact_algorithms;  // our collision tests (registered in the constructor)
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  PatchFrictionSolver solver;
  GodFingerDynamicsWorld world{&dispatcher, &broadphase, &solver, &config, this};
  std::vector<Body> bodies;
  std::vector<Finger> fingers;
  std::vector<OverlapPair> overlaps;
  std::vector<btPersistentManifold*> injected;
  AggregateScratch aggregate_scratch;
  // World::snapshot's storage for splitting each contact's loads over its points (solvedLoads).
  mutable AggregateScratch snapshot_scratch;
  mutable ContactLoads snapshot_loads;
  SolveRows rows{solver, dispatcher, injected, aggregate_scratch};  // where the models add rows
  std::vector<SavedState> saved;
  double time = 0.0;
  // Time is counted in steps of one dt from the last change of dt, so k steps of 1 ms read
  // exactly k / 1000 s instead of a running sum's rounding.
  double time_base = 0.0, steps_dt = 0.0;
  long steps_since_base = 0;
  std::size_t next_change = 0;  // desc.changes[next_change] is the first not yet applied
  WorldCounters counters;
  bool check_walks = false;  // checkWarmWalks: each patch computed from scratch too, into check_patch
  Patch check_patch;
};

}  // namespace gf::sim
