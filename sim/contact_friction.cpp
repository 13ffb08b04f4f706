// Bullet's own contacts (a body on the ground, a body on a body) in PatchFrictionSolver: their
// friction rows warm-started across steps, limited after every iteration, and kept for the next
// step (sim/detail/patch_friction.hpp).
#include <algorithm>
#include <cmath>

#include "sim/detail/patch_friction.hpp"

namespace gf::sim {

// Warm-starts the friction rows of Bullet's own contacts (ours carry no friction: their blocks
// do): last step's impulse, kept as components along btPlaneSpace1 of the point's normal
// (keepContactFriction), onto this step's row directions, within mu times the point's
// warm-started normal impulse. Without it a pressed body's friction on the ground is rebuilt
// from zero every step, and the slip the iterations leave, in proportion to the load, turns
// into more load through a finger's coupling spring: a held press pushed the body away.
void PatchFrictionSolver::warmStartContactFriction(const btContactSolverInfo& info) {
  const bool two = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) != 0;
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    const auto* cp = static_cast<const btManifoldPoint*>(c.m_originalContactPoint);
    if (!cp || !(c.m_friction > 0.0) || c.m_frictionIndex < 0) continue;
    const double along1 = cp->m_appliedImpulseLateral1, along2 = cp->m_appliedImpulseLateral2;
    if (along1 == 0.0 && along2 == 0.0) continue;
    btVector3 e1, e2;
    btPlaneSpace1(cp->m_normalWorldOnB, e1, e2);
    const btVector3 kept = along1 * e1 + along2 * e2;
    btSolverConstraint* rows[2] = {&m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex],
                                   two ? &m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + 1] : nullptr};
    const double f = info.m_warmstartingFactor;
    const double lambda[2] = {f * kept.dot(rows[0]->m_contactNormal1), rows[1] ? f * kept.dot(rows[1]->m_contactNormal1) : 0.0};
    // The point's normal row is warm-started already (m_appliedImpulse).
    const double limit = c.m_friction * std::max(0.0, static_cast<double>(c.m_appliedImpulse));
    const double size = std::sqrt(lambda[0] * lambda[0] + lambda[1] * lambda[1]);
    const double scale = size > limit ? (size > 0.0 ? limit / size : 0.0) : 1.0;
    for (int k = 0; k < 2; ++k) {
      btSolverConstraint* row = rows[k];
      if (!row) continue;
      const double l = lambda[k] * scale;
      row->m_appliedImpulse = static_cast<btScalar>(l);
      if (l == 0.0) continue;
      btSolverBody& a = m_tmpSolverBodyPool[row->m_solverBodyIdA];
      btSolverBody& b = m_tmpSolverBodyPool[row->m_solverBodyIdB];
      a.internalApplyImpulse(row->m_contactNormal1 * a.internalGetInvMass(), row->m_angularComponentA, static_cast<btScalar>(l));
      b.internalApplyImpulse(row->m_contactNormal2 * b.internalGetInvMass(), row->m_angularComponentB, static_cast<btScalar>(l));
    }
  }
}

// Bullet solves a contact's friction rows only while its normal impulse is above zero: a warm
// start (warmStartContactFriction) on a point the iteration released would stay. After every
// iteration each of Bullet's friction rows is brought within mu times its contact's normal
// impulse, as Bullet limits it.
double PatchFrictionSolver::limitContactFriction(const btContactSolverInfo& info) {
  const int per_contact = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ? 2 : 1;
  double residual = 0.0;
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    if (!c.m_originalContactPoint || !(c.m_friction > 0.0) || c.m_frictionIndex < 0) continue;
    const double limit = c.m_friction * std::max(0.0, static_cast<double>(c.m_appliedImpulse));
    for (int k = 0; k < per_contact; ++k) {
      btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + k];
      const double l = row.m_appliedImpulse, clamped = std::clamp(l, -limit, limit);
      if (clamped == l) continue;
      const double d = clamped - l;
      row.m_appliedImpulse = static_cast<btScalar>(clamped);
      btSolverBody& a = m_tmpSolverBodyPool[row.m_solverBodyIdA];
      btSolverBody& b = m_tmpSolverBodyPool[row.m_solverBodyIdB];
      a.internalApplyImpulse(row.m_contactNormal1 * a.internalGetInvMass(), row.m_angularComponentA, static_cast<btScalar>(d));
      b.internalApplyImpulse(row.m_contactNormal2 * b.internalGetInvMass(), row.m_angularComponentB, static_cast<btScalar>(d));
      residual = std::max(residual, d * d);
    }
  }
  return residual;
}

// Bullet's own contacts' solved friction as components along btPlaneSpace1 of each point's
// normal, for the next step's warm start (read before Bullet's write-back, which stores them
// along this step's row directions, written after it).
void PatchFrictionSolver::keepContactFriction() {
  kept_friction_.clear();
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    auto* cp = static_cast<btManifoldPoint*>(c.m_originalContactPoint);
    if (!cp || !(c.m_friction > 0.0) || c.m_frictionIndex < 0) continue;
    btVector3 impulse(0, 0, 0);
    for (int k = 0; k < 2 && c.m_frictionIndex + k < m_tmpSolverContactFrictionConstraintPool.size(); ++k) {
      const btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + k];
      if (row.m_frictionIndex != j) break;  // a friction row of this contact names it
      impulse += row.m_appliedImpulse * row.m_contactNormal1;
    }
    btVector3 e1, e2;
    btPlaneSpace1(cp->m_normalWorldOnB, e1, e2);
    kept_friction_.push_back({cp, impulse.dot(e1), impulse.dot(e2)});
  }
}

}  // namespace gf::sim
