#include "sim/patch/god_finger.hpp"

#include "sim/patch/patch_ring.hpp"
#include "sim/patch/warm_walk.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace gf::sim {
namespace {

// Below this length a direction has vanished (unit vectors; dimensionless).
constexpr double kDegenerateLength = 1e-12;
// Entry scores (dot products of unit vectors) closer than this are a tie.
constexpr double kScoreTolerance = 1e-9;
// A walk direction this close to parallel to an edge (dot product with the edge's inward
// normal) runs along it rather than out through it.
constexpr double kParallelRate = 1e-9;
// A walk direction whose squared length is this far from 1 is projected and normalized again.
constexpr double kUnitDrift = 1e-12;
// A walk may cross this many edges per mean edge length of its start face in d_i, on top of
// PatchSettings::max_face_crossings: a straight line crosses at most about 4 edges per edge
// length of a regular triangulation, so a fine mesh keeps the full radius.
constexpr double kCrossingsPerEdgeLength = 8.0;
constexpr double kMaxCrossings = 1e6;  // whatever the mesh: every walk ends
// An SGO's load share uses a lever of at least this fraction of r (an SGO that stopped at the
// contact would otherwise take the whole load).
constexpr double kMinLeverFraction = 0.05;

// The faces a radial vector may start on, and the walk's angular limit.
struct WalkContext {
  const Mesh& mesh;
  const PatchSettings& s;
  Vec3 normal;        // outward contact normal (unit)
  double cos_limit;   // a face is within the thresholds while cos(angle to normal) >= cos_limit
  bool has_limit;
  double cos_facing;  // a face with cos(angle to normal) <= this faces away from the press
  double cos_start;   // at an edge or vertex hit, faces this well aligned are start faces
  WalkLimits limits{normal, cos_limit, has_limit, cos_facing};  // the above, for carried walks
};

// Rotates x by the smallest rotation taking unit a onto unit b; projects when a = -b.
Vec3 rotateOnto(const Vec3& x, const Vec3& a, const Vec3& b) {
  const double c = a.dot(b);
  if (c <= -1.0 + 1e-9) {
    const Vec3 p = x - x.dot(b) * b;
    return p.norm() > kDegenerateLength ? Vec3(p.normalized()) : Vec3::Zero();
  }
  const Vec3 k = a.cross(b);
  return c * x + k.cross(x) + (k.dot(x) / (1.0 + c)) * k;
}

// Cosine of an angle widened by the comparison tolerance (clamped at pi).
double cosWithTolerance(double angle) {
  return std::cos(std::min(angle + kAngleTolerance, std::numbers::pi));
}

bool withinThresholds(const WalkContext& ctx, const Vec3& oriented_normal) {
  return !ctx.has_limit || oriented_normal.dot(ctx.normal) >= ctx.cos_limit;
}

bool facesAway(const WalkContext& ctx, const Vec3& oriented_normal) {
  return oriented_normal.dot(ctx.normal) <= ctx.cos_facing;
}

// A face the walk may enter: within the thresholds and not facing away.
bool faceAllowed(const WalkContext& ctx, const Vec3& oriented_normal) {
  return withinThresholds(ctx, oriented_normal) && !facesAway(ctx, oriented_normal);
}

// Which test stops the walk at a face with the given oriented normal.
WalkStop stopReason(const WalkContext& ctx, const Vec3& oriented_normal) {
  if (withinThresholds(ctx, oriented_normal)) return WalkStop::kFacingAway;
  const double angle = std::acos(std::clamp(oriented_normal.dot(ctx.normal), -1.0, 1.0));
  return ctx.s.angular_threshold && angle > ctx.s.tau_a + kAngleTolerance ? WalkStop::kAngularThreshold
                                                                           : WalkStop::kFrictionCone;
}

// How far direction d points into face f from the hit's edge or vertex (+inf on a face hit).
double enterScore(const Mesh& m, const SurfacePoint& hit, int f, const Vec3& d) {
  if (hit.feature == Feature::kFace) return std::numeric_limits<double>::infinity();
  const auto& tri = m.triangles()[f];
  const auto& hit_tri = m.triangles()[hit.face];
  if (hit.feature == Feature::kEdge) {
    const std::int32_t a = hit_tri[hit.feature_index], b = hit_tri[(hit.feature_index + 1) % 3];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t u = tri[k], w = tri[(k + 1) % 3];
      if ((u == a && w == b) || (u == b && w == a)) return d.dot(m.edgeInwardNormal(f, k));
    }
    return -std::numeric_limits<double>::infinity();
  }
  const std::int32_t v = hit_tri[hit.feature_index];
  for (int k = 0; k < 3; ++k) {
    if (tri[k] == v) {
      return std::min(d.dot(m.edgeInwardNormal(f, k)), d.dot(m.edgeInwardNormal(f, (k + 2) % 3)));
    }
  }
  return -std::numeric_limits<double>::infinity();
}

