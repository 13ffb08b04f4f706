#include "sim/mesh/tet_shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "tests/sim/mesh/tet_checks.hpp"

namespace gf::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// The refusal's message, or "accepted".
template <class Generate>
std::string refusal(Generate generate) {
  try {
    generate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

// The quality of `mesh` and its volume's error against `exact`, printed for the record.
TetQuality report(const char* shape, double element_size, const TetMesh& mesh, double exact) {
  const TetQuality q = tetQuality(mesh);
  std::printf(
      "%s, element size %g m: %zu tetrahedra, min dihedral %.2f deg, max %.2f deg, radius ratio "
      "%.3f, "
      "volume error %.3g %%\n",
      shape, element_size, mesh.tets.size(), q.min_dihedral_deg, q.max_dihedral_deg,
      q.min_radius_ratio, 100.0 * (q.volume - exact) / exact);
  return q;
}

TEST(SoftBox, FillsTheBoxExactlyWithKuhnTetrahedra) {
  struct Case {
    Vec3 half;
    double size;
  };
  for (const Case& c : {Case{Vec3(0.05, 0.02, 0.01), 0.01}, Case{Vec3(0.05, 0.02, 0.01), 0.1},
                        Case{Vec3(0.03, 0.03, 0.03), 0.007}, Case{Vec3(1.0, 0.001, 0.5), 0.05}}) {
    SCOPED_TRACE(c.size);
    const TetMesh mesh = generateSoftBox(c.half, c.size);
    long cells = 1;
    for (int axis = 0; axis < 3; ++axis) {
      cells *= std::max(1L, std::lround(std::ceil(2.0 * c.half[axis] / c.size - 1e-9)));
    }
    EXPECT_EQ(static_cast<long>(mesh.tets.size()), 6 * cells);
    const double exact = 8.0 * c.half.prod();
    const TetQuality q = report("box", c.size, mesh, exact);
    EXPECT_NEAR(q.volume, exact, 1e-12 * exact);
    EXPECT_GT(q.min_volume, 0.0);
    for (const Vec3& p : mesh.nodes) {
      EXPECT_TRUE((p.cwiseAbs() - c.half).maxCoeff() <= 1e-15) << p.transpose();
    }
    EXPECT_TRUE(mesh.bone_nodes.empty());
    expectClosedAndOutward(mesh);
  }
}

TEST(SoftBox, CubicCellsGiveKuhnsAngles) {
  const TetQuality q = tetQuality(generateSoftBox(Vec3(0.02, 0.01, 0.03), 0.005));
  // Each of Kuhn's six tetrahedra of a cube has dihedral angles of 45, 60 and 90 degrees only.
  EXPECT_NEAR(q.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(q.max_dihedral_deg, 90.0, 1e-9);
}

TEST(SoftSphere, VolumeConvergesAndNoTetrahedronIsASliver) {
  const double radius = 0.05, exact = 4.0 / 3.0 * kPi * std::pow(radius, 3);
  double last_error = 1.0;
  for (double size : {0.05, 0.025, 0.0125, 0.00625}) {
    const TetMesh mesh = generateSoftSphere(radius, size);
    const TetQuality q = report("sphere", size, mesh, exact);
    EXPECT_GT(q.min_volume, 0.0);
    // The blend keeps the grid's corner cells near a cube's shape: 33 degrees and more measured.
    EXPECT_GT(q.min_dihedral_deg, 25.0);
    EXPECT_LT(q.max_dihedral_deg, 125.0);
    // Flat faces inside the sphere: the error falls as the element size squared, a quarter for
    // each halving (22 %, 6.1 %, 1.6 %, 0.39 % measured).
    const double error = (exact - q.volume) / exact;
    EXPECT_GT(error, 0.0) << "the mesh lies inside the sphere";
    EXPECT_LT(error, last_error / 3.5);
    last_error = error;
    expectClosedAndOutward(mesh);
  }
  EXPECT_LT(last_error, 0.005);
}

TEST(SoftSphere, SurfaceNodesLieOnTheSphere) {
  const double radius = 0.02;
  const TetMesh mesh = generateSoftSphere(radius, 0.004);
  EXPECT_EQ(mesh.cells_across, 10);
  EXPECT_EQ(mesh.tets.size(), 6u * 10 * 10 * 10);
  for (const auto& face : mesh.surface) {
    for (int i : face) EXPECT_NEAR(mesh.nodes[static_cast<std::size_t>(i)].norm(), radius, 1e-15);
  }
  for (const Vec3& p : mesh.nodes) EXPECT_LE(p.norm(), radius * (1.0 + 1e-15));
}

TEST(SoftCylinder, VolumeConvergesAndNoTetrahedronIsASliver) {
  const double radius = 0.02, half_height = 0.03, exact = kPi * radius * radius * 2.0 * half_height;
  double last_error = 1.0;
  for (double size : {0.01, 0.005, 0.0025}) {
    const TetMesh mesh = generateSoftCylinder(radius, half_height, size);
    EXPECT_EQ(mesh.layers, static_cast<int>(std::lround(2.0 * half_height / size)));
    EXPECT_EQ(mesh.tets.size(),
              6u * static_cast<std::size_t>(mesh.cells_across * mesh.cells_across * mesh.layers));
    const TetQuality q = report("cylinder", size, mesh, exact);
    EXPECT_GT(q.min_volume, 0.0);
    EXPECT_GT(q.min_dihedral_deg, 25.0);
    EXPECT_LT(q.max_dihedral_deg, 125.0);
    // A polygon inside the disc: 2.6 %, 0.64 %, 0.16 % measured.
    const double error = (exact - q.volume) / exact;
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, last_error / 3.5);
    last_error = error;
    expectClosedAndOutward(mesh);
  }
  EXPECT_LT(last_error, 0.002);
}

TEST(SoftCylinder, TheSideIsOnTheCylinderAndTheEndsAreFlat) {
  const double radius = 0.01, half_height = 0.004;
  const TetMesh mesh = generateSoftCylinder(radius, half_height, 0.002);
  for (const Vec3& p : mesh.nodes) {
    const double r = std::hypot(p.x(), p.z());
    EXPECT_LE(r, radius * (1.0 + 1e-15));
    EXPECT_LE(std::abs(p.y()), half_height);
    EXPECT_TRUE(std::abs(std::abs(p.y()) - half_height) < 1e-18 || std::abs(r - radius) < 1e-15 ||
                r < radius * (1.0 - 1e-3))
        << "an inner node near the side " << p.transpose();
  }
}

TEST(SoftShapes, TheSameArgumentsGiveTheSameMesh) {
  const TetMesh a = generateSoftSphere(0.03, 0.01), b = generateSoftSphere(0.03, 0.01);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.surface, b.surface);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) EXPECT_EQ(a.nodes[i], b.nodes[i]);
}

