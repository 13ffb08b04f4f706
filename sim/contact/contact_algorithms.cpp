// The plane contact test (sim/contact/contact_algorithms.hpp): a box's, a cylinder's or a hull's
// points near a static plane, chosen by the body's geometry so that a resting body keeps them.
#include "sim/contact/contact_algorithms.hpp"

#include <algorithm>
#include <cmath>

namespace gf::sim {
namespace {

// A point within this distance of the deepest one takes part in the contact (m). Far above
// the tilt of a body at rest (a 3 cm puck tilted by 1e-7 rad: 6e-9 m), far below what a tilt
// that lifts one side off the plane shows. A point chosen this far above the plane is a
// speculative contact: the solver lets it close, it pushes nothing.
constexpr btScalar kActiveBand = 1e-5;
// The extremes are taken along two body-fixed directions at this angle (rad) to the body's
// axes: along an axis itself, a box face's corners or a regular polygon's vertices tie.
constexpr btScalar kPickAngle = 0.349;  // 20 degrees
// A cylinder's points on each end's rim, at quarter turns from its first cross axis.
constexpr int kRimPoints = 4;

// The four extremes, along +u, -u, +w and -w, of the points offered: the first offered wins
// a tie, so points that belong to the body (offered in a fixed order) win over computed ones.
struct Extremes {
  btVector3 u, w;
  btVector3 point[4];
  btScalar key[4] = {-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT};

  void offer(const btVector3& q) {
    const btScalar along[4] = {u.dot(q), -u.dot(q), w.dot(q), -w.dot(q)};
    for (int k = 0; k < 4; ++k) {
      if (along[k] > key[k]) {
        key[k] = along[k];
        point[k] = q;
      }
    }
  }
};

// The plane in the convex body's frame: its outward normal and the distance of a point above it.
struct LocalPlane {
  btVector3 normal;
  btScalar offset = 0;
  btScalar distance(const btVector3& q) const { return normal.dot(q) - offset; }
};

// Visits the points of `shape` that can touch a plane below `plane.normal`, in the body frame
// (its rounding margin included): a box's or a hull's vertices; a cylinder's rim points at quarter turns on
// both ends, and the lowest point of an end's rim where that end is tilted more than the active
// band (on a flat end the rim points stand for the whole face).
template <class Visit>
void visitCandidates(const btConvexShape& shape, const LocalPlane& plane, Visit&& visit) {
  const btScalar margin = shape.getMargin();
  const btVector3 rounding = -margin * plane.normal;
  if (shape.getShapeType() == CYLINDER_SHAPE_PROXYTYPE) {
    const auto& cylinder = static_cast<const btCylinderShape&>(shape);
    const int up = cylinder.getUpAxis();
    const btVector3 inner = cylinder.getHalfExtentsWithoutMargin();
    const int a = (up + 1) % 3, b = (up + 2) % 3;
    const btScalar radius = inner[up == 0 ? 1 : 0];  // Bullet's: x, or y when the axis is x
    btVector3 axis(0, 0, 0), e1(0, 0, 0), e2(0, 0, 0);
    axis[up] = 1;
    e1[a] = 1;
    e2[b] = 1;
    const btVector3 down_in_end = -(plane.normal - plane.normal.dot(axis) * axis);
    const btScalar tilt = down_in_end.length();
    for (const btScalar side : {btScalar(-1), btScalar(1)}) {
      const btVector3 centre = side * inner[up] * axis;
      for (int k = 0; k < kRimPoints; ++k) {
        const btScalar angle = SIMD_2_PI * k / kRimPoints;
        visit(centre + radius * (std::cos(angle) * e1 + std::sin(angle) * e2) + rounding);
      }
    }
    if (2 * radius * tilt > kActiveBand) {
      for (const btScalar side : {btScalar(-1), btScalar(1)}) {
        visit(side * inner[up] * axis + (radius / tilt) * down_in_end + rounding);
      }
    }
    return;
  }
  const auto& polyhedron = static_cast<const btPolyhedralConvexShape&>(shape);
  btVector3 vertex;
  for (int i = 0; i < polyhedron.getNumVertices(); ++i) {
    polyhedron.getVertex(i, vertex);
    visit(vertex + rounding);
  }
}

// A test of a pair with one manifold, its own unless it was given one (a compound's parts may
// share their parent's); the manifold's first body is `first`.
class ManifoldAlgorithm : public btCollisionAlgorithm {
 public:
  ManifoldAlgorithm(btPersistentManifold* shared, const btCollisionAlgorithmConstructionInfo& ci,
                    const btCollisionObject* first, const btCollisionObject* second)
      : btCollisionAlgorithm(ci), manifold_(shared) {
    if (!manifold_ && m_dispatcher->needsCollision(first, second)) {
      manifold_ = m_dispatcher->getNewManifold(first, second);
      own_manifold_ = true;
    }
  }
  ~ManifoldAlgorithm() override {
    if (own_manifold_ && manifold_) m_dispatcher->releaseManifold(manifold_);
  }
  ManifoldAlgorithm(const ManifoldAlgorithm&) = delete;
  ManifoldAlgorithm& operator=(const ManifoldAlgorithm&) = delete;

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (manifold_ && own_manifold_) manifolds.push_back(manifold_);
  }