// Winding of candidate face f relative to the hit face (-1 across a flipped shared edge).
double relativeSide(const Mesh& m, int hit_face, int f) {
  for (int k = 0; k < 3; ++k) {
    const FaceLink& l = m.link(hit_face, k);
    if (l.face == f) return l.flipped ? -1.0 : 1.0;
  }
  return 1.0;
}

bool faceHasVertex(const Mesh& m, int f, std::int32_t v) {
  const auto& t = m.triangles()[f];
  return t[0] == v || t[1] == v || t[2] == v;
}

// Calls visit(f) for the hit face and every other face around the hit's edge or vertex.
template <class Visit>
void forEachFaceAroundHit(const Mesh& m, const SurfacePoint& hit, Visit&& visit) {
  visit(hit.face);
  if (hit.feature == Feature::kFace) return;
  const auto& hit_tri = m.triangles()[hit.face];
  const std::int32_t v = hit_tri[hit.feature_index];
  const std::int32_t w = hit.feature == Feature::kEdge ? hit_tri[(hit.feature_index + 1) % 3] : v;
  for (const std::int32_t* f = m.vertexFacesBegin(v); f != m.vertexFacesEnd(v); ++f) {
    if (*f != hit.face && faceHasVertex(m, *f, w)) visit(*f);
  }
}

// Winding sign of face f around the hit (side of the hit face times the relative winding).
double sideOf(const Mesh& m, const SurfacePoint& hit, double side, int f) {
  return side * (f == hit.face ? 1.0 : relativeSide(m, hit.face, f));
}

// The start of one radial vector: its face, winding sign there and in-plane direction.
struct Start {
  int face = -1;
  double side = 1.0;
  Vec3 dir = Vec3::Zero();
  bool usable = false;  // a start face, or a face around the hit within the thresholds
};

// Paper Fig. 3: maps radial vector r onto the face around the hit it points into. Exact ties of
// the entry score (a vector along the hit edge enters both faces at 0) go to a usable face,
// then to the face better aligned with the normal: the same on either side of the edge.
Start startFace(const WalkContext& ctx, const SurfacePoint& hit, double side, const Vec3& r) {
  const Mesh& m = ctx.mesh;
  Start best;
  double best_score = -std::numeric_limits<double>::infinity(), best_align = -2.0;
  forEachFaceAroundHit(m, hit, [&](int f) {
    const double sf = sideOf(m, hit, side, f);
    const Vec3 nf = sf * m.faceNormal(f);
    const double align = nf.dot(ctx.normal);
    const bool usable = f == hit.face && hit.feature == Feature::kFace ? true
                        : align >= ctx.cos_start || faceAllowed(ctx, nf);
    const Vec3 dir = rotateOnto(r, ctx.normal, nf);
    const double score = enterScore(m, hit, f, dir);
    const bool tie = std::abs(score - best_score) <= kScoreTolerance;
    if ((!tie && score > best_score) || (tie && (usable > best.usable || (usable == best.usable && align > best_align)))) {
      best_score = score, best_align = align, best = {f, sf, dir, usable};
    }
  });
  return best;
}

