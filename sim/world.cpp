#include "sim/world.hpp"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "sim/assert.hpp"
#include "sim/detail/body_factory.hpp"
#include "sim/detail/contact_injection.hpp"
#include "sim/detail/contact_models.hpp"
#include "sim/contact_record.hpp"
#include "sim/detail/patch_friction.hpp"
#include "sim/effective_settings.hpp"
#include "sim/settings.hpp"

namespace gf::sim {
namespace {

// A finger handles at most this many touched bodies per step; further ones stay god-objects.
constexpr int kMaxContactsPerFinger = 4;
// Collision group of proxies: they touch bodies, never each other.
constexpr int kFingerGroup = 1 << 6;
// Bullet user index marking a proxy (bodies carry their index, >= 0).
constexpr int kProxyTag = -1;
// A patch starts when the proxy touches (separation <= 0) and lasts while the separation stays
// below this (m): a few micrometres of gap in one step do not drop the contact area.
constexpr double kPatchReleaseGap = 1e-4;
// The pad plane keeps the orientation the finger met the body with (the proxy does not turn)
// while the contact normal stays within this angle of it (rad), and follows beyond: a tilt of
// the body loads one side of the pad, a finger moved around a curved body keeps its pad on it.
constexpr double kPadFollowAngle = 0.2617993877991494;  // 15 degrees

btTransform poseOf(const Vec3& p, const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond n = q.normalized();
  return btTransform(btQuaternion(n.x(), n.y(), n.z(), n.w()), toBt(p));
}

struct Body {
  BodyShapes shapes;
  std::unique_ptr<btRigidBody> rigid;
};

struct Finger {
  std::unique_ptr<btSphereShape> shape;
  std::unique_ptr<btRigidBody> proxy;
  EffectiveSettings settings;  // after the scene's effect switches (applySettings)
  const FingerModel* model = nullptr;  // the model of settings.patch.model
  DeviceSample device;
  Vec3 force = Vec3::Zero();
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

}  // namespace

struct World::Impl final : SolveHooks {
  explicit Impl(const SceneDesc& d);
  ~Impl() override;
  void beforeSolve() override;
  void afterSolve() override;

