#include "sim/patch/warm_walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/patch/patch_settings.hpp"

namespace gf::sim {
namespace {

// A carried crossing or end closer than this to its edge's ends or its face's edges (m) is not
// trusted: the walk from the contact might pass the other side of a vertex.
constexpr double kCarryMargin = 1e-10;
// A path meeting an edge at a sine below this is walked from the contact (the crossing point
// would move far along the edge for a small turn).
constexpr double kMinCrossingSine = 1e-6;
// A full check leaves this fraction of each check's slack (whatever rounds in the checks is
// then far from deciding: slacks of 1e-10 m and more against rounding of 1e-17 m).
constexpr double kSlackFraction = 0.5;
constexpr double kUnbounded = std::numeric_limits<double>::infinity();
// A ring axis shorter than this in a start plane (unit vectors) has no direction there.
constexpr double kDegenerateAxis = 1e-12;

// A walk's line in the start face's plane: start, unit direction, length.
struct Line {
  double hx, hy, dx, dy, d;
};

// z of the cross product of two vectors of the start plane.
double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

bool faceAllowed(const WalkLimits& l, const Vec3& oriented_normal) {
  const double c = oriented_normal.dot(l.normal);
  return (!l.has_limit || c >= l.cos_limit) && c > l.cos_facing;
}

// How far a face entered is within the thresholds: the turn of the normal it allows.
double allowedBy(const WalkLimits& l, const Vec3& oriented_normal) {
  const double c = oriented_normal.dot(l.normal);
  return std::min(l.has_limit ? c - l.cos_limit : kUnbounded, c - l.cos_facing);
}

// Distance of p from the nearest edge of face f, inwards (m).
double insideBy(const Mesh& m, int f, const Vec3& p) {
  double least = kUnbounded;
  for (int k = 0; k < 3; ++k) least = std::min(least, (p - m.corner(f, k)).dot(m.edgeInwardNormal(f, k)));
  return least;
}

// Whether line `a` and the limits moved less than path p's slack since its last full check.
// Crossings then stay inside their edges (each moves along its edge by at most move / (sine -
// turn), sine its line's sine to the edge there), in order and on faces within the thresholds,
// and the end inside its face: every check of checkCrossings and the end holds.
// The contact normal's turn from path p's reference normal is worked out again only when p's
// reference differs from the last one looked at (the cache's memo, reset by keyWalkCache): once a
// patch when the paths share one, as they do after a full check of them all.
bool withinSlack(const WalkPath& p, const WalkLimits& l, const Line& a, WalkCache& cache) {
  if (!p.slack || l.cos_limit != p.ref_cos_limit || l.cos_facing != p.ref_cos_facing ||
      l.has_limit != p.ref_has_limit) {
    return false;
  }
  const double tx = a.dx - p.ref_dx, ty = a.dy - p.ref_dy, mx = a.hx - p.ref_hx, my = a.hy - p.ref_hy;
  const double turn = std::sqrt(tx * tx + ty * ty);
  const double move = std::sqrt(mx * mx + my * my) + p.ref_d * turn;
  if (!(turn <= p.turn_slack && move <= p.move_slack && move + std::abs(a.d - p.ref_d) <= p.end_slack)) return false;
  if (p.ref_normal != cache.turn_ref) {
    cache.turn_ref = p.ref_normal;
    cache.turn_of_ref = (l.normal - p.ref_normal).norm();
  }
  return cache.turn_of_ref <= p.normal_slack;
}

// Within the slack: each crossing where line `a` meets its edge, unchecked, into `out`.
void placeCrossings(const WalkPath& p, const WalkCrossing* first, const Line& a, Vec3* out) {
  for (int j = 0; j < p.crossings; ++j) {
    const WalkCrossing& c = first[j];
    const double along = cross2(a.hx - c.x, a.hy - c.y, a.dx, a.dy) / cross2(c.ux, c.uy, a.dx, a.dy);
    out[j] = c.point + along * c.edge;
  }
}

// Each crossing: where line `a` meets the edge, X + along u; it must stay on the edge, in
// order, short of d, into a face still within the thresholds. Moves the crossings there (and
// into `out`) and leaves the path's slack for them; false when a check fails. A crossing moved
// before a later check fails stays consistent (its point, unfolded point and edge ends move
// together): the walk from the contact records the path anew anyway.
bool checkCrossings(WalkPath& p, WalkCrossing* first, const WalkLimits& limits, const Line& a, Vec3* out) {
  double last_t = 0.0, turn = kUnbounded, move = kUnbounded, allowed = kUnbounded;
  for (int j = 0; j < p.crossings; ++j) {
    WalkCrossing& c = first[j];
    const double det = cross2(c.ux, c.uy, a.dx, a.dy);
    if (std::abs(det) < kMinCrossingSine || !faceAllowed(limits, c.entered_normal)) return false;
    const double wx = a.hx - c.x, wy = a.hy - c.y, inv = 1.0 / det;
    const double along = cross2(wx, wy, a.dx, a.dy) * inv, t = cross2(wx, wy, c.ux, c.uy) * inv;
    if (!(t > last_t) || !(t < a.d) || !(along > c.to_first + kCarryMargin) ||
        !(along < c.to_second - kCarryMargin)) {
      return false;
    }
    last_t = t;
    c.point += along * c.edge;
    c.to_first -= along;
    c.to_second -= along;
    c.x += along * c.ux;
    c.y += along * c.uy;
    out[j] = c.point;
    // The slack: the sine kept above half its value and kMinCrossingSine, the crossing inside
    // its edge, the start on its side of the first edge (t sine from it), the face allowed.
    const double sine = std::abs(det);
    turn = std::min(turn, std::min(kSlackFraction * sine, sine - kMinCrossingSine));
    move = std::min(move, kSlackFraction * sine * (std::min(-c.to_first, c.to_second) - kCarryMargin));
    if (j == 0) move = std::min(move, kSlackFraction * sine * t);
    allowed = std::min(allowed, allowedBy(limits, c.entered_normal));
  }
  p.turn_slack = turn, p.move_slack = move, p.normal_slack = kSlackFraction * allowed;
  return true;
}

// A full check passed for line `a`: it is the path's reference.
void renewReference(WalkPath& p, const WalkLimits& l, const Line& a, double end_inside) {
  p.slack = true;
  p.ref_hx = a.hx, p.ref_hy = a.hy, p.ref_dx = a.dx, p.ref_dy = a.dy, p.ref_d = a.d;
  p.ref_normal = l.normal;
  p.ref_cos_limit = l.cos_limit, p.ref_cos_facing = l.cos_facing, p.ref_has_limit = l.has_limit;
  p.end_slack = kSlackFraction * (end_inside - kCarryMargin);
}

// A carried walk that does not hold: its path points taken back.
bool fail(std::vector<Vec3>& path_points, std::size_t mark) {
  path_points.resize(mark);
  return false;
}

}  // namespace

void WalkCache::reserve(int radials) {
  const auto n = static_cast<std::size_t>(std::clamp(radials, 0, kMaxSgo));
  if (paths.size() >= n) return;
  paths.resize(n);
  crossings.resize(n * kWarmCrossingsPerSgo);
}

StartPlane startPlane(const Mesh& m, int f, double side) {
  const Vec3& x = m.edgeDirection(f, 0);
  return {m.corner(f, 0), x, (side * m.faceNormal(f)).cross(x)};
}

void keyWalkCache(const Mesh* mesh, int n_sgo, const SurfacePoint& hit, bool was_valid, WalkCache& cache) {
  if (cache.paths.size() < static_cast<std::size_t>(n_sgo)) cache.reserve(n_sgo);  // sized before a step, normally
  const bool same = was_valid && cache.mesh == mesh && cache.n_sgo == n_sgo && cache.hit_face == hit.face &&
                    cache.feature == hit.feature && cache.feature_index == hit.feature_index;
  if (!same) {
    cache.mesh = mesh, cache.n_sgo = n_sgo, cache.hit_face = hit.face;
    cache.feature = hit.feature, cache.feature_index = hit.feature_index;
    for (std::size_t i = 0; i < cache.paths.size(); ++i) uncachePath(cache, static_cast<int>(i));
  }
  cache.plane_face = -1;
  cache.turn_ref.setConstant(std::numeric_limits<double>::quiet_NaN());
  cache.valid = true;
}

WalkRecorder::WalkRecorder(WalkCache* cache, int i, const Mesh& m, int face, double side, const Vec3& from,
                           const Vec3& dir) {
  if (!cache) return;
  path_ = &cache->paths[static_cast<std::size_t>(i)];
  crossings_ = cache->crossings.data() + static_cast<std::ptrdiff_t>(i) * kWarmCrossingsPerSgo;
  *path_ = WalkPath{};
  path_->start_face = face;
  path_->side = side;
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

StartPlane carryPlane(const Mesh& m, int f, double side, const Vec3& from, WalkCache& cache) {
  const StartPlane plane = startPlane(m, f, side);
  cache.plane_face = f, cache.plane_side = side;
  const Vec3 rel = from - plane.origin;
  cache.from_x = rel.dot(plane.x_axis), cache.from_y = rel.dot(plane.y_axis);
  return plane;
}

PlaneAxes ringInPlane(const StartPlane& plane, const Vec3& f1, const Vec3& f2) {
  const double x1 = f1.dot(plane.x_axis), y1 = f1.dot(plane.y_axis);
  const double x2 = f2.dot(plane.x_axis), y2 = f2.dot(plane.y_axis);
  const double l1 = std::hypot(x1, y1), l2 = std::hypot(x2, y2);
  if (!(l1 > kDegenerateAxis) || !(l2 > kDegenerateAxis) || !std::isfinite(l1) || !std::isfinite(l2)) return {};
  return {true, x1 / l1, y1 / l1, x2 / l2, y2 / l2};
}

bool carryWalk(const Mesh& m, const WalkLimits& limits, const WalkStart& s, int i, WalkCache& cache,
               std::vector<Vec3>& path_points, Vec3& end, int& end_face) {
  WalkPath& p = cache.paths[static_cast<std::size_t>(i)];
  if (!p.cached || p.start_face != s.face || p.side != s.side || p.crossings > s.budget ||
      cache.plane_face != s.face || cache.plane_side != s.side) {
    return false;
  }
  // The start and direction in the start face's plane (the start once a patch: the contact).
  const Line a{cache.from_x, cache.from_y, s.dx, s.dy, s.d};
  WalkCrossing* first = cache.crossings.data() + static_cast<std::ptrdiff_t>(i) * kWarmCrossingsPerSgo;
  // The path's points: from, the crossings, the end.
  const std::size_t mark = path_points.size();
  path_points.resize(mark + static_cast<std::size_t>(p.crossings) + 2);
  Vec3* out = path_points.data() + mark;
  out[0] = s.from;
  const bool unchecked = withinSlack(p, limits, a, cache);
  p.pending = unchecked && !s.place;
  if (p.pending) {
    p.line_hx = a.hx, p.line_hy = a.hy, p.line_dx = a.dx, p.line_dy = a.dy;
  } else if (unchecked) {
    placeCrossings(p, first, a, out + 1);
  } else if (!checkCrossings(p, first, limits, a, out + 1)) {
    return fail(path_points, mark);
  }
  // The end: the last end moved by the difference, unfolded onto the end face.
  const double ex = a.hx + a.d * a.dx, ey = a.hy + a.d * a.dy;
  const Vec3 moved = p.end + (ex - p.end_x) * p.axis_x + (ey - p.end_y) * p.axis_y;
  if (!unchecked) {
    const double inside = insideBy(m, p.end_face, moved);
    if (!(inside >= kCarryMargin)) return fail(path_points, mark);
    renewReference(p, limits, a, inside);
  }
  out[p.crossings + 1] = moved;
  p.end = moved;
  p.end_x = ex;
  p.end_y = ey;
  end = moved;
  end_face = p.end_face;
  ++cache.warm_walks;
  cache.slack_walks += unchecked;
  return true;
}

bool pendingCrossings(const WalkCache& cache, int i, Vec3* out) {
  const WalkPath& p = cache.paths[static_cast<std::size_t>(i)];
  if (!p.pending) return false;
  const WalkCrossing* first = cache.crossings.data() + static_cast<std::ptrdiff_t>(i) * kWarmCrossingsPerSgo;
  placeCrossings(p, first, {p.line_hx, p.line_hy, p.line_dx, p.line_dy, 0.0}, out);
  return true;
}

}  // namespace gf::sim
