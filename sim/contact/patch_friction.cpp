#include "sim/contact/patch_friction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace gf::sim {
namespace {

constexpr int kFrictionRows = 3;  // tangential t1, tangential t2, torsional about n
constexpr int kNormalRow = 3;     // aggregate: the normal row, then the two tilt rows
// A row whose effective inverse mass is below this fraction of the largest one moves nothing
// (a static body and a proxy that cannot turn have no torsion row).
constexpr double kInactiveRow = 1e-12;


double squared(double x) { return x * x; }

// The largest ratio (x, y) . d_j / (normal h_j) over the tilt limit's directions: the tilt
// impulse (x, y) (tilt-axis coordinates) is within the hull of the points while it is <= 1.
// Infinite when (x, y) leans towards a direction the hull has no extent in.
double tiltGauge(const PressRows& p, double x, double y, double normal) {
  double gauge = 0.0;
  for (std::size_t j = 0; j < kTiltDirectionTable.c.size(); ++j) {
    const double along = x * kTiltDirectionTable.c[j] + y * kTiltDirectionTable.s[j];
    if (!(along > 0.0)) continue;
    const double room = normal * p.support[j];
    gauge = room > 0.0 ? std::max(gauge, along / room) : std::numeric_limits<double>::infinity();
  }
  return gauge;
}

// Moves the tilt impulse (x, y) into the limit {x . d_j <= normal h_j}: with both tilt rows,
// onto each violated side in turn (a few sweeps), which keeps the part of the demand the limit
// allows (a demand far past one side keeps its component along that side, where scaling the
// whole impulse back would shrink it); then, or with one row (where the limit is an interval),
// scaled into it so the result lies inside.
void projectTilt(const PressRows& p, double normal, bool both, double& x, double& y) {
  constexpr int kSweeps = 8;
  for (int sweep = 0; both && sweep < kSweeps; ++sweep) {
    bool moved = false;
    for (std::size_t j = 0; j < kTiltDirectionTable.c.size(); ++j) {
      const double excess = x * kTiltDirectionTable.c[j] + y * kTiltDirectionTable.s[j] - normal * std::max(0.0, p.support[j]);
      if (!(excess > 0.0)) continue;
      x -= excess * kTiltDirectionTable.c[j];
      y -= excess * kTiltDirectionTable.s[j];
      moved = true;
    }
    if (!moved) break;
  }
  const double gauge = tiltGauge(p, x, y, normal);
  if (gauge > 1.0) {
    const double scale = std::isfinite(gauge) ? 1.0 / gauge : 0.0;
    x *= scale, y *= scale;
  }
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
  arm_.reserve(kPoints);
  by_address_.reserve(kPoints);
  memos_.reserve(kPoints);
  last_memos_.reserve(kPoints);
}

void PatchFrictionSolver::clearBlocks() {
  rollContactMemos();
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
  iterations_ = 0;
  const btScalar r = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debug);
  if (info.m_solverMode & SOLVER_USE_WARMSTARTING) {
    recallContacts(manifolds, numManifolds, info);
    warmStartContacts(info);
  }
  bind(info);
  return r;
}

