#include "sim/contact/contact_injection.hpp"

#include <algorithm>
#include <cmath>

namespace gf::sim {
namespace {

// Bullet's persistent manifolds hold this many points.
constexpr int kPointsPerManifold = MANIFOLD_CACHE_SIZE;

void applyMaterial(btManifoldPoint& p, const PointMaterial& mat, const WarmStart& warm) {
  p.m_combinedFriction = mat.friction;
  p.m_combinedRollingFriction = 0.0;
  p.m_combinedSpinningFriction = 0.0;
  p.m_combinedRestitution = 0.0;
  // Compliant contact; friction directions given here (with the solver's direction caching).
  p.m_contactPointFlags =
      BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING | BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
  p.m_combinedContactStiffness1 = mat.stiffness;
  p.m_combinedContactDamping1 = mat.damping;
  btPlaneSpace1(p.m_normalWorldOnB, p.m_lateralFrictionDir1, p.m_lateralFrictionDir2);
  p.m_appliedImpulse = warm.normal;
  p.m_appliedImpulseLateral1 = warm.lateral1;
  p.m_appliedImpulseLateral2 = warm.lateral2;
}

}  // namespace

bool deepestContact(const btPersistentManifold& m, const btCollisionObject* proxy, TrueContact& out) {
  if (m.getNumContacts() == 0) return false;
  int best = 0;
  for (int i = 1; i < m.getNumContacts(); ++i) {
    if (m.getContactPoint(i).getDistance() < m.getContactPoint(best).getDistance()) best = i;
  }
  const btManifoldPoint& p = m.getContactPoint(best);
  // normalWorldOnB points from B towards A; the object is B when the proxy is A.
  const bool proxy_is_a = m.getBody0() == proxy;
  out.object = proxy_is_a ? m.getBody1() : m.getBody0();
  out.point_world = proxy_is_a ? p.m_positionWorldOnB : p.m_positionWorldOnA;
  out.outward_normal_world = proxy_is_a ? p.m_normalWorldOnB : -p.m_normalWorldOnB;
  out.separation = p.getDistance();
  out.index = best;
  return true;
}

void keepOnlyPoint(btPersistentManifold& m, int index, const PointMaterial& mat, const WarmStart& warm) {
  btManifoldPoint kept = m.getContactPoint(index);
  applyMaterial(kept, mat, warm);
  m.clearManifold();
  m.addManifoldPoint(kept);
}

void injectPoints(btDispatcher& dispatcher, const btCollisionObject* proxy,
                  const btCollisionObject* object, const btVector3* points_world, int count,
                  const btVector3& outward_normal_world, const double* separations,
                  const PointMaterial* materials, const WarmStart* warm,
                  std::vector<btPersistentManifold*>& added) {
  const btTransform proxy_inv = proxy->getWorldTransform().inverse();
  const btTransform object_inv = object->getWorldTransform().inverse();
  for (int first = 0; first < count; first += kPointsPerManifold) {
    btPersistentManifold* m = dispatcher.getNewManifold(proxy, object);
    added.push_back(m);
    for (int i = first; i < std::min(count, first + kPointsPerManifold); ++i) {
      // On B (object): the SGO. On A (proxy): displaced along the normal by the separation.
      const btVector3 on_b = points_world[i];
      const btVector3 on_a = on_b + outward_normal_world * separations[i];
      btManifoldPoint p(proxy_inv * on_a, object_inv * on_b, outward_normal_world, separations[i]);
      p.m_positionWorldOnA = on_a;
      p.m_positionWorldOnB = on_b;
      applyMaterial(p, materials[i], warm[i]);
      m->addManifoldPoint(p);
    }
  }
}

WarmStart warmStartByAngle(const WarmStart* remembered, int n_old, int i, int n) {
  if (n_old == n) return remembered[i];
  if (n_old <= 0 || n <= 0) return {};
  const double x = static_cast<double>(i) * n_old / n;
  const int i0 = static_cast<int>(x) % n_old, i1 = (i0 + 1) % n_old;
  const double w = x - std::floor(x), scale = static_cast<double>(n_old) / n;
  const WarmStart& a = remembered[i0];
  const WarmStart& b = remembered[i1];
  return {scale * ((1 - w) * a.normal + w * b.normal), scale * ((1 - w) * a.lateral1 + w * b.lateral1),
          scale * ((1 - w) * a.lateral2 + w * b.lateral2)};
}

WarmStart solvedImpulses(const btManifoldPoint& p) {
  return {p.m_appliedImpulse, p.m_appliedImpulseLateral1, p.m_appliedImpulseLateral2};
}

WarmStart solvedImpulses(const std::vector<btPersistentManifold*>& added, int first, int i) {
  const btPersistentManifold& m = *added[first + i / kPointsPerManifold];
  return solvedImpulses(m.getContactPoint(i % kPointsPerManifold));
}

void releaseInjected(btDispatcher& dispatcher, std::vector<btPersistentManifold*>& added) {
  for (auto it = added.rbegin(); it != added.rend(); ++it) dispatcher.releaseManifold(*it);
  added.clear();
}

}  // namespace gf::sim
