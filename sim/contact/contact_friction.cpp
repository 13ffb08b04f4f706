// Bullet's own contacts (a body on the ground, on a wall, on a body) in PatchFrictionSolver: each
// point found again from last step by its bodies and its point on the first, its normal and
// friction rows warm-started from there, its friction anchored while it sticks and limited
// after every iteration (sim/contact/patch_friction.hpp).
#include <algorithm>
#include <cmath>
#include <tuple>

#include "sim/contact/patch_friction.hpp"

namespace gf::sim {
namespace {

// Last step's point of the same bodies whose point on body A lies within this of this one's is
// the same point (m). Bullet keeps a manifold's points while they move less than its breaking
// threshold; a resting point moves by nanometres.
constexpr double kSamePoint = 1e-4;
// A point that slid further than this since its anchor has slid: it anchors afresh (m).
constexpr double kAnchorReach = 1e-3;
// A point whose friction ends the solve within this share of its limit slides.
constexpr double kSlideMargin = 1e-3;

// Bullet's own points: ours (a finger's) carry no friction of their own, their blocks do.
bool bulletPoint(const btSolverConstraint& c) {
  return c.m_originalContactPoint && c.m_friction > 0.0 && c.m_frictionIndex >= 0;
}

void applyRow(btSolverBody& a, btSolverBody& b, const btSolverConstraint& row, double impulse) {
  a.internalApplyImpulse(row.m_contactNormal1 * a.internalGetInvMass(), row.m_angularComponentA, static_cast<btScalar>(impulse));
  b.internalApplyImpulse(row.m_contactNormal2 * b.internalGetInvMass(), row.m_angularComponentB, static_cast<btScalar>(impulse));
}

}  // namespace

PatchFrictionSolver::ContactMemo* PatchFrictionSolver::memoOf(const btManifoldPoint* point) {
  const auto it = std::lower_bound(memos_.begin(), memos_.end(), point,
                                   [](const ContactMemo& x, const btManifoldPoint* p) { return x.point < p; });
  return it != memos_.end() && it->point == point ? &*it : nullptr;
}

// Last step's memo of the point of bodies (a, b) nearest to `at_a` (on a, its frame) within
// kSamePoint, or null. last_memos_ is sorted by bodies.
const PatchFrictionSolver::ContactMemo* PatchFrictionSolver::lastMemo(const btCollisionObject* a, const btCollisionObject* b,
                                                                      const btVector3& at_a) const {
  const auto key = [](const ContactMemo& m) { return std::make_tuple(m.a, m.b); };
  auto it = std::lower_bound(last_memos_.begin(), last_memos_.end(), std::make_tuple(a, b),
                             [&](const ContactMemo& m, const auto& k) { return key(m) < k; });
  const ContactMemo* best = nullptr;
  double nearest = kSamePoint;
  for (; it != last_memos_.end() && it->a == a && it->b == b; ++it) {
    const double d = (it->at_a - at_a).length();
    if (d <= nearest) nearest = d, best = &*it;
  }
  return best;
}

// Finds each of Bullet's own points from last step (lastMemo) with how far it has slid since it
// started sticking (its solved relative velocity summed step by step: a ball rolling on the
// ground slides nowhere), which its friction rows take back while it sticks (target relative
// velocity -erp2 slip / h, Bullet's share for contact depths). Friction rows that aim at a velocity only let the
// slip the iterations leave add up: a box pressed against a wall by a still finger crept along
// it by 60 micrometres a minute under the 0.1 N the press left.
// Bullet may solve a step's islands in several batches: each adds its points to the step's.
void PatchFrictionSolver::recallContacts(btPersistentManifold** manifolds, int count, const btContactSolverInfo& info) {
  for (int m = 0; m < count; ++m) {
    const btPersistentManifold* manifold = manifolds[m];
    const btCollisionObject *a = manifold->getBody0(), *b = manifold->getBody1();
    for (int i = 0; i < manifold->getNumContacts(); ++i) {
      const btManifoldPoint& cp = manifold->getContactPoint(i);
      if (!(cp.m_combinedFriction > 0.0) || cp.getDistance() > manifold->getContactProcessingThreshold()) continue;
      ContactMemo memo;
      memo.point = &cp;
      memo.a = a, memo.b = b;
      memo.at_a = cp.m_localPointA;
      if (const ContactMemo* last = lastMemo(a, b, cp.m_localPointA)) {
        memo.normal = last->normal, memo.along1 = last->along1, memo.along2 = last->along2;
        if (last->sticks) {
          const btVector3 slip = last->slip - last->slip.dot(cp.m_normalWorldOnB) * cp.m_normalWorldOnB;
          if (slip.length() <= kAnchorReach) memo.slip = slip;
        }
      }
      memos_.push_back(memo);
    }
  }
  std::sort(memos_.begin(), memos_.end(), [](const ContactMemo& x, const ContactMemo& y) { return x.point < y.point; });
  const double pull = info.m_timeStep > 0.0 ? info.m_erp2 / info.m_timeStep : 0.0;
  const int per_contact = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ? 2 : 1;
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    const ContactMemo* memo = bulletPoint(c) ? memoOf(static_cast<const btManifoldPoint*>(c.m_originalContactPoint)) : nullptr;
    if (!memo) continue;
    for (int k = 0; k < per_contact; ++k) {
      btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + k];
      row.m_rhs -= static_cast<btScalar>(pull * memo->slip.dot(row.m_contactNormal1) * row.m_jacDiagABInv);
    }
  }
}