TEST(BoundaryTriangles, WindsOutwardWhateverTheTetrahedronsOrder) {
  const std::vector<Vec3> nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  for (const std::array<int, 4>& tet :
       {std::array<int, 4>{0, 1, 2, 3}, std::array<int, 4>{0, 2, 1, 3}}) {
    TetMesh mesh;
    mesh.nodes = nodes;
    mesh.tets = {tet};
    mesh.surface = boundaryTriangles(mesh.tets, mesh.nodes);
    EXPECT_EQ(mesh.surface.size(), 4u);
    double enclosed = 0.0;
    for (const auto& [a, b, c] : mesh.surface) {
      enclosed += nodes[a].dot(nodes[b].cross(nodes[c])) / 6.0;
    }
    EXPECT_NEAR(enclosed, 1.0 / 6.0, 1e-15) << "outward whichever way the tetrahedron turns";
  }
}

TEST(SoftShapes, ValuesOutsideTheLimitsAreRefusedNamingTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  const auto box = [](Vec3 h, double e) { return refusal([&] { generateSoftBox(h, e); }); };
  const auto sphere = [](double r, double e) { return refusal([&] { generateSoftSphere(r, e); }); };
  const auto cylinder = [](double r, double h, double e) {
    return refusal([&] { generateSoftCylinder(r, h, e); });
  };
  EXPECT_EQ(box(Vec3(0.01, 0.01, 0.01), 0.02), "accepted")
      << "one cell: the size up to the box's largest dimension";
  EXPECT_EQ(box(Vec3(0.0, 0.01, 0.01), 0.005).rfind("half_extents: ", 0), 0u);
  EXPECT_EQ(box(Vec3(0.01, nan, 0.01), 0.005).rfind("half_extents: ", 0), 0u);
  EXPECT_EQ(box(Vec3(0.01, 0.01, 1.5), 0.005).rfind("half_extents: ", 0), 0u);
  EXPECT_EQ(box(Vec3(0.01, 0.01, 0.01), 0.021).rfind("element_size: ", 0), 0u) << "beyond the box";
  EXPECT_EQ(box(Vec3(0.01, 0.01, 0.01), 5e-5).rfind("element_size: ", 0), 0u);
  EXPECT_EQ(box(Vec3(0.01, 0.01, 0.01), nan).rfind("element_size: ", 0), 0u);
  EXPECT_EQ(box(Vec3(1.0, 1.0, 1.0), 1e-4).rfind("element_size: ", 0), 0u) << "4.8e13 tetrahedra";
  EXPECT_NE(box(Vec3(1.0, 1.0, 1.0), 1e-4).find("at most 200000"), std::string::npos);
  EXPECT_EQ(sphere(5e-4, 1e-4).rfind("radius: ", 0), 0u);
  EXPECT_EQ(sphere(inf, 1e-2).rfind("radius: ", 0), 0u);
  EXPECT_EQ(sphere(0.05, 0.003).rfind("element_size: ", 0), 0u)
      << "34 cells across: 235 824 tetrahedra";
  EXPECT_EQ(sphere(0.05, 0.11).rfind("element_size: ", 0), 0u);
  EXPECT_EQ(cylinder(0.01, 2.0, 0.01).rfind("half_height: ", 0), 0u);
  EXPECT_EQ(cylinder(-0.01, 0.02, 0.01).rfind("radius: ", 0), 0u);
  EXPECT_EQ(cylinder(0.01, 0.02, 0.04), "accepted") << "the size up to the cylinder's height";
  EXPECT_EQ(cylinder(0.01, 0.02, -inf).rfind("element_size: ", 0), 0u);
}

}  // namespace
}  // namespace gf::sim
