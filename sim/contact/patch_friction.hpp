// A finger's contact with one body as blocks of rows of Bullet's sequential-impulse solve.
//
// Friction: two tangential rows at the patch's load centre and a torsional row about its normal,
// limited together by the contact's total normal impulse. With the "points" solver the patch's
// points carry only normal rows (their own friction is zero) and the block gives the whole
// contact one isotropic friction disc instead of a pyramid per point, a torsion limit of mu N
// times the points' load-weighted mean lever for a god-finger patch (the aggregate's) or mu_t N
// for a soft finger, and it converges in the iterations Bullet already runs. A god-finger
// patch's block has two rolling rows too: the body may not turn about the contact's tangent axes
// while the moment that takes stays within N times the rim's mean lever (the pressure moving to
// the patch's edge, the r of theta + r / R >= 1). The points' normal rows alone hold that turn
// only through their damping, on a sphere (where turning changes no depth) not at all: a pushed
// ball crept into rolling under a filled patch.
//
// Aggregate ("aggregate" solver): the patch's points reach the solver as three more rows of the
// same block instead of one contact row each: the normal at the load centre and two tilt rows
// about the principal axes of the points' second moment. They are the points' rows summed: the
// normal row has the contact's whole stiffness and damping and the centre's depth, a tilt row
// the stiffness of the points' springs about its axis (k times the load-weighted second moment)
// and the tilt their depths make. Their limits are the points' unilateral loads: the normal
// impulse pushes, and the tilt moment keeps the centre of pressure within the hull of the
// points (each point only pushes); the friction rows' limits are mu N and mu N times the
// points' mean lever. The solve's cost no longer grows with the points.
//
// Bullet's own contacts (a body on the ground, a body on a body): Bullet 3 starts their friction
// rows from zero every step (only their normal rows are warm-started), so ten iterations never
// quite rebuild the friction that holds a loaded body, and what they leave slips. This solver
// warm-starts those rows too, from last step's friction impulse kept in a frame of the normal
// (the rows' own directions follow the sliding velocity and change from step to step), and
// anchors a sticking point: its friction rows take back the slip since it started sticking.
// Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <Eigen/Core>

#include <vector>

#include "sim/contact/aggregate_patch.hpp"

