// The sphere test against a box or a cylinder (sim/detail/contact_algorithms.hpp) against
// Bullet's own test (GJK on the shapes' cores: a press under the radius plus the rounding
// needs no EPA) on the same shapes, margins included: a sphere of 8 mm (the proxy)
// at 400 random poses around a rounded box and a rounded cylinder (each a random pose itself),
// apart by up to 0.1 mm (within the pair's contact breaking threshold, 0.28 mm) and
// pressed up to 2 mm in; every pose is a contact for both. The gap agrees within 1e-6 m and the normal
// within 1e-3 rad, the point within 1e-5 m, GJK's own tolerance (measured: the box to 1e-16 m,
// the cylinder, a curved support, to 2e-7 m and 3e-5 rad).
#include <gtest/gtest.h>

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "sim/detail/contact_algorithms.hpp"

namespace gf::sim {
namespace {

constexpr btScalar kMargin = 0.0005;  // m: the bodies' rounding (sim/body_factory.cpp)
constexpr btScalar kProxy = 0.008;    // m

// A collision world with Bullet's tests or with ours added.
struct Collide {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  ContactAlgorithms ours;
  std::unique_ptr<btCollisionWorld> world;
  explicit Collide(bool with_ours) {
    if (with_ours) ours.registerWith(dispatcher);
    world = std::make_unique<btCollisionWorld>(&dispatcher, &broadphase, &config);
  }
};

struct Hit {
  bool found = false;
  btScalar gap = 0;
  btVector3 normal_on_solid{0, 0, 0}, on_solid{0, 0, 0};
};

// The deepest point between the sphere and the solid after one collision pass.
Hit collide(bool with_ours, btCollisionShape& solid, const btTransform& solid_pose, const btVector3& centre) {
  Collide c(with_ours);
  btSphereShape sphere(kProxy);
  btCollisionObject a, b;
  a.setCollisionShape(&sphere);
  a.setWorldTransform(btTransform(btQuaternion::getIdentity(), centre));
  b.setCollisionShape(&solid);
  b.setWorldTransform(solid_pose);
  c.world->addCollisionObject(&a);
  c.world->addCollisionObject(&b);
  c.world->performDiscreteCollisionDetection();
  Hit h;
  for (int m = 0; m < c.dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& pm = *c.dispatcher.getManifoldByIndexInternal(m);
    const bool sphere_first = pm.getBody0() == &a;
    for (int k = 0; k < pm.getNumContacts(); ++k) {
      const btManifoldPoint& p = pm.getContactPoint(k);
      if (h.found && p.getDistance() >= h.gap) continue;
      h.found = true;
      h.gap = p.getDistance();
      // m_normalWorldOnB points from body 1 towards body 0.
      h.normal_on_solid = sphere_first ? p.m_normalWorldOnB : -p.m_normalWorldOnB;
      h.on_solid = sphere_first ? p.getPositionWorldOnB() : p.getPositionWorldOnA();
    }
  }
  c.world->removeCollisionObject(&a);
  c.world->removeCollisionObject(&b);
  return h;
}

void compareWithBullet(btConvexShape& solid) {
  solid.setMargin(kMargin);
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), gap(-0.002, 0.0001);
  int compared = 0;
  double worst_gap = 0, worst_angle = 0, worst_point = 0;
  for (int i = 0; i < 400; ++i) {
    const btQuaternion turn(btVector3(unit(rng), unit(rng), unit(rng)).normalized(), 3.0 * unit(rng));
    const btTransform pose(turn, btVector3(unit(rng), unit(rng), unit(rng)) * 0.01);
    // The point of the rounded surface whose normal is a random direction, then the sphere's
    // centre at `gap` outside it along that normal.
    btVector3 dir(unit(rng), unit(rng), unit(rng));
    dir.normalize();
    const btVector3 centre = pose * (solid.localGetSupportingVertexWithoutMargin(dir) + (kMargin + kProxy + gap(rng)) * dir);
    const Hit theirs = collide(false, solid, pose, centre), mine = collide(true, solid, pose, centre);
    ASSERT_EQ(mine.found, theirs.found) << "pose " << i;
    if (!theirs.found) continue;
    ++compared;
    worst_gap = std::max(worst_gap, std::abs(static_cast<double>(mine.gap - theirs.gap)));
    worst_angle = std::max(worst_angle, static_cast<double>(mine.normal_on_solid.angle(theirs.normal_on_solid)));
    worst_point = std::max(worst_point, static_cast<double>((mine.on_solid - theirs.on_solid).length()));
    EXPECT_NEAR(mine.gap, theirs.gap, 1e-6) << "pose " << i;
    EXPECT_GT(mine.normal_on_solid.dot(theirs.normal_on_solid), std::cos(1e-3)) << "pose " << i;
    EXPECT_LT((mine.on_solid - theirs.on_solid).length(), 1e-5) << "pose " << i;
  }
  std::printf("%d poses: gap within %.2g m, normal within %.2g rad, point within %.2g m of GJK/EPA\n", compared,
              worst_gap, worst_angle, worst_point);
  EXPECT_EQ(compared, 400) << "every pose within the breaking threshold is a contact";
}

TEST(RoundedContact, SphereOnABoxAgreesWithBulletsGjk) {
  const btVector3 half(0.03, 0.02, 0.01);
  btBoxShape box(half);
  compareWithBullet(box);
}

TEST(RoundedContact, SphereOnACylinderAgreesWithBulletsGjk) {
  const btVector3 half(0.03, 0.05, 0.03);
  btCylinderShape cylinder(half);
  compareWithBullet(cylinder);
}

}  // namespace
}  // namespace gf::sim