// Warm-starts Bullet's own points from their memos: the normal row where Bullet has nothing (a
// point new to its manifold, as a concave mesh's are every step), and the friction rows always
// (Bullet 3 starts them at zero): last step's impulse, kept along btPlaneSpace1 of the normal,
// onto this step's row directions, within mu times the normal impulse. Without it a pressed
// body's friction on the ground was rebuilt from zero every step, and the slip the iterations
// left, in proportion to the load, turned into more load through a finger's coupling spring: a
// held press pushed the body away.
void PatchFrictionSolver::warmStartContacts(const btContactSolverInfo& info) {
  const bool two = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) != 0;
  const double f = info.m_warmstartingFactor;
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    const ContactMemo* memo = bulletPoint(c) ? memoOf(static_cast<const btManifoldPoint*>(c.m_originalContactPoint)) : nullptr;
    if (!memo) continue;
    btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
    btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
    if (c.m_appliedImpulse == 0.0 && memo->normal > 0.0) {
      c.m_appliedImpulse = static_cast<btScalar>(f * memo->normal);
      applyRow(a, b, c, c.m_appliedImpulse);
    }
    if (memo->along1 == 0.0 && memo->along2 == 0.0) continue;
    const auto* cp = static_cast<const btManifoldPoint*>(c.m_originalContactPoint);
    btVector3 e1, e2;
    btPlaneSpace1(cp->m_normalWorldOnB, e1, e2);
    const btVector3 kept = memo->along1 * e1 + memo->along2 * e2;
    btSolverConstraint* rows[2] = {&m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex],
                                   two ? &m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + 1] : nullptr};
    const double lambda[2] = {f * kept.dot(rows[0]->m_contactNormal1), rows[1] ? f * kept.dot(rows[1]->m_contactNormal1) : 0.0};
    const double limit = c.m_friction * std::max(0.0, static_cast<double>(c.m_appliedImpulse));
    const double size = std::sqrt(lambda[0] * lambda[0] + lambda[1] * lambda[1]);
    const double scale = size > limit ? (size > 0.0 ? limit / size : 0.0) : 1.0;
    for (int k = 0; k < 2; ++k) {
      if (!rows[k]) continue;
      const double l = lambda[k] * scale;
      rows[k]->m_appliedImpulse = static_cast<btScalar>(l);
      if (l != 0.0) applyRow(a, b, *rows[k], l);
    }
  }
}