 protected:
  // Drops the manifold's points that none of `kept` (world points on its first body, within
  // the breaking threshold) continues.
  void dropOthers(const btVector3* kept, int count);

  btPersistentManifold* manifold_;
  bool own_manifold_ = false;
};

class PlaneContactAlgorithm final : public ManifoldAlgorithm {
 public:
  PlaneContactAlgorithm(btPersistentManifold* shared, const btCollisionAlgorithmConstructionInfo& ci,
                        const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1, bool swapped)
      : ManifoldAlgorithm(shared, ci, (swapped ? body1 : body0)->getCollisionObject(),
                          (swapped ? body0 : body1)->getCollisionObject()),
        swapped_(swapped) {}

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo&, btManifoldResult* result) override;

 private:
  bool swapped_;
};

class SphereContactAlgorithm final : public ManifoldAlgorithm {
 public:
  SphereContactAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                         const btCollisionObjectWrapper* body1)
      : ManifoldAlgorithm(ci.m_manifold, ci, body0->getCollisionObject(), body1->getCollisionObject()) {}

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo&, btManifoldResult* result) override;
};

// A sphere (a proxy, a ball) on a box or a cylinder: the closest point of the solid, its
// rounding margin included, to the sphere's centre, in closed form. Bullet's GJK finds the same
// point iteratively, and how many iterations it takes depends on the last digits of the pose: a
// pinch held still cost from 19 to 25 M instructions per 1000 steps by how the cylinder stood.
class RoundedContactAlgorithm final : public ManifoldAlgorithm {
 public:
  RoundedContactAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                          const btCollisionObjectWrapper* body1, bool swapped)
      : ManifoldAlgorithm(ci.m_manifold, ci, body0->getCollisionObject(), body1->getCollisionObject()),
        swapped_(swapped) {}

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo&, btManifoldResult* result) override;

 private:
  bool swapped_;  // the sphere is body1
};

// The point of the solid inner shape (a box's or a cylinder's, without its rounding) nearest to
// `c` (shape frame), and the outward normal there; a centre inside leaves by the nearest side.
// Returns the signed distance from the inner shape (negative inside).
btScalar nearestOnInner(const btConvexShape& shape, const btVector3& c, btVector3& nearest, btVector3& normal) {
  if (shape.getShapeType() == BOX_SHAPE_PROXYTYPE) {
    // A box thinner than twice the rounding has no inner extent left along that axis.
    btVector3 h = static_cast<const btBoxShape&>(shape).getHalfExtentsWithoutMargin();
    h.setMax(btVector3(0, 0, 0));
    nearest = btVector3(btClamped(c.x(), -h.x(), h.x()), btClamped(c.y(), -h.y(), h.y()), btClamped(c.z(), -h.z(), h.z()));
    const btVector3 out = c - nearest;
    const btScalar length = out.length();
    if (length > SIMD_EPSILON) {
      normal = out / length;
      return length;
    }
    int axis = 0;  // inside: the face nearest to the centre
    btScalar room = BT_LARGE_FLOAT;
    for (int i = 0; i < 3; ++i) {
      if (h[i] - std::abs(c[i]) < room) room = h[i] - std::abs(c[i]), axis = i;
    }
    normal = btVector3(0, 0, 0);
    normal[axis] = c[axis] < 0 ? -1 : 1;
    nearest = c;
    nearest[axis] = normal[axis] * h[axis];
    return -room;
  }
  const auto& cylinder = static_cast<const btCylinderShape&>(shape);
  // Bullet's cylinder takes its radius from x, or from y when its axis is x.
  const int up = cylinder.getUpAxis(), a = up == 0 ? 1 : 0;
  const btVector3 inner = cylinder.getHalfExtentsWithoutMargin();
  const btScalar radius = std::max<btScalar>(inner[a], 0), half = std::max<btScalar>(inner[up], 0);
  btVector3 across = c;
  across[up] = 0;
  const btScalar rho = across.length();
  const btVector3 radial = rho > SIMD_EPSILON ? across / rho : btVector3(a == 0 ? 1 : 0, a == 1 ? 1 : 0, a == 2 ? 1 : 0);
  nearest = std::min(rho, radius) * radial;
  nearest[up] = btClamped(c[up], -half, half);
  const btVector3 out = c - nearest;
  const btScalar length = out.length();
  if (length > SIMD_EPSILON) {
    normal = out / length;
    return length;
  }
  const btScalar to_side = radius - rho, to_end = half - std::abs(c[up]);
  if (to_side < to_end) {
    normal = radial;
    nearest = radius * radial;
    nearest[up] = c[up];
    return -to_side;
  }
  normal = btVector3(0, 0, 0);
  normal[up] = c[up] < 0 ? -1 : 1;
  nearest = c;
  nearest[up] = normal[up] * half;
  return -to_end;
}

void RoundedContactAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                               const btCollisionObjectWrapper* body1, const btDispatcherInfo&,
                                               btManifoldResult* result) {
  if (!manifold_) return;
  result->setPersistentManifold(manifold_);
  const btCollisionObjectWrapper* sphere_wrap = swapped_ ? body1 : body0;
  const btCollisionObjectWrapper* solid_wrap = swapped_ ? body0 : body1;
  const btScalar r = static_cast<const btSphereShape*>(sphere_wrap->getCollisionShape())->getRadius();
  const auto& solid = *static_cast<const btConvexShape*>(solid_wrap->getCollisionShape());
  const btTransform& pose = solid_wrap->getWorldTransform();
  const btVector3 centre = sphere_wrap->getWorldTransform().getOrigin();
  btVector3 nearest, normal;
  const btScalar inner = nearestOnInner(solid, pose.invXform(centre), nearest, normal);
  const btScalar margin = solid.getMargin(), gap = inner - margin - r;
  if (gap > manifold_->getContactBreakingThreshold()) {
    if (own_manifold_) manifold_->clearManifold();
    return;
  }
  const btVector3 n = pose.getBasis() * normal;  // from the solid towards the sphere
  const btVector3 on_solid = pose * nearest + margin * n, on_sphere = centre - r * n;
  if (own_manifold_) {
    const btVector3 on_first = manifold_->getBody0() == sphere_wrap->getCollisionObject() ? on_sphere : on_solid;
    dropOthers(&on_first, 1);
  }
  // The manifold result takes the normal on body1 and the point on body1.
  if (swapped_) {
    result->addContactPoint(-n, on_sphere, gap);
  } else {
    result->addContactPoint(n, on_solid, gap);
  }
}

void PlaneContactAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                             const btCollisionObjectWrapper* body1, const btDispatcherInfo&,
                                             btManifoldResult* result) {
  if (!manifold_) return;
  const btCollisionObjectWrapper* convex_wrap = swapped_ ? body1 : body0;
  const btCollisionObjectWrapper* plane_wrap = swapped_ ? body0 : body1;
  const auto& shape = *static_cast<const btConvexShape*>(convex_wrap->getCollisionShape());
  const auto& plane_shape = *static_cast<const btStaticPlaneShape*>(plane_wrap->getCollisionShape());
  const btTransform& body = convex_wrap->getWorldTransform();
  const btTransform& plane_pose = plane_wrap->getWorldTransform();
  const btVector3 normal = plane_pose.getBasis() * plane_shape.getPlaneNormal();
  const btVector3 on_plane = plane_pose * (plane_shape.getPlaneNormal() * plane_shape.getPlaneConstant());
  LocalPlane plane;
  plane.normal = body.getBasis().transpose() * normal;
  plane.offset = plane.normal.dot(body.invXform(on_plane));
  result->setPersistentManifold(manifold_);

  btScalar deepest = BT_LARGE_FLOAT;
  visitCandidates(shape, plane, [&](const btVector3& q) { deepest = std::min(deepest, plane.distance(q)); });
  const btScalar breaking = manifold_->getContactBreakingThreshold();
  if (deepest >= breaking) {
    if (own_manifold_) manifold_->clearManifold();
    return;
  }
  // Two body-fixed directions across the plane: the body axes least along its normal, turned.
  int across = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(plane.normal[i]) > std::abs(plane.normal[across])) across = i;
  }
  btVector3 e1(0, 0, 0), e2(0, 0, 0);
  e1[(across + 1) % 3] = 1;
  e2[(across + 2) % 3] = 1;
  Extremes ex;
  ex.u = std::cos(kPickAngle) * e1 + std::sin(kPickAngle) * e2;
  ex.w = -std::sin(kPickAngle) * e1 + std::cos(kPickAngle) * e2;
  visitCandidates(shape, plane, [&](const btVector3& q) {
    if (plane.distance(q) < deepest + kActiveBand) ex.offer(q);
  });
  btVector3 chosen[4], world[4];
  int count = 0;
  for (const btVector3& q : ex.point) {
    bool seen = false;
    for (int k = 0; k < count; ++k) seen = seen || chosen[k] == q;
    if (!seen) {
      chosen[count] = q;
      world[count++] = body * q;
    }
  }
  if (own_manifold_) dropOthers(world, count);
  for (int k = 0; k < count; ++k) {
    const btScalar d = plane.distance(chosen[k]);
    result->addContactPoint(normal, world[k] - d * normal, d);
  }
  if (own_manifold_ && manifold_->getNumContacts() > 0) result->refreshContactPoints();
}

