#include "sim/mesh/primitives.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace gf::sim {
namespace {

void expectClosedAndOutward(const Mesh& m) {
  EXPECT_EQ(m.report().boundary_edges, 0);
  EXPECT_EQ(m.report().non_manifold_edges, 0);
  EXPECT_EQ(m.report().inconsistent_edges, 0);
  EXPECT_GT(m.signedVolume(), 0.0);
}

TEST(Primitives, SphereVolumeConvergesWithResolution) {
  const double r = 0.05, exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const Mesh coarse = tessellateSphere(r, 1), fine = tessellateSphere(r, 4);
  expectClosedAndOutward(fine);
  EXPECT_EQ(fine.faceCount(), 20 * 256);
  EXPECT_LT(std::abs(fine.signedVolume() - exact), std::abs(coarse.signedVolume() - exact));
  EXPECT_NEAR(fine.signedVolume(), exact, 0.005 * exact);
  for (const Vec3& p : fine.vertices()) EXPECT_NEAR(p.norm(), r, 1e-15);
}

TEST(Primitives, BoxIsClosedWithExactVolume) {
  const Mesh box = tessellateBox(Vec3(0.1, 0.2, 0.3), 3);
  expectClosedAndOutward(box);
  EXPECT_EQ(box.faceCount(), 6 * 9 * 2);
  EXPECT_NEAR(box.signedVolume(), 0.2 * 0.4 * 0.6, 1e-12);
}

TEST(Primitives, CylinderAndCapsuleAreClosed) {
  const Mesh cyl = tessellateCylinder(0.03, 0.06, 32);
  expectClosedAndOutward(cyl);
  EXPECT_NEAR(cyl.signedVolume(), std::numbers::pi * 0.03 * 0.03 * 0.12, 0.02 * 0.0003393);
  const Mesh cap = tessellateCapsule(0.02, 0.05, 32);
  expectClosedAndOutward(cap);
  const double exact = std::numbers::pi * 0.0004 * 0.1 + 4.0 / 3.0 * std::numbers::pi * 8e-6;
  EXPECT_NEAR(cap.signedVolume(), exact, 0.02 * exact);
}

TEST(Primitives, PlaneIsAnOpenSquareFacingUp) {
  const Mesh plane = tessellatePlane(2.0, 4);
  EXPECT_EQ(plane.faceCount(), 32);
  EXPECT_EQ(plane.report().boundary_edges, 16);
  for (int f = 0; f < plane.faceCount(); ++f) EXPECT_NEAR(plane.faceNormal(f).y(), 1.0, 1e-15);
}

TEST(Primitives, RejectsBadParameters) {
  EXPECT_THROW(tessellateSphere(-1.0, 2), std::invalid_argument);
  EXPECT_THROW(tessellateSphere(1.0, 9), std::invalid_argument);
  EXPECT_THROW(tessellateBox(Vec3(1, 0, 1), 1), std::invalid_argument);
  EXPECT_THROW(tessellateCylinder(1.0, NAN, 8), std::invalid_argument);
  EXPECT_THROW(tessellateCapsule(1.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(tessellatePlane(1.0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace gf::sim