// Bullet solves a contact's friction rows only while its normal impulse is above zero: a warm
// start (warmStartContacts) on a point the iteration released would stay. After every iteration
// each of Bullet's friction rows is brought within mu times its contact's normal impulse, as
// Bullet limits it.
double PatchFrictionSolver::limitContactFriction(const btContactSolverInfo& info) {
  const int per_contact = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ? 2 : 1;
  double residual = 0.0;
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    if (!bulletPoint(c)) continue;
    const double limit = c.m_friction * std::max(0.0, static_cast<double>(c.m_appliedImpulse));
    for (int k = 0; k < per_contact; ++k) {
      btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + k];
      const double l = row.m_appliedImpulse, clamped = std::clamp(l, -limit, limit);
      if (clamped == l) continue;
      row.m_appliedImpulse = static_cast<btScalar>(clamped);
      applyRow(m_tmpSolverBodyPool[row.m_solverBodyIdA], m_tmpSolverBodyPool[row.m_solverBodyIdB], row, clamped - l);
      // Bullet's residual: the change of velocity, the impulse over the row's effective mass.
      const double speed = row.m_jacDiagABInv != 0.0 ? (clamped - l) / row.m_jacDiagABInv : 0.0;
      residual = std::max(residual, speed * speed);
    }
  }
  return residual;
}

// What each of Bullet's own points leaves for the next step: its normal impulse, its friction
// impulse along btPlaneSpace1 of its normal, and whether it stuck.
void PatchFrictionSolver::keepContacts(const btContactSolverInfo& info) {
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    ContactMemo* memo = bulletPoint(c) ? memoOf(static_cast<const btManifoldPoint*>(c.m_originalContactPoint)) : nullptr;
    if (!memo) continue;
    const btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
    const btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
    btVector3 impulse(0, 0, 0), moved(0, 0, 0);
    for (int k = 0; k < 2 && c.m_frictionIndex + k < m_tmpSolverContactFrictionConstraintPool.size(); ++k) {
      const btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + k];
      if (row.m_frictionIndex != j) break;  // a friction row of this contact names it
      impulse += row.m_appliedImpulse * row.m_contactNormal1;
      // The row's relative velocity (A's side against B's along its direction) after the solve.
      const double v = row.m_contactNormal1.dot(velocityOf(a)) + row.m_relpos1CrossNormal.dot(spinOf(a)) +
                       row.m_contactNormal2.dot(velocityOf(b)) + row.m_relpos2CrossNormal.dot(spinOf(b));
      moved += info.m_timeStep * v * row.m_contactNormal1;
    }
    btVector3 e1, e2;
    btPlaneSpace1(memo->point->m_normalWorldOnB, e1, e2);
    memo->normal = std::max(0.0, static_cast<double>(c.m_appliedImpulse));
    memo->along1 = impulse.dot(e1), memo->along2 = impulse.dot(e2);
    memo->sticks = memo->normal > 0.0 && impulse.length() < (1.0 - kSlideMargin) * c.m_friction * memo->normal;
    memo->slip = memo->sticks ? memo->slip + moved : btVector3(0, 0, 0);
    memo->kept = true;
  }
}

// The step's memos become last step's (what did not reach a solve leaves nothing), sorted by
// bodies for lastMemo.
void PatchFrictionSolver::rollContactMemos() {
  std::swap(memos_, last_memos_);
  for (ContactMemo& m : last_memos_) {
    if (!m.kept) m.normal = m.along1 = m.along2 = 0.0, m.sticks = false, m.slip.setZero();
  }
  std::sort(last_memos_.begin(), last_memos_.end(), [](const ContactMemo& x, const ContactMemo& y) {
    return std::make_tuple(x.a, x.b) < std::make_tuple(y.a, y.b);
  });
  memos_.clear();
}

}  // namespace gf::sim
