#include "sim/mesh/tet_pad.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace gf::sim {
namespace {

// The cap's volume: the shell between the bone and the skin over the square of directions
// (tan α, -1, tan β), |α|, |β| ≤ cap_angle, whose solid angle is 4 asin(sin² cap_angle).
double capVolume(const PadShape& s) {
  const double outer = s.bone_radius + s.thickness;
  const double solid_angle = 4.0 * std::asin(std::pow(std::sin(s.cap_angle), 2));
  return solid_angle * (std::pow(outer, 3) - std::pow(s.bone_radius, 3)) / 3.0;
}

// The three resolutions of the pad the studies use, and the shape's extremes.
std::vector<PadShape> shapes() {
  std::vector<PadShape> out;
  for (double size : {0.003, 0.0015, 0.00075}) out.push_back({0.006, 0.003, 0.7, size});
  out.push_back({0.006, 0.0005, 0.1, 0.0005});   // thin and narrow
  out.push_back({0.003, 0.003, 0.8, 0.003});     // as thick as the bone, wide, one layer
  out.push_back({0.003, 0.003, 0.8, 0.0003});    // the same, ten layers
  out.push_back({0.02, 0.001, 0.8, 0.001});      // a large bone, thin
  return out;
}

TEST(TetPad, EveryTetrahedronIsPositiveAndNoneIsASliver) {
  for (const PadShape& s : shapes()) {
    const TetMesh mesh = generatePad(s);
    ASSERT_FALSE(mesh.tets.empty());
    EXPECT_EQ(mesh.tets.size(), 6u * mesh.cells_across * mesh.cells_across * mesh.layers);
    const TetQuality q = tetQuality(mesh);
    EXPECT_GT(q.min_volume, 0.0) << "element size " << s.element_size;
    // Kuhn's split of a cube has dihedral angles of 45, 60 and 90 degrees; the cap's cells are
    // curved, and wedge-shaped where one layer spans a pad as thick as the bone (18 degrees at
    // worst): these bounds allow that and refuse a sliver.
    EXPECT_GT(q.min_dihedral_deg, 15.0) << "element size " << s.element_size;
    EXPECT_LT(q.max_dihedral_deg, 150.0) << "element size " << s.element_size;
    EXPECT_GT(q.min_radius_ratio, 0.25) << "element size " << s.element_size;
  }
}

TEST(TetPad, VolumeConvergesToTheCapsWithResolution) {
  double last_error = 1.0;
  for (double size : {0.003, 0.0015, 0.00075}) {
    const PadShape s{0.006, 0.003, 0.7, size};
    const double exact = capVolume(s), error = std::abs(tetQuality(generatePad(s)).volume - exact) / exact;
    EXPECT_LT(error, last_error) << "element size " << size;
    last_error = error;
  }
  EXPECT_LT(last_error, 0.005) << "flat faces on a curved cap: the error falls as the size squared";
}

TEST(TetPad, TheBoneNodesAreOnTheBoneAndTheSkinIsOutside) {
  const PadShape s;
  const TetMesh mesh = generatePad(s);
  EXPECT_EQ(mesh.bone_nodes.size(), static_cast<std::size_t>((mesh.cells_across + 1) * (mesh.cells_across + 1)));
  for (int i : mesh.bone_nodes) EXPECT_NEAR(mesh.nodes[static_cast<std::size_t>(i)].norm(), s.bone_radius, 1e-15);
  for (const Vec3& p : mesh.nodes) {
    EXPECT_GE(p.norm(), s.bone_radius - 1e-15);
    EXPECT_LE(p.norm(), s.bone_radius + s.thickness + 1e-15);
    EXPECT_LT(p.y(), 0.0) << "the cap is on the pressing side (-y)";
  }
}

// The boundary is closed and wound outward: every edge is met once each way, and the volume it
// encloses (divergence theorem) is the tetrahedra's.
TEST(TetPad, TheSurfaceIsClosedAndOutward) {
  for (const PadShape& s : shapes()) {
    const TetMesh mesh = generatePad(s);
    std::map<std::pair<int, int>, int> directed;
    double enclosed = 0.0;
    for (const auto& [a, b, c] : mesh.surface) {
      ++directed[{a, b}];
      ++directed[{b, c}];
      ++directed[{c, a}];
      const auto& p = mesh.nodes;
      enclosed += p[static_cast<std::size_t>(a)].dot(p[static_cast<std::size_t>(b)].cross(p[static_cast<std::size_t>(c)])) / 6.0;
    }
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " twice the same way";
      EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "an open edge";
    }
    EXPECT_NEAR(enclosed, tetQuality(mesh).volume, 1e-12 * enclosed);
  }
}

TEST(TetPad, ShapesOutsideTheLimitsAreRefusedNamingTheField) {
  const auto message = [](PadShape s) {
    try {
      generatePad(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({0.0, 0.003, 0.7, 0.0015}).find("pad.bone_radius"), std::string::npos);
  EXPECT_NE(message({0.006, std::nan(""), 0.7, 0.0015}).find("pad.thickness"), std::string::npos);
  EXPECT_NE(message({0.006, 0.007, 0.7, 0.0015}).find("pad.thickness"), std::string::npos) << "thicker than the bone";
  EXPECT_NE(message({0.006, 0.003, 0.9, 0.0015}).find("pad.cap_angle"), std::string::npos);
  EXPECT_NE(message({0.006, 0.003, 0.7, 1e-4}).find("pad.element_size"), std::string::npos);
  EXPECT_NE(message({0.006, 0.003, 0.7, 0.004}).find("pad.element_size"), std::string::npos);
  EXPECT_NE(message({0.1, 0.02, 0.8, 0.02 / 16}).find("pad.element_size"), std::string::npos) << "too many cells";
}

}  // namespace
}  // namespace gf::sim