// A few indices, remembered in the order met; insert says whether one is new. Past its
// capacity it remembers nothing more and calls every index new (the caller then repeats work
// whose answer it already has, which changes nothing).
class SmallSet {
 public:
  bool insert(std::int32_t x) {
    for (int i = 0; i < size_; ++i) {
      if (items_[static_cast<std::size_t>(i)] == x) return false;
    }
    if (size_ < kCapacity) items_[static_cast<std::size_t>(size_++)] = x;
    return true;
  }

 private:
  static constexpr int kCapacity = 48;
  std::array<std::int32_t, kCapacity> items_{};
  int size_ = 0;
};

// The point of segment [a, b] closest to p.
Vec3 onSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const double len2 = e.squaredNorm();
  if (!(len2 > 0.0)) return a;
  return a + std::clamp((p - a).dot(e) / len2, 0.0, 1.0) * e;
}

// Projects dir onto the plane of unit normal nf and normalizes it; false if nothing is left.
bool inPlane(const Vec3& nf, Vec3& dir) {
  dir -= dir.dot(nf) * nf;
  const double len = dir.norm();
  if (!(len > kDegenerateLength)) return false;
  dir /= len;
  return true;
}

// The edge crossings a walk of length d from face f may make.
long walkBudget(const WalkContext& ctx, int f, double d) {
  const double extra = std::min(kMaxCrossings, std::ceil(kCrossingsPerEdgeLength * d / ctx.mesh.meanEdge(f)));
  return ctx.s.max_face_crossings + static_cast<long>(extra);
}

// Algorithm 1: walks distance d from the hit along dir, crossing edges while the next face stays
// within the angular limit. Appends the path; returns the SGO. With a cache, records the path
// of radial i in it.
Sgo walk(const WalkContext& ctx, const Start& start, const Vec3& from, double d, Patch& out,
         WalkCache* cache = nullptr, int i = 0) {
  const Mesh& m = ctx.mesh;
  Sgo sgo{from, start.face, -1, 0.0, WalkStop::kDistance, 0.0};
  Vec3 dir = start.dir;
  double side = start.side, remaining = d;
  const long budget = walkBudget(ctx, start.face, d);
  out.path_points.push_back(from);
  // r_i <- projection of r_i on f (Alg. 1, line 3), kept unit length. Carried over an edge
  // below, a unit direction in f's plane stays unit and in the neighbour's plane (its parts
  // along the edge and across it, on orthonormal in-plane axes), so only the start projects.
  if (!inPlane(m.faceNormal(sgo.face), dir)) return sgo.stop = WalkStop::kDegenerate, sgo;
  if (remaining <= 0.0) return sgo;
  WalkRecorder record(cache, i, m, start.face, start.side, from, dir);
  for (long crossings = 0;; ++crossings) {
    // Does d_i * r_i cross an edge of f? First edge the ray leaves through: the smallest
    // gap / speed, compared as products (speeds are positive) with one division at the end.
    double gap_exit = 1.0, speed_exit = 0.0;
    int k_exit = -1;
    for (int k = 0; k < 3; ++k) {
      const Vec3& in = m.edgeInwardNormal(sgo.face, k);
      const double speed = -dir.dot(in);
      if (speed <= kParallelRate) continue;
      const double gap = std::max(0.0, (sgo.position - m.corner(sgo.face, k)).dot(in));
      if (k_exit < 0 || gap * speed_exit < gap_exit * speed) gap_exit = gap, speed_exit = speed, k_exit = k;
    }
    if (k_exit < 0) return sgo.stop = WalkStop::kDegenerate, sgo;
    const double t_exit = gap_exit / speed_exit;
    if (t_exit >= remaining) {  // ends inside f: p_SGO += d_i r_i
      sgo.position += remaining * dir;
      sgo.walked += remaining;
      out.path_points.push_back(sgo.position);
      record.end(m, side, dir, sgo.face, sgo.position, d);
      return sgo;
    }
    // Reached edge e: p_SGO on e, d_i reduced by the distance travelled. A direction nearly
    // along another edge of a sliver can reach e's line past its end: the point is kept on e.
    sgo.position = onSegment(sgo.position + t_exit * dir, m.corner(sgo.face, k_exit), m.corner(sgo.face, (k_exit + 1) % 3));
    sgo.walked += t_exit;
    remaining -= t_exit;
    out.path_points.push_back(sgo.position);
    const FaceLink& link = m.link(sgo.face, k_exit);
    if (link.face < 0) return sgo.stop = WalkStop::kBoundary, sgo;
    if (crossings >= budget) return sgo.stop = WalkStop::kCrossingLimit, sgo;
    const double next_side = link.flipped ? -side : side;
    const Vec3 next_normal = next_side * m.faceNormal(link.face);
    if (!faceAllowed(ctx, next_normal)) return sgo.stop = stopReason(ctx, next_normal), sgo;
    record.crossing(m, sgo.face, k_exit, side, dir, sgo.position, sgo.walked, next_normal);
    // Carry the direction over the edge: keep its component along the edge, turn the rest into
    // the neighbour (the unfolded straight line; equals the projection to first order).
    const Vec3& edge = m.edgeDirection(sgo.face, k_exit);
    dir = dir.dot(edge) * edge + speed_exit * m.edgeInwardNormal(link.face, link.edge);
    sgo.face = link.face;
    side = next_side;
    // A sliver's or degenerate face's axes are not orthonormal to rounding: project again.
    if (std::abs(dir.squaredNorm() - 1.0) > kUnitDrift && !inPlane(m.faceNormal(sgo.face), dir)) {
      return sgo.stop = WalkStop::kDegenerate, sgo;
    }
  }
}

