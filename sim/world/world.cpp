// The public World API: each call checks the owner thread and reads or drives World::Impl
// (sim/world/world_impl.hpp), whose jobs live in world_bullet.cpp, world_contacts.cpp and
// world_safety.cpp.
#include "sim/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/assert.hpp"
#include "sim/world/world_impl.hpp"
#include "sim/scene/settings.hpp"

namespace gf::sim {

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
  w.applyChangesDue(dt);
  w.applyCouplings(devices, dt);
  w.applyLoads();
  w.stepPads(dt);
  w.stepSoftBodies(dt);
  w.saveStates();
  w.world.stepSimulation(dt, 0, dt);
  w.countStep(dt);
  w.checkStep();
  w.slewSentForces(dt);
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
  const Impl::Body& b = impl_->bodies[body];
  if (b.soft) return impl_->softPose(body);
  const btTransform t = b.rigid->getWorldTransform() * b.shapes.desc_from_body.inverse();
  const btQuaternion q = t.getRotation();
  return {toEigen(t.getOrigin()), Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z())};
}

Vec3 World::bodyLinearVelocity(int body) const {
  GF_ASSERT_OWNER();
  const Impl::Body& b = impl_->bodies[body];
  return b.soft ? b.soft->velocity() : toEigen(b.rigid->getLinearVelocity());
}

Vec3 World::bodyAngularVelocity(int body) const {
  GF_ASSERT_OWNER();
  const Impl::Body& b = impl_->bodies[body];
  return b.soft ? b.soft->angularVelocity() : toEigen(b.rigid->getAngularVelocity());
}

namespace {

// How deep two objects overlap (m; 0 when apart), by their own collision test.
double overlapDepth(btCollisionWorld& world, btCollisionObject& a, btCollisionObject& b) {
  struct Deepest : btCollisionWorld::ContactResultCallback {
    double depth = 0.0;
    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      depth = std::max(depth, -static_cast<double>(p.getDistance()));
      return 0;
    }
  };
  Deepest deepest;
  world.contactPairTest(&a, &b, deepest);
  return deepest.depth;
}

}  // namespace

std::vector<World::Overlap> World::bodyOverlaps(double tolerance) const {
  GF_ASSERT_OWNER();
  std::vector<Overlap> out;
  auto& bodies = impl_->bodies;
  for (std::size_t a = 0; a < bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < bodies.size(); ++b) {
      if (bodies[a].soft || bodies[b].soft) continue;  // soft bodies are not Bullet's
      btRigidBody& ra = *bodies[a].rigid;
      btRigidBody& rb = *bodies[b].rigid;
      if (ra.getInvMass() == 0.0 && rb.getInvMass() == 0.0) continue;
      const double depth = overlapDepth(impl_->world, ra, rb);
      if (depth > tolerance) out.push_back({static_cast<int>(a), static_cast<int>(b), depth});
    }
  }
  return out;
}

