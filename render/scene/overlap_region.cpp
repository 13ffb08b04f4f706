#include "render/scene/overlap_region.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace gf::render {
namespace {

using Vec3 = sim::Vec3;

constexpr int kEdgeSamples = 48;  // points around the lens's edge

// How far from `from` (inside the disc) along unit `u` the circle of centre `c`, radius r is.
double exitDistance(const Vec3& from, const Vec3& u, const Vec3& c, double r) {
  const Vec3 m = from - c;
  const double b = u.dot(m), q = m.squaredNorm() - r * r;
  return -b + std::sqrt(std::max(0.0, b * b - q));
}

}  // namespace

bool patchesOverlap(const sim::ContactSnapshot& a, const sim::ContactSnapshot& b) {
  if (a.body != b.body || !(a.radius > 0.0) || !(b.radius > 0.0)) return false;
  if (!(a.outward_normal_world.dot(b.outward_normal_world) > 0.0)) return false;
  const Vec3 n = (a.outward_normal_world + b.outward_normal_world).normalized();
  const Vec3 gap = b.point_world - a.point_world;
  return (gap - gap.dot(n) * n).norm() < a.radius + b.radius;
}

void buildOverlapRegion(const sim::ContactSnapshot& a, const sim::ContactSnapshot& b, const sim::Mesh& mesh,
                        const sim::Pose& pose, double lift, std::vector<Vertex>& triangles,
                        std::vector<Vertex>& outline) {
  if (!patchesOverlap(a, b)) return;
  // The common tangent plane and the two discs' centres in it (as sim::discOverlap takes them).
  const Vec3 n = (a.outward_normal_world + b.outward_normal_world).normalized();
  const Vec3 ca = a.point_world;
  Vec3 cb = b.point_world - (b.point_world - ca).dot(n) * n;
  const Vec3 gap = cb - ca;
  const double d = gap.norm();
  // A point inside both discs: the middle of their overlap along the line between the centres.
  const Vec3 e = d > 1e-12 ? Vec3(gap / d) : Vec3(n.unitOrthogonal());
  const double lo = std::max(-a.radius, d - b.radius), hi = std::min(a.radius, d + b.radius);
  const Vec3 mid = ca + 0.5 * (lo + hi) * e;
  const Vec3 f = n.cross(e);
  const auto onSurface = [&](const Vec3& world) {
    const sim::SurfacePoint sp = mesh.closestPoint(pose.orientation.conjugate() * (world - pose.position), 0.0);
    if (sp.face < 0) return makeVertex(world + lift * n, n);
    const Vec3 normal = pose.orientation * mesh.faceNormal(sp.face);
    return makeVertex(pose.toWorld(sp.point) + lift * normal, normal);
  };
  const Vertex centre = onSurface(mid);
  std::array<Vertex, kEdgeSamples> edge;
  for (int k = 0; k < kEdgeSamples; ++k) {
    const double t = 2.0 * std::numbers::pi * k / kEdgeSamples;
    const Vec3 u = std::cos(t) * e + std::sin(t) * f;
    const double reach = std::min(exitDistance(mid, u, ca, a.radius), exitDistance(mid, u, cb, b.radius));
    edge[static_cast<std::size_t>(k)] = onSurface(mid + reach * u);
  }
  for (int k = 0; k < kEdgeSamples; ++k) {
    const Vertex& p = edge[static_cast<std::size_t>(k)];
    const Vertex& q = edge[static_cast<std::size_t>((k + 1) % kEdgeSamples)];
    triangles.insert(triangles.end(), {centre, p, q});
    outline.insert(outline.end(), {p, q});
  }
}

}  // namespace gf::render
