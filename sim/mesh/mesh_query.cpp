// Bounding-volume hierarchy over the triangles of a Mesh and the closest-point query.
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <numeric>

#include "sim/mesh/mesh.hpp"

namespace gf::sim {
namespace {

constexpr int kLeafSize = 4;
constexpr int kMaxStack = 64;

// Closest point on triangle abc (unit normal n) to p. The regions are Ericson's (Real-Time
// Collision Detection 5.1.5); the points are not his barycentric combinations, whose
// cancellation grows with the square of the triangle's aspect ratio (on a 10 cm x 1 um sliver,
// the closest point to a point of the triangle came out 24 nm away), but the projection of p on
// the face's plane and on the edge's line, exact to rounding. Returns the point; `feature` and
// `index` name the region: a corner k, an edge k (k to k+1), or the face.
Vec3 closestByRegion(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n,
                     Feature& feature, int& index) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return feature = Feature::kVertex, index = 0, a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return feature = Feature::kVertex, index = 1, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    feature = Feature::kEdge, index = 0;
    return a + std::clamp(d1 / ab.squaredNorm(), 0.0, 1.0) * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return feature = Feature::kVertex, index = 2, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    feature = Feature::kEdge, index = 2;
    return a + std::clamp(d2 / ac.squaredNorm(), 0.0, 1.0) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    feature = Feature::kEdge, index = 1;
    const Vec3 bc = c - b;
    return b + std::clamp(bc.dot(bp) / bc.squaredNorm(), 0.0, 1.0) * bc;
  }
  feature = Feature::kFace, index = -1;
  return p - ap.dot(n) * n;
}

// closestByRegion, checked against each edge's nearest point: on a huge sliver the regions'
// tests cancel (products of 1e36 m edges), and a point on one long edge was taken for the
// other's region, 1.1e28 m across the sliver (fuzz_patch, a 7e36 m triangle). An edge point
// nearer than the region's point wins; on any other triangle none is.
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n,
                       Feature& feature, int& index) {
  Vec3 best = closestByRegion(p, a, b, c, n, feature, index);
  double best_d2 = (best - p).squaredNorm();
  const Vec3* corners[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Vec3& u = *corners[k];
    const Vec3 e = *corners[(k + 1) % 3] - u;
    const double t = std::clamp((p - u).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec3 q = u + t * e;
    const double d2 = (q - p).squaredNorm();
    if (!(d2 < best_d2)) continue;
    best = q, best_d2 = d2;
    if (t == 0.0 || t == 1.0) feature = Feature::kVertex, index = t == 0.0 ? k : (k + 1) % 3;
    else feature = Feature::kEdge, index = k;
  }
  return best;
}

double boxDistance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const Vec3 d = (lo - p).cwiseMax(Vec3::Zero()).cwiseMax(p - hi);
  return d.squaredNorm();
}

