#include "sim/mesh/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

namespace gf::sim {
namespace {

using Tris = std::vector<std::array<std::int32_t, 3>>;

void requirePositive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string(what) + " must be a positive finite number");
  }
}

void requireRange(int value, int lo, int hi, const char* what) {
  if (value < lo || value > hi) {
    throw std::invalid_argument(std::string(what) + " must be in " + std::to_string(lo) + ".." +
                                std::to_string(hi));
  }
}

// Appends a grid of quads spanning origin + u*[0,1] + v*[0,1], wound so u x v is the normal.
void addGrid(const Vec3& origin, const Vec3& u, const Vec3& v, int nu, int nv,
             std::vector<Vec3>& pos, Tris& tris) {
  const auto base = static_cast<std::int32_t>(pos.size());
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) pos.push_back(origin + u * (double(i) / nu) + v * (double(j) / nv));
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::int32_t a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
  }
}

// Surface of revolution about y from a profile of (radius, y) points, bottom to top; profile
// points with radius 0 become poles. `segments` around.
Mesh revolve(const std::vector<std::pair<double, double>>& profile, int segments) {
  std::vector<Vec3> pos;
  Tris tris;
  const double step = 2.0 * std::numbers::pi / segments;
  for (const auto& [r, y] : profile) {
    for (int s = 0; s < segments; ++s) {
      pos.emplace_back(r * std::cos(s * step), y, -r * std::sin(s * step));
    }
  }
  for (std::size_t ring = 0; ring + 1 < profile.size(); ++ring) {
    for (int s = 0; s < segments; ++s) {
      const auto a = static_cast<std::int32_t>(ring * segments + s);
      const auto b = static_cast<std::int32_t>(ring * segments + (s + 1) % segments);
      const auto c = a + segments, d = b + segments;
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
  }
  // Welding merges the pole copies; the triangles that collapse there are dropped.
  return buildMesh(pos, tris);
}

}  // namespace

Mesh tessellateSphere(double radius, int subdivisions) {
  requirePositive(radius, "sphere radius");
  requireRange(subdivisions, 0, kMaxSphereSubdivisions, "sphere subdivisions");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> pos = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  Tris tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : pos) p.normalize();
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> mid;
    auto midpoint = [&](std::int32_t a, std::int32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace(key, static_cast<std::int32_t>(pos.size()));
      if (inserted) pos.push_back((pos[a] + pos[b]).normalized());
      return it->second;
    };
    Tris next;
    next.reserve(tris.size() * 4);
    for (const auto& f : tris) {
      const std::int32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  for (Vec3& p : pos) p *= radius;
  return buildMesh(pos, tris);
}

Mesh tessellateBox(const Vec3& h, int segments) {
  requirePositive(h.minCoeff(), "box half extent");
  requireRange(segments, kMinBoxSegments, kMaxBoxSegments, "box segments");
  std::vector<Vec3> pos;
  Tris tris;
  const Vec3 x = Vec3::UnitX() * 2 * h.x(), y = Vec3::UnitY() * 2 * h.y(), z = Vec3::UnitZ() * 2 * h.z();
  const int n = segments;
  addGrid(Vec3(h.x(), -h.y(), h.z()), -z, y, n, n, pos, tris);   // +x
  addGrid(Vec3(-h.x(), -h.y(), -h.z()), z, y, n, n, pos, tris);  // -x
  addGrid(Vec3(-h.x(), h.y(), h.z()), x, -z, n, n, pos, tris);   // +y
  addGrid(Vec3(-h.x(), -h.y(), -h.z()), x, z, n, n, pos, tris);  // -y
  addGrid(Vec3(-h.x(), -h.y(), h.z()), x, y, n, n, pos, tris);   // +z
  addGrid(Vec3(h.x(), -h.y(), -h.z()), -x, y, n, n, pos, tris);  // -z
  return buildMesh(pos, tris);
}

Mesh tessellateCylinder(double radius, double half_height, int segments) {
  requirePositive(radius, "cylinder radius");
  requirePositive(half_height, "cylinder half height");
  requireRange(segments, kMinCylinderSegments, kMaxRoundSegments, "cylinder segments");
  const double arc = 2.0 * std::numbers::pi * radius / segments;
  const int rings = std::clamp(static_cast<int>(std::lround(2.0 * half_height / arc)), 1, 4096);
  std::vector<std::pair<double, double>> profile = {{0.0, -half_height}};
  for (int i = 0; i <= rings; ++i) profile.emplace_back(radius, -half_height + 2.0 * half_height * i / rings);
  profile.emplace_back(0.0, half_height);
  return revolve(profile, segments);
}

Mesh tessellateCapsule(double radius, double half_height, int segments) {
  requirePositive(radius, "capsule radius");
  requirePositive(half_height, "capsule half height");
  requireRange(segments, kMinCapsuleSegments, kMaxRoundSegments, "capsule segments");
  const int cap_rings = std::max(1, segments / 4);
  std::vector<std::pair<double, double>> profile;
  for (int i = 0; i <= cap_rings; ++i) {  // bottom hemisphere, pole to equator
    const double a = -std::numbers::pi / 2 + (std::numbers::pi / 2) * i / cap_rings;
    profile.emplace_back(radius * std::cos(a), -half_height + radius * std::sin(a));
  }
  for (int i = 0; i <= cap_rings; ++i) {  // top hemisphere, equator to pole
    const double a = (std::numbers::pi / 2) * i / cap_rings;
    profile.emplace_back(radius * std::cos(a), half_height + radius * std::sin(a));
  }
  profile.front().first = 0.0;
  profile.back().first = 0.0;
  return revolve(profile, segments);
}

Mesh tessellatePlane(double half_size, int segments) {
  requirePositive(half_size, "plane half size");
  requireRange(segments, kMinPlaneSegments, kMaxPlaneSegments, "plane segments");
  std::vector<Vec3> pos;
  Tris tris;
  addGrid(Vec3(-half_size, 0, half_size), Vec3(2 * half_size, 0, 0), Vec3(0, 0, -2 * half_size),
          segments, segments, pos, tris);
  return buildMesh(pos, tris);
}

}  // namespace gf::sim