// Ring: the load shares of the SGOs, inversely proportional to their distance from the contact
// across the normal, so sum_i share_i (p_i - c) is sum_i of unit directions, zero for a balanced
// ring whatever its stretch; the contact takes 1 / (1 + SGOs).
void shareRingLoad(const Vec3& centre, const Vec3& n, double radius, Patch& out) {
  double total = 0.0;
  for (Sgo& sgo : out.sgos) {
    const Vec3 offset = sgo.position - centre;
    const double lever = (offset - offset.dot(n) * n).norm();
    sgo.load_share = 1.0 / std::max(lever, kMinLeverFraction * radius);
    total += sgo.load_share;
  }
  const double count = static_cast<double>(out.sgos.size());
  out.centre_share = 1.0 / (1.0 + count);
  for (Sgo& sgo : out.sgos) sgo.load_share *= (1.0 - out.centre_share) / total;
}

// The point at arc length `at` along the polyline [first, last).
Vec3 alongPath(const Vec3* first, const Vec3* last, double at) {
  for (const Vec3* p = first; p + 1 < last; ++p) {
    const double len = (p[1] - p[0]).norm();
    if (at <= len && len > 0.0) return p[0] + (at / len) * (p[1] - p[0]);
    at -= len;
  }
  return last[-1];
}

// Filled: rings - 1 points along the path just walked to `end` (walked length w), and the areas
// of the annular sectors of angle `sector` each point stands for: ring k between (k - 1/2) w /
// rings and (k + 1/2) w / rings, the last out to w, the contact's disc within w / (2 rings).
void fillPath(int rings, double sector, Sgo& end, Patch& out) {
  const double w = end.walked, step = w / rings;
  const auto annulus = [&](double a, double b) { return 0.5 * sector * (b * b - a * a); };
  out.centre_area += annulus(0.0, 0.5 * step);
  const Vec3* first = out.path_points.data() + out.path_offsets.back();
  const Vec3* last = out.path_points.data() + out.path_points.size();
  for (int k = 1; k < rings; ++k) {
    Sgo p = end;
    p.position = alongPath(first, last, k * step);
    p.walked = k * step;
    p.stop = WalkStop::kDistance;
    p.ring = k;
    p.area = annulus((k - 0.5) * step, (k + 0.5) * step);
    out.inner.push_back(p);
  }
  end.ring = rings;
  end.area = annulus((rings - 0.5) * step, w);
}

