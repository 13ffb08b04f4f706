#include "sim/patch_friction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace gf::sim {
namespace {

constexpr int kRows = 3;  // tangential t1, tangential t2, torsional about n
// A row whose effective inverse mass is below this fraction of the largest one moves nothing
// (a static body and a proxy that cannot turn have no torsion row).
constexpr double kInactiveRow = 1e-12;

btVector3 velocityOf(const btSolverBody& b) {
  return b.m_originalBody ? b.m_linearVelocity + b.m_externalForceImpulse + b.m_deltaLinearVelocity : btVector3(0, 0, 0);
}

btVector3 spinOf(const btSolverBody& b) {
  return b.m_originalBody ? b.m_angularVelocity + b.m_externalTorqueImpulse + b.m_deltaAngularVelocity
                          : btVector3(0, 0, 0);
}

}  // namespace

PatchFrictionSolver::PatchFrictionSolver() {
  constexpr std::size_t kBlocks = 64, kPoints = 4096;
  blocks_.reserve(kBlocks);
  bound_.reserve(kBlocks);
  proxy_body_of_.reserve(kBlocks);
  object_body_of_.reserve(kBlocks);
  points_.reserve(kPoints);
  pool_index_.reserve(kPoints);
  by_address_.reserve(kPoints);
}

void PatchFrictionSolver::clearBlocks() {
  blocks_.clear();
  points_.clear();
}

int PatchFrictionSolver::addBlock(const FrictionBlock& block) {
  blocks_.push_back(block);
  FrictionBlock& b = blocks_.back();
  b.first_point = static_cast<int>(points_.size());
  b.point_count = 0;
  b.solved = false;
  return static_cast<int>(blocks_.size()) - 1;
}

void PatchFrictionSolver::addPoint(const FrictionPoint& point) {
  points_.push_back(point);
  ++blocks_.back().point_count;
}

btScalar PatchFrictionSolver::solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies,
                                                           btPersistentManifold** manifolds, int numManifolds,
                                                           btTypedConstraint** constraints, int numConstraints,
                                                           const btContactSolverInfo& info, btIDebugDraw* debug) {
  const btScalar r = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debug);
  bind(info);
  return r;
}

// Finds each block's points among this solve's contact rows, sets up its rows and applies its
// warm start.
void PatchFrictionSolver::bind(const btContactSolverInfo& info) {
  bound_.clear();
  if (blocks_.empty()) return;
  pool_index_.assign(points_.size(), -1);
  by_address_.clear();
  for (std::size_t i = 0; i < points_.size(); ++i) by_address_.emplace_back(points_[i].point, static_cast<int>(i));
  std::sort(by_address_.begin(), by_address_.end());
  // Solver bodies of each block, from its first point found in the pool.
  std::vector<int>& proxy_of = proxy_body_of_;
  std::vector<int>& object_of = object_body_of_;
  proxy_of.assign(blocks_.size(), -1);
  object_of.assign(blocks_.size(), -1);
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    const auto* p = static_cast<const btManifoldPoint*>(c.m_originalContactPoint);
    const auto it = std::lower_bound(by_address_.begin(), by_address_.end(), std::make_pair(p, -1));
    if (it == by_address_.end() || it->first != p) continue;
    const int i = it->second;
    pool_index_[static_cast<std::size_t>(i)] = j;
    const FrictionPoint& fp = points_[static_cast<std::size_t>(i)];
    // The block owning point i: blocks hold consecutive points.
    const auto owner = std::upper_bound(blocks_.begin(), blocks_.end(), i,
                                        [](int x, const FrictionBlock& b) { return x < b.first_point; });
    const std::size_t k = static_cast<std::size_t>(owner - blocks_.begin()) - 1;
    proxy_of[k] = fp.proxy_is_a ? c.m_solverBodyIdA : c.m_solverBodyIdB;
    object_of[k] = fp.proxy_is_a ? c.m_solverBodyIdB : c.m_solverBodyIdA;
  }
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    if (proxy_of[k] < 0) continue;
    const FrictionBlock& fb = blocks_[k];
    Bound b;
    b.block = static_cast<int>(k);
    b.proxy_body = proxy_of[k];
    b.object_body = object_of[k];
    const btSolverBody& sp = m_tmpSolverBodyPool[b.proxy_body];
    const btSolverBody& so = m_tmpSolverBodyPool[b.object_body];
    b.n = fb.normal;
    btPlaneSpace1(b.n, b.t1, b.t2);
    b.r_proxy = fb.centre - sp.m_worldTransform.getOrigin();
    b.r_object = fb.centre - so.m_worldTransform.getOrigin();
    const btVector3 zero(0, 0, 0);
    const btVector3 dirs[kRows] = {b.t1, b.t2, zero};
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    for (int row = 0; row < kRows; ++row) {
      const btVector3 ang_p = row < 2 ? b.r_proxy.cross(dirs[row]) : b.n;
      const btVector3 ang_o = row < 2 ? b.r_object.cross(dirs[row]) : b.n;
      b.lin_p[row] = sp.m_originalBody ? dirs[row] * sp.m_invMass : zero;
      b.ang_p[row] = sp.m_originalBody ? sp.m_originalBody->getInvInertiaTensorWorld() * ang_p * sp.m_angularFactor : zero;
      b.lin_o[row] = so.m_originalBody ? -dirs[row] * so.m_invMass : zero;
      b.ang_o[row] = so.m_originalBody ? so.m_originalBody->getInvInertiaTensorWorld() * -ang_o * so.m_angularFactor : zero;
    }
    for (int row = 0; row < kRows; ++row) {
      const btVector3 jp_ang = row < 2 ? b.r_proxy.cross(dirs[row]) : b.n;
      const btVector3 jo_ang = row < 2 ? -b.r_object.cross(dirs[row]) : -b.n;
      for (int col = 0; col < kRows; ++col) {
        K(row, col) = dirs[row].dot(b.lin_p[col]) + jp_ang.dot(b.ang_p[col]) - dirs[row].dot(b.lin_o[col]) +
                      jo_ang.dot(b.ang_o[col]);
      }
    }
    // Rows that cannot act: no friction (tangential), no torsion limit or nothing to turn.
    const double largest = std::max({K(0, 0), K(1, 1), K(2, 2), 0.0});
    bool active[kRows] = {fb.friction > 0.0, fb.friction > 0.0, fb.torsion != 0.0};
    for (int row = 0; row < kRows; ++row) active[row] = active[row] && K(row, row) > kInactiveRow * largest;
    for (int row = 0; row < kRows; ++row) {
      if (active[row]) continue;
      K.row(row).setZero();
      K.col(row).setZero();
      K(row, row) = 1.0;
    }
    const Eigen::Matrix3d inv = K.inverse();
    for (int row = 0; row < kRows; ++row) {
      for (int col = 0; col < kRows; ++col) b.k_inv[row][col] = active[row] && active[col] ? inv(row, col) : 0.0;
    }
    // Warm start: last step's impulses on this step's rows, within this step's limits.
    b.lambda[0] = b.lambda[1] = b.lambda[2] = 0.0;
    const double warm[kRows] = {active[0] ? fb.warm_force.dot(b.t1) : 0.0, active[1] ? fb.warm_force.dot(b.t2) : 0.0,
                                active[2] ? fb.warm_torque * fb.normal.dot(b.n) : 0.0};
    if (info.m_solverMode & SOLVER_USE_WARMSTARTING) {
      double delta[kRows];
      for (int row = 0; row < kRows; ++row) delta[row] = warm[row] * info.m_warmstartingFactor;
      apply(b, delta);
    }
    bound_.push_back(b);
  }
}