namespace gf::sim {

/// A solver body's velocity and spin with the step's external forces and the impulses applied so
/// far (zero for a static body).
inline btVector3 velocityOf(const btSolverBody& b) {
  return b.m_originalBody ? b.m_linearVelocity + b.m_externalForceImpulse + b.m_deltaLinearVelocity : btVector3(0, 0, 0);
}
inline btVector3 spinOf(const btSolverBody& b) {
  return b.m_originalBody ? b.m_angularVelocity + b.m_externalTorqueImpulse + b.m_deltaAngularVelocity
                          : btVector3(0, 0, 0);
}

/// One finger's contact with one body, as the solver sees it. Filled before the solve (World's
/// beforeSolve), read after it.
struct FrictionBlock {
  const btCollisionObject* proxy = nullptr;
  const btCollisionObject* object = nullptr;
  btVector3 centre{0, 0, 0};  ///< where the tangential (and aggregate normal) rows act (world, m)
  btVector3 normal{0, 1, 0};  ///< outward contact normal of the object (unit, world)
  double friction = 0.0;      ///< Coulomb coefficient against sliding
  /// Torsion limit per unit normal impulse (m); 0 for none.
  double torsion = 0.0;
  /// Rolling limit per unit normal impulse (m), the moment about the tangent axes; 0 for no
  /// rolling rows.
  double rolling = 0.0;
  /// Warm start: last step's friction impulse on the proxy (world, N s) and torsional impulse
  /// about the normal (N m s).
  btVector3 warm_force{0, 0, 0};
  double warm_torque = 0.0;
  btVector3 warm_rolling{0, 0, 0};  ///< last step's rolling impulse (world, N m s)
  /// How far the proxy's side of the contact has slid from the body's since the block started
  /// sticking (its anchor; world, across the normal, m).
  btVector3 slip{0, 0, 0};
  /// How far the proxy has turned against the body about the normal since then (rad): the
  /// torsion row takes it back. (A turn about the tangents is the pad's tilt, which the points'
  /// depths, or the aggregate's tilt rows, already push back.)
  double turn_slip = 0.0;
  /// The spring and damper that take the slip back (N/m, N s/m: the contact's own), as Bullet's
  /// compliant rows do: target relative velocity -k slip / (h k + d).
  double anchor_stiffness = 0.0, anchor_damping = 0.0;
  /// The pressing points' polar second moment about the centre, over their shares of the
  /// contact's stiffness: sum_i w_i |rho_i|^2 (m^2). The torsion row is the pad's spring about
  /// the normal, anchor_stiffness and anchor_damping times it, as a tilt row is about its axis:
  /// compliance 1 / (h (h k + d) J) beside the pull. 0: a stiff torsion row (a point contact).
  double twist_moment = 0.0;
  /// Aggregate: the block carries the contact's normal and tilt rows too (`press`) and has no
  /// points; its bodies are found by their solver bodies.
  bool aggregate = false;
  PressRows press;
  int first_point = 0, point_count = 0;  ///< its points in PatchFrictionSolver::points()
  // Results of the solve (the same quantities as the warm start, and the normal impulse).
  btVector3 force{0, 0, 0};
  double torque = 0.0;
  btVector3 rolling_impulse{0, 0, 0};
  double normal_impulse = 0.0;
  /// This step's relative motion, from the solved velocities times the step: the centre's across
  /// the normal (proxy side against the body's, m) and the turn about the normal (rad).
  btVector3 moved{0, 0, 0};
  double turned = 0.0;
  bool solved = false;  ///< false when none of its points (or bodies) reached the solver this step
};

/// One contact point of a block: which manifold point it is.
struct FrictionPoint {
  const btManifoldPoint* point = nullptr;
  bool proxy_is_a = true;  ///< the proxy is body 0 of the point's manifold
};

/// Bullet's sequential-impulse solver with friction and aggregate blocks solved after Bullet's
/// own rows in every iteration. Deterministic: blocks in the order they were added.
class PatchFrictionSolver final : public btSequentialImpulseConstraintSolver {
 public:
  PatchFrictionSolver();
  /// Empties the blocks (keeps storage) and begins the step's memory of Bullet's own contacts.
  /// Call once a step, before adding this step's blocks.
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
  int iterations_ = 0;  // iterations of the solve under way
  void drawSkippedShuffles(const btContactSolverInfo& info);
  // tangential t1, t2, torsion; aggregate: normal, tilt a0, a1; then with a rolling limit:
  // rolling about t1, t2
  static constexpr int kRows = 8;
  // A block bound to this solve: its solver bodies, rows and accumulated impulses.
  struct Bound {
    int block = -1;
    int proxy_body = -1, object_body = -1;  // indices into m_tmpSolverBodyPool
    int rows = 3;                           // 3, or 6 for an aggregate block; + 2 rolling rows
    int roll = -1;                          // the first rolling row, -1 for none
    bool aggregate = false;
    btVector3 t1, t2, n;                    // friction row directions
    btVector3 r_proxy, r_object;            // centre relative to each body's centre of mass
    // Per row: the Jacobian (linear part along `lin` at the centre, proxy +, object -; angular
    // parts of the proxy and the object) and each body's velocity change per unit impulse.
    btVector3 lin[kRows], jac_p[kRows], jac_o[kRows];
    bool angular[kRows];  // an angular row: about jac_p (lin zero)
    btVector3 lin_p[kRows], ang_p[kRows], lin_o[kRows], ang_o[kRows];
    double k_inv[3][3];      // inverse of the friction rows' effective mass (active rows only)
    double press_k[3][3];    // the pressing rows' effective mass matrix plus compliance
    double press_inv[3][3];  // its inverse (active rows only)
    double bias[3];          // pressing rows: target relative velocity is -bias - cfm lambda
    double cfm[3];
    double roll_inv[2][2];   // inverse of the rolling rows' effective mass
    double slip_bias[3];     // the friction rows' pull back to the anchor: along t1, t2, about n
    double twist_cfm = 0.0;  // the torsion row's compliance (the pad's spring): -cfm lambda more
    double lambda[kRows];    // accumulated impulses
    // Each row's relative velocity per unit impulse (its effective mass's diagonal, compliance
    // in): an iteration's change of impulse times it is the residual Bullet's rows report, the
    // change of velocity (m/s, rad/s), so one threshold can end the iterations.
    double speed[kRows] = {};
  };
  // The bodies' relative motion a block's rows read (with the impulses applied so far).
  struct Motion {
    btVector3 centre;  // velocity of the proxy's point at the centre minus the object's
    btVector3 spin;    // spin of the proxy minus the object's
  };
  Motion motion(const Bound& b) const;
  static double relativeVelocity(const Bound& b, const Motion& m, int row);
  void apply(Bound& b, const double* delta, int first, int count);
  void bind(const btContactSolverInfo& info);
  void recallContacts(btPersistentManifold** manifolds, int count, const btContactSolverInfo& info);
  void warmStartContacts(const btContactSolverInfo& info);
  void keepContacts(const btContactSolverInfo& info);
  void rollContactMemos();
  double limitContactFriction(const btContactSolverInfo& info);
  bool findBodies(const FrictionBlock& fb, const btContactSolverInfo& info, int& proxy, int& object);
  void setRows(Bound& b) const;
  void bindPress(Bound& b, const FrictionBlock& fb, const btContactSolverInfo& info) const;
  static Eigen::Matrix3d rowMass(const Bound& b, int first);
  static bool moves(const Eigen::Matrix3d& K, int row);
  static void invertActive(Eigen::Matrix3d K, const bool active[3], double inv[3][3], double kept[3][3]);
  double solvePress(Bound& b);
  double solveBlock(Bound& b, double normal);
  void bindRolling(Bound& b, const FrictionBlock& fb);
  btVector3 pressMoment(const Bound& b, double& normal) const;
  double solveRolling(Bound& b, double normal, const btVector3& press);
  double blockNormal(const Bound& b) const;
  static Eigen::Vector3d projectOntoLimit(const Eigen::Matrix3d& e, const Eigen::Vector3d& d, const Eigen::Vector3d& y,
                                          double outside);