// Filled: every point's share in proportion to its area.
void shareFilledLoad(Patch& out) {
  double total = out.centre_area;
  for (const Sgo& p : out.sgos) total += p.area;
  for (const Sgo& p : out.inner) total += p.area;
  if (!(total > 0.0)) return shareRingLoad(out.hit.point, -out.press_dir, out.radius, out);
  out.centre_share = out.centre_area / total;
  for (Sgo& p : out.sgos) p.load_share = p.area / total;
  for (Sgo& p : out.inner) p.load_share = p.area / total;
}

void resetPatch(int n, Patch& out) {
  out.valid = false;
  out.press_depth = out.radius = 0.0;
  out.hit = {};
  out.press_dir.setZero();
  out.ring_tangent.setZero();
  out.radial.clear();
  out.d_i.clear();
  out.radial_stop.clear();
  out.sgos.clear();
  out.inner.clear();
  out.centre_share = 1.0;
  out.centre_area = 0.0;
  out.path_points.clear();
  out.path_offsets.clear();
  out.crossings_pending = false;
  if (out.radial.capacity() < static_cast<std::size_t>(n)) {
    out.radial.reserve(kMaxSgo);
    out.d_i.reserve(kMaxSgo);
    out.radial_stop.reserve(kMaxSgo);
    out.sgos.reserve(kMaxSgo);
    out.inner.reserve(kMaxSgo * (kMaxRings - 1));
    out.path_offsets.reserve(kMaxSgo + 1);
    out.path_points.reserve(kMaxSgo * 8);
  }
}

// The input the patch can be computed from: the preconditions of Eq. 1, Eq. 2 and the walk
// (what users may set is narrower and checked in settings.cpp).
bool computable(const PatchSettings& s) {
  const auto finite = [](double x) { return std::isfinite(x); };
  return s.n_sgo >= kMinSgo && s.n_sgo <= kMaxSgo && finite(s.r_max) && s.r_max >= 0 && finite(s.d0) &&
         s.d0 > 0 && finite(s.alpha) && s.alpha > 0 && finite(s.stretch_length) && s.stretch_length > 0 &&
         finite(s.max_stretch) && s.max_stretch >= 1 &&
         finite(s.tau_a) && s.tau_a >= 0 && s.tau_a <= std::numbers::pi && finite(s.friction) &&
         s.friction >= 0 && s.max_face_crossings >= 0 && s.max_face_crossings <= 1000000 &&
         finite(s.feature_tolerance) && s.feature_tolerance >= 0 && s.rings >= 1 && s.rings <= kMaxRings;
}

// Eq. 2's logarithms, computed once per patch.
struct StretchLogs {
  bool on;
  double log_alpha, bound;
  explicit StretchLogs(const PatchSettings& s)
      : on(s.tangential_stretch && s.alpha != 1.0),
        log_alpha(on ? std::log(s.alpha) : 0.0),
        bound(on ? std::log(s.max_stretch) : 0.0) {}
};

// log(d_i / r) = -(v_t . r_i) / stretch_length * log(alpha), kept within +-log(max_stretch).
double stretched(double radius, const Vec3& v_tangential, const Vec3& radial_unit, const PatchSettings& s,
                 const StretchLogs& logs) {
  if (!logs.on) return radius;
  const double x = -v_tangential.dot(radial_unit) / s.stretch_length * logs.log_alpha;
  return radius * std::exp(std::clamp(x, -logs.bound, logs.bound));
}