  void addBody(int index, const BodyDesc& d);
  void addFinger(int index, const FingerDesc& d);
  void gatherProxyManifold(btPersistentManifold& m, const btCollisionObject* proxy);
  void handleContact(Finger& f, FingerContact& c);
  void recordContact(const Finger& f, const ContactMemory* mem, FingerContact& c) const;
  void computeContactPatch(Finger& f, FingerContact& c, const ContactMemory* mem);
  Pose bodyFrame(int body) const;
  bool ownedHere() const { return std::this_thread::get_id() == owner; }
  void rememberImpulses(Finger& f);
  void applySettings(Finger& f, const PatchSettings& patch) const;
  void applyLoads();
  void saveStates();
  void stopTunnelling();
  bool statesFinite() const;
  void restoreStates();
  std::vector<btRigidBody*> allRigidBodies() const;

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

World::Impl::Impl(const SceneDesc& d) : desc(d) {
  requireValid(desc);
  btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
  world.setGravity(desc.effects.gravity ? toBt(desc.world.gravity) : btVector3(0, 0, 0));
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = desc.world.solver_iterations;
  info.m_warmstartingFactor = 1.0;
  // Direction caching lets our points keep fixed friction directions, so that their
  // impulses can warm-start the next step; Bullet's own contacts are not affected.
  // A patch's rows are nearly redundant (same bodies, same normal, lever arms of a few mm):
  // sweeping them in a fixed order biases the load towards the first points, and the
  // twist-resisting share converges slowly. Bullet's randomized order (its own seeded
  // generator, so runs stay bit-identical) holds the pinch within 1 degree in 10 iterations
  // where the fixed order needs 30.
  info.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_SIMD | SOLVER_USE_2_FRICTION_DIRECTIONS |
                      SOLVER_ENABLE_FRICTION_DIRECTION_CACHING | SOLVER_RANDMIZE_ORDER;
  bodies.resize(desc.bodies.size());
  for (std::size_t i = 0; i < desc.bodies.size(); ++i) addBody(static_cast<int>(i), desc.bodies[i]);
  fingers.resize(desc.fingers.size());
  for (std::size_t i = 0; i < desc.fingers.size(); ++i) addFinger(static_cast<int>(i), desc.fingers[i]);
  injected.reserve(desc.fingers.size() * kMaxContactsPerFinger * (kMaxSgo / MANIFOLD_CACHE_SIZE + 1));
  saved.resize(bodies.size() + fingers.size());
}

World::Impl::~Impl() {
  for (btRigidBody* r : allRigidBodies()) world.removeRigidBody(r);
  GF_ASSERT(world.getNumCollisionObjects() == 0 && "every body leaves the Bullet world before it is destroyed");
}

void World::Impl::addBody(int index, const BodyDesc& d) {
  Body& b = bodies[index];
  b.shapes = makeBodyShapes(d);
  btRigidBody::btRigidBodyConstructionInfo ci(d.mass, nullptr, b.shapes.shape.get(), b.shapes.local_inertia);
  ci.m_startWorldTransform = poseOf(d.position, d.orientation) * b.shapes.desc_from_body;
  ci.m_friction = desc.effects.friction ? d.friction : 0.0;
  ci.m_restitution = d.restitution;
  ci.m_linearDamping = desc.world.linear_damping;
  ci.m_angularDamping = desc.world.angular_damping;
  b.rigid = std::make_unique<btRigidBody>(ci);
  b.rigid->setUserIndex(index);
  if (d.mass > 0.0) b.rigid->setActivationState(DISABLE_DEACTIVATION);
  world.addRigidBody(b.rigid.get());
}

void World::Impl::addFinger(int index, const FingerDesc& d) {
  Finger& f = fingers[index];
  applySettings(f, d.patch);
  f.device = d.device.sample(0.0);
  f.shape = std::make_unique<btSphereShape>(d.proxy.radius);
  btVector3 inertia(0, 0, 0);
  f.shape->calculateLocalInertia(d.proxy.mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo ci(d.proxy.mass, nullptr, f.shape.get(), inertia);
  ci.m_startWorldTransform = btTransform(btQuaternion::getIdentity(), toBt(f.device.position));
  f.proxy = std::make_unique<btRigidBody>(ci);
  f.proxy->setUserIndex(kProxyTag);
  f.proxy->setUserIndex2(index);
  f.proxy->setAngularFactor(0.0);  // rotation locked: a 3-DOF proxy
  f.proxy->setActivationState(DISABLE_DEACTIVATION);
  f.proxy->setFlags(f.proxy->getFlags() | BT_DISABLE_WORLD_GRAVITY);
  world.addRigidBody(f.proxy.get(), kFingerGroup, btBroadphaseProxy::AllFilter & ~kFingerGroup);
  f.proxy->setGravity(btVector3(0, 0, 0));  // gravity compensated
}

// The finger's settings from now on, with the scene's effects applied once.
void World::Impl::applySettings(Finger& f, const PatchSettings& patch) const {
  f.settings = effectiveSettings(patch, desc.effects, desc.world.contact_solver);
  f.model = &fingerModel(f.settings.patch.model);
}

void World::Impl::beforeSolve() {
  for (Finger& f : fingers) f.contact_count = 0;
  solver.clearBlocks();
  const int n = dispatcher.getNumManifolds();  // injected manifolds are appended after these
  for (int i = 0; i < n; ++i) {
    btPersistentManifold& m = *dispatcher.getManifoldByIndexInternal(i);
    const btCollisionObject* b0 = m.getBody0();
    const btCollisionObject* b1 = m.getBody1();
    if (b0->getUserIndex() == kProxyTag) gatherProxyManifold(m, b0);
    else if (b1->getUserIndex() == kProxyTag) gatherProxyManifold(m, b1);
  }
  for (Finger& f : fingers) {
    for (int k = 0; k < f.contact_count; ++k) handleContact(f, f.contacts[k]);
  }
}

// Groups the manifolds of a proxy by touched body: the deepest point of all of them is the
// finger's contact with that body; the other manifolds are emptied for this step.
void World::Impl::gatherProxyManifold(btPersistentManifold& m, const btCollisionObject* proxy) {
  const int finger = proxy->getUserIndex2();
  Finger& f = fingers[finger];
  TrueContact truth;
  if (!deepestContact(m, proxy, truth)) return;
  const int body = truth.object->getUserIndex();
  for (int k = 0; k < f.contact_count; ++k) {
    FingerContact& c = f.contacts[k];
    if (c.truth.object->getUserIndex() != body) continue;
    if (truth.separation < c.truth.separation) {
      c.manifold->clearManifold();
      c.truth = truth;
      c.manifold = &m;
    } else {
      m.clearManifold();
    }
    return;
  }
  if (f.contact_count == kMaxContactsPerFinger) {  // beyond the tracked contacts: a god-object
    const FingerDesc& fd = desc.fingers[finger];
    keepOnlyPoint(m, truth.index, {fd.proxy.contact_stiffness, fd.proxy.contact_damping,
                                   f.settings.patch.friction}, {});
    return;
  }
  FingerContact& c = f.contacts[f.contact_count++];
  c.truth = truth;
  c.manifold = &m;
}

void World::Impl::handleContact(Finger& f, FingerContact& c) {
  const FingerDesc& fd = desc.fingers[&f - fingers.data()];
  const ContactMemory* mem = f.memoryOf(c.truth.object->getUserIndex());
  c.sgo_count = 0;
  recordContact(f, mem, c);
  // A patch starts on touching and survives a small gap (kPatchReleaseGap).
  const bool touching = c.truth.separation <= 0.0 ||
                        (mem && mem->had_patch && c.truth.separation <= kPatchReleaseGap);
  if (f.model->wantsPatch() && touching) computeContactPatch(f, c, mem);
  // The finger's model turns the contact (and its patch's points) into the solver's rows.
  f.model->addRows({c, mem, f.settings, f.proxy.get(), fd.proxy.contact_stiffness, fd.proxy.contact_damping},
                   rows);
  counters.sgos_injected += c.sgo_count;
}

void World::Impl::rememberImpulses(Finger& f) {
  f.memory_count = f.contact_count;
  for (int k = 0; k < f.contact_count; ++k) {
    FingerContact& c = f.contacts[k];
    GF_ASSERT(c.manifold != nullptr && "impulses are read between beforeSolve and afterSolve only");
    ContactMemory& mem = f.memory[k];
    const Patch& patch = c.record.patch;
    mem.body = c.record.body;
    mem.truth = c.aggregate ? WarmStart{} : solvedImpulses(c.manifold->getContactPoint(0));
    mem.had_patch = c.sgo_count > 0;
    mem.n_sgo = c.sgo_count > 0 && !c.aggregate ? f.settings.patch.n_sgo : 0;
    mem.ring_tangent_local = patch.ring_tangent;
    mem.pad_normal = c.pad_normal;
    // Only the radials of the layers this patch has are read back (warmStartByAngle).
    mem.layer_count = mem.n_sgo > 0 ? (f.settings.patch.fill == PatchFill::kFilled ? f.settings.patch.rings : 1) : 0;
    for (int l = 0; l < mem.layer_count; ++l) std::fill_n(mem.layers[l].begin(), mem.n_sgo, WarmStart{});
    for (int i = 0; i < c.sgo_count && !c.aggregate; ++i) {
      const Sgo& p = injectedPoint(patch, i);
      mem.layers[layerOf(p)][p.radial] = solvedImpulses(injected, c.first_injected, i);
    }
    const FrictionBlock& block = solver.block(c.block);
    mem.friction_force = block.solved ? block.force : btVector3(0, 0, 0);
    mem.friction_torque = block.solved ? block.torque : 0.0;
    mem.normal_impulse = block.solved ? block.normal_impulse : 0.0;
    mem.tilt_impulse = block.solved && block.aggregate ? block.press.tilt : btVector3(0, 0, 0);
    c.manifold = nullptr;  // Bullet may free it at the next collision pass
    c.truth.object = nullptr;
  }
}

// The contact in the touched body's frame (the frame of its walk mesh), with the press depth
// of Eq. 1 and the ring's reference carried from the last step; no patch yet.
void World::Impl::recordContact(const Finger& f, const ContactMemory* mem, FingerContact& c) const {
  const btTransform& t = c.truth.object->getWorldTransform();
  const btMatrix3x3 to_local = t.getBasis().transpose();
  const btVector3 v_world = toBt(f.device.position) - f.proxy->getCenterOfMassPosition();
  c.v_local = toEigen(to_local * v_world);
  ContactRecord& r = c.record;
  r.body = c.truth.object->getUserIndex();
  r.contact = {toEigen(t.invXform(c.truth.point_world)), toEigen(to_local * c.truth.outward_normal_world),
               c.truth.separation, bodies[r.body].shapes.rounding,
               mem ? mem->ring_tangent_local : Vec3::Zero()};
  r.press_depth = pressDepth(c.v_local, r.contact.outward_normal_local.normalized());
  clearPatch(r.patch);
}

// The patch of a god-finger contact, its points in the world and their depths. Every point has
// the contact's depth (the paper, Sec. 3.2) while the body's surface keeps the orientation the
// finger met it with; a tilt of the surface since (the contact normal turned from the pad's
// normal, which the proxy, not turning, keeps) deepens the points on one side and lifts the
// others by their offset along the turn, so the pad pushes back. Beyond kPadFollowAngle the pad
// turns with the surface: a finger moved around a curved body keeps its pad on it.
void World::Impl::computeContactPatch(Finger& f, FingerContact& c, const ContactMemory* mem) {
  ContactRecord& r = c.record;
  const Mesh& mesh = *bodies[r.body].shapes.walk_mesh;
  const auto start = std::chrono::steady_clock::now();
  computePatch(mesh, r.contact, c.v_local, f.settings.patch, r.patch);
  counters.patch_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++counters.patch_calls;
  if (!r.patch.valid) {
    ++counters.invalid_patches;
    return;
  }
  const Vec3 n = toEigen(c.truth.outward_normal_world);
  Vec3 pad = mem && mem->had_patch ? mem->pad_normal : n;
  if (pad.dot(n) < std::cos(kPadFollowAngle)) {
    const Vec3 across = pad - pad.dot(n) * n;
    pad = across.norm() > 1e-12 ? Vec3(std::cos(kPadFollowAngle) * n + std::sin(kPadFollowAngle) * across.normalized()) : n;
  }
  c.pad_normal = pad;
  const btTransform& t = c.truth.object->getWorldTransform();
  const btVector3 tilt = toBt(pad) - c.truth.outward_normal_world;
  const auto place = [&](const Sgo& p) {
    const int i = c.sgo_count++;
    c.sgo_world[i] = t * toBt(p.position);
    c.sgo_separation[i] = c.truth.separation - (c.sgo_world[i] - c.truth.point_world).dot(tilt);
    counters.crossing_limit_stops += p.stop == WalkStop::kCrossingLimit;
  };
  for (const Sgo& p : r.patch.sgos) place(p);
  for (const Sgo& p : r.patch.inner) place(p);
}

Pose World::Impl::bodyFrame(int body) const {
  const btTransform& t = bodies[body].rigid->getWorldTransform();
  const btQuaternion q = t.getRotation();
  return {toEigen(t.getOrigin()), Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z())};
}

void World::Impl::afterSolve() {
  for (Finger& f : fingers) rememberImpulses(f);
  releaseInjected(dispatcher, injected);
}

std::vector<btRigidBody*> World::Impl::allRigidBodies() const {
  std::vector<btRigidBody*> out;
  for (const Body& b : bodies) out.push_back(b.rigid.get());
  for (const Finger& f : fingers) out.push_back(f.proxy.get());
  return out;
}

// The scene's loads at the step's start time; Bullet clears applied forces after each step.
void World::Impl::applyLoads() {
  for (const LoadDesc& load : desc.loads) {
    const double factor = loadFactor(load, time);
    if (factor == 0.0) continue;
    btRigidBody& r = *bodies[static_cast<std::size_t>(load.body)].rigid;
    r.applyCentralForce(toBt(factor * load.force));
    r.applyTorque(toBt(factor * load.torque));
  }
}

void World::Impl::saveStates() {
  std::size_t i = 0;
  auto save = [&](const btRigidBody& r) {
    saved[i++] = {r.getWorldTransform(), r.getLinearVelocity(), r.getAngularVelocity()};
  };
  for (const Body& b : bodies) save(*b.rigid);
  for (const Finger& f : fingers) save(*f.proxy);
}

// A proxy that moves far in one step can pass a thin body between two collision checks (a 1 mm
// proxy at 40 m/s crossed a 1 mm wall). When a proxy moved more than half its radius, the path
// of its centre over the step is cast as a ray against the bodies; where it entered one, the
// proxy is put back touching the surface there and loses its velocity into it (the inelastic
// impact its contact would have made). Shorter steps are left to the contacts: the validator
// keeps the deepest press (max_force / contact_stiffness) within the proxy's radius.
void World::Impl::stopTunnelling() {
  for (std::size_t i = 0; i < fingers.size(); ++i) {
    btRigidBody& proxy = *fingers[i].proxy;
    const btVector3 from = saved[bodies.size() + i].transform.getOrigin();
    const btVector3 to = proxy.getWorldTransform().getOrigin();
    const btScalar r = fingers[i].shape->getRadius();
    if (!((to - from).length2() > 0.25 * r * r)) continue;
    btCollisionWorld::ClosestRayResultCallback hit(from, to);
    hit.m_collisionFilterGroup = kFingerGroup;
    hit.m_collisionFilterMask = btBroadphaseProxy::AllFilter & ~kFingerGroup;
    world.rayTest(from, to, hit);
    if (!hit.hasHit()) continue;
    const btVector3 n = hit.m_hitNormalWorld.normalized();
    if (!(n.dot(to - from) < 0.0)) continue;  // left a surface: not entering a body
    btTransform t = proxy.getWorldTransform();
    t.setOrigin(hit.m_hitPointWorld + r * n);
    proxy.setCenterOfMassTransform(t);
    const btVector3 v = proxy.getLinearVelocity();
    if (const btScalar into = v.dot(n); into < 0.0) proxy.setLinearVelocity(v - into * n);
    ++counters.tunnelling_stops;
  }
}

bool World::Impl::statesFinite() const {
  auto finite = [](const btRigidBody& r) {
    const btTransform& t = r.getWorldTransform();
    const btVector3 v = r.getLinearVelocity(), w = r.getAngularVelocity();
    const btQuaternion q = t.getRotation();
    return std::isfinite(t.getOrigin().length2() + v.length2() + w.length2() + q.length2());
  };
  for (const Body& b : bodies) if (!finite(*b.rigid)) return false;
  for (const Finger& f : fingers) if (!finite(*f.proxy)) return false;
  return true;
}

void World::Impl::restoreStates() {
  std::size_t i = 0;
  auto restore = [&](btRigidBody& r) {
    const SavedState& s = saved[i++];
    r.setWorldTransform(s.transform);
    r.setLinearVelocity(btVector3(0, 0, 0));
    r.setAngularVelocity(btVector3(0, 0, 0));
    r.clearForces();
  };
  for (Body& b : bodies) restore(*b.rigid);
  for (Finger& f : fingers) restore(*f.proxy);
}

World::World(const SceneDesc& desc) : impl_(std::make_unique<Impl>(desc)) {}

World::~World() {
  GF_ASSERT(impl_->ownedHere() && "destroy a World on the thread that built it (the haptic thread)");
}

// Every call into a World checks that it comes from the thread that built it.
#define GF_ASSERT_OWNER() \
  GF_ASSERT(impl_->ownedHere() && "call a World only from the thread that built it (the haptic thread); other threads read Snapshots")

void World::step(double dt, std::span<const DeviceSample> devices) {
  GF_ASSERT_OWNER();
  Impl& w = *impl_;
  // Scripted changes due by this step's start (half a step early, so that t = k dt lands on step
  // k whatever the rounding of the accumulated time); checked by requireValid.
  while (w.next_change < w.desc.changes.size() && w.desc.changes[w.next_change].time <= w.time + 0.5 * dt) {
    const PatchChange& c = w.desc.changes[w.next_change++];
    w.applySettings(w.fingers[static_cast<std::size_t>(c.finger)], c.patch);
  }
  for (std::size_t i = 0; i < w.fingers.size(); ++i) {
    Finger& f = w.fingers[i];
    if (i < devices.size() && devices[i].position.allFinite() && devices[i].velocity.allFinite()) {
      f.device = devices[i];
    }
    const CouplingSettings& cs = w.desc.fingers[i].coupling;
    f.force = sim::couplingForce(cs, f.device.position, f.device.velocity,
                                 toEigen(f.proxy->getCenterOfMassPosition()),
                                 toEigen(f.proxy->getLinearVelocity()));
    f.proxy->applyCentralForce(toBt(f.force));
  }
  w.applyLoads();
  w.saveStates();
  w.world.stepSimulation(dt, 0, dt);
  if (dt != w.steps_dt) {
    w.time_base = w.time;
    w.steps_dt = dt;
    w.steps_since_base = 0;
  }
  w.time = w.time_base + static_cast<double>(++w.steps_since_base) / (1.0 / dt);
  ++w.counters.steps;
  if (!w.statesFinite()) {
    w.restoreStates();
    ++w.counters.nan_recoveries;
  } else {
    w.stopTunnelling();
  }
}

double World::time() const {
  GF_ASSERT_OWNER();
  return impl_->time;
}

const SceneDesc& World::desc() const { return impl_->desc; }  // immutable: any thread

const WorldCounters& World::counters() const {
  GF_ASSERT_OWNER();
  return impl_->counters;
}

Pose World::bodyPose(int body) const {
  GF_ASSERT_OWNER();
  const Body& b = impl_->bodies[body];
  const btTransform t = b.rigid->getWorldTransform() * b.shapes.desc_from_body.inverse();
  const btQuaternion q = t.getRotation();
  return {toEigen(t.getOrigin()), Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z())};
}

Vec3 World::bodyLinearVelocity(int body) const {
  GF_ASSERT_OWNER();
  return toEigen(impl_->bodies[body].rigid->getLinearVelocity());
}

Vec3 World::bodyAngularVelocity(int body) const {
  GF_ASSERT_OWNER();
  return toEigen(impl_->bodies[body].rigid->getAngularVelocity());
}

std::vector<World::Overlap> World::bodyOverlaps(double tolerance) const {
  GF_ASSERT_OWNER();
  struct Deepest : btCollisionWorld::ContactResultCallback {
    double depth = 0.0;
    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      depth = std::max(depth, -static_cast<double>(p.getDistance()));
      return 0;
    }
  };
  std::vector<Overlap> out;
  auto& bodies = impl_->bodies;
  for (std::size_t a = 0; a < bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < bodies.size(); ++b) {
      btRigidBody& ra = *bodies[a].rigid;
      btRigidBody& rb = *bodies[b].rigid;
      if (ra.getInvMass() == 0.0 && rb.getInvMass() == 0.0) continue;
      Deepest deepest;
      impl_->world.contactPairTest(&ra, &rb, deepest);
      if (deepest.depth > tolerance) out.push_back({static_cast<int>(a), static_cast<int>(b), deepest.depth});
    }
  }
  return out;
}