// Finds each block's solver bodies (a points block: from its points among this solve's contact
// rows; an aggregate block: from its bodies), sets up its rows and applies its warm start.
void PatchFrictionSolver::bind(const btContactSolverInfo& info) {
  bound_.clear();
  if (blocks_.empty()) return;
  pool_index_.assign(points_.size(), -1);
  by_address_.clear();
  for (std::size_t i = 0; i < points_.size(); ++i) by_address_.emplace_back(points_[i].point, static_cast<int>(i));
  std::sort(by_address_.begin(), by_address_.end());
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
    const FrictionBlock& fb = blocks_[k];
    if (fb.aggregate && !findBodies(fb, info, proxy_of[k], object_of[k])) continue;
    if (proxy_of[k] < 0) continue;
    Bound b;
    b.block = static_cast<int>(k);
    b.proxy_body = proxy_of[k];
    b.object_body = object_of[k];
    b.aggregate = fb.aggregate;
    b.rows = fb.aggregate ? kNormalRow + 3 : kFrictionRows;
    if (fb.rolling > 0.0) b.roll = b.rows, b.rows += 2;
    b.n = fb.normal;
    btPlaneSpace1(b.n, b.t1, b.t2);
    setRows(b);
    // The friction rows' effective mass; rows that cannot act (no friction, no torsion limit or
    // nothing to turn) are left out.
    Eigen::Matrix3d K = rowMass(b, 0);
    bool active[kFrictionRows] = {fb.friction > 0.0, fb.friction > 0.0, fb.torsion != 0.0};
    for (int row = 0; row < kFrictionRows; ++row) active[row] = active[row] && moves(K, row);
    const double h = info.m_timeStep, spring = h * fb.anchor_stiffness + fb.anchor_damping;
    // Two pads on one body turn it about one axis: stiff torsion rows with anchors that differ
    // by a rounding would twist against each other without end; the pads' springs settle.
    b.twist_cfm = active[2] && fb.twist_moment > 0.0 && spring > 0.0 ? 1.0 / (h * spring * fb.twist_moment) : 0.0;
    K(2, 2) += b.twist_cfm;
    for (int row = 0; row < kFrictionRows; ++row) b.speed[row] = K(row, row);
    invertActive(K, active, b.k_inv, nullptr);
    const double pull = fb.anchor_stiffness / std::max(spring, 1e-300);
    b.slip_bias[0] = pull * fb.slip.dot(b.t1);
    b.slip_bias[1] = pull * fb.slip.dot(b.t2);
    b.slip_bias[2] = pull * fb.turn_slip * fb.normal.dot(b.n);
    for (double& l : b.lambda) l = 0.0;
    if (fb.aggregate) bindPress(b, fb, info);
    if (b.roll >= 0) bindRolling(b, fb);
    // Warm start: last step's impulses on this step's rows, within this step's limits.
    if (info.m_solverMode & SOLVER_USE_WARMSTARTING) {
      double delta[kRows] = {active[0] ? fb.warm_force.dot(b.t1) : 0.0, active[1] ? fb.warm_force.dot(b.t2) : 0.0,
                             active[2] ? fb.warm_torque * fb.normal.dot(b.n) : 0.0};
      if (fb.aggregate) {
        delta[kNormalRow] = std::max(0.0, fb.press.warm_normal);
        for (int k2 = 0; k2 < 2; ++k2) {
          delta[kNormalRow + 1 + k2] = b.press_inv[1 + k2][1 + k2] != 0.0 ? fb.press.warm_tilt.dot(fb.press.tilt_axis[k2]) : 0.0;
        }
        if (tiltGauge(fb.press, delta[4], delta[5], delta[3]) > 1.0) delta[4] = delta[5] = 0.0;
      }
      if (b.roll >= 0 && b.roll_inv[0][0] != 0.0) {
        delta[b.roll] = fb.warm_rolling.dot(b.t1);
        delta[b.roll + 1] = fb.warm_rolling.dot(b.t2);
      }
      for (double& d : delta) d *= info.m_warmstartingFactor;
      apply(b, delta, 0, b.rows);
    }
    bound_.push_back(b);
  }
}

// An aggregate block's solver bodies: the proxy's (false when it is not in this solve: another
// batch of islands) and the object's, the fixed body for a static one.
bool PatchFrictionSolver::findBodies(const FrictionBlock& fb, const btContactSolverInfo& info, int& proxy, int& object) {
  proxy = fb.proxy->getCompanionId();
  if (proxy < 0) return false;
  const btRigidBody* rb = btRigidBody::upcast(fb.object);
  if (rb && !rb->isStaticOrKinematicObject()) {
    object = fb.object->getCompanionId();
    return object >= 0;
  }
  object = getOrInitSolverBody(*const_cast<btCollisionObject*>(fb.object), info.m_timeStep);
  return true;
}

