// The Bullet world with god-finger contacts: bodies, proxies, couplings and SGO injection.
// One thread owns a World: every call below must come from that thread (the haptic thread).
#pragma once

#include <memory>
#include <span>

#include "sim/scene_desc.hpp"
#include "sim/snapshot.hpp"

namespace gf::sim {

/// Counters of numerical trouble and work done.
struct WorldCounters {
  long steps = 0;
  long nan_recoveries = 0;   ///< steps whose result was not finite and was rolled back
  long invalid_patches = 0;  ///< contacts whose patch input was rejected (no SGO that step)
  long sgos_injected = 0;    ///< sum over steps of SGOs fed to the solver
};

class World {
 public:
  /// Builds bodies, proxies and effects from the description. Throws std::invalid_argument
  /// (naming body or finger and field) for a description that cannot be built. Allocates.
  explicit World(const SceneDesc& desc);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// One haptic step of `dt` seconds (no substeps) with each finger's device sample, in finger
  /// order. Does not allocate in steady state.
  void step(double dt, std::span<const DeviceSample> devices);

  /// Simulated time (s).
  double time() const;
  const SceneDesc& desc() const;
  const WorldCounters& counters() const;

  /// Fills `out` (reusing its storage) with the current state.
  void snapshot(Snapshot& out) const;

  /// Pose of body i's description frame; linear (m/s) and angular (rad/s) velocity.
  BodySnapshot bodyPose(int body) const;
  Vec3 bodyLinearVelocity(int body) const;
  Vec3 bodyAngularVelocity(int body) const;
  /// Proxy centre and coupling force (N) of finger i.
  Vec3 proxyPosition(int finger) const;
  Vec3 couplingForce(int finger) const;
  /// SGOs finger i fed to the solver in the last step, over all its contacts.
  int sgoCount(int finger) const;
  /// Kinetic plus gravitational potential energy of the dynamic bodies and proxies (J).
  double mechanicalEnergy() const;

  /// Applies an angular impulse (N m s, world frame) to body i now.
  void applyTorqueImpulse(int body, const Vec3& impulse);
  /// Sets the god-finger settings of finger i from the next step on (n_sgo 0: god-object).
  void setPatchSettings(int finger, const PatchSettings& settings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::sim
