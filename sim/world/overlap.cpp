#include "sim/world/overlap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace gf::sim {

double discOverlapArea(double r1, double r2, double distance) {
  if (!(r1 > 0.0) || !(r2 > 0.0)) return 0.0;
  const double d = std::abs(distance);
  if (d >= r1 + r2) return 0.0;
  const double small = std::min(r1, r2);
  if (d <= std::abs(r1 - r2)) return std::numbers::pi * small * small;
  // The lens: two circular segments, each a sector less its triangle (the kite's area once).
  const double c1 = std::clamp((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1), -1.0, 1.0);
  const double c2 = std::clamp((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2), -1.0, 1.0);
  const double kite = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
  return r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) - 0.5 * std::sqrt(std::max(0.0, kite));
}

DiscOverlap discOverlap(const PatchDisc& a, const PatchDisc& b) {
  DiscOverlap o;
  if (!(a.radius > 0.0) || !(b.radius > 0.0)) return o;
  // Patches facing apart (90 degrees or more between their normals: opposite faces of a pinched
  // body, two faces of an edge) share no tangent plane and never overlap.
  if (!(a.outward_normal.dot(b.outward_normal) > 0.0)) return o;
  // The common tangent plane: normal to the mean of the two normals.
  const Vec3 n = (a.outward_normal + b.outward_normal).normalized();
  Vec3 gap = a.centre - b.centre;
  gap -= gap.dot(n) * n;
  o.distance = gap.norm();
  o.area = discOverlapArea(a.radius, b.radius, o.distance);
  o.depth = std::max(0.0, a.radius + b.radius - o.distance);
  if (o.distance > 1e-12) o.apart = gap / o.distance;
  return o;
}

Vec3 pushApartForce(const DiscOverlap& o, double stiffness, double max_force) {
  return std::min(stiffness * o.depth, max_force) * o.apart;
}

namespace {

// The contact's points with their solved normal loads: the true point, then sgos_world.
template <class F>
void forEachPoint(const ContactSnapshot& c, F&& f) {
  f(c.point_world, c.point_load.normal);
  for (std::size_t k = 0; k < c.sgos_world.size(); ++k) {
    f(c.sgos_world[k], k < c.loads.size() ? c.loads[k].normal : 0.0);
  }
}

}  // namespace

void mergePatches(const ContactSnapshot& a, const ContactSnapshot& b, double press_a, double press_b,
                  std::vector<MergedPoint>& out) {
  out.clear();
  const double presses = std::max(0.0, press_a) + std::max(0.0, press_b);
  const double split = presses > 0.0 ? std::max(0.0, press_a) / presses : 0.5;
  forEachPoint(a, [&](const Vec3& p, double load) { out.push_back({p, load, 1.0}); });
  const std::size_t a_count = out.size();
  const double reach = kMergeDistanceFraction * std::min(a.radius, b.radius);
  forEachPoint(b, [&](const Vec3& p, double load) {
    // The nearest point of a within reach takes this one's load: counted once, split by presses.
    std::size_t best = a_count;
    double best_distance = reach;
    for (std::size_t k = 0; k < a_count; ++k) {
      const double d = (out[k].position - p).norm();
      if (d < best_distance) best = k, best_distance = d;
    }
    if (best == a_count) {
      out.push_back({p, load, 0.0});
      return;
    }
    out[best].normal += load;
    out[best].share_a = split;
  });
}

double minPointDistance(const std::vector<MergedPoint>& points) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j) best = std::min(best, (points[i].position - points[j].position).norm());
  }
  return best;
}

}  // namespace gf::sim