// Every row's Jacobian and each body's velocity change per unit impulse along it: tangential
// rows at the centre, torsion about n; aggregate: the normal at the centre, tilt about its axes.
void PatchFrictionSolver::setRows(Bound& b) const {
  const FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
  const btSolverBody& sp = m_tmpSolverBodyPool[b.proxy_body];
  const btSolverBody& so = m_tmpSolverBodyPool[b.object_body];
  b.r_proxy = fb.centre - sp.m_worldTransform.getOrigin();
  b.r_object = fb.centre - so.m_worldTransform.getOrigin();
  const btVector3 zero(0, 0, 0);
  const auto linear = [&](int row, const btVector3& d) {
    b.angular[row] = false;
    b.lin[row] = d;
    b.jac_p[row] = b.r_proxy.cross(d);
    b.jac_o[row] = -b.r_object.cross(d);
  };
  const auto angular = [&](int row, const btVector3& axis) {
    b.angular[row] = true;
    b.lin[row] = zero;
    b.jac_p[row] = axis;
    b.jac_o[row] = -axis;
  };
  linear(0, b.t1);
  linear(1, b.t2);
  angular(2, b.n);
  if (b.aggregate) {
    linear(kNormalRow, b.n);
    angular(kNormalRow + 1, fb.press.tilt_axis[0]);
    angular(kNormalRow + 2, fb.press.tilt_axis[1]);
  }
  if (b.roll >= 0) {
    angular(b.roll, b.t1);
    angular(b.roll + 1, b.t2);
  }
  for (int row = 0; row < b.rows; ++row) {
    b.lin_p[row] = sp.m_originalBody ? b.lin[row] * sp.m_invMass : zero;
    b.ang_p[row] = sp.m_originalBody ? sp.m_originalBody->getInvInertiaTensorWorld() * b.jac_p[row] * sp.m_angularFactor : zero;
    b.lin_o[row] = so.m_originalBody ? -b.lin[row] * so.m_invMass : zero;
    b.ang_o[row] = so.m_originalBody ? so.m_originalBody->getInvInertiaTensorWorld() * b.jac_o[row] * so.m_angularFactor : zero;
  }
}

// The pressing rows of an aggregate block as compliant rows, as Bullet makes a contact point
// with stiffness k and damping d: erp = h k / (h k + d), cfm = 1 / (h (h k + d)); the target
// relative velocity is -erp s / h while the centre penetrates (s <= 0) and -s / h (speculative)
// before; a tilt row's stiffness is k times its second moment.
void PatchFrictionSolver::bindPress(Bound& b, const FrictionBlock& fb, const btContactSolverInfo& info) const {
  const PressRows& p = fb.press;
  const double h = info.m_timeStep;
  const double denom = std::max(h * p.stiffness + p.damping, static_cast<double>(SIMD_EPSILON));
  const double erp = h * p.stiffness / denom, cfm = 1.0 / (denom * h);
  b.bias[0] = p.separation <= 0.0 ? erp * p.separation / h : p.separation / h;
  b.cfm[0] = cfm;
  Eigen::Matrix3d K = rowMass(b, kNormalRow);
  bool active[3] = {true, true, true};
  for (int k = 0; k < 2; ++k) {
    active[1 + k] = p.tilt_moment[k] > 0.0 && moves(K, 1 + k);
    b.bias[1 + k] = erp * p.tilt_error[k] / h;
    b.cfm[1 + k] = active[1 + k] ? cfm / p.tilt_moment[k] : 0.0;
  }
  for (int row = 0; row < 3; ++row) K(row, row) += b.cfm[row], b.speed[kNormalRow + row] = K(row, row);
  invertActive(K, active, b.press_inv, b.press_k);
}