// The walk's angular limit, min(tau_a, atan(theta)) over the active tests, and the start
// faces: the hit face, or at an edge or vertex the faces best aligned with unit normal n.
WalkContext walkContext(const Mesh& mesh, const PatchSettings& s, const Vec3& n, const SurfacePoint& hit, double side) {
  double limit = std::numbers::pi;
  if (s.angular_threshold) limit = std::min(limit, s.tau_a);
  if (s.friction_cone) limit = std::min(limit, std::atan(s.friction));
  WalkContext ctx{mesh, s, n, cosWithTolerance(limit), limit < std::numbers::pi,
                  std::sin(kAngleTolerance), 1.0};
  double best_align = -1.0;
  forEachFaceAroundHit(mesh, hit, [&](int f) {
    best_align = std::max(best_align, sideOf(mesh, hit, side, f) * mesh.faceNormal(f).dot(n));
  });
  ctx.cos_start = cosWithTolerance(std::acos(std::clamp(best_align, -1.0, 1.0)));
  return ctx;
}

// One radial vector's walk: carried from the cache's path when it still holds, else Algorithm 1
// from the contact (recorded in the cache when there is one). (dx, dy): the direction in the
// cache's start plane (ringInPlane; not `axes_ok`: no carry).
Sgo walkRadial(const WalkContext& ctx, const Start& start, const Vec3& from, double d, WalkCache* cache, int i,
               bool axes_ok, double dx, double dy, Patch& out) {
  if (!cache) return walk(ctx, start, from, d, out);
  if (d > 0.0 && axes_ok) {
    // The budget is at least max_face_crossings: worked out only for a path crossing more.
    const int crossings = cache->paths[static_cast<std::size_t>(i)].crossings;
    const long budget = crossings > ctx.s.max_face_crossings ? walkBudget(ctx, start.face, d) : ctx.s.max_face_crossings;
    // A ring's crossings within the slack are left pending (the SGOs do not read them).
    const WalkStart ws{start.face, start.side, dx, dy, from, d, budget, ctx.s.fill == PatchFill::kFilled};
    Sgo sgo{from, start.face, -1, d, WalkStop::kDistance, 0.0};
    if (carryWalk(ctx.mesh, ctx.limits, ws, i, *cache, out.path_points, sgo.position, sgo.face)) return sgo;
  }
  uncachePath(*cache, i);
  ++cache->cold_walks;
  return walk(ctx, start, from, d, out, cache, i);
}

}  // namespace

void clearPatch(Patch& patch) { resetPatch(0, patch); }

double pressDepth(const Vec3& v, const Vec3& outward_normal) { return -v.dot(outward_normal); }

double contactRadius(double press_depth, double r_max, double d0) {
  if (!(press_depth > 0.0) || !(d0 > 0.0)) return 0.0;
  // r = r_max (1 - e^(-x)); -expm1(-x) is exact for small x and tends to 1 without overflow.
  return r_max * -std::expm1(-press_depth / d0);
}

double stretchedDistance(double radius, const Vec3& v_tangential, const Vec3& radial_unit,
                         const PatchSettings& s) {
  return stretched(radius, v_tangential, radial_unit, s, StretchLogs(s));
}