// The two spheres' closest points while their gap is within the breaking threshold, one point.
void SphereContactAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                              const btCollisionObjectWrapper* body1, const btDispatcherInfo&,
                                              btManifoldResult* result) {
  if (!manifold_) return;
  result->setPersistentManifold(manifold_);
  const btScalar r0 = static_cast<const btSphereShape*>(body0->getCollisionShape())->getRadius();
  const btScalar r1 = static_cast<const btSphereShape*>(body1->getCollisionShape())->getRadius();
  const btVector3 c0 = body0->getWorldTransform().getOrigin(), c1 = body1->getWorldTransform().getOrigin();
  const btVector3 apart = c0 - c1;
  const btScalar length = apart.length();
  const btScalar gap = length - r0 - r1;
  if (gap > manifold_->getContactBreakingThreshold()) {
    if (own_manifold_) manifold_->clearManifold();
    return;
  }
  const btVector3 normal_on_1 = length > SIMD_EPSILON ? apart / length : btVector3(1, 0, 0);
  const btVector3 on_0 = c0 - r0 * normal_on_1;
  // The manifold's first body is the first sphere (getNewManifold(body0, body1)).
  if (own_manifold_ && manifold_->getBody0() == body0->getCollisionObject()) dropOthers(&on_0, 1);
  result->addContactPoint(normal_on_1, c1 + r1 * normal_on_1, gap);
}

void ManifoldAlgorithm::dropOthers(const btVector3* kept, int count) {
  // The points are kept in the first object's frame (a compound's, for a part of one).
  const btTransform& object = manifold_->getBody0()->getWorldTransform();
  const btScalar reach2 = manifold_->getContactBreakingThreshold() * manifold_->getContactBreakingThreshold();
  for (int i = manifold_->getNumContacts() - 1; i >= 0; --i) {
    const btVector3 on_body = object * manifold_->getContactPoint(i).m_localPointA;
    bool continued = false;
    for (int k = 0; k < count; ++k) continued = continued || (kept[k] - on_body).length2() < reach2;
    if (!continued) manifold_->removeContactPoint(i);
  }
}

}  // namespace

btCollisionAlgorithm* PlaneContactCreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                       const btCollisionObjectWrapper* body0,
                                                                       const btCollisionObjectWrapper* body1) {
  void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(PlaneContactAlgorithm));
  return new (memory) PlaneContactAlgorithm(ci.m_manifold, ci, body0, body1, m_swapped);
}

btCollisionAlgorithm* SphereContactCreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                        const btCollisionObjectWrapper* body0,
                                                                        const btCollisionObjectWrapper* body1) {
  void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(SphereContactAlgorithm));
  return new (memory) SphereContactAlgorithm(ci, body0, body1);
}

btCollisionAlgorithm* RoundedContactCreateFunc::CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                                         const btCollisionObjectWrapper* body0,
                                                                         const btCollisionObjectWrapper* body1) {
  void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(RoundedContactAlgorithm));
  return new (memory) RoundedContactAlgorithm(ci, body0, body1, m_swapped);
}

void ContactAlgorithms::registerWith(btCollisionDispatcher& dispatcher) {
  dispatcher.registerCollisionCreateFunc(SPHERE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE, &spheres);
  for (const int solid : {BOX_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE}) {
    dispatcher.registerCollisionCreateFunc(SPHERE_SHAPE_PROXYTYPE, solid, &sphere_first);
    dispatcher.registerCollisionCreateFunc(solid, SPHERE_SHAPE_PROXYTYPE, &solid_first);
  }
  for (const int convex : {BOX_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE}) {
    dispatcher.registerCollisionCreateFunc(convex, STATIC_PLANE_PROXYTYPE, &convex_first);
    dispatcher.registerCollisionCreateFunc(STATIC_PLANE_PROXYTYPE, convex, &plane_first);
  }
}

}  // namespace gf::sim
