#include "sim/mesh/tet_pad.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sim/mesh/tet_shapes.hpp"

namespace gf::sim {
namespace {

void requireRange(double value, double lo, double hi, const char* field, const char* unit) {
  if (!(value >= lo && value <= hi)) {
    throw std::invalid_argument(std::string("pad.") + field + ": must be in " + std::to_string(lo) + ".." +
                                std::to_string(hi) + " " + unit + ", got " + std::to_string(value));
  }
}

// Cells of about `size` over `length`, at least `least`.
int cellsOver(double length, double size, int least, const char* field) {
  const double n = std::ceil(length / size - 1e-9);
  if (n > kMaxPadElementsAcross) {
    throw std::invalid_argument(std::string("pad.element_size: ") + std::to_string(size) + " m makes " +
                                std::to_string(static_cast<long>(n)) + " cells " + field + " (at most " +
                                std::to_string(kMaxPadElementsAcross) + ")");
  }
  return std::max(least, static_cast<int>(n));
}

// The node at grid point (i, j, k): i, j across the cap at equal angles (as an equiangular
// cubed sphere's face), k through the thickness from the bone out.
Vec3 padNode(const PadShape& s, int n, int m, int i, int j, int k) {
  const double u = std::tan(s.cap_angle * (2.0 * i / n - 1.0)), v = std::tan(s.cap_angle * (2.0 * j / n - 1.0));
  const double r = s.bone_radius + s.thickness * k / m;
  return r * Vec3(u, -1.0, v).normalized();
}

double angleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Dihedral angles (rad) of one tetrahedron, at its six edges.
std::array<double, 6> dihedrals(const std::array<Vec3, 4>& p) {
  static constexpr std::array<std::array<int, 4>, 6> kEdges = {
      {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}}};
  std::array<double, 6> out{};
  for (std::size_t e = 0; e < 6; ++e) {
    const auto& [a, b, c, d] = kEdges[e];
    const Vec3 axis = (p[b] - p[a]).normalized();
    Vec3 u = p[c] - p[a], w = p[d] - p[a];
    u -= u.dot(axis) * axis;  // each face's direction away from the edge
    w -= w.dot(axis) * axis;
    out[e] = angleBetween(u, w);
  }
  return out;
}

// 3 × inradius / circumradius of one tetrahedron.
double radiusRatio(const std::array<Vec3, 4>& p) {
  const double volume = std::abs(tetVolume(p[0], p[1], p[2], p[3]));
  double area = 0.0;
  for (const auto& [a, b, c] : std::array<std::array<int, 3>, 4>{{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}}) {
    area += 0.5 * (p[b] - p[a]).cross(p[c] - p[a]).norm();
  }
  if (area <= 0.0 || volume <= 0.0) return 0.0;
  const double inradius = 3.0 * volume / area;
  // Circumcentre x solves 2 (p_i − p_0)·x = |p_i|² − |p_0|² for i = 1..3.
  Eigen::Matrix3d m;
  Vec3 rhs;
  for (int i = 0; i < 3; ++i) {
    m.row(i) = 2.0 * (p[static_cast<std::size_t>(i) + 1] - p[0]).transpose();
    rhs[i] = p[static_cast<std::size_t>(i) + 1].squaredNorm() - p[0].squaredNorm();
  }
  const double circumradius = (m.fullPivLu().solve(rhs) - p[0]).norm();
  return circumradius > 0.0 ? 3.0 * inradius / circumradius : 0.0;
}

}  // namespace

double tetVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

TetMesh generatePad(const PadShape& s) {
  requireRange(s.bone_radius, kMinPadLength, kMaxPadLength, "bone_radius", "m");
  requireRange(s.thickness, kMinPadLength, s.bone_radius, "thickness", "m (at most the bone's radius)");
  requireRange(s.element_size, s.thickness / 16.0, s.thickness, "element_size",
               "m (a sixteenth of the thickness to the thickness)");
  requireRange(s.cap_angle, kMinCapAngle, kMaxCapAngle, "cap_angle", "rad");
  // Cells of about element_size along the cap's middle radius, and through the thickness.
  const double arc = 2.0 * s.cap_angle * (s.bone_radius + 0.5 * s.thickness);
  const int n = cellsOver(arc, s.element_size, 2, "across the cap");
  const int m = cellsOver(s.thickness, s.element_size, 1, "through the thickness");
  TetMesh mesh = kuhnGrid({n, n, m}, [&](int i, int j, int k) { return padNode(s, n, m, i, j, k); }, false);
  mesh.cells_across = n;
  mesh.layers = m;
  // The grid's first layer (k = 0) is on the bone.
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) mesh.bone_nodes.push_back(j * (n + 1) + i);
  }
  return mesh;
}

TetQuality tetQuality(const TetMesh& mesh) {
  TetQuality q;
  q.min_volume = mesh.tets.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  q.min_dihedral_deg = 180.0;
  q.min_radius_ratio = 1.0;
  constexpr double kDeg = 180.0 / std::numbers::pi;
  for (const std::array<int, 4>& t : mesh.tets) {
    const std::array<Vec3, 4> p = {mesh.nodes[static_cast<std::size_t>(t[0])], mesh.nodes[static_cast<std::size_t>(t[1])],
                                   mesh.nodes[static_cast<std::size_t>(t[2])], mesh.nodes[static_cast<std::size_t>(t[3])]};
    const double v = tetVolume(p[0], p[1], p[2], p[3]);
    q.volume += v;
    q.min_volume = std::min(q.min_volume, v);
    for (double angle : dihedrals(p)) {
      q.min_dihedral_deg = std::min(q.min_dihedral_deg, angle * kDeg);
      q.max_dihedral_deg = std::max(q.max_dihedral_deg, angle * kDeg);
    }
    q.min_radius_ratio = std::min(q.min_radius_ratio, radiusRatio(p));
  }
  return q;
}

}  // namespace gf::sim