double PatchFrictionSolver::relativeVelocity(const Bound& b, int row) const {
  const btSolverBody& sp = m_tmpSolverBodyPool[b.proxy_body];
  const btSolverBody& so = m_tmpSolverBodyPool[b.object_body];
  if (row == 2) return b.n.dot(spinOf(sp) - spinOf(so));
  const btVector3& t = row == 0 ? b.t1 : b.t2;
  const btVector3 vp = velocityOf(sp) + spinOf(sp).cross(b.r_proxy);
  const btVector3 vo = velocityOf(so) + spinOf(so).cross(b.r_object);
  return t.dot(vp - vo);
}

void PatchFrictionSolver::apply(Bound& b, const double delta[3]) {
  btSolverBody& sp = m_tmpSolverBodyPool[b.proxy_body];
  btSolverBody& so = m_tmpSolverBodyPool[b.object_body];
  for (int row = 0; row < kRows; ++row) {
    if (delta[row] == 0.0) continue;
    sp.internalApplyImpulse(b.lin_p[row], b.ang_p[row], delta[row]);
    so.internalApplyImpulse(b.lin_o[row], b.ang_o[row], delta[row]);
    b.lambda[row] += delta[row];
  }
}

// One projected block step: the impulses that would stop the centre's sliding and the turning
// about the normal together (y), kept when they lie inside the limit ellipsoid
// (|f_t| / (mu N))^2 + (tau / tau_max)^2 <= 1. Outside it, the contact slides and the impulse is
// the point x of the ellipsoid where the relative motion left after it opposes the ellipsoid's
// normal (maximum dissipation): A (x - y) = -nu D x with D = diag(1 / limit^2), nu > 0, that is
// (I + nu E D) x = y with E = A^-1 (the rows' effective mass). Scaling y onto the ellipsoid
// instead is wrong whenever one row's demand dwarfs the others': a pad on a disc spinning under
// it (sliding 0.9 m/s, turning 30 rad/s about its normal, torsion limit about mu N 1 mm) spent its
// whole friction on the torsion row and slid with no friction force at all.
double PatchFrictionSolver::solveBlock(Bound& b) {
  const FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
  double normal = 0.0, levered = 0.0;
  for (int i = fb.first_point; i < fb.first_point + fb.point_count; ++i) {
    const int j = pool_index_[static_cast<std::size_t>(i)];
    if (j < 0) continue;
    const double lambda_n = std::max(0.0, static_cast<double>(m_tmpSolverContactConstraintPool[j].m_appliedImpulse));
    normal += lambda_n;
    levered += lambda_n * points_[static_cast<std::size_t>(i)].lever;
  }
  const double slide_limit = fb.friction * normal;
  const double twist_limit = fb.torsion < 0.0 ? fb.friction * levered : fb.torsion * normal;
  const double limit[kRows] = {slide_limit, slide_limit, twist_limit};
  double u[kRows];
  for (int row = 0; row < kRows; ++row) u[row] = b.k_inv[row][row] != 0.0 ? relativeVelocity(b, row) : 0.0;
  Eigen::Vector3d y, d = Eigen::Vector3d::Zero();
  Eigen::Matrix3d e;
  for (int row = 0; row < kRows; ++row) {
    y(row) = b.lambda[row] - (b.k_inv[row][0] * u[0] + b.k_inv[row][1] * u[1] + b.k_inv[row][2] * u[2]);
    for (int col = 0; col < kRows; ++col) e(row, col) = b.k_inv[row][col];
  }
  for (int row = 0; row < kRows; ++row) {
    if (limit[row] > 0.0) {
      d(row) = 1.0 / (limit[row] * limit[row]);
    } else {  // no friction on this row: it carries nothing, the others are projected alone
      y(row) = 0.0;
      e.row(row).setZero();
      e.col(row).setZero();
    }
  }
  const double outside = y.dot(d.asDiagonal() * y);
  if (outside > 1.0) y = projectOntoLimit(e, d, y, outside);
  double delta[kRows], residual = 0.0;
  for (int row = 0; row < kRows; ++row) {
    delta[row] = y(row) - b.lambda[row];
    residual = std::max(residual, delta[row] * delta[row]);
  }
  apply(b, delta);
  return residual;
}