// The effective mass of the three rows from `first`: entry (r, c) is row r's relative velocity
// per unit impulse along row c.
Eigen::Matrix3d PatchFrictionSolver::rowMass(const Bound& b, int first) {
  Eigen::Matrix3d K;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      const int r = first + row, c = first + col;
      K(row, col) = b.lin[r].dot(b.lin_p[c]) + b.jac_p[r].dot(b.ang_p[c]) - b.lin[r].dot(b.lin_o[c]) +
                    b.jac_o[r].dot(b.ang_o[c]);
    }
  }
  return K;
}

// Whether row `row` of effective mass `K` moves anything: its diagonal is not negligible against
// the largest (a static body and a proxy that cannot turn have no torsion or tilt).
bool PatchFrictionSolver::moves(const Eigen::Matrix3d& K, int row) {
  return K(row, row) > kInactiveRow * std::max({K(0, 0), K(1, 1), K(2, 2), 0.0});
}

// `K` restricted to its active rows and columns, inverted into `inv` (zero elsewhere); `kept`,
// when given, receives `K` on the same entries.
void PatchFrictionSolver::invertActive(Eigen::Matrix3d K, const bool active[3], double inv[3][3], double kept[3][3]) {
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      if (kept) kept[row][col] = active[row] && active[col] ? K(row, col) : 0.0;
    }
  }
  for (int row = 0; row < 3; ++row) {
    if (active[row]) continue;
    K.row(row).setZero();
    K.col(row).setZero();
    K(row, row) = 1.0;
  }
  const Eigen::Matrix3d inverse = K.inverse();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) inv[row][col] = active[row] && active[col] ? inverse(row, col) : 0.0;
  }
}

PatchFrictionSolver::Motion PatchFrictionSolver::motion(const Bound& b) const {
  const btSolverBody& sp = m_tmpSolverBodyPool[b.proxy_body];
  const btSolverBody& so = m_tmpSolverBodyPool[b.object_body];
  const btVector3 vp = velocityOf(sp) + spinOf(sp).cross(b.r_proxy);
  const btVector3 vo = velocityOf(so) + spinOf(so).cross(b.r_object);
  return {vp - vo, spinOf(sp) - spinOf(so)};
}

// A row along `lin` reads the centre's relative velocity; an angular row (lin zero), the
// relative spin about its axis.
double PatchFrictionSolver::relativeVelocity(const Bound& b, const Motion& m, int row) {
  return b.angular[row] ? b.jac_p[row].dot(m.spin) : b.lin[row].dot(m.centre);
}

void PatchFrictionSolver::apply(Bound& b, const double* delta, int first, int count) {
  btSolverBody& sp = m_tmpSolverBodyPool[b.proxy_body];
  btSolverBody& so = m_tmpSolverBodyPool[b.object_body];
  for (int row = first; row < first + count; ++row) {
    const double d = delta[row - first];
    if (d == 0.0) continue;
    sp.internalApplyImpulse(b.lin_p[row], b.ang_p[row], d);
    so.internalApplyImpulse(b.lin_o[row], b.ang_o[row], d);
    b.lambda[row] += d;
  }
}

