// Collision tests of our own, where Bullet's lose a contact a body rests on.
//
// A box, a cylinder or a convex hull on a static plane: the face it rests on, whole, at every
// step. Bullet's own convex–plane test adds one support point a step to a four-point
// manifold. A flat cylinder's support point is anywhere on its rim, chosen by the last digits
// of its tilt (a finger's patch wobbles it by 1e-7 rad), and so is a flat hull face's among its
// vertices; the manifold's area rule then keeps, now and then, three points on one side of the
// load, the body tips for a step and is kicked back (a pressed puck: 21 to 36 steps in 1.5 s
// above 1 mm/s). A spinning box's corners move farther a step than the manifold keeps a point,
// so its support came and went, and the press on it with it (a pressed box spun at 12 rad/s
// lost 6 % of its press). This test picks the points from the body's geometry instead: the points of
// the shape within a few micrometres of its deepest point, reduced to the four extremes along
// two body-fixed directions, so a body that rests keeps the same four points step after step.
//
// Two spheres (a proxy on a ball): Bullet's test empties the manifold and adds no point while
// the spheres are apart, so a proxy pushed a micrometre off a ball lost its contact, and its
// patch, for that step (Fig. 5 with a filled patch flickered 24 <-> 0 SGOs every few steps and
// the ball was shot ahead). This one keeps the point while the gap is within the contact
// breaking threshold, as Bullet's tests of other shapes do.
//
// A sphere on a box or a cylinder (a proxy on the bodies most scenes hold): the nearest point in
// closed form, where Bullet's GJK takes as many iterations as the pose's last digits ask.
// Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

namespace gf::sim {

/// Creates the plane contact test for a (box, cylinder or convex hull; plane) pair; `swapped`
/// for (plane; box, cylinder or convex hull).
class PlaneContactCreateFunc final : public btCollisionAlgorithmCreateFunc {
 public:
  explicit PlaneContactCreateFunc(bool swapped) { m_swapped = swapped; }
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override;
};

/// Creates the sphere–sphere test.
class SphereContactCreateFunc final : public btCollisionAlgorithmCreateFunc {
 public:
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override;
};

/// Creates the sphere test against a box or a cylinder; `swapped` for (box or cylinder; sphere).
class RoundedContactCreateFunc final : public btCollisionAlgorithmCreateFunc {
 public:
  explicit RoundedContactCreateFunc(bool swapped) { m_swapped = swapped; }
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override;
};

/// The tests' create functions; declared before the dispatcher they are registered with, so
/// that they outlive it.
struct ContactAlgorithms {
  PlaneContactCreateFunc convex_first{false}, plane_first{true};
  SphereContactCreateFunc spheres;
  RoundedContactCreateFunc sphere_first{false}, solid_first{true};
  /// Registers the plane test for boxes, cylinders and convex hulls (alone or as parts of a
  /// compound) against static planes, the sphere–sphere test and the sphere's test against a
  /// box or a cylinder.
  void registerWith(btCollisionDispatcher& dispatcher);
};

}  // namespace gf::sim
