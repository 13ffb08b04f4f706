// Two fingers' patches on one body (docs/overlap.md): their overlap measured every step, and
// handled as the scene's `world.overlap` asks: ignored (the paper), pushed apart (a force on
// both proxies, felt through their couplings) or merged (coinciding points share one point's
// load). Runs in beforeSolve, after every contact's patch and before the models' rows.
#include <algorithm>
#include <cmath>

#include "sim/world/world_impl.hpp"
#include "sim/world/overlap.hpp"

namespace gf::sim {
namespace {

// A contact's patch as a disc in the world: its true point, its normal and its Eq. 1 radius.
PatchDisc discOf(const FingerContact& c) {
  const bool patch = c.record.patch.valid && c.sgo_count > 0;
  return {toEigen(c.truth.point_world), toEigen(c.truth.outward_normal_world), patch ? c.record.patch.radius : 0.0};
}

// How hard the finger presses the contact's body (N): its coupling force along the press direction.
double pressOf(const Vec3& coupling_force, const FingerContact& c) {
  return std::max(0.0, -coupling_force.dot(toEigen(c.truth.outward_normal_world)));
}

// Patch point i of a contact (its SGOs, then a filled patch's inner points), to change its share.
Sgo& patchPoint(Patch& patch, int i) {
  const auto k = static_cast<std::size_t>(i);
  return k < patch.sgos.size() ? patch.sgos[k] : patch.inner[k - patch.sgos.size()];
}

// Scales a patch's shares (its centre's and its points') to add up to 1 again.
void renormalise(Patch& patch, int count) {
  double total = patch.centre_share;
  for (int i = 0; i < count; ++i) total += patchPoint(patch, i).load_share;
  if (!(total > 0.0)) return;
  patch.centre_share /= total;
  for (int i = 0; i < count; ++i) patchPoint(patch, i).load_share /= total;
}

// A merged point's share never falls below this fraction of one point's: a point of zero
// stiffness would be a rigid row to Bullet (its softness is 1 / (dt k + c)).
constexpr double kMinMergedShare = 1e-3;

}  // namespace

void World::Impl::makeOverlapPairs() {
  const int n = static_cast<int>(fingers.size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) overlaps.push_back({a, b});
  }
}

void World::Impl::handleOverlaps() {
  const OverlapMode mode = desc.world.overlap;
  if (mode == OverlapMode::kPushApart) {
    for (Finger& f : fingers) f.overlap_push = Vec3::Zero();
  }
  const double dt = world.getSolverInfo().m_timeStep;
  for (OverlapPair& pair : overlaps) {
    Finger& fa = fingers[static_cast<std::size_t>(pair.a)];
    Finger& fb = fingers[static_cast<std::size_t>(pair.b)];
    pair.area = 0.0;
    for (int i = 0; i < fa.contact_count; ++i) {
      for (int j = 0; j < fb.contact_count; ++j) {
        FingerContact& ca = fa.contacts[i];
        FingerContact& cb = fb.contacts[j];
        if (ca.record.body != cb.record.body) continue;
        const DiscOverlap o = discOverlap(discOf(ca), discOf(cb));
        pair.area += o.area;
        if (mode == OverlapMode::kPushApart) {
          const double limit = std::min(desc.fingers[static_cast<std::size_t>(pair.a)].coupling.max_force,
                                        desc.fingers[static_cast<std::size_t>(pair.b)].coupling.max_force);
          const Vec3 push = pushApartForce(o, desc.world.overlap_stiffness, limit);
          fa.overlap_push += push;
          fb.overlap_push -= push;
        } else if (mode == OverlapMode::kMerge && o.area > 0.0) {
          const double pa = pressOf(fa.force, ca), pb = pressOf(fb.force, cb);
          mergeCoinciding(ca, cb, pa + pb > 0.0 ? pa / (pa + pb) : 0.5);
        }
      }
    }
    pair.peak = std::max(pair.peak, pair.area);
    pair.integral += pair.area * dt;
  }
}

// Each point of b's patch closer than kMergeDistanceFraction times the smaller radius to a point
// of a's is one point with it: the two carry one point's share between them (the mean of their
// shares), a's part `share_a`, b's the rest; each patch's shares then add up to 1 again.
void World::Impl::mergeCoinciding(FingerContact& a, FingerContact& b, double share_a) const {
  Patch& pa = a.record.patch;
  Patch& pb = b.record.patch;
  const double reach = kMergeDistanceFraction * std::min(pa.radius, pb.radius);
  bool merged = false;
  for (int j = 0; j < b.sgo_count; ++j) {
    int best = -1;
    btScalar best_distance = reach;
    for (int i = 0; i < a.sgo_count; ++i) {
      const btScalar d = a.sgo_world[static_cast<std::size_t>(i)].distance(b.sgo_world[static_cast<std::size_t>(j)]);
      if (d < best_distance) best = i, best_distance = d;
    }
    if (best < 0) continue;
    Sgo& p = patchPoint(pa, best);
    Sgo& q = patchPoint(pb, j);
    const double one = 0.5 * (p.load_share + q.load_share);
    p.load_share = one * std::max(share_a, kMinMergedShare);
    q.load_share = one * std::max(1.0 - share_a, kMinMergedShare);
    merged = true;
  }
  if (!merged) return;
  renormalise(pa, a.sgo_count);
  renormalise(pb, b.sgo_count);
}

}  // namespace gf::sim