// One step of an aggregate block's pressing rows: the impulses that meet their targets
// together, then their limits: no pull (a normal impulse <= 0 releases the tilt too), and a tilt
// impulse within the points' hull times the normal impulse (moved onto the hull's sides when
// outside, projectTilt, and the normal row solved again with that tilt).
double PatchFrictionSolver::solvePress(Bound& b) {
  const PressRows& p = blocks_[static_cast<std::size_t>(b.block)].press;
  double rho[3], y[3];
  const Motion m = motion(b);
  for (int row = 0; row < 3; ++row) {
    const int r = kNormalRow + row;
    rho[row] = b.press_inv[row][row] != 0.0 ? relativeVelocity(b, m, r) + b.bias[row] + b.cfm[row] * b.lambda[r] : 0.0;
  }
  for (int row = 0; row < 3; ++row) {
    y[row] = b.lambda[kNormalRow + row] -
             (b.press_inv[row][0] * rho[0] + b.press_inv[row][1] * rho[1] + b.press_inv[row][2] * rho[2]);
  }
  if (y[0] > 0.0) {
    if (tiltGauge(p, y[1], y[2], y[0]) > 1.0) {
      const bool both = b.press_inv[1][1] != 0.0 && b.press_inv[2][2] != 0.0;
      projectTilt(p, y[0], both, y[1], y[2]);
      // The normal row again, the tilt held where the limit put it.
      const double moved = b.press_k[0][1] * (y[1] - b.lambda[kNormalRow + 1]) + b.press_k[0][2] * (y[2] - b.lambda[kNormalRow + 2]);
      y[0] = b.lambda[kNormalRow] - (rho[0] + moved) / b.press_k[0][0];
      if (y[0] > 0.0) projectTilt(p, y[0], both, y[1], y[2]);
    }
  }
  if (!(y[0] > 0.0)) y[0] = y[1] = y[2] = 0.0;
  double delta[3], residual = 0.0;
  for (int row = 0; row < 3; ++row) {
    delta[row] = y[row] - b.lambda[kNormalRow + row];
    residual = std::max(residual, squared(delta[row] * b.speed[kNormalRow + row]));
  }
  apply(b, delta, kNormalRow, 3);
  return residual;
}

// The rolling rows' effective mass, inverted over the rows that move anything (none against a
// static body: the proxy cannot turn).
void PatchFrictionSolver::bindRolling(Bound& b, const FrictionBlock& fb) {
  Eigen::Matrix2d K;
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 2; ++col) {
      const int r = b.roll + row, c = b.roll + col;
      K(row, col) = b.jac_p[r].dot(b.ang_p[c]) + b.jac_o[r].dot(b.ang_o[c]);
    }
  }
  b.speed[b.roll] = K(0, 0), b.speed[b.roll + 1] = K(1, 1);
  const double largest = std::max({K(0, 0), K(1, 1), 0.0});
  const bool active = largest > 0.0 && K.determinant() > kInactiveRow * largest * largest;
  const Eigen::Matrix2d inverse = active ? Eigen::Matrix2d(K.inverse()) : Eigen::Matrix2d::Zero();
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 2; ++col) b.roll_inv[row][col] = inverse(row, col);
  }
  // A points block's points' levers for pressMoment: they do not move during the solve.
  if (fb.aggregate) return;
  if (arm_.size() < points_.size()) arm_.resize(points_.size());
  for (int i = fb.first_point; i < fb.first_point + fb.point_count; ++i) {
    const FrictionPoint& fp = points_[static_cast<std::size_t>(i)];
    const btVector3& at = fp.proxy_is_a ? fp.point->getPositionWorldOnB() : fp.point->getPositionWorldOnA();
    arm_[static_cast<std::size_t>(i)] = (at - fb.centre).cross(b.n);
  }
}

// The moment (about the block's centre, tangential, N m s) the block's pressing rows already
// take from the body: a points block's points' normal impulses at their offsets, an aggregate's
// tilt impulse. The rolling rows' impulse L acts on the body as -L, these as -P. `normal`
// receives the block's normal impulse (blockNormal), summed in the same pass.
btVector3 PatchFrictionSolver::pressMoment(const Bound& b, double& normal) const {
  const FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
  if (fb.aggregate) {
    normal = b.lambda[kNormalRow];
    return b.lambda[kNormalRow + 1] * fb.press.tilt_axis[0] + b.lambda[kNormalRow + 2] * fb.press.tilt_axis[1];
  }
  btVector3 moment(0, 0, 0);
  normal = 0.0;
  for (int i = fb.first_point; i < fb.first_point + fb.point_count; ++i) {
    const int j = pool_index_[static_cast<std::size_t>(i)];
    if (j < 0) continue;
    const double lambda_n = std::max(0.0, static_cast<double>(m_tmpSolverContactConstraintPool[j].m_appliedImpulse));
    moment += lambda_n * arm_[static_cast<std::size_t>(i)];
    normal += lambda_n;
  }
  return moment;
}

