// Friction of a finger's contact as one block: two tangential rows at the patch's centre and a
// torsional row about its normal, limited together by the contact's total normal impulse. The
// contact's points carry only normal rows (their own friction is zero); the block gives the
// whole contact one isotropic friction disc instead of a pyramid per point, a torsion limit
// that is the sum of the points' own (mu N_i times their distance from the centre) for a
// god-finger patch or mu_t N for a soft finger, and it converges in the iterations Bullet
// already runs. Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <Eigen/Core>

#include <vector>

namespace gf::sim {

/// One finger's contact with one body, as the solver sees it. Filled before the solve (World's
/// beforeSolve), read after it.
struct FrictionBlock {
  const btCollisionObject* proxy = nullptr;
  const btCollisionObject* object = nullptr;
  btVector3 centre{0, 0, 0};  ///< where the tangential rows act (world, m)
  btVector3 normal{0, 1, 0};  ///< outward contact normal of the object (unit, world)
  double friction = 0.0;      ///< Coulomb coefficient against sliding
  /// Torsion limit per unit normal impulse (m): < 0 for "from the points" (mu times the sum of
  /// each point's normal impulse times its lever, FrictionPoint::lever); 0 for none.
  double torsion = 0.0;
  /// Warm start: last step's friction impulse on the proxy (world, N s) and torsional impulse
  /// about the normal (N m s).
  btVector3 warm_force{0, 0, 0};
  double warm_torque = 0.0;
  int first_point = 0, point_count = 0;  ///< its points in PatchFrictionSolver::points()
  // Results of the solve (the same quantities as the warm start, and the normal impulse).
  btVector3 force{0, 0, 0};
  double torque = 0.0;
  double normal_impulse = 0.0;
  bool solved = false;  ///< false when none of its points reached the solver this step
};

/// One contact point of a block: which manifold point it is and its lever about the centre.
struct FrictionPoint {
  const btManifoldPoint* point = nullptr;
  double lever = 0.0;  ///< distance from the block's centre across the normal (m)
  bool proxy_is_a = true;  ///< the proxy is body 0 of the point's manifold
};

/// Bullet's sequential-impulse solver with friction blocks solved after Bullet's own rows in
/// every iteration. Deterministic: blocks in the order they were added.
class PatchFrictionSolver final : public btSequentialImpulseConstraintSolver {
 public:
  PatchFrictionSolver();
  /// Empties the blocks (keeps storage). Call before adding this step's blocks.
  void clearBlocks();
  /// Adds a block whose points are the next `points` added with addPoint; returns its index.
  int addBlock(const FrictionBlock& block);
  void addPoint(const FrictionPoint& point);
  const FrictionBlock& block(int index) const { return blocks_[static_cast<std::size_t>(index)]; }

 protected:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
                                        int numManifolds, btTypedConstraint** constraints, int numConstraints,
                                        const btContactSolverInfo& info, btIDebugDraw* debug) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                btPersistentManifold** manifolds, int numManifolds, btTypedConstraint** constraints,
                                int numConstraints, const btContactSolverInfo& info, btIDebugDraw* debug) override;
  btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                         const btContactSolverInfo& info) override;

 private:
  // A block bound to this solve: its solver bodies, rows and accumulated impulses.
  struct Bound {
    int block = -1;
    int proxy_body = -1, object_body = -1;  // indices into m_tmpSolverBodyPool
    btVector3 t1, t2, n;                    // row directions
    btVector3 r_proxy, r_object;            // centre relative to each body's centre of mass
    // Per row k: each body's velocity change per unit impulse (linear, angular).
    btVector3 lin_p[3], ang_p[3], lin_o[3], ang_o[3];
    double k_inv[3][3];  // inverse of the rows' effective mass matrix (active rows only)
    double lambda[3];    // accumulated impulses: tangential t1, t2, torsional
  };
  double relativeVelocity(const Bound& b, int row) const;
  void apply(Bound& b, const double delta[3]);
  void bind(const btContactSolverInfo& info);
  double solveBlock(Bound& b);
  static Eigen::Vector3d projectOntoLimit(const Eigen::Matrix3d& e, const Eigen::Vector3d& d, const Eigen::Vector3d& y,
                                          double outside);

  std::vector<FrictionBlock> blocks_;
  std::vector<FrictionPoint> points_;
  std::vector<int> pool_index_;  // per point: its row in m_tmpSolverContactConstraintPool, or -1
  std::vector<std::pair<const btManifoldPoint*, int>> by_address_;  // points sorted by address
  std::vector<Bound> bound_;
  std::vector<int> proxy_body_of_, object_body_of_;  // per block: its solver bodies, or -1
};

}  // namespace gf::sim
