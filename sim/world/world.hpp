// The Bullet world with god-finger contacts: bodies, proxies, couplings and SGO injection.
// One thread owns a World: the thread that builds it (the haptic thread). Every call below but
// desc() must come from that thread; debug and sanitizer builds assert it. Other threads read
// Snapshots.
#pragma once

#include <memory>
#include <span>

#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::sim {

/// One contact of a finger, in the world frame.
struct Touch {
  int body = -1;
  Vec3 point = Vec3::Zero();   ///< on the body's surface (m)
  Vec3 normal = Vec3::UnitY(); ///< unit, from the body towards the proxy
  double separation = 0.0;     ///< signed, negative when penetrating (m)
};

/// Two fingers' patch overlap (World::overlap).
struct OverlapStats {
  int finger_a = -1, finger_b = -1;  ///< finger indices, a < b
  double area = 0.0;                 ///< m^2 in the last step
  double peak = 0.0;                 ///< m^2: the largest area so far
  double integral = 0.0;             ///< m^2 s: the area integrated over time so far
};

/// Counters of numerical trouble and work done.
struct WorldCounters {
  long steps = 0;
  long nan_recoveries = 0;   ///< steps whose result was not finite and was rolled back
  long invalid_patches = 0;  ///< contacts whose patch input was rejected (no SGO that step)
  long sgos_injected = 0;    ///< sum over steps of SGOs fed to the solver
  long crossing_limit_stops = 0;  ///< SGOs whose walk used up its edge-crossing budget (stopped short)
  long tunnelling_stops = 0;      ///< proxies stopped where their step's path entered a body
  long pad_resets = 0;            ///< fem_pad pads put back at rest (turned inside out or not finite)
  long soft_resets = 0;           ///< soft bodies' steps undone (turned inside out or not finite)
  long patch_calls = 0;           ///< patches computed (one per god-finger contact per step)
  double patch_seconds = 0.0;     ///< wall time spent computing them (steady clock)
  long warm_walks = 0;            ///< radial walks carried from the last step's path
  long cold_walks = 0;            ///< radial walks done from the contact point
  long slack_walks = 0;           ///< carried walks within their slack (crossings unchecked)
  /// With checkWarmWalks on: patches also computed from scratch, and the largest distance (m)
  /// between a point (SGO, filled inner point or path point) of the two, or +inf where their
  /// counts differ.
  long walk_checks = 0;
  double walk_check_error = 0.0;
};

class World {
 public:
  /// Builds bodies, proxies and effects from the description; the calling thread owns the
  /// World. Throws DescriptionError (settings.hpp: body, finger or load, field, reason) for a
  /// description that cannot be built. Allocates.
  explicit World(const SceneDesc& desc);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// One haptic step of `dt` seconds (no substeps) with each finger's device sample, in finger
  /// order; the scene's loads act over the step at their value at time() before it. Does not
  /// allocate in steady state.
  void step(double dt, std::span<const DeviceSample> devices);

  /// Simulated time (s).
  double time() const;
  /// The description it was built from (immutable: any thread).
  const SceneDesc& desc() const;
  const WorldCounters& counters() const;

  /// Fills `out` (reusing its storage) with the current state: bodies, fingers, and each
  /// contact's record of the last step at its body's current pose.
  void snapshot(Snapshot& out) const;

