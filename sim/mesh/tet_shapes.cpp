#include "sim/mesh/tet_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace gf::sim {
namespace {

// The ball's (the disc's) shells near the centre are cubes (squares) of this half-size for each
// unit of radius; the blend takes them to spheres by the surface. With 0.8 the spacing of the
// shells stays within about 0.6 .. 1.4 of the mean, and the worst dihedral angle near 33 degrees.
constexpr double kCoreScale = 0.8;

std::string text(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

void requireLength(double value, const char* field) {
  if (!(value >= kMinSoftLength && value <= kMaxSoftLength)) {
    throw std::invalid_argument(std::string(field) + ": must be in " + text(kMinSoftLength) + ".." +
                                text(kMaxSoftLength) + " m, got " + text(value));
  }
}

void requireElementSize(double value, double largest) {
  if (!(value >= kMinSoftElementSize && value <= largest)) {
    throw std::invalid_argument("element_size: must be in " + text(kMinSoftElementSize) + ".." +
                                text(largest) + " m (up to the shape's largest dimension), got " +
                                text(value));
  }
}

// Cells of about `size` over `length`, at least `least`, rounded up to even when `even`.
int cellsOver(double length, double size, int least, bool even) {
  double n = std::max<double>(least, std::ceil(length / size - 1e-9));
  if (even) n = 2.0 * std::ceil(n / 2.0);
  return static_cast<int>(std::min(n, 1e9));  // the tetrahedra's limit refuses anything near this
}

void requireTetCount(const std::array<int, 3>& cells, double element_size) {
  const double tets = 6.0 * cells[0] * cells[1] * cells[2];
  if (tets > static_cast<double>(kMaxTetrahedra)) {
    throw std::invalid_argument("element_size: " + text(element_size) + " m makes " + text(tets) +
                                " tetrahedra (at most " + std::to_string(kMaxTetrahedra) + ")");
  }
}

// A grid coordinate in -1..1: exactly opposite for i and n - i.
double gridCoordinate(int i, int n) {
  return (2.0 * i - n) / n;
}

// The unit direction of a point q on the surface of the cube [-1, 1]³ (or, with q.y() = 0, on the
// square's boundary in x–z) at equal angles: each face's coordinates u taken to tan(π u / 4).
Vec3 equalAngleDirection(const Vec3& q) {
  const auto angle = [](double u) { return std::tan(0.25 * std::numbers::pi * u); };
  return Vec3(angle(q.x()), angle(q.y()), angle(q.z())).normalized();
}

// The point of the unit ball (the unit disc, when p.y() = 0) for grid point p in [-1, 1]³: on the
// shell m = |p|∞, a blend of the cube of half-size kCoreScale · m and the sphere of radius m, by
// m: the cube at the centre, the sphere at the surface.
Vec3 ballPoint(const Vec3& p) {
  const double m = p.cwiseAbs().maxCoeff();
  if (m == 0.0) return Vec3::Zero();
  const Vec3 q = p / m;
  return m * ((1.0 - m) * kCoreScale * q + m * equalAngleDirection(q));
}

// The six tetrahedra of one cell: Kuhn's split along the diagonal from corner 0 to corner 7, one
// per order of the three axes (corners as bits: i 1, j 2, k 4); `mirror` flips the axes whose bits
// it holds, so the diagonal runs the other way along them. Neighbours share their faces'
// diagonals as long as each axis's flip depends on the cell's place along that axis alone.
void splitCell(std::vector<std::array<int, 4>>& tets, const std::vector<Vec3>& nodes,
               const std::array<int, 8>& corner, int mirror) {
  static constexpr std::array<std::array<int, 3>, 6> kOrders = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  const auto at = [&](int bits) { return corner[static_cast<std::size_t>(bits ^ mirror)]; };
  for (const std::array<int, 3>& order : kOrders) {
    int bits = 0;
    std::array<int, 4> tet{at(0), 0, 0, at(7)};
    for (std::size_t step = 0; step < 2; ++step) {
      bits |= 1 << order[step];
      tet[step + 1] = at(bits);
    }
    const auto p = [&](std::size_t k) { return nodes[static_cast<std::size_t>(tet[k])]; };
    if (tetVolume(p(0), p(1), p(2), p(3)) < 0.0) std::swap(tet[1], tet[2]);
    tets.push_back(tet);
  }
}

// Faces of one tetrahedron, each wound outward when the tetrahedron's volume is positive.
std::array<std::array<int, 3>, 4> facesOf(const std::array<int, 4>& t) {
  return {{{t[0], t[2], t[1]}, {t[0], t[1], t[3]}, {t[1], t[2], t[3]}, {t[0], t[3], t[2]}}};
}

}  // namespace

std::vector<std::array<int, 3>> boundaryTriangles(const std::vector<std::array<int, 4>>& tets,
                                                  const std::vector<Vec3>& nodes) {
  struct Face {
    std::array<int, 3> key;    // its nodes sorted
    std::array<int, 3> wound;  // outward
  };
  std::vector<Face> faces;
  faces.reserve(4 * tets.size());
  for (const std::array<int, 4>& t : tets) {
    const double volume =
        tetVolume(nodes[static_cast<std::size_t>(t[0])], nodes[static_cast<std::size_t>(t[1])],
                  nodes[static_cast<std::size_t>(t[2])], nodes[static_cast<std::size_t>(t[3])]);
    for (std::array<int, 3> f : facesOf(t)) {
      // An inverted tetrahedron's faces turn the other way.
      if (volume < 0.0) std::swap(f[1], f[2]);
      std::array<int, 3> key = f;
      std::sort(key.begin(), key.end());
      faces.push_back({key, f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  // A face met once is on the boundary; one met twice (or more, a non-manifold mesh) is inside.
  std::vector<std::array<int, 3>> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) out.push_back(faces[i].wound);
    i = j;
  }
  return out;
}

TetMesh kuhnGrid(const std::array<int, 3>& cells, const std::function<Vec3(int, int, int)>& node,
                 bool outward) {
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  const auto index = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  TetMesh mesh;
  mesh.nodes.reserve(static_cast<std::size_t>(nx + 1) * static_cast<std::size_t>(ny + 1) *
                     static_cast<std::size_t>(nz + 1));
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) mesh.nodes.push_back(node(i, j, k));
    }
  }
  // A cell below the middle along an axis flips that axis, so its diagonal points outward.
  const auto flip = [&](int i, int n, int bit) { return outward && 2 * i + 1 < n ? bit : 0; };
  mesh.tets.reserve(6 * static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) *
                    static_cast<std::size_t>(nz));
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        std::array<int, 8> corner{};
        for (int bits = 0; bits < 8; ++bits) {
          corner[static_cast<std::size_t>(bits)] =
              index(i + (bits & 1), j + ((bits >> 1) & 1), k + ((bits >> 2) & 1));
        }
        splitCell(mesh.tets, mesh.nodes, corner, flip(i, nx, 1) | flip(j, ny, 2) | flip(k, nz, 4));
      }
    }
  }
  mesh.surface = boundaryTriangles(mesh.tets, mesh.nodes);
  return mesh;
}

