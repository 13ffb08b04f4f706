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

#include "sim/detail/body_factory.hpp"
#include "sim/detail/contact_models.hpp"
#include "sim/world.hpp"

namespace gf::sim {

/// A finger handles at most this many touched bodies per step; further ones stay god-objects.
inline constexpr int kMaxContactsPerFinger = 4;
/// Collision group of proxies: they touch bodies, never each other.
inline constexpr int kFingerGroup = 1 << 6;
/// Bullet user index marking a proxy (bodies carry their index, >= 0).
inline constexpr int kProxyTag = -1;

struct World::Impl final : SolveHooks {
  struct Body {
    BodyShapes shapes;
    std::unique_ptr<btRigidBody> rigid;
  };
  struct Finger {
    std::unique_ptr<btSphereShape> shape;
    std::unique_ptr<btRigidBody> proxy;
    EffectiveSettings settings;          // after the scene's effect switches (applySettings)
    const FingerModel* model = nullptr;  // the model of settings.patch.model
    DeviceSample device;
    Vec3 force = Vec3::Zero();  // coupling force on the proxy (N)
    std::array<FingerContact, kMaxContactsPerFinger> contacts;
    int contact_count = 0;
    std::array<ContactMemory, kMaxContactsPerFinger> memory;
    int memory_count = 0;

    const ContactMemory* memoryOf(int body) const {
      for (int k = 0; k < memory_count; ++k) {
        if (memory[k].body == body) return &memory[k];
      }
      return nullptr;
    }
  };
  // Last finite state of a rigid body, for rolling back a step that produced NaN.
  struct SavedState {
    btTransform transform;
    btVector3 linear, angular;
  };

  // The Bullet world (world_bullet.cpp).
  explicit Impl(const SceneDesc& d);
  ~Impl() override;
  void configureSolver();
  void addBody(int index, const BodyDesc& d);
  void addFinger(int index, const FingerDesc& d);
  void applySettings(Finger& f, const PatchSettings& patch) const;
  void applyChangesDue(double dt);
  void applyCouplings(std::span<const DeviceSample> devices);
  void applyLoads();
  void countStep(double dt);
  Pose bodyFrame(int body) const;
  std::vector<btRigidBody*> allRigidBodies() const;
  bool ownedHere() const { return std::this_thread::get_id() == owner; }

  // The contact pipeline (world_contacts.cpp).
  void beforeSolve() override;
  void afterSolve() override;
  void gatherProxyManifold(btPersistentManifold& m, const btCollisionObject* proxy);
  void handleContact(Finger& f, FingerContact& c);
  void recordContact(const Finger& f, const ContactMemory* mem, FingerContact& c) const;
  void computeContactPatch(const Finger& f, FingerContact& c, const ContactMemory* mem);
  void placePatchPoints(FingerContact& c, const ContactMemory* mem);
  void rememberImpulses(Finger& f);

  // Step safety (world_safety.cpp).
  void saveStates();
  void checkStep();
  bool statesFinite() const;
  void restoreStates();
  void stopTunnelling();

  SceneDesc desc;
  std::thread::id owner = std::this_thread::get_id();
  // Bullet's parts, each declared after what it points to: the world is destroyed first, and
  // ~Impl removes every body from it before that.
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  PatchFrictionSolver solver;
  GodFingerDynamicsWorld world{&dispatcher, &broadphase, &solver, &config, this};
  std::vector<Body> bodies;
  std::vector<Finger> fingers;
  std::vector<btPersistentManifold*> injected;
  AggregateScratch aggregate_scratch;
  SolveRows rows{solver, dispatcher, injected, aggregate_scratch};  // where the models add rows
  std::vector<SavedState> saved;
  double time = 0.0;
  // Time is counted in steps of one dt from the last change of dt, so k steps of 1 ms read
  // exactly k / 1000 s instead of a running sum's rounding.
  double time_base = 0.0, steps_dt = 0.0;
  long steps_since_base = 0;
  std::size_t next_change = 0;  // desc.changes[next_change] is the first not yet applied
  WorldCounters counters;
};

}  // namespace gf::sim