// One step of a block's rolling rows: the impulse L that stops the body turning about the
// tangent axes, such that the contact's whole moment about them, L plus what its pressing rows
// take (pressMoment), stays within `rolling` N: the pressure cannot move past the patch's edge.
double PatchFrictionSolver::solveRolling(Bound& b, double normal, const btVector3& press) {
  if (b.roll_inv[0][0] == 0.0) return 0.0;
  const FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
  // Angular rows: only the relative spin is read.
  const btVector3 spin = spinOf(m_tmpSolverBodyPool[b.proxy_body]) - spinOf(m_tmpSolverBodyPool[b.object_body]);
  const int r = b.roll;
  const double u0 = b.jac_p[r].dot(spin), u1 = b.jac_p[r + 1].dot(spin);
  double y0 = b.lambda[r] - (b.roll_inv[0][0] * u0 + b.roll_inv[0][1] * u1);
  double y1 = b.lambda[r + 1] - (b.roll_inv[1][0] * u0 + b.roll_inv[1][1] * u1);
  const double p0 = press.dot(b.t1), p1 = press.dot(b.t2);
  const double limit = fb.rolling * normal, size = std::sqrt((y0 + p0) * (y0 + p0) + (y1 + p1) * (y1 + p1));
  if (size > limit) {
    const double scale = limit > 0.0 ? limit / size : 0.0;
    y0 = (y0 + p0) * scale - p0;
    y1 = (y1 + p1) * scale - p1;
  }
  const double delta[2] = {y0 - b.lambda[r], y1 - b.lambda[r + 1]};
  apply(b, delta, r, 2);
  return std::max(squared(delta[0] * b.speed[r]), squared(delta[1] * b.speed[r + 1]));
}

