// The Bullet world of a World: its construction, the bodies and proxies, a finger's settings,
// and what each step puts into it before the solve (scripted changes, couplings, loads).
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include <algorithm>

#include "sim/assert.hpp"
#include "sim/world/world_impl.hpp"
#include "sim/scene/settings.hpp"

namespace gf::sim {
namespace {

// A solve's iterations stop once an iteration changes no row's velocity by more than this (m/s,
// rad/s about an axis): over a minute's hold at 1 kHz, 6 nm if every step kept it.
constexpr double kSolverTolerance = 1e-10;

btTransform poseOf(const Vec3& p, const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond n = q.normalized();
  return btTransform(btQuaternion(n.x(), n.y(), n.z(), n.w()), toBt(p));
}

// The manifolds the fingers inject in one step at most (contact_injection.cpp): each touched
// body's patch points, MANIFOLD_CACHE_SIZE to a manifold, at the largest patch a live setting can
// ask for (the true contact stays in its own pair's manifold).
std::size_t injectedManifolds(const SceneDesc& scene) {
  const std::size_t per_contact = (kMaxPatchPoints + MANIFOLD_CACHE_SIZE - 1) / MANIFOLD_CACHE_SIZE;
  return scene.fingers.size() * kMaxContactsPerFinger * per_contact;
}

// A shape whose pair with another opens one manifold and one algorithm: not a compound of
// convex parts, not a triangle mesh, not a soft body (each of those opens one per part touching).
bool onePerPair(ShapeKind shape) {
  static_assert(ShapeKind::kConvexHull < ShapeKind::kConvexDecomposition &&
                    ShapeKind::kConvexDecomposition < ShapeKind::kConcaveMesh && ShapeKind::kConcaveMesh < ShapeKind::kSoftBox,
                "the primitives and hulls come first in ShapeKind");
  return shape <= ShapeKind::kConvexHull;
}

}  // namespace

btDefaultCollisionConstructionInfo collisionPools(const SceneDesc& scene) {
  btDefaultCollisionConstructionInfo info;
  for (const BodyDesc& b : scene.bodies) {
    if (!onePerPair(b.shape)) return info;
  }
  const std::size_t objects = scene.bodies.size() + scene.fingers.size();
  const std::size_t pairs = objects * (objects + 1) / 2;
  // At least 64 (Bullet cannot make an empty pool, and a scene without bodies or fingers would
  // ask for none), at most Bullet's default (the pairs grow with the square of the bodies).
  const auto within = [&](std::size_t n, std::size_t least, int most) {
    return static_cast<int>(std::clamp<std::size_t>(n, least, static_cast<std::size_t>(most)));
  };
  info.m_defaultMaxPersistentManifoldPoolSize =
      within(2 * pairs + injectedManifolds(scene), 64, info.m_defaultMaxPersistentManifoldPoolSize);
  info.m_defaultMaxCollisionAlgorithmPoolSize = within(4 * pairs, 256, info.m_defaultMaxCollisionAlgorithmPoolSize);
  return info;
}

World::Impl::Impl(const SceneDesc& d) : desc(d) {
  requireValid(desc);
  btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
  contact_algorithms.registerWith(dispatcher);
  world.setGravity(desc.effects.gravity ? toBt(desc.world.gravity) : btVector3(0, 0, 0));
  configureSolver();
  bodies.resize(desc.bodies.size());
  for (std::size_t i = 0; i < desc.bodies.size(); ++i) addBody(static_cast<int>(i), desc.bodies[i]);
  fingers.resize(desc.fingers.size());
  for (std::size_t i = 0; i < desc.fingers.size(); ++i) addFinger(static_cast<int>(i), desc.fingers[i]);
  injected.reserve(injectedManifolds(desc));
  saved.resize(bodies.size() + fingers.size());
  makeOverlapPairs();
}

World::Impl::~Impl() {
  for (btRigidBody* r : allRigidBodies()) world.removeRigidBody(r);
  GF_ASSERT(world.getNumCollisionObjects() == 0 && "every body leaves the Bullet world before it is destroyed");
}

void World::Impl::configureSolver() {
  btContactSolverInfo& info = world.getSolverInfo();
  info.m_numIterations = desc.world.solver_iterations;
  info.m_warmstartingFactor = 1.0;
  // The iterations end once one changes no row's velocity by more than kSolverTolerance (each
  // row reports its change of velocity squared, Bullet's and ours alike): a held step that its
  // warm start already solves ends after one or two.
  info.m_leastSquaresResidualThreshold = kSolverTolerance * kSolverTolerance;
  // Direction caching lets our points keep fixed friction directions, so that their
  // impulses can warm-start the next step; Bullet's own contacts are not affected.
  // A patch's rows are nearly redundant (same bodies, same normal, lever arms of a few mm):
  // sweeping them in a fixed order biases the load towards the first points, and the
  // twist-resisting share converges slowly. Bullet's randomized order (its own seeded
  // generator, so runs stay bit-identical) holds the pinch within 1 degree in 10 iterations
  // where the fixed order needs 30.
  info.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_SIMD | SOLVER_USE_2_FRICTION_DIRECTIONS |
                      SOLVER_ENABLE_FRICTION_DIRECTION_CACHING | SOLVER_RANDMIZE_ORDER;
}

void World::Impl::addBody(int index, const BodyDesc& d) {
  Body& b = bodies[index];
  b.shapes = makeBodyShapes(d);
  if (isSoftShape(d.shape)) {  // its placeholder: static, colliding with nothing
    addSoftBody(index, d);
    btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, b.shapes.shape.get());
    ci.m_startWorldTransform = poseOf(d.position, d.orientation);
    b.rigid = std::make_unique<btRigidBody>(ci);
    b.rigid->setUserIndex(index);
    b.rigid->setCollisionFlags(b.rigid->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    world.addRigidBody(b.rigid.get(), 0, 0);
    return;
  }
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
  // Warm-started walks: every cache sized now for the most radial vectors the finger's scripted
  // settings use, so no step allocates for them (setPatchSettings sizes them for a new n_sgo).
  int n_sgo = d.patch.n_sgo;
  for (const PatchChange& c : desc.changes) {
    if (c.finger == index) n_sgo = std::max(n_sgo, c.patch.n_sgo);
  }
  sizeWalks(f, n_sgo);
  // A soft pad's proxy is its bone, inside the skin by the pad's thickness.
  const bool pad = d.patch.model == ContactModel::kFemPad;
  f.shape = std::make_unique<btSphereShape>(pad ? d.proxy.radius - d.pad.thickness : d.proxy.radius);
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
  if (pad) addPad(f, d);
}

void World::Impl::sizeWalks(Finger& f, int n_sgo) {
  for (FingerContact& c : f.contacts) c.walks.reserve(n_sgo);
  for (WalkCache& w : f.memory_walks) w.reserve(n_sgo);
}

// The finger's settings from now on: the scene's effects applied and its model chosen, once.
void World::Impl::applySettings(Finger& f, const PatchSettings& patch) const {
  f.given = patch;
  f.settings = effectiveSettings(patch, desc.effects, desc.world.contact_solver);
  f.model = &fingerModel(f.settings.patch.model);
}

// Scripted changes due by this step's start (half a step early, so that t = k dt lands on step
// k whatever the rounding of the accumulated time); checked by requireValid.
void World::Impl::applyChangesDue(double dt) {
  while (next_change < desc.changes.size() && desc.changes[next_change].time <= time + 0.5 * dt) {
    const PatchChange& c = desc.changes[next_change++];
    applySettings(fingers[static_cast<std::size_t>(c.finger)], c.patch);
  }
}

// Each finger's newest finite device sample (a sample missing or not finite keeps the last)
// and the coupling force it puts on the proxy for this step. The work against the force sent
// goes to the port's observer (PortObserver), a jump's apart: a move faster than
// max_device_speed over the step or over the interval the device reports (a sender at 250 Hz
// moves once in four steps).
void World::Impl::applyCouplings(std::span<const DeviceSample> devices, double dt) {
  for (std::size_t i = 0; i < fingers.size(); ++i) {
    Finger& f = fingers[i];
    const CouplingSettings& cs = desc.fingers[i].coupling;
    if (i < devices.size() && devices[i].position.allFinite() && devices[i].velocity.allFinite()) {
      DeviceSample sample = devices[i];
      // A resumed stream (after a dropout or a takeover) starts where the device was held.
      if (sample.resumed) f.resume_offset = f.device.position - sample.position;
      sample.position += f.resume_offset;
      const Vec3 moved = sample.position - f.device.position;
      if (moved.squaredNorm() > 0.0) {
        const bool jump = moved.norm() > cs.max_device_speed * std::max(dt, sample.interval);
        f.port.observe(-f.told.dot(moved), jump);
      }
      f.device = sample;
      washOutResume(f, dt);
    }
    f.force = sim::couplingForce(cs, f.device.position, f.device.velocity,
                                 toEigen(f.proxy->getCenterOfMassPosition()),
                                 toEigen(f.proxy->getLinearVelocity()));
    // push_apart's force from the last step's overlap acts on the proxy beside the coupling; the
    // device feels it through the coupling, which the proxy, pushed off, stretches.
    const bool push = desc.world.overlap == OverlapMode::kPushApart;
    f.proxy->applyCentralForce(toBt(push ? Vec3(f.force + f.overlap_push) : f.force));
  }
}

// A resumed device's offset (Finger::resume_offset) washed out towards the hand's position by at
// most max(kResumeWashSpeed, |offset| / kResumeWashTime) dt a step. A step that would put energy
// into the coupling (the device moving along the force the hand was told, -told . move > 0) is
// energy the hand did not give, which the hand may later take back through the port: all such
// energy put in so far (resume_spent) may not exceed the port's energy, so the port stays at or
// above zero whatever comes back; a step that takes energy out goes on freely. A hand that
// pressed deeper during a dropout gets no more force back than its own work paid for.
void World::Impl::washOutResume(Finger& f, double dt) {
  const double size = f.resume_offset.norm();
  if (!(size > 0.0)) return;
  double step = std::min(size, std::max(kResumeWashSpeed, size / kResumeWashTime) * dt);
  const Vec3 toward = -f.resume_offset / size;  // the device's move: towards the hand
  const double put_in = -f.told.dot(toward);  // J per metre put into the coupling
  if (put_in > 0.0) step = std::min(step, std::max(0.0, f.port.energy - f.resume_spent) / put_in);
  if (!(step > 0.0)) return;
  f.resume_offset += step * toward;
  if (f.resume_offset.norm() < kResumeWashDone) f.resume_offset.setZero();
  f.device.position += step * toward;
  if (put_in > 0.0) f.resume_spent += put_in * step;
}

// The force each finger's device is to render after this step: the coupling force's opposite
// (none without force feedback), approached by at most max_force_rate dt, so that a device
// that jumps (a new sender, a tracking glitch, a scripted move) or a contact that snaps never
// reaches the hand as a step.
void World::Impl::slewSentForces(double dt) {
  for (std::size_t i = 0; i < fingers.size(); ++i) {
    Finger& f = fingers[i];
    const Vec3 target = desc.effects.force_feedback ? Vec3(-f.force) : Vec3::Zero();
    const double limit = maxForceRate(desc.fingers[i].coupling) * dt;
    const Vec3 change = target - f.sent;
    const double size = change.norm();
    f.sent = size > limit ? Vec3(f.sent + (limit / size) * change) : target;
    f.told = f.sent;  // a device source may tell its device otherwise (World::setToldForce)
  }
}

// The scene's loads at the step's start time; Bullet clears applied forces after each step.
void World::Impl::applyLoads() {
  for (int b : soft_bodies) bodies[static_cast<std::size_t>(b)].soft->setLoad(Vec3::Zero(), Vec3::Zero());
  for (const LoadDesc& load : desc.loads) {
    const double factor = loadFactor(load, time);
    if (factor == 0.0) continue;
    if (SoftBody* soft = bodies[static_cast<std::size_t>(load.body)].soft.get()) {
      soft->addLoad(factor * load.force, factor * load.torque);
      continue;
    }
    btRigidBody& r = *bodies[static_cast<std::size_t>(load.body)].rigid;
    r.applyCentralForce(toBt(factor * load.force));
    r.applyTorque(toBt(factor * load.torque));
  }
}

// Time after a step of dt, counted in steps from the last change of dt.
void World::Impl::countStep(double dt) {
  if (dt != steps_dt) {
    time_base = time;
    steps_dt = dt;
    steps_since_base = 0;
  }
  time = time_base + static_cast<double>(++steps_since_base) / (1.0 / dt);
  ++counters.steps;
}

Pose World::Impl::bodyFrame(int body) const {
  const btTransform& t = bodies[body].rigid->getWorldTransform();
  const btQuaternion q = t.getRotation();
  return {toEigen(t.getOrigin()), Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z())};
}

std::vector<btRigidBody*> World::Impl::allRigidBodies() const {
  std::vector<btRigidBody*> out;
  for (const Body& b : bodies) out.push_back(b.rigid.get());
  for (const Finger& f : fingers) out.push_back(f.proxy.get());
  return out;
}

}  // namespace gf::sim