  std::vector<FrictionBlock> blocks_;
  std::vector<FrictionPoint> points_;
  std::vector<int> pool_index_;  // per point: its row in m_tmpSolverContactConstraintPool, or -1
  std::vector<btVector3> arm_;    // per point of a block with rolling rows: (point - centre) x n
  std::vector<std::pair<const btManifoldPoint*, int>> by_address_;  // points sorted by address
  std::vector<Bound> bound_;
  // What each of Bullet's own contact points leaves for the next step (sim/contact/contact_friction.cpp),
  // found again by its bodies and its point on the first (Bullet's manifolds keep most points
  // from step to step, but a concave mesh's, GImpact's, are new every step): the impulses that
  // warm-start it, and how far it has slid since it started sticking. This step's, sorted by the
  // manifold point's address, and last step's, sorted by bodies.
  struct ContactMemo {
    const btManifoldPoint* point = nullptr;
    const btCollisionObject *a = nullptr, *b = nullptr;
    btVector3 at_a{0, 0, 0};                 // the point on body A, its frame (m)
    btVector3 slip{0, 0, 0};                 // A's side against B's since it stuck, tangential (world, m)
    double normal = 0.0;                     // normal impulse (N s)
    double along1 = 0.0, along2 = 0.0;       // friction impulse along btPlaneSpace1 of the normal (N s)
    bool sticks = false;                     // ended the solve inside its friction limit
    bool kept = false;                       // reached a solve this step (keepContacts)
  };
  std::vector<ContactMemo> memos_, last_memos_;
  ContactMemo* memoOf(const btManifoldPoint* point);
  const ContactMemo* lastMemo(const btCollisionObject* a, const btCollisionObject* b, const btVector3& at_a) const;
  std::vector<int> proxy_body_of_, object_body_of_;  // per block: its solver bodies, or -1
};

}  // namespace gf::sim