  /// Pose of body i's description frame; linear (m/s) and angular (rad/s) velocity.
  Pose bodyPose(int body) const;
  Vec3 bodyLinearVelocity(int body) const;
  Vec3 bodyAngularVelocity(int body) const;
  /// Principal moments of inertia of a dynamic body in its own frame (kg m^2), as Bullet
  /// computed them from its shape and mass; zero for a static body.
  Vec3 bodyInertia(int body) const;
  /// Proxy centre and coupling force (N) of finger i.
  Vec3 proxyPosition(int finger) const;
  /// The finger's device position of the last step (m).
  Vec3 devicePosition(int finger) const;
  /// The finger's device orientation of the last step (identity for a 3-DOF device).
  Quat deviceOrientation(int finger) const;
  Vec3 couplingForce(int finger) const;
  /// The force the finger's device is to render (N): the opposite of the coupling force (zero
  /// when the scene turns force feedback off), followed at most max_force_rate fast, so that it
  /// never jumps whatever the device's position or the contact does.
  Vec3 feedbackForce(int finger) const;
  /// The force the finger's device was told to render after the last step (N, scene frame):
  /// feedbackForce unless its device source said otherwise (setToldForce: a live device's link
  /// fades it while the device is stale or was taken over).
  Vec3 toldForce(int finger) const;
  /// What the finger's device source told its device after the step (haptic thread, after
  /// step()): the force it renders until the next step, which the port observer prices the
  /// device's next move with. Non-finite forces are ignored.
  void setToldForce(int finger, const Vec3& force);
  /// The passivity observer of the finger's device port (Hannaford and Ryu 2002): the work the
  /// hand has done on the device against the force it was told, the sum over steps of
  /// -toldForce . (device displacement) (J), leaving out the steps where the device jumped
  /// (PortObserver). A passive simulation never lets it fall below zero: it returns no more
  /// energy than it was given.
  double portEnergy(int finger) const;
  /// The same observer with its lowest value and the device's jumps, whose work it leaves out.
  const PortObserver& portObserver(int finger) const;
  /// Finger i's proxy touched a body in the last step.
  bool touching(int finger) const;
  /// SGOs finger i fed to the solver in the last step, over all its contacts.
  int sgoCount(int finger) const;
  /// Mean Eq. 1 radius of the finger's patches this step (m); 0 without a patch.
  double contactRadius(int finger) const;
  /// Two fingers' patches on one body (docs/overlap.md), one pair per two fingers a < b in
  /// finger order (pair index: a's pairs with every later finger, then b's, ...).
  int overlapPairCount() const;
  /// Pair `pair`'s overlap: this step's area (summed over the bodies both touch), its peak and
  /// its integral over time so far.
  OverlapStats overlap(int pair) const;
  /// push_apart's force on the finger's proxy this step (N); zero with the other modes.
  Vec3 overlapForce(int finger) const;
  /// Kinetic plus gravitational potential energy of the dynamic bodies and proxies (J).
  double mechanicalEnergy() const;
  /// Finger i's deepest contact of the last step, at its body's pose now (world frame): false
  /// when the proxy touched no body. `out.point` is on the body's surface, `out.normal` points
  /// from the body to the proxy, `out.separation` is negative while the proxy penetrates (m).
  bool deepestTouch(int finger, Touch& out) const;

  /// Applies an angular impulse (N m s, world frame) to body i now (a rigid one: a soft body
  /// takes none).
  void applyTorqueImpulse(int body, const Vec3& impulse);
  /// Sets the god-finger settings of finger i from the next step on (n_sgo 0: god-object).
  /// Throws DescriptionError naming the finger and the first setting that is not legal.
  /// Allocates when n_sgo grows past what the finger was sized for (sizeForLiveSettings).
  void setPatchSettings(int finger, const PatchSettings& settings);
  /// Sizes every finger's stores for the largest patch a live setting may ask for (kMaxSgo
  /// radial vectors), so that setPatchSettings on a realtime haptic thread allocates nothing. A
  /// World is otherwise sized for the n_SGO its scene and scripted changes use.
  void sizeForLiveSettings();
  /// Test hook: from the next step on, every patch is also computed from scratch (no warm-
  /// started walk) and compared with the one used (counters().walk_checks, walk_check_error).
  /// Owner thread; does not allocate per step.
  void checkWarmWalks(bool on);

  /// Two bodies whose shapes overlap: `depth` metres into each other (> 0).
  struct Overlap {
    int body_a = -1, body_b = -1;
    double depth = 0.0;
  };
  /// The pairs of bodies (static ones included, proxies not; two static bodies never) whose
  /// shapes overlap now by more than `tolerance` metres, each with its deepest point: a check
  /// for scenes that start with bodies inside each other. Runs the collision tests of those
  /// pairs on their own, leaving the world's contact state as it was. Allocates.
  std::vector<Overlap> bodyOverlaps(double tolerance) const;
  /// A finger's proxy inside a body: `depth` metres into it (> 0).
  struct ProxyOverlap {
    int finger = -1, body = -1;
    double depth = 0.0;
  };
  /// The proxies that overlap a body now by more than `tolerance` metres (a scene whose device
  /// starts inside a body: the contact throws the body out at once). Allocates.
  std::vector<ProxyOverlap> proxyOverlaps(double tolerance) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::sim