TetMesh generateSoftBox(const Vec3& half_extents, double element_size) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!(half_extents[axis] >= kMinSoftLength && half_extents[axis] <= kMaxSoftLength)) {
      throw std::invalid_argument("half_extents: each must be in " + text(kMinSoftLength) + ".." +
                                  text(kMaxSoftLength) + " m, got (" + text(half_extents.x()) +
                                  ", " + text(half_extents.y()) + ", " + text(half_extents.z()) +
                                  ")");
    }
  }
  requireElementSize(element_size, 2.0 * half_extents.maxCoeff());
  std::array<int, 3> cells{};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    cells[axis] = cellsOver(2.0 * half_extents[static_cast<int>(axis)], element_size, 1, false);
  }
  requireTetCount(cells, element_size);
  const auto node = [&](int i, int j, int k) -> Vec3 {
    return Vec3(half_extents.x() * gridCoordinate(i, cells[0]),
                half_extents.y() * gridCoordinate(j, cells[1]),
                half_extents.z() * gridCoordinate(k, cells[2]));
  };
  return kuhnGrid(cells, node, true);
}

TetMesh generateSoftSphere(double radius, double element_size) {
  requireLength(radius, "radius");
  requireElementSize(element_size, 2.0 * radius);
  const int n = cellsOver(2.0 * radius, element_size, 2, true);
  requireTetCount({n, n, n}, element_size);
  const auto node = [&](int i, int j, int k) -> Vec3 {
    return radius *
           ballPoint(Vec3(gridCoordinate(i, n), gridCoordinate(j, n), gridCoordinate(k, n)));
  };
  TetMesh mesh = kuhnGrid({n, n, n}, node, true);
  mesh.cells_across = n;
  return mesh;
}

TetMesh generateSoftCylinder(double radius, double half_height, double element_size) {
  requireLength(radius, "radius");
  requireLength(half_height, "half_height");
  requireElementSize(element_size, 2.0 * std::max(radius, half_height));
  const int n = cellsOver(2.0 * radius, element_size, 2, true);
  const int layers = cellsOver(2.0 * half_height, element_size, 1, false);
  requireTetCount({n, layers, n}, element_size);
  const auto node = [&](int i, int j, int k) -> Vec3 {
    Vec3 p = radius * ballPoint(Vec3(gridCoordinate(i, n), 0.0, gridCoordinate(k, n)));
    p.y() = half_height * gridCoordinate(j, layers);
    return p;
  };
  TetMesh mesh = kuhnGrid({n, layers, n}, node, true);
  mesh.cells_across = n;
  mesh.layers = layers;
  return mesh;
}

}  // namespace gf::sim
