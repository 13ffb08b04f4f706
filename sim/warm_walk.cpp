#include "sim/warm_walk.hpp"

#include <array>
#include <cmath>

#include "sim/patch_settings.hpp"

namespace gf::sim {
namespace {

// A carried crossing or end closer than this to its edge's ends or its face's edges (m) is not
// trusted: the walk from the contact might pass the other side of a vertex.
constexpr double kCarryMargin = 1e-10;
// A path meeting an edge at a sine below this is walked from the contact (the crossing point
// would move far along the edge for a small turn).
constexpr double kMinCrossingSine = 1e-6;

// z of the cross product of two vectors of the start plane.
double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

bool faceAllowed(const WalkLimits& l, const Vec3& oriented_normal) {
  const double c = oriented_normal.dot(l.normal);
  return (!l.has_limit || c >= l.cos_limit) && c > l.cos_facing;
}

bool insideFace(const Mesh& m, int f, const Vec3& p) {
  for (int k = 0; k < 3; ++k) {
    if ((p - m.corner(f, k)).dot(m.edgeInwardNormal(f, k)) < kCarryMargin) return false;
  }
  return true;
}

}  // namespace

void WalkCache::reserve() {
  paths.resize(kMaxSgo);
  crossings.resize(static_cast<std::size_t>(kMaxSgo) * kWarmCrossingsPerSgo);
}

StartPlane startPlane(const Mesh& m, int f, double side) {
  const Vec3& x = m.edgeDirection(f, 0);
  return {m.corner(f, 0), x, (side * m.faceNormal(f)).cross(x)};
}

bool carryWalk(const Mesh& m, const WalkLimits& limits, const WalkStart& s, int i, WalkCache& cache,
               std::vector<Vec3>& path_points, Vec3& end, int& end_face) {
  WalkPath& p = cache.paths[static_cast<std::size_t>(i)];
  if (!p.cached || p.start_face != s.face || p.side != s.side || p.crossings > s.budget) return false;
  // The start and direction in the start face's plane.
  const StartPlane plane = startPlane(m, s.face, s.side);
  const Vec3 rel = s.from - plane.origin;
  const double hx = rel.dot(plane.x_axis), hy = rel.dot(plane.y_axis);
  const double dx = s.dir.dot(plane.x_axis), dy = s.dir.dot(plane.y_axis);
  // Each crossing: where the moved line h + t dir meets the edge, X + shift u; it must stay on
  // the edge, in order, short of d, into a face still within the thresholds.
  WalkCrossing* first = cache.crossings.data() + static_cast<std::ptrdiff_t>(i) * kWarmCrossingsPerSgo;
  std::array<double, kWarmCrossingsPerSgo> shift{};
  double last_t = 0.0;
  for (int j = 0; j < p.crossings; ++j) {
    const WalkCrossing& c = first[j];
    const double det = cross2(c.ux, c.uy, dx, dy);
    if (std::abs(det) < kMinCrossingSine || !faceAllowed(limits, c.entered_normal)) return false;
    const double wx = hx - c.x, wy = hy - c.y;
    const double along = cross2(wx, wy, dx, dy) / det, t = cross2(wx, wy, c.ux, c.uy) / det;
    if (!(t > last_t) || !(t < s.d) || !(along > c.to_first + kCarryMargin) ||
        !(along < c.to_second - kCarryMargin)) {
      return false;
    }
    shift[static_cast<std::size_t>(j)] = along;
    last_t = t;
  }
  // The end: the last end moved by the difference, unfolded onto the end face.
  const double ex = hx + s.d * dx, ey = hy + s.d * dy;
  const Vec3 moved = p.end + (ex - p.end_x) * p.axis_x + (ey - p.end_y) * p.axis_y;
  if (!insideFace(m, p.end_face, moved)) return false;
  // The path holds: append it and carry the cache to it.
  path_points.push_back(s.from);
  for (int j = 0; j < p.crossings; ++j) {
    WalkCrossing& c = first[j];
    const double a = shift[static_cast<std::size_t>(j)];
    c.point += a * c.edge;
    c.to_first -= a;
    c.to_second -= a;
    c.x += a * c.ux;
    c.y += a * c.uy;
    path_points.push_back(c.point);
  }
  path_points.push_back(moved);
  p.end = moved;
  p.end_x = ex;
  p.end_y = ey;
  end = moved;
  end_face = p.end_face;
  ++cache.warm_walks;
  return true;
}

}  // namespace gf::sim