SurfacePoint contactFeature(const Mesh& m, const PatchContact& c, double tol) {
  SurfacePoint hit = m.closestPoint(c.point_local, tol);
  const double nlen = c.outward_normal_local.norm();
  if (hit.face < 0 || !(c.rounding > 0.0) || !(nlen > 0.5)) return hit;
  const Vec3 n = c.outward_normal_local / nlen;
  const Vec3& p = c.point_local;
  const double turned = -std::sin(kAngleTolerance);  // n . t below this: n turned away from t
  // The feature lies within the rounding of p: an edge or corner of a face around the hit
  // face's corners (the hit face itself need not touch it).
  SurfacePoint edge_hit;
  double edge_distance2 = std::numeric_limits<double>::infinity();
  // Distances compared squared: most candidates are far and cost no square root.
  const double corner_reach = std::numbers::sqrt2 * c.rounding + tol, edge_reach = c.rounding + tol;
  const double corner_reach2 = corner_reach * corner_reach, edge_reach2 = edge_reach * edge_reach;
  // A face around two or three of the hit's corners is looked at once, and a corner found
  // outside its cone is not tested again: the answer is the one of the first visit.
  SmallSet faces_seen, corners_outside;
  for (int hk = 0; hk < 3; ++hk) {
    const std::int32_t hv = m.triangles()[hit.face][hk];
    for (const std::int32_t* g = m.vertexFacesBegin(hv); g != m.vertexFacesEnd(hv); ++g) {
      if (!faces_seen.insert(*g)) continue;
      for (int k = 0; k < 3; ++k) {
        // A rounded corner: n in the interior of the vertex's normal cone, where every edge
        // leaving the vertex points away from n.
        const Vec3& v = m.corner(*g, k);
        if ((p - v).squaredNorm() <= corner_reach2 && corners_outside.insert(m.triangles()[*g][k])) {
          const std::int32_t vi = m.triangles()[*g][k];
          bool inside = true;
          for (const std::int32_t* h = m.vertexFacesBegin(vi); h != m.vertexFacesEnd(vi) && inside; ++h) {
            for (int j = 0; j < 3; ++j) {
              const Vec3 e = m.corner(*h, j) - v;
              if (m.triangles()[*h][j] != vi && !(n.dot(e) < turned * e.norm())) inside = false;
            }
          }
          if (inside) return {*g, Feature::kVertex, k, v, (p - v).norm()};
        }
        // A rounded edge: n turned from both faces towards the edge (off each face's inward
        // direction), the point within the rounding of the edge.
        // The normals first: on a face hit n lies along the face, and no edge passes.
        const FaceLink& link = m.link(*g, k);
        if (link.face < 0 || !(n.dot(m.edgeInwardNormal(*g, k)) < turned) ||
            !(n.dot(m.edgeInwardNormal(link.face, link.edge)) < turned)) {
          continue;
        }
        const Vec3 e = m.corner(*g, (k + 1) % 3) - v;
        const Vec3 on_edge = v + std::clamp((p - v).dot(e) / e.squaredNorm(), 0.0, 1.0) * e;
        const double distance2 = (p - on_edge).squaredNorm();
        if (distance2 > edge_reach2 || distance2 >= edge_distance2) continue;
        edge_hit = {*g, Feature::kEdge, k, on_edge, std::sqrt(distance2)};
        edge_distance2 = distance2;
      }
    }
  }
  return edge_hit.face >= 0 ? edge_hit : hit;
}

void computePatch(const Mesh& mesh, const PatchContact& contact, const Vec3& v,
                  const PatchSettings& s, Patch& out) {
  computePatch(mesh, contact, v, s, out, nullptr);
}