std::vector<World::ProxyOverlap> World::proxyOverlaps(double tolerance) const {
  GF_ASSERT_OWNER();
  std::vector<ProxyOverlap> out;
  for (std::size_t f = 0; f < impl_->fingers.size(); ++f) {
    for (std::size_t b = 0; b < impl_->bodies.size(); ++b) {
      if (impl_->bodies[b].soft) continue;
      const double depth = overlapDepth(impl_->world, *impl_->fingers[f].proxy, *impl_->bodies[b].rigid);
      if (depth > tolerance) out.push_back({static_cast<int>(f), static_cast<int>(b), depth});
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

Quat World::deviceOrientation(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->fingers[finger].device.orientation;
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
  return impl_->fingers[finger].sent;
}

Vec3 World::toldForce(int finger) const {
  GF_ASSERT(finger >= 0 && finger < static_cast<int>(impl_->fingers.size()));
  return impl_->fingers[static_cast<std::size_t>(finger)].told;
}

void World::setToldForce(int finger, const Vec3& force) {
  GF_ASSERT(finger >= 0 && finger < static_cast<int>(impl_->fingers.size()));
  if (force.allFinite()) impl_->fingers[static_cast<std::size_t>(finger)].told = force;
}

double World::portEnergy(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->fingers[finger].port.energy;
}

const PortObserver& World::portObserver(int finger) const {
  GF_ASSERT_OWNER();
  return impl_->fingers[finger].port;
}

bool World::touching(int finger) const {
  GF_ASSERT_OWNER();
  const Impl::Finger& f = impl_->fingers[finger];
  return f.contact_count > 0 || (f.pad && !f.pad->contacts().empty()) || f.soft_count > 0;
}

int World::sgoCount(int finger) const {
  GF_ASSERT_OWNER();
  const Impl::Finger& f = impl_->fingers[finger];
  int n = 0;
  for (int k = 0; k < f.contact_count; ++k) n += f.contacts[k].sgo_count;
  for (int k = 0; k < f.soft_count; ++k) {  // a soft body's pad: its pressed nodes (a god-object's one point is none)
    const SoftTouch& t = f.soft[static_cast<std::size_t>(k)];
    n += t.centre_press ? 0 : t.press_count;
  }
  // A soft pad's points: its skin nodes pressed into bodies.
  return n + (f.pad ? static_cast<int>(f.pad->contacts().size()) : 0);
}

int World::overlapPairCount() const {
  GF_ASSERT_OWNER();
  return static_cast<int>(impl_->overlaps.size());
}

OverlapStats World::overlap(int pair) const {
  GF_ASSERT_OWNER();
  const Impl::OverlapPair& p = impl_->overlaps[static_cast<std::size_t>(pair)];
  return {p.a, p.b, p.area, p.peak, p.integral};
}

Vec3 World::overlapForce(int finger) const {
  GF_ASSERT_OWNER();
  const bool push = impl_->desc.world.overlap == OverlapMode::kPushApart;
  return push ? impl_->fingers[static_cast<std::size_t>(finger)].overlap_push : Vec3::Zero();
}

double World::contactRadius(int finger) const {
  GF_ASSERT_OWNER();
  const Impl::Finger& f = impl_->fingers[finger];
  double sum = 0.0;
  int n = 0;
  if (f.pad) {  // a soft pad's: the radius of a disc of its pressed skin's area, per body
    std::array<PadTouch, kMaxContactsPerFinger> touches;
    const int count = impl_->padTouches(f, touches);
    for (int k = 0; k < count; ++k) sum += std::sqrt(touches[static_cast<std::size_t>(k)].area / std::numbers::pi);
    n += count;
  }
  for (int k = 0; k < f.soft_count; ++k) {
    if (f.soft[static_cast<std::size_t>(k)].radius <= 0.0) continue;
    sum += f.soft[static_cast<std::size_t>(k)].radius;
    ++n;
  }
  for (int k = 0; k < f.contact_count; ++k) {
    if (!f.contacts[k].record.patch.valid) continue;
    sum += f.contacts[k].record.patch.radius;
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

bool World::deepestTouch(int finger, Touch& out) const {
  GF_ASSERT_OWNER();
  const Impl::Finger& f = impl_->fingers[finger];
  const FingerContact* deepest = nullptr;
  for (int k = 0; k < f.contact_count; ++k) {
    const FingerContact& c = f.contacts[k];
    if (!deepest || c.record.contact.separation < deepest->record.contact.separation) deepest = &c;
  }
  if (f.pad) {  // a soft pad's deepest touch, when deeper than the bone's own
    std::array<PadTouch, kMaxContactsPerFinger> touches;
    const int count = impl_->padTouches(f, touches);
    const PadTouch* pad = nullptr;
    for (int k = 0; k < count; ++k) {
      if (!pad || touches[static_cast<std::size_t>(k)].depth > pad->depth) pad = &touches[static_cast<std::size_t>(k)];
    }
    if (pad && (!deepest || -pad->depth < deepest->record.contact.separation)) {
      out = Touch{pad->body, pad->deepest_point, pad->deepest_normal, -pad->depth};
      return true;
    }
  }
  const SoftTouch* soft = nullptr;  // a soft body's deepest touch, when deeper
  for (int k = 0; k < f.soft_count; ++k) {
    if (!soft || f.soft[static_cast<std::size_t>(k)].separation < soft->separation) soft = &f.soft[static_cast<std::size_t>(k)];
  }
  if (soft && (!deepest || soft->separation < deepest->record.contact.separation)) {
    out = Touch{soft->body, soft->point, soft->normal, soft->separation};
    return true;
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
  for (int b : impl_->soft_bodies) {  // a soft body's motion, its weight's height
    const SoftBody& s = *impl_->bodies[static_cast<std::size_t>(b)].soft;
    e += s.kineticEnergy();
    if (impl_->desc.effects.gravity) e -= s.mass() * impl_->desc.world.gravity.dot(s.frame().position);
  }
  for (const Impl::Finger& f : impl_->fingers) {
    if (f.pad) e += f.pad->kineticEnergy();  // its tissue's motion (its bone's is the proxy's, above)
  }
  return e;
}

void World::applyTorqueImpulse(int body, const Vec3& impulse) {
  GF_ASSERT_OWNER();
  if (impl_->bodies[body].soft) return;  // a soft body takes none (its loads are spread over its nodes)
  impl_->bodies[body].rigid->applyTorqueImpulse(toBt(impulse));
}

void World::setPatchSettings(int finger, const PatchSettings& settings) {
  GF_ASSERT_OWNER();
  std::optional<FieldError> e = validateModelChange(impl_->desc.fingers[finger].patch.model, settings.model);
  if (!e) e = validatePatch(settings);
  if (e) throw DescriptionError("finger '" + impl_->desc.fingers[finger].name + "'", *e);
  impl_->sizeWalks(impl_->fingers[finger], settings.n_sgo);
  impl_->applySettings(impl_->fingers[finger], settings);
}

void World::sizeForLiveSettings() {
  GF_ASSERT_OWNER();
  for (Impl::Finger& f : impl_->fingers) Impl::sizeWalks(f, kMaxSgo);
}

void World::checkWarmWalks(bool on) {
  GF_ASSERT_OWNER();
  impl_->check_walks = on;
}

void World::snapshot(Snapshot& out) const {
  GF_ASSERT_OWNER();
  const Impl& w = *impl_;
  out.time = w.time;
  out.step = w.counters.steps;
  out.nan_recoveries = w.counters.nan_recoveries;
  out.bodies.resize(w.bodies.size());
  out.body_velocities.resize(w.bodies.size());
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const int b = static_cast<int>(i);
    out.bodies[i] = bodyPose(b);
    out.body_velocities[i] = {bodyLinearVelocity(b), bodyAngularVelocity(b)};
  }
  out.fingers.resize(w.fingers.size());
  for (std::size_t i = 0; i < w.fingers.size(); ++i) {
    const Impl::Finger& f = w.fingers[i];
    FingerSnapshot& fs = out.fingers[i];
    fs.device = f.device.position;
    fs.device_orientation = f.device.orientation;
    fs.proxy = toEigen(f.proxy->getCenterOfMassPosition());
    fs.coupling_force = f.force;
    fs.feedback_force = feedbackForce(static_cast<int>(i));
    fs.sgo_count = sgoCount(static_cast<int>(i));
    fs.patch = f.given;
    fs.contacts.resize(f.contact_count);
    // One pose per contact: the body's now, after the step that computed its patch.
    for (int k = 0; k < f.contact_count; ++k) {
      const ContactRecord& r = f.contacts[k].record;
      // Contact k's walks are memory k's since the step (rememberImpulses).
      const Pose frame = w.bodyFrame(r.body);
      toContactSnapshot(r, frame, fs.contacts[k], &f.memory_walks[static_cast<std::size_t>(k)]);
      // The loads on its points, split from the last solve's result only now: snapshots are
      // taken at frame times, and the split costs more than the rest of the contact's step.
      const FingerContact& c = f.contacts[k];
      if (c.block < 0) continue;
      solvedLoads(c, w.solver.block(c.block), w.snapshot_scratch, w.snapshot_loads);
      toSnapshotLoads(w.snapshot_loads, frame, fs.contacts[k]);
    }
    if (f.pad) w.padSnapshot(f, fs);
    w.softSnapshot(f, fs);
  }
  w.softBodySnapshot(out);
}

}  // namespace gf::sim
