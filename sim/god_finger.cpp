#include "sim/god_finger.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace gf::sim {
namespace {

// Below this length a direction has vanished (unit vectors; dimensionless).
constexpr double kDegenerateLength = 1e-12;

// The faces a radial vector may start on, and the walk's angular limit.
struct WalkContext {
  const Mesh& mesh;
  const PatchSettings& s;
  Vec3 normal;       // outward contact normal (unit)
  double cos_limit;  // a face is allowed while cos(angle to normal) > cos_limit
  bool has_limit;
};

// Orthonormal tangent basis of a unit normal (Duff et al., JCGT 2017, branchless form).
void tangentBasis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  t1 = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

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

bool faceAllowed(const WalkContext& ctx, const Vec3& oriented_normal) {
  return !ctx.has_limit || oriented_normal.dot(ctx.normal) > ctx.cos_limit;
}

// Which test stops the walk at a face with the given oriented normal.
WalkStop stopReason(const WalkContext& ctx, const Vec3& oriented_normal) {
  const double angle = std::acos(std::clamp(oriented_normal.dot(ctx.normal), -1.0, 1.0));
  return ctx.s.angular_threshold && angle >= ctx.s.tau_a ? WalkStop::kAngularThreshold
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

// The start of one radial vector: its face, winding sign there and in-plane direction.
struct Start {
  int face = -1;
  double side = 1.0;
  Vec3 dir = Vec3::Zero();
};

// Paper Fig. 3: maps radial vector r onto the face around the hit it points into.
Start startFace(const WalkContext& ctx, const SurfacePoint& hit, double side, const Vec3& r) {
  const Mesh& m = ctx.mesh;
  Start best;
  double best_score = -std::numeric_limits<double>::infinity();
  auto consider = [&](int f) {
    const double sf = side * (f == hit.face ? 1.0 : relativeSide(m, hit.face, f));
    const Vec3 dir = rotateOnto(r, ctx.normal, sf * m.faceNormal(f));
    const double score = enterScore(m, hit, f, dir);
    if (score > best_score) best_score = score, best = {f, sf, dir};
  };
  consider(hit.face);
  if (hit.feature == Feature::kFace) return best;
  const auto& hit_tri = m.triangles()[hit.face];
  const std::int32_t v = hit_tri[hit.feature_index];
  const std::int32_t w = hit.feature == Feature::kEdge ? hit_tri[(hit.feature_index + 1) % 3] : v;
  for (const std::int32_t* f = m.vertexFacesBegin(v); f != m.vertexFacesEnd(v); ++f) {
    if (*f != hit.face && faceHasVertex(m, *f, w)) consider(*f);
  }
  return best;
}

// Algorithm 1: walks distance d from the hit along dir, crossing edges while the next face stays
// within the angular limit. Appends the path; returns the SGO.
Sgo walk(const WalkContext& ctx, const Start& start, const Vec3& from, double d, Patch& out) {
  const Mesh& m = ctx.mesh;
  Sgo sgo{from, start.face, -1, 0.0, WalkStop::kDistance};
  Vec3 dir = start.dir;
  double side = start.side, remaining = d;
  out.path_points.push_back(from);
  for (int crossings = 0;; ++crossings) {
    // r_i <- projection of r_i on f (Alg. 1, line 3), kept unit length.
    const Vec3& nf = m.faceNormal(sgo.face);
    dir -= dir.dot(nf) * nf;
    const double len = dir.norm();
    if (!(len > kDegenerateLength)) return sgo.stop = WalkStop::kDegenerate, sgo;
    dir /= len;
    if (remaining <= 0.0) return sgo;
    // Does d_i * r_i cross an edge of f? First edge the ray leaves through.
    double t_exit = std::numeric_limits<double>::infinity();
    int k_exit = -1;
    for (int k = 0; k < 3; ++k) {
      const Vec3& in = m.edgeInwardNormal(sgo.face, k);
      const double rate = dir.dot(in);
      if (rate >= 0.0) continue;
      const double gap = std::max(0.0, (sgo.position - m.corner(sgo.face, k)).dot(in));
      if (const double t = gap / -rate; t < t_exit) t_exit = t, k_exit = k;
    }
    if (k_exit < 0) return sgo.stop = WalkStop::kDegenerate, sgo;
    if (t_exit >= remaining) {  // ends inside f: p_SGO += d_i r_i
      sgo.position += remaining * dir;
      sgo.walked += remaining;
      out.path_points.push_back(sgo.position);
      return sgo;
    }
    // Reached edge e: p_SGO on e, d_i reduced by the distance travelled.
    sgo.position += t_exit * dir;
    sgo.walked += t_exit;
    remaining -= t_exit;
    out.path_points.push_back(sgo.position);
    const FaceLink& link = m.link(sgo.face, k_exit);
    if (link.face < 0) return sgo.stop = WalkStop::kBoundary, sgo;
    if (crossings >= ctx.s.max_face_crossings) return sgo.stop = WalkStop::kCrossingLimit, sgo;
    const double next_side = link.flipped ? -side : side;
    const Vec3 next_normal = next_side * m.faceNormal(link.face);
    if (!faceAllowed(ctx, next_normal)) return sgo.stop = stopReason(ctx, next_normal), sgo;
    // Carry the direction over the edge: keep its component along the edge, turn the rest into
    // the neighbour (the unfolded straight line; equals the projection to first order).
    const Vec3 edge = (m.corner(sgo.face, (k_exit + 1) % 3) - m.corner(sgo.face, k_exit)).normalized();
    const double across = -dir.dot(m.edgeInwardNormal(sgo.face, k_exit));
    dir = dir.dot(edge) * edge + across * m.edgeInwardNormal(link.face, link.edge);
    sgo.face = link.face;
    side = next_side;
  }
}

void resetPatch(int n, Patch& out) {
  out.valid = false;
  out.press_depth = out.radius = 0.0;
  out.hit = {};
  out.press_dir.setZero();
  out.radial.clear();
  out.d_i.clear();
  out.radial_stop.clear();
  out.sgos.clear();
  out.path_points.clear();
  out.path_offsets.clear();
  if (out.radial.capacity() < static_cast<std::size_t>(n)) {
    out.radial.reserve(kMaxSgo);
    out.d_i.reserve(kMaxSgo);
    out.radial_stop.reserve(kMaxSgo);
    out.sgos.reserve(kMaxSgo);
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
         finite(s.max_stretch_exponent) && s.max_stretch_exponent >= 0 && s.max_stretch_exponent <= 50 &&
         finite(s.tau_a) && s.tau_a >= 0 && s.tau_a <= std::numbers::pi && finite(s.friction) &&
         s.friction >= 0 && s.max_face_crossings >= 0 && s.max_face_crossings <= 1000000 &&
         finite(s.feature_tolerance) && s.feature_tolerance >= 0;
}

}  // namespace

void clearPatch(Patch& patch) { resetPatch(0, patch); }

double pressDepth(const Vec3& v, const Vec3& outward_normal) { return -v.dot(outward_normal); }

double contactRadius(double press_depth, double r_max, double d0) {
  if (!(press_depth > 0.0) || !(d0 > 0.0)) return 0.0;
  // r = r_max (1 - e^(-x)); -expm1(-x) is exact for small x and tends to 1 without overflow.
  return r_max * -std::expm1(-press_depth / d0);
}

double stretchedDistance(double radius, const Vec3& v, const Vec3& radial_unit,
                         const PatchSettings& s) {
  if (!s.tangential_stretch) return radius;
  const double e = std::clamp(-v.dot(radial_unit) / s.stretch_length, -s.max_stretch_exponent,
                              s.max_stretch_exponent);
  return radius * std::exp(e * std::log(s.alpha));
}

void computePatch(const Mesh& mesh, const PatchContact& contact, const Vec3& v,
                  const PatchSettings& s, Patch& out) {
  resetPatch(s.n_sgo, out);
  // Step 1: reject what cannot be computed.
  const double nlen = contact.outward_normal_local.norm();
  if (!computable(s) || !contact.point_local.allFinite() || !std::isfinite(contact.separation) ||
      !v.allFinite() || !std::isfinite(nlen) || nlen < 0.5 || mesh.faceCount() == 0) {
    return;
  }
  const Vec3 n = contact.outward_normal_local / nlen;
  out.valid = true;
  out.press_dir = -n;
  // Step 2: Eq. 1, the contact radius from the press depth.
  out.press_depth = pressDepth(v, n);
  out.radius = contactRadius(out.press_depth, s.r_max, s.d0);
  out.hit = mesh.closestPoint(contact.point_local, s.feature_tolerance);
  if (!(out.radius > 0.0)) return;
  // Step 3: the walk's angular limit, min(tau_a, atan(theta)) over the active tests.
  double limit = std::numbers::pi;
  if (s.angular_threshold) limit = std::min(limit, s.tau_a);
  if (s.friction_cone) limit = std::min(limit, std::atan(s.friction));
  const WalkContext ctx{mesh, s, n, std::cos(limit), limit < std::numbers::pi};
  const double side = mesh.faceNormal(out.hit.face).dot(n) < 0.0 ? -1.0 : 1.0;
  Vec3 t1, t2;
  tangentBasis(n, t1, t2);
  // Step 4: per radial vector, its start face (Fig. 3), Eq. 2 distance and the walk (Alg. 1).
  out.path_offsets.push_back(0);
  for (int i = 0; i < s.n_sgo; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / s.n_sgo;
    const Vec3 r = std::cos(angle) * t1 + std::sin(angle) * t2;
    const Start start = startFace(ctx, out.hit, side, r);
    const bool usable = start.dir.norm() > kDegenerateLength &&
                        faceAllowed(ctx, start.side * mesh.faceNormal(start.face));
    out.radial.push_back(usable ? start.dir : r);
    out.d_i.push_back(usable ? stretchedDistance(out.radius, v, start.dir, s) : 0.0);
    if (!usable) {
      out.radial_stop.push_back(WalkStop::kDropped);
      continue;
    }
    Sgo sgo = walk(ctx, start, out.hit.point, out.d_i.back(), out);
    sgo.radial = i;
    out.radial_stop.push_back(sgo.stop);
    out.sgos.push_back(sgo);
    out.path_offsets.push_back(static_cast<std::int32_t>(out.path_points.size()));
  }
}

}  // namespace gf::sim
