// Step safety of a World: the states saved before each step, a step whose result is not finite
// rolled back (counted in WorldCounters::nan_recoveries), and proxies stopped where a long step
// would have carried them through a thin body.
#include <cmath>

#include "sim/world/world_impl.hpp"

namespace gf::sim {

void World::Impl::saveStates() {
  std::size_t i = 0;
  auto save = [&](const btRigidBody& r) {
    saved[i++] = {r.getWorldTransform(), r.getLinearVelocity(), r.getAngularVelocity()};
  };
  for (const Body& b : bodies) save(*b.rigid);
  for (const Finger& f : fingers) save(*f.proxy);
}

// After the solve: a state that is not finite rolls the step back; else proxies that went
// through a body in this step are stopped at its surface.
void World::Impl::checkStep() {
  if (!statesFinite()) {
    restoreStates();
    ++counters.nan_recoveries;
  } else {
    stopTunnelling();
  }
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

}  // namespace gf::sim
