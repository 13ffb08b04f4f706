#include "sim/warm_walk.hpp"

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

// A carried walk that does not hold: its path points taken back.
bool fail(std::vector<Vec3>& path_points, std::size_t mark) {
  path_points.resize(mark);
  return false;
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

void keyWalkCache(const Mesh* mesh, int n_sgo, const SurfacePoint& hit, bool was_valid, WalkCache& cache) {
  if (cache.paths.size() < static_cast<std::size_t>(kMaxSgo)) cache.reserve();
  const bool same = was_valid && cache.mesh == mesh && cache.n_sgo == n_sgo && cache.hit_face == hit.face &&
                    cache.feature == hit.feature && cache.feature_index == hit.feature_index;
  if (!same) {
    cache.mesh = mesh, cache.n_sgo = n_sgo, cache.hit_face = hit.face;
    cache.feature = hit.feature, cache.feature_index = hit.feature_index;
    for (WalkPath& p : cache.paths) p.cached = false;
  }
  cache.plane_face = -1;
  cache.valid = true;
}

WalkRecorder::WalkRecorder(WalkCache* cache, int i, const Mesh& m, int face, double side, const Vec3& from,
                           const Vec3& dir) {
  if (!cache) return;
  path_ = &cache->paths[static_cast<std::size_t>(i)];
  crossings_ = cache->crossings.data() + static_cast<std::ptrdiff_t>(i) * kWarmCrossingsPerSgo;
  *path_ = {false, face, side, -1, 0, Vec3::Zero(), 0.0, 0.0, Vec3::Zero(), Vec3::Zero()};
  const StartPlane plane = startPlane(m, face, side);
  hx_ = (from - plane.origin).dot(plane.x_axis), hy_ = (from - plane.origin).dot(plane.y_axis);
  dx_ = dir.dot(plane.x_axis), dy_ = dir.dot(plane.y_axis);
}

void WalkRecorder::crossing(const Mesh& m, int f, int k, double side, const Vec3& dir, const Vec3& point,
                            double walked, const Vec3& entered) {
  if (!path_) return;
  if (path_->crossings == kWarmCrossingsPerSgo) return void(path_ = nullptr);  // too long to carry
  // The edge unfolded: its parts along the walk's direction and across it, in the start plane.
  const Vec3& u = m.edgeDirection(f, k);
  const double along = u.dot(dir), across = u.dot((side * m.faceNormal(f)).cross(dir));
  crossings_[path_->crossings++] = {point, u, (m.corner(f, k) - point).dot(u),
                                    (m.corner(f, (k + 1) % 3) - point).dot(u), hx_ + walked * dx_,
                                    hy_ + walked * dy_, along * dx_ - across * dy_, along * dy_ + across * dx_,
                                    entered};
}

void WalkRecorder::end(const Mesh& m, double side, const Vec3& dir, int f, const Vec3& point, double d) {
  if (!path_) return;
  // The start plane's axes on the end face: (1, 0) = dx dir - dy perp, (0, 1) = dy dir + dx perp.
  const Vec3 perp = (side * m.faceNormal(f)).cross(dir);
  path_->cached = true;
  path_->end_face = f;
  path_->end = point;
  path_->end_x = hx_ + d * dx_, path_->end_y = hy_ + d * dy_;
  path_->axis_x = dx_ * dir - dy_ * perp;
  path_->axis_y = dy_ * dir + dx_ * perp;
}

bool carryWalk(const Mesh& m, const WalkLimits& limits, const WalkStart& s, int i, WalkCache& cache,
               std::vector<Vec3>& path_points, Vec3& end, int& end_face) {
  WalkPath& p = cache.paths[static_cast<std::size_t>(i)];
  if (!p.cached || p.start_face != s.face || p.side != s.side || p.crossings > s.budget) return false;
  // The start and direction in the start face's plane.
  if (cache.plane_face != s.face || cache.plane_side != s.side) {
    cache.plane = startPlane(m, s.face, s.side);
    cache.plane_face = s.face, cache.plane_side = s.side;
  }
  const StartPlane& plane = cache.plane;
  const Vec3 rel = s.from - plane.origin;
  const double hx = rel.dot(plane.x_axis), hy = rel.dot(plane.y_axis);
  const double dx = s.dir.dot(plane.x_axis), dy = s.dir.dot(plane.y_axis);
  // Each crossing: where the moved line h + t dir meets the edge, X + along u; it must stay on
  // the edge, in order, short of d, into a face still within the thresholds. A crossing moved
  // before a later check fails stays consistent (its point, unfolded point and edge ends move
  // together): the walk from the contact records the path anew anyway.
  WalkCrossing* first = cache.crossings.data() + static_cast<std::ptrdiff_t>(i) * kWarmCrossingsPerSgo;
  const std::size_t mark = path_points.size();
  path_points.push_back(s.from);
  double last_t = 0.0;
  for (int j = 0; j < p.crossings; ++j) {
    WalkCrossing& c = first[j];
    const double det = cross2(c.ux, c.uy, dx, dy);
    if (std::abs(det) < kMinCrossingSine || !faceAllowed(limits, c.entered_normal)) return fail(path_points, mark);
    const double wx = hx - c.x, wy = hy - c.y, inv = 1.0 / det;
    const double along = cross2(wx, wy, dx, dy) * inv, t = cross2(wx, wy, c.ux, c.uy) * inv;
    if (!(t > last_t) || !(t < s.d) || !(along > c.to_first + kCarryMargin) ||
        !(along < c.to_second - kCarryMargin)) {
      return fail(path_points, mark);
    }
    last_t = t;
    c.point += along * c.edge;
    c.to_first -= along;
    c.to_second -= along;
    c.x += along * c.ux;
    c.y += along * c.uy;
    path_points.push_back(c.point);
  }
  // The end: the last end moved by the difference, unfolded onto the end face.
  const double ex = hx + s.d * dx, ey = hy + s.d * dy;
  const Vec3 moved = p.end + (ex - p.end_x) * p.axis_x + (ey - p.end_y) * p.axis_y;
  if (!insideFace(m, p.end_face, moved)) return fail(path_points, mark);
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