void computePatch(const Mesh& mesh, const PatchContact& contact, const Vec3& v, const PatchSettings& s,
                  Patch& out, WalkCache* warm) {
  const bool was_valid = warm && warm->valid;
  if (warm) warm->valid = false;  // until this patch's walks are in it
  resetPatch(s.n_sgo, out);
  // Step 1: reject what cannot be computed.
  const double nlen = contact.outward_normal_local.norm();
  if (!computable(s) || !contact.point_local.allFinite() || !std::isfinite(contact.separation) ||
      !std::isfinite(contact.rounding) || !contact.ring_reference_local.allFinite() || !v.allFinite() ||
      !contact.pad_normal_local.allFinite() ||
      !std::isfinite(nlen) || nlen < 0.5 || mesh.faceCount() == 0) {
    return;
  }
  const Vec3 n = contact.outward_normal_local / nlen;
  out.valid = true;
  out.press_dir = -n;
  // Step 2: Eq. 1, the contact radius from the press depth; the hit's feature.
  out.press_depth = pressDepth(v, n);
  out.radius = contactRadius(out.press_depth, s.r_max, s.d0);
  out.hit = contactFeature(mesh, contact, s.feature_tolerance);
  if (!(out.radius > 0.0)) return;
  // Step 3: the walk's angular limit and start faces (walkContext).
  const double side = mesh.faceNormal(out.hit.face).dot(n) < 0.0 ? -1.0 : 1.0;
  const WalkContext ctx = walkContext(mesh, s, n, out.hit, side);
  // The ring of radial vectors: radial 0 along the reference carried from the last step.
  Vec3 t1, t2;
  ringAxes(contact.ring_reference_local, n, t1, t2);
  out.ring_tangent = t1;
  // The 6-DOF pad's ellipse (off for pad_model disc or a flat pad: the disc, exactly).
  const PadEllipse pad = padEllipse(s, contact.pad_normal_local, n);
  // Eq. 2 reads the tangential part of v: pressing alone stretches nothing.
  const Vec3 v_t = v - v.dot(n) * n;
  const bool filled = s.fill == PatchFill::kFilled;
  const StretchLogs logs(s);
  // Step 4: per radial vector, its start face (Fig. 3), Eq. 2 distance and the walk (Alg. 1), carried
  // from the cache on face hits only (edge and vertex scenes are sensitive to rounding), crossings pending.
  WalkCache* carry = warm && out.hit.feature == Feature::kFace ? warm : nullptr;
  if (carry) keyWalkCache(&mesh, s.n_sgo, out.hit, was_valid, *carry);
  out.crossings_pending = carry && !filled;
  out.path_offsets.push_back(0);
  const RingAngles& ring = ringAngles(s.n_sgo);
  // On a face hit every radial vector starts on the hit face, turned onto it by one rotation
  // (linear: the face is within 90 degrees of n): the ring's axes turned once.
  const bool face_hit = out.hit.feature == Feature::kFace;
  const Vec3 hit_normal = side * mesh.faceNormal(out.hit.face);
  const Vec3 f1 = face_hit ? rotateOnto(t1, n, hit_normal) : t1, f2 = face_hit ? rotateOnto(t2, n, hit_normal) : t2;
  // Carried walks (face hits only) start in the hit face's plane: the ring's axes there.
  const PlaneAxes axes = carry ? ringInPlane(carryPlane(mesh, out.hit.face, side, out.hit.point, *carry), f1, f2)
                               : PlaneAxes{};
  for (int i = 0; i < s.n_sgo; ++i) {
    const double ci = ring.c[static_cast<std::size_t>(i)], si = ring.s[static_cast<std::size_t>(i)];
    const Vec3 r = ci * t1 + si * t2;
    const Start start = face_hit ? Start{out.hit.face, side, ci * f1 + si * f2, true} : startFace(ctx, out.hit, side, r);
    const bool usable = start.usable && start.dir.squaredNorm() > kDegenerateLength * kDegenerateLength;
    out.radial.push_back(usable ? start.dir : r);
    const double pad_scale = pad.on ? padRadiusScale(pad, r) : 1.0;  // the disc: no call per radial
    out.d_i.push_back(usable ? stretched(out.radius * pad_scale, v_t, r, s, logs) : 0.0);
    if (!usable) {
      if (carry) uncachePath(*carry, i);
      out.radial_stop.push_back(WalkStop::kDropped);
      continue;
    }
    Sgo sgo = walkRadial(ctx, start, out.hit.point, out.d_i.back(), carry, i, axes.ok, ci * axes.x1 + si * axes.x2,
                         ci * axes.y1 + si * axes.y2, out);
    if (warm && !carry) ++warm->cold_walks;
    sgo.radial = i;
    if (filled) fillPath(s.rings, padSectorAngle(pad, r, n, 2.0 * std::numbers::pi / s.n_sgo), sgo, out);
    out.radial_stop.push_back(sgo.stop);
    out.sgos.push_back(sgo);
    out.path_offsets.push_back(static_cast<std::int32_t>(out.path_points.size()));
  }
  if (out.sgos.empty()) return;
  if (filled) {
    shareFilledLoad(out);
  } else {
    shareRingLoad(out.hit.point, n, out.radius, out);
  }
}

void placePendingCrossings(const WalkCache& warm, Patch& patch) {
  if (!patch.crossings_pending) return;
  for (std::size_t k = 0; k < patch.sgos.size(); ++k) {
    pendingCrossings(warm, patch.sgos[k].radial, patch.path_points.data() + patch.path_offsets[k] + 1);
  }
  patch.crossings_pending = false;
}

}  // namespace gf::sim