// The normal impulse a block's friction is limited by.
double PatchFrictionSolver::blockNormal(const Bound& b) const {
  const FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
  if (fb.aggregate) return b.lambda[kNormalRow];
  double normal = 0.0;
  for (int i = fb.first_point; i < fb.first_point + fb.point_count; ++i) {
    const int j = pool_index_[static_cast<std::size_t>(i)];
    if (j < 0) continue;
    const double lambda_n = std::max(0.0, static_cast<double>(m_tmpSolverContactConstraintPool[j].m_appliedImpulse));
    normal += lambda_n;
  }
  return normal;
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
double PatchFrictionSolver::solveBlock(Bound& b, double normal) {
  const FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
  const double slide_limit = fb.friction * normal;
  const double twist_limit = fb.torsion * normal;
  const double limit[kFrictionRows] = {slide_limit, slide_limit, twist_limit};
  double u[kFrictionRows];
  const Motion m = motion(b);
  for (int row = 0; row < kFrictionRows; ++row) u[row] = b.k_inv[row][row] != 0.0 ? relativeVelocity(b, m, row) : 0.0;
  // A sticking contact's rows also take back its slip and turn since its anchor.
  for (int row = 0; row < kFrictionRows; ++row) u[row] += b.k_inv[row][row] != 0.0 ? b.slip_bias[row] : 0.0;
  u[2] += b.twist_cfm * b.lambda[2];
  Eigen::Vector3d y, d = Eigen::Vector3d::Zero();
  Eigen::Matrix3d e;
  for (int row = 0; row < kFrictionRows; ++row) {
    y(row) = b.lambda[row] - (b.k_inv[row][0] * u[0] + b.k_inv[row][1] * u[1] + b.k_inv[row][2] * u[2]);
    for (int col = 0; col < kFrictionRows; ++col) e(row, col) = b.k_inv[row][col];
  }
  for (int row = 0; row < kFrictionRows; ++row) {
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
  double delta[kFrictionRows], residual = 0.0;
  for (int row = 0; row < kFrictionRows; ++row) {
    delta[row] = y(row) - b.lambda[row];
    residual = std::max(residual, squared(delta[row] * b.speed[row]));
  }
  apply(b, delta, 0, kFrictionRows);
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
  ++iterations_;
  double residual = btSequentialImpulseConstraintSolver::solveSingleIteration(
      iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debug);
  if (info.m_solverMode & SOLVER_USE_WARMSTARTING) residual = std::max(residual, limitContactFriction(info));
  for (Bound& b : bound_) {
    if (b.aggregate) residual = std::max(residual, solvePress(b));
    // The normal impulse that limits the friction (and with rolling rows, the moment the
    // pressing rows take) in one pass over the points; neither changes until the next iteration.
    double normal = 0.0;
    const btVector3 press = b.roll >= 0 ? pressMoment(b, normal) : btVector3(0, 0, 0);
    if (b.roll < 0) normal = blockNormal(b);
    residual = std::max(residual, solveBlock(b, normal));
    if (b.roll >= 0) residual = std::max(residual, solveRolling(b, normal, press));
  }
  return static_cast<btScalar>(residual);
}

btScalar PatchFrictionSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                            const btContactSolverInfo& info) {
  for (const Bound& b : bound_) {
    FrictionBlock& fb = blocks_[static_cast<std::size_t>(b.block)];
    fb.force = b.lambda[0] * b.t1 + b.lambda[1] * b.t2;
    fb.torque = b.lambda[2];
    fb.rolling_impulse = b.roll >= 0 ? b.lambda[b.roll] * b.t1 + b.lambda[b.roll + 1] * b.t2 : btVector3(0, 0, 0);
    fb.normal_impulse = blockNormal(b);
    const Motion m = motion(b);
    fb.moved = info.m_timeStep * (m.centre - m.centre.dot(b.n) * b.n);
    fb.turned = info.m_timeStep * m.spin.dot(b.n);
    if (fb.aggregate) fb.press.tilt = b.lambda[kNormalRow + 1] * fb.press.tilt_axis[0] + b.lambda[kNormalRow + 2] * fb.press.tilt_axis[1];
    fb.solved = true;
  }
  bound_.clear();
  if (info.m_solverMode & SOLVER_USE_WARMSTARTING) keepContacts(info);
  drawSkippedShuffles(info);
  return btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
}

// The shuffles of the iterations a converged solve skipped, drawn all the same: Bullet draws
// one number a row of its non-contact pool every iteration, and one a row of its contact and
// friction pools in each of the first m_numIterations (btRandInt2, SOLVER_RANDMIZE_ORDER), from a
// generator that runs on across steps; so the next step's orders are those of a solve that ran
// every iteration. Ending early would otherwise change them from that step on, and a contact
// that the iterations leave short of convergence depends on them: a ball pressed into a bowl at
// 9 or 11 iterations chatters at 500 Hz, 1.3 um, under orders that alternate from step to step
// (a generator's low bit alternates).
void PatchFrictionSolver::drawSkippedShuffles(const btContactSolverInfo& info) {
  if (!(info.m_solverMode & SOLVER_RANDMIZE_ORDER)) return;
  const int iterations = std::max(m_maxOverrideNumSolverIterations, info.m_numIterations);
  const long non_contact = m_tmpSolverNonContactConstraintPool.size();
  const long contact = static_cast<long>(m_tmpSolverContactConstraintPool.size()) + m_tmpSolverContactFrictionConstraintPool.size();
  long draws = 0;
  for (int it = iterations_; it < iterations; ++it) draws += non_contact + (it < info.m_numIterations ? contact : 0);
  for (; draws > 0; --draws) btRand2();
}

}  // namespace gf::sim