// Promotes a face or edge hit to an edge or vertex hit when it lies within tol of one.
void classifyWithTolerance(const Mesh& m, double tol, SurfacePoint& sp) {
  if (sp.feature == Feature::kVertex) return;
  for (int k = 0; k < 3; ++k) {
    if ((m.corner(sp.face, k) - sp.point).norm() <= tol) {
      sp.feature = Feature::kVertex, sp.feature_index = k, sp.point = m.corner(sp.face, k);
      return;
    }
  }
  if (sp.feature == Feature::kEdge) return;
  for (int k = 0; k < 3; ++k) {
    const Vec3& a = m.corner(sp.face, k);
    const Vec3 e = m.corner(sp.face, (k + 1) % 3) - a;
    const double t = std::clamp((sp.point - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const Vec3 on_edge = a + t * e;
    if ((on_edge - sp.point).norm() <= tol) {
      sp.feature = Feature::kEdge, sp.feature_index = k, sp.point = on_edge;
      return;
    }
  }
}

}  // namespace

void Mesh::buildBvh() {
  bvh_nodes_.clear();
  bvh_faces_.resize(triangles_.size());
  std::iota(bvh_faces_.begin(), bvh_faces_.end(), 0);
  if (triangles_.empty()) return;
  std::vector<Vec3> centroid(triangles_.size());
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    centroid[f] = (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0;
  }
  // Iterative top-down build: split at the median centroid along the longest axis.
  struct Task { std::int32_t node, first, count; };
  std::vector<Task> tasks{{0, 0, static_cast<std::int32_t>(triangles_.size())}};
  bvh_nodes_.push_back({});
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    Vec3 lo = corner(bvh_faces_[t.first], 0), hi = lo;
    for (std::int32_t i = t.first; i < t.first + t.count; ++i) {
      for (int k = 0; k < 3; ++k) {
        lo = lo.cwiseMin(corner(bvh_faces_[i], k));
        hi = hi.cwiseMax(corner(bvh_faces_[i], k));
      }
    }
    BvhNode& node = bvh_nodes_[t.node];
    node.lo = lo, node.hi = hi;
    if (t.count <= kLeafSize) {
      node.first = t.first, node.count = t.count;
      continue;
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const auto begin = bvh_faces_.begin() + t.first;
    const std::int32_t half = t.count / 2;
    std::nth_element(begin, begin + half, begin + t.count, [&](std::int32_t a, std::int32_t b) {
      return centroid[a][axis] < centroid[b][axis] ||
             (centroid[a][axis] == centroid[b][axis] && a < b);
    });
    const auto left = static_cast<std::int32_t>(bvh_nodes_.size());
    node.first = left, node.count = 0;  // `node` is not used after the push_back below
    bvh_nodes_.push_back({});
    bvh_nodes_.push_back({});
    tasks.push_back({left, t.first, half});
    tasks.push_back({left + 1, t.first + half, t.count - half});
  }
}

// The boxes again, children before parents (a child is always stored after its parent).
void Mesh::refitBvh() {
  for (std::size_t i = bvh_nodes_.size(); i-- > 0;) {
    BvhNode& node = bvh_nodes_[i];
    if (node.count > 0) {
      node.lo = node.hi = corner(bvh_faces_[node.first], 0);
      for (std::int32_t k = node.first; k < node.first + node.count; ++k) {
        for (int c = 0; c < 3; ++c) {
          node.lo = node.lo.cwiseMin(corner(bvh_faces_[k], c));
          node.hi = node.hi.cwiseMax(corner(bvh_faces_[k], c));
        }
      }
      continue;
    }
    const BvhNode& a = bvh_nodes_[static_cast<std::size_t>(node.first)];
    const BvhNode& b = bvh_nodes_[static_cast<std::size_t>(node.first) + 1];
    node.lo = a.lo.cwiseMin(b.lo);
    node.hi = a.hi.cwiseMax(b.hi);
  }
}

SurfacePoint Mesh::closestPoint(const Vec3& p, double feature_tol) const {
  SurfacePoint best;
  if (bvh_nodes_.empty()) return best;
  double best_d2 = std::numeric_limits<double>::infinity();
  std::int32_t stack[kMaxStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = bvh_nodes_[stack[--top]];
    if (boxDistance2(p, node.lo, node.hi) > best_d2) continue;
    if (node.count > 0) {
      for (std::int32_t i = node.first; i < node.first + node.count; ++i) {
        const int f = bvh_faces_[i];
        Feature feat;
        int idx;
        const Vec3 q = closestOnTriangle(p, corner(f, 0), corner(f, 1), corner(f, 2), normals_[f], feat, idx);
        const double d2 = (q - p).squaredNorm();
        if (d2 < best_d2 || (d2 == best_d2 && f < best.face)) {
          best_d2 = d2;
          best = {f, feat, idx, q, 0.0};
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last).
    const std::int32_t l = node.first, r = node.first + 1;
    const double dl = boxDistance2(p, bvh_nodes_[l].lo, bvh_nodes_[l].hi);
    const double dr = boxDistance2(p, bvh_nodes_[r].lo, bvh_nodes_[r].hi);
    if (top + 2 > kMaxStack) continue;  // unreachable for balanced trees below 2^60 faces
    stack[top++] = dl < dr ? r : l;
    stack[top++] = dl < dr ? l : r;
  }
  classifyWithTolerance(*this, feature_tol, best);
  best.query_distance = (best.point - p).norm();
  return best;
}

Vec3 pressedNormal(const Mesh& mesh, const SurfacePoint& hit, const Vec3& push) {
  if (hit.feature == Feature::kFace || !(push.norm() > 0.0)) return mesh.faceNormal(hit.face);
  const auto& tri = mesh.triangles()[static_cast<std::size_t>(hit.face)];
  const std::int32_t v = tri[static_cast<std::size_t>(hit.feature_index)];
  const std::int32_t w = hit.feature == Feature::kEdge ? tri[static_cast<std::size_t>((hit.feature_index + 1) % 3)] : v;
  Vec3 best = mesh.faceNormal(hit.face);
  double most = -best.dot(push);
  for (const std::int32_t* f = mesh.vertexFacesBegin(v); f != mesh.vertexFacesEnd(v); ++f) {
    const auto& t = mesh.triangles()[static_cast<std::size_t>(*f)];
    if (t[0] != w && t[1] != w && t[2] != w) continue;
    if (const double press = -mesh.faceNormal(*f).dot(push); press > most) most = press, best = mesh.faceNormal(*f);
  }
  return best;
}

}  // namespace gf::sim
