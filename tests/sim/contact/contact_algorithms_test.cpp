// The sphere test against a box or a cylinder (sim/contact/contact_algorithms.hpp): a sphere of
// 8 mm (the proxy) at 400 random poses around a rounded box and a rounded cylinder (each at a
// random pose), apart by up to 0.1 mm (within the pair's contact breaking threshold, 0.28 mm)
// or pressed up to 2 mm in, over corners and rims, face, side and end interiors, and with the
// centre inside the solid's core. The answer is known by construction: outside the core
// the gap, normal and point match it to rounding; so they do inside the core (the shortest way
// out among the faces). Where Bullet's own test is exact (every box pose, a cylinder's corners
// and rims) they match it too, with either body first, and each is a contact for both.
#include <gtest/gtest.h>

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>
#include <memory>
#include <random>

#include "sim/contact/contact_algorithms.hpp"

namespace gf::sim {
namespace {

constexpr btScalar kMargin = 0.0005;  // m: the bodies' rounding (sim/world/body_factory.cpp)
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
// `solid_first`: the solid is added first, so that it is the pair's first body (the World adds
// bodies before proxies).
Hit collide(bool with_ours, bool solid_first, btCollisionShape& solid, const btTransform& solid_pose,
            const btVector3& centre) {
  Collide c(with_ours);
  btSphereShape sphere(kProxy);
  btCollisionObject a, b;
  a.setCollisionShape(&sphere);
  a.setWorldTransform(btTransform(btQuaternion::getIdentity(), centre));
  b.setCollisionShape(&solid);
  b.setWorldTransform(solid_pose);
  c.world->addCollisionObject(solid_first ? &b : &a);
  c.world->addCollisionObject(solid_first ? &a : &b);
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

// The sphere's centre for pose i: outside the rounded surface by `gap` along the normal of a
// point with a random normal (a corner's or a rim's rounding, mostly), of a random point of a
// face, a side or an end (every third pose), or inside the solid's core (every fifth: Bullet
// then runs EPA).
struct Sample {
  btVector3 centre;
  bool deep = false;
  // Outside the core, the answer by construction (the solid's frame): the gap, the outward
  // normal and the nearest point of the rounded surface.
  btScalar gap = 0;
  btVector3 normal{0, 0, 0}, on_solid{0, 0, 0};
};
// For a centre inside the core, the answer by construction: the shortest way out of the core
// among its faces (a box's six; a cylinder's side and two ends), then the rounding.
void deepAnswer(const btConvexShape& solid, Sample& s) {
  struct Exit {
    btScalar depth;
    btVector3 normal, on_core;
  };
  std::vector<Exit> exits;
  const btVector3& c = s.centre;
  if (solid.getShapeType() == BOX_SHAPE_PROXYTYPE) {
    const btVector3 h = static_cast<const btBoxShape&>(solid).getHalfExtentsWithoutMargin();
    for (int axis = 0; axis < 3; ++axis) {
      for (const btScalar side : {btScalar(-1), btScalar(1)}) {
        btVector3 n(0, 0, 0), q = c;
        n[axis] = side;
        q[axis] = side * h[axis];
        exits.push_back({h[axis] - side * c[axis], n, q});
      }
    }
  } else {  // a cylinder along y: radius x, half height y
    const btVector3 h = static_cast<const btCylinderShape&>(solid).getHalfExtentsWithoutMargin();
    const btVector3 radial = btVector3(c.x(), 0, c.z()).normalized();
    exits.push_back({h.x() - btVector3(c.x(), 0, c.z()).length(), radial, btVector3(0, c.y(), 0) + h.x() * radial});
    for (const btScalar side : {btScalar(-1), btScalar(1)}) {
      exits.push_back({h.y() - side * c.y(), btVector3(0, side, 0), btVector3(c.x(), side * h.y(), c.z())});
    }
  }
  const Exit& best = *std::min_element(exits.begin(), exits.end(), [](const Exit& a, const Exit& b) { return a.depth < b.depth; });
  s.gap = -best.depth - kMargin - kProxy;
  s.normal = best.normal;
  s.on_solid = best.on_core + kMargin * best.normal;
}

Sample sampleAround(const btConvexShape& solid, std::mt19937_64& rng, int i) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), gap(-0.002, 0.0001);
  if (i % 5 == 4) {  // inside the core: within the inner shape's half extents, shrunk
    btVector3 lo, hi;
    solid.getAabb(btTransform::getIdentity(), lo, hi);
    const btVector3 half = 0.5 * (hi - lo) - btVector3(1, 1, 1) * (kMargin + 0.004);
    const btVector3 c(0.9 * half.x() * unit(rng), 0.9 * half.y() * unit(rng), 0.9 * half.z() * unit(rng));
    const bool inside = solid.getShapeType() != CYLINDER_SHAPE_PROXYTYPE || c.x() * c.x() + c.z() * c.z() < half.x() * half.x();
    Sample deep{inside ? c : btVector3(0.001, c.y(), 0), true, 0, {0, 0, 0}, {0, 0, 0}};
    deepAnswer(solid, deep);
    return deep;
  }
  btVector3 dir(unit(rng), unit(rng), unit(rng));
  if (i % 3 == 2) {  // a face (a box's, a cylinder's side or end): one axis dominates
    const int axis = static_cast<int>(rng() % 3);
    for (int k = 0; k < 3; ++k) dir[k] = k == axis ? (unit(rng) < 0 ? -1.0 : 1.0) : 0.0;
  }
  dir.normalize();
  btVector3 on_core = solid.localGetSupportingVertexWithoutMargin(dir);
  if (i % 3 == 2) {  // a random point of that face, not its corner
    for (int k = 0; k < 3; ++k) {
      if (dir[k] == 0.0) on_core[k] *= 0.8 * std::abs(unit(rng));
    }
  }
  const btScalar g = gap(rng);
  return {on_core + (kMargin + kProxy + g) * dir, false, g, dir, on_core + kMargin * dir};
}

void compareWithBullet(btConvexShape& solid) {
  solid.setMargin(kMargin);
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0, deep = 0;
  double worst_gap = 0, worst_angle = 0, worst_point = 0;
  for (int i = 0; i < 400; ++i) {
    const btQuaternion turn(btVector3(unit(rng), unit(rng), unit(rng)).normalized(), 3.0 * unit(rng));
    const btTransform pose(turn, btVector3(unit(rng), unit(rng), unit(rng)) * 0.01);
    const Sample sample = sampleAround(solid, rng, i);
    const btVector3 centre = pose * sample.centre;
    {  // against the construction: exact to rounding
      const Hit mine = collide(true, true, solid, pose, centre);
      ASSERT_TRUE(mine.found) << "pose " << i;
      EXPECT_NEAR(mine.gap, sample.gap, 1e-12) << "pose " << i;
      EXPECT_GT(mine.normal_on_solid.dot(pose.getBasis() * sample.normal), 1.0 - 1e-12) << "pose " << i;
      EXPECT_LT((mine.on_solid - pose * sample.on_solid).length(), 1e-12) << "pose " << i;
    }
    for (const bool solid_first : {false, true}) {
      const Hit theirs = collide(false, solid_first, solid, pose, centre);
      const Hit mine = collide(true, solid_first, solid, pose, centre);
      ASSERT_EQ(mine.found, theirs.found) << "pose " << i;
      if (!theirs.found) continue;
      ++compared;
      deep += sample.deep;
      // Against Bullet's test where it is exact: a box's polytope, a cylinder's corners and rims
      // (GJK stops within 1e-3 of the cores' distance on a curved support, so a cylinder's
      // face, side or end point and EPA inside its core are only its approximations).
      if (solid.getShapeType() == CYLINDER_SHAPE_PROXYTYPE && (sample.deep || i % 3 == 2)) continue;
      const double tolerance = 2e-5;
      worst_gap = std::max(worst_gap, std::abs(static_cast<double>(mine.gap - theirs.gap)));
      worst_angle = std::max(worst_angle, static_cast<double>(mine.normal_on_solid.angle(theirs.normal_on_solid)));
      worst_point = std::max(worst_point, static_cast<double>((mine.on_solid - theirs.on_solid).length()));
      EXPECT_NEAR(mine.gap, theirs.gap, tolerance) << "pose " << i;
      EXPECT_GT(mine.normal_on_solid.dot(theirs.normal_on_solid), std::cos(1e-3)) << "pose " << i;
      EXPECT_LT((mine.on_solid - theirs.on_solid).length(), 10 * tolerance) << "pose " << i;
    }
  }
  std::printf("%d contacts (%d with the centre in the core): gap within %.2g m, normal within %.2g rad, point within "
              "%.2g m of Bullet's\n",
              compared, deep, worst_gap, worst_angle, worst_point);
  EXPECT_GT(compared, 400) << "poses compared with Bullet's test";
}

TEST(RoundedContact, SphereOnABoxIsExactAndMatchesBullet) {
  const btVector3 half(0.03, 0.02, 0.01);
  btBoxShape box(half);
  compareWithBullet(box);
}

TEST(RoundedContact, SphereOnACylinderIsExactAndMatchesBullet) {
  const btVector3 half(0.03, 0.05, 0.03);
  btCylinderShape cylinder(half);
  compareWithBullet(cylinder);
}

}  // namespace
}  // namespace gf::sim
