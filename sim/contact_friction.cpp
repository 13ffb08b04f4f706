// Bullet's own contacts (a body on the ground, a body on a body) in PatchFrictionSolver: their
// friction rows warm-started across steps, limited after every iteration, and kept for the next
// step (sim/detail/patch_friction.hpp).
#include <algorithm>
#include <cmath>

#include "sim/detail/patch_friction.hpp"

namespace gf::sim {
namespace {

// A point whose own point on body A moved further than this from its anchor's is another point
// (Bullet reuses a manifold's slots): it anchors afresh (m).
constexpr double kSamePoint = 1e-4;
// A point that slid further than this since its anchor has slid: it anchors afresh (m).
constexpr double kAnchorReach = 1e-3;
// A point whose friction ends the solve within this share of its limit slides.
constexpr double kSlideMargin = 1e-3;

}  // namespace

// Anchors Bullet's own contact points (a body on the ground, on a wall, on a body): where both
// bodies' material points met when the point started sticking, kept while it sticks, and how
// far they have slid apart since, which the point's friction rows take back (their target
// relative velocity is -erp2 slip / h, Bullet's share for contact depths). Friction rows that
// aim at a velocity only let the slip the iterations leave add up: a box pressed against a wall
// by a still finger crept along it by 60 micrometres a minute under the 0.1 N the press left.
void PatchFrictionSolver::anchorContacts(btPersistentManifold** manifolds, int count, const btContactSolverInfo& info) {
  std::swap(anchors_, last_anchors_);
  anchors_.clear();
  for (int m = 0; m < count; ++m) {
    const btPersistentManifold* manifold = manifolds[m];
    const btCollisionObject *a = manifold->getBody0(), *b = manifold->getBody1();
    for (int i = 0; i < manifold->getNumContacts(); ++i) {
      const btManifoldPoint& cp = manifold->getContactPoint(i);
      if (!(cp.m_combinedFriction > 0.0) || cp.getDistance() > manifold->getContactProcessingThreshold()) continue;
      ContactAnchor anchor{&cp, a, b, cp.m_localPointA, cp.m_localPointB, btVector3(0, 0, 0), false};
      const ContactAnchor* last = nullptr;
      const auto it = std::lower_bound(last_anchors_.begin(), last_anchors_.end(), &cp,
                                       [](const ContactAnchor& x, const btManifoldPoint* p) { return x.point < p; });
      if (it != last_anchors_.end() && it->point == &cp) last = &*it;
      if (last && last->sticks && last->a == a && last->b == b && (last->on_a - cp.m_localPointA).length() <= kSamePoint) {
        btVector3 slip = a->getWorldTransform() * last->on_a - b->getWorldTransform() * last->on_b;
        slip -= slip.dot(cp.m_normalWorldOnB) * cp.m_normalWorldOnB;
        if (slip.length() <= kAnchorReach) anchor.on_a = last->on_a, anchor.on_b = last->on_b, anchor.slip = slip;
      }
      anchors_.push_back(anchor);
    }
  }
  std::sort(anchors_.begin(), anchors_.end(), [](const ContactAnchor& x, const ContactAnchor& y) { return x.point < y.point; });
  const double pull = info.m_timeStep > 0.0 ? info.m_erp2 / info.m_timeStep : 0.0;
  const int per_contact = (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ? 2 : 1;
  for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[j];
    const ContactAnchor* anchor = anchorOf(static_cast<const btManifoldPoint*>(c.m_originalContactPoint));
    if (!anchor || !(c.m_friction > 0.0) || c.m_frictionIndex < 0) continue;
    for (int k = 0; k < per_contact; ++k) {
      btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[c.m_frictionIndex + k];
      row.m_rhs -= static_cast<btScalar>(pull * anchor->slip.dot(row.m_contactNormal1) * row.m_jacDiagABInv);
    }
  }
}

PatchFrictionSolver::ContactAnchor* PatchFrictionSolver::anchorOf(const btManifoldPoint* point) {
  if (!point) return nullptr;
  const auto it = std::lower_bound(anchors_.begin(), anchors_.end(), point,
                                   [](const ContactAnchor& x, const btManifoldPoint* p) { return x.point < p; });
  return it != anchors_.end() && it->point == point ? &*it : nullptr;
}

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
    if (ContactAnchor* anchor = anchorOf(cp)) {
      const double normal = std::max(0.0, static_cast<double>(c.m_appliedImpulse));
      anchor->sticks = normal > 0.0 && impulse.length() < (1.0 - kSlideMargin) * c.m_friction * normal;
    }
  }
}

}  // namespace gf::sim