// The x with (I + nu E D) x = y and x^T D x = 1, nu > 0, for a y with y^T D y = `outside` > 1:
// Newton's method on 1 / sqrt(x^T D x) - 1, nearly linear in nu (as for a Euclidean projection
// onto an ellipsoid), from nu = 0; a few iterations. The result is scaled onto the ellipsoid
// exactly. Does not allocate.
Eigen::Vector3d PatchFrictionSolver::projectOntoLimit(const Eigen::Matrix3d& e, const Eigen::Vector3d& d,
                                                      const Eigen::Vector3d& y, double outside) {
  constexpr int kIterations = 30;
  const Eigen::Matrix3d ed = e * d.asDiagonal();
  double nu = 0.0;
  Eigen::Vector3d x = y;
  double phi = outside;
  for (int k = 0; k < kIterations && std::abs(phi - 1.0) > 1e-12; ++k) {
    const Eigen::Matrix3d m = Eigen::Matrix3d::Identity() + nu * ed;
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(m);
    const Eigen::Vector3d dx = -lu.solve(ed * x);        // dx / dnu
    const double dphi = 2.0 * x.dot(d.asDiagonal() * dx);  // dphi / dnu
    const double h = 1.0 / std::sqrt(phi) - 1.0;          // < 0 while outside
    const double dh = -0.5 * dphi / (phi * std::sqrt(phi));
    double next = dh > 0.0 ? nu - h / dh : 2.0 * nu + 1.0;
    if (!(next > nu * 0.5)) next = nu * 0.5;               // stay positive, never jump back far
    nu = next;
    x = Eigen::PartialPivLU<Eigen::Matrix3d>(Eigen::Matrix3d::Identity() + nu * ed).solve(y);
    phi = x.dot(d.asDiagonal() * x);
    if (!std::isfinite(phi) || phi <= 0.0) return y / std::sqrt(outside);  // degenerate: scale
  }
  return x / std::sqrt(phi);
}

btScalar PatchFrictionSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                                   btPersistentManifold** manifolds, int numManifolds,
                                                   btTypedConstraint** constraints, int numConstraints,
                                                   const btContactSolverInfo& info, btIDebugDraw* debug) {
  double residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
      iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debug);
  for (Bound& b : bound_) residual = std::max(residual, solveBlock(b));
  return static_cast<btScalar>(residual);
}

btScalar PatchFrictionSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                            const btContactSolverInfo& info) {
  for (const Bound& b : bound_) {
    FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
    fb.force = b.lambda[0] * b.t1 + b.lambda[1] * b.t2;
    fb.torque = b.lambda[2];
    double normal = 0.0;
    for (int i = fb.first_point; i < fb.first_point + fb.point_count; ++i) {
      const int j = pool_index_[static_cast<std::size_t>(i)];
      if (j >= 0) normal += std::max(0.0, static_cast<double>(m_tmpSolverContactConstraintPool[j].m_appliedImpulse));
    }
    fb.normal_impulse = normal;
    fb.solved = true;
  }
  bound_.clear();
  return btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
}

}  // namespace gf::sim
