// Bullet-level mechanics of god-finger contacts: a dynamics world that lets us add contact
// points between collision detection and the solve, and the manifold helpers. Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <vector>

namespace gf::sim {

/// Called by GodFingerDynamicsWorld around each constraint solve (haptic thread).
class SolveHooks {
 public:
  virtual ~SolveHooks() = default;
  /// After collision detection: read the true contacts, add SGO points.
  virtual void beforeSolve() = 0;
  /// After the solve: release what beforeSolve added.
  virtual void afterSolve() = 0;
};

/// btDiscreteDynamicsWorld whose solve is bracketed by SolveHooks.
class GodFingerDynamicsWorld final : public btDiscreteDynamicsWorld {
 public:
  GodFingerDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                         btConstraintSolver* solver, btCollisionConfiguration* config,
                         SolveHooks* hooks)
      : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, config), hooks_(hooks) {}

  void solveConstraints(btContactSolverInfo& info) override {
    hooks_->beforeSolve();
    btDiscreteDynamicsWorld::solveConstraints(info);
    hooks_->afterSolve();
  }

 private:
  SolveHooks* hooks_;
};

/// The deepest point of a proxy's manifold, expressed from the touched object's side, as Bullet
/// reports it this step (world frame). `object` is valid for the step only.
struct TrueContact {
  const btCollisionObject* object = nullptr;
  btVector3 point_world{0, 0, 0};           ///< c_p: on the object's surface (m)
  btVector3 outward_normal_world{0, 1, 0};  ///< from the object towards the proxy (unit)
  double separation = 0.0;                  ///< c_d: signed, negative when penetrating (m)
  int index = -1;                           ///< index of the point in the manifold
};

/// Impulses of one contact point from the previous step, to warm-start the solver (N s).
struct WarmStart {
  double normal = 0.0;
  double lateral1 = 0.0;
  double lateral2 = 0.0;
};

/// The warm start of radial `i` of an n-vector ring from the impulses of an n_old-vector ring
/// (radial j at angle 2 pi j / n_old): radial i itself when n is unchanged, else interpolated
/// between the two remembered radials around its angle and scaled by n_old / n (the load spreads
/// over more or fewer points). Nothing remembered (n_old 0): zero.
WarmStart warmStartByAngle(const WarmStart* remembered, int n_old, int i, int n);

/// Compliant material of one injected or kept point.
struct PointMaterial {
  double stiffness = 0.0;  ///< N/m
  double damping = 0.0;    ///< N s/m
  double friction = 0.0;   ///< Coulomb coefficient
};

/// Finds the deepest point of `m`, one of whose bodies is `proxy`. Bullet may order the bodies
/// either way: the normal and point are turned to the object's side. False when m is empty.
bool deepestContact(const btPersistentManifold& m, const btCollisionObject* proxy, TrueContact& out);

/// Leaves only point `index` in `m`, made compliant with `mat`, warm-started from `warm`.
void keepOnlyPoint(btPersistentManifold& m, int index, const PointMaterial& mat, const WarmStart& warm);

/// Adds `count` points between proxy (body 0) and object (body 1) at the given object-surface
/// points (world frame), all with the true contact's normal (paper, Sec. 3.2), point i with
/// separation separations[i] (m, negative when penetrating), four per new manifold. The new manifolds are appended to `added` (reserve it: no allocation
/// then). Point i has materials[i] and is warm-started from warm[i]. A finger's points carry
/// friction 0: their contact's friction is one FrictionBlock (sim/contact/patch_friction.hpp).
void injectPoints(btDispatcher& dispatcher, const btCollisionObject* proxy,
                  const btCollisionObject* object, const btVector3* points_world, int count,
                  const btVector3& outward_normal_world, const double* separations,
                  const PointMaterial* materials, const WarmStart* warm,
                  std::vector<btPersistentManifold*>& added);

/// The solved impulses of point i of the points injected from manifold `added[first]` on.
WarmStart solvedImpulses(const std::vector<btPersistentManifold*>& added, int first, int i);

/// The solved impulses of a manifold point.
WarmStart solvedImpulses(const btManifoldPoint& p);

/// Releases the manifolds of `added` (newest first, so Bullet's own order is untouched).
void releaseInjected(btDispatcher& dispatcher, std::vector<btPersistentManifold*>& added);

}  // namespace gf::sim