Vec3 World::bodyInertia(int body) const {
  GF_ASSERT_OWNER();
  const btRigidBody& r = *impl_->bodies[body].rigid;
  return r.getInvMass() > 0.0 ? toEigen(r.getLocalInertia()) : Vec3::Zero();
}

Vec3 World::devicePosition(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->fingers[finger].device.position;
}

Vec3 World::proxyPosition(int finger) const {
  GF_ASSERT_OWNER();
  return toEigen(impl_->fingers[finger].proxy->getCenterOfMassPosition());
}

Vec3 World::couplingForce(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->fingers[finger].force;
}

Vec3 World::feedbackForce(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->desc.effects.force_feedback ? Vec3(-impl_->fingers[finger].force) : Vec3::Zero();
}

bool World::touching(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->fingers[finger].contact_count > 0;
}

int World::sgoCount(int finger) const {
  GF_ASSERT_OWNER();
  const Finger& f = impl_->fingers[finger];
  int n = 0;
  for (int k = 0; k < f.contact_count; ++k) n += f.contacts[k].sgo_count;
  return n;
}

double World::contactRadius(int finger) const {
  GF_ASSERT_OWNER();
  const Finger& f = impl_->fingers[finger];
  double sum = 0.0;
  int n = 0;
  for (int k = 0; k < f.contact_count; ++k) {
    if (!f.contacts[k].record.patch.valid) continue;
    sum += f.contacts[k].record.patch.radius;
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

bool World::deepestTouch(int finger, Touch& out) const {
  GF_ASSERT_OWNER();
  const Finger& f = impl_->fingers[finger];
  const FingerContact* deepest = nullptr;
  for (int k = 0; k < f.contact_count; ++k) {
    const FingerContact& c = f.contacts[k];
    if (!deepest || c.record.contact.separation < deepest->record.contact.separation) deepest = &c;
  }
  if (!deepest) return false;
  const ContactRecord& r = deepest->record;
  const Pose frame = impl_->bodyFrame(r.body);
  out.body = r.body;
  out.point = frame.toWorld(r.contact.point_local);
  out.normal = frame.orientation * r.contact.outward_normal_local;
  out.separation = r.contact.separation;
  return true;
}

double World::mechanicalEnergy() const {
  GF_ASSERT_OWNER();
  double e = 0.0;
  for (const btRigidBody* r : impl_->allRigidBodies()) {
    if (r->getInvMass() == 0.0) continue;
    const double m = 1.0 / r->getInvMass();
    const btVector3 w = r->getAngularVelocity();
    const btVector3 iw = r->getInvInertiaTensorWorld().inverse() * w;
    e += 0.5 * m * r->getLinearVelocity().length2() + 0.5 * w.dot(iw);
    e -= m * r->getGravity().dot(r->getCenterOfMassPosition());
  }
  return e;
}

void World::applyTorqueImpulse(int body, const Vec3& impulse) {
  GF_ASSERT_OWNER();
  impl_->bodies[body].rigid->applyTorqueImpulse(toBt(impulse));
}

void World::setPatchSettings(int finger, const PatchSettings& settings) {
  GF_ASSERT_OWNER();
  if (std::optional<FieldError> e = validatePatch(settings)) {
    throw DescriptionError("finger '" + impl_->desc.fingers[finger].name + "'", *e);
  }
  impl_->applySettings(impl_->fingers[finger], settings);
}

void World::snapshot(Snapshot& out) const {
  GF_ASSERT_OWNER();
  const Impl& w = *impl_;
  out.time = w.time;
  out.step = w.counters.steps;
  out.nan_recoveries = w.counters.nan_recoveries;
  out.bodies.resize(w.bodies.size());
  for (std::size_t i = 0; i < w.bodies.size(); ++i) out.bodies[i] = bodyPose(static_cast<int>(i));
  out.fingers.resize(w.fingers.size());
  for (std::size_t i = 0; i < w.fingers.size(); ++i) {
    const Finger& f = w.fingers[i];
    FingerSnapshot& fs = out.fingers[i];
    fs.device = f.device.position;
    fs.proxy = toEigen(f.proxy->getCenterOfMassPosition());
    fs.coupling_force = f.force;
    fs.feedback_force = feedbackForce(static_cast<int>(i));
    fs.sgo_count = sgoCount(static_cast<int>(i));
    fs.contacts.resize(f.contact_count);
    // One pose per contact: the body's now, after the step that computed its patch.
    for (int k = 0; k < f.contact_count; ++k) {
      const ContactRecord& r = f.contacts[k].record;
      toContactSnapshot(r, w.bodyFrame(r.body), fs.contacts[k]);
    }
  }
}

}  // namespace gf::sim
