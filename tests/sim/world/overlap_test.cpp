// The overlap of two patches (sim/world/overlap.hpp): the lens area against its closed form and a
// quadrature, the discs projected on their common tangent plane, push_apart's force and the
// merged patch.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/world/overlap.hpp"

namespace gf::sim {
namespace {

using std::numbers::pi;

// Two equal discs of radius r at distance d: 2 r^2 acos(d / 2r) - (d / 2) sqrt(4 r^2 - d^2).
double equalLens(double r, double d) { return 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d); }

// The common area of two discs on the x axis by the midpoint rule over x (2e5 strips): the
// length of the intersection of the two chords at each x.
double lensByQuadrature(double r1, double r2, double d) {
  const int n = 200000;
  const double lo = std::max(-r1, d - r2), hi = std::min(r1, d + r2);
  if (hi <= lo) return 0.0;
  const double h = (hi - lo) / n;
  double area = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = lo + (i + 0.5) * h;
    const double y1 = std::sqrt(std::max(0.0, r1 * r1 - x * x));
    const double y2 = std::sqrt(std::max(0.0, r2 * r2 - (x - d) * (x - d)));
    area += 2 * std::min(y1, y2) * h;
  }
  return area;
}

TEST(DiscOverlapArea, EqualDiscsMatchTheClosedFormOfTheLens) {
  const double r = 0.007;
  for (double f : {0.0, 0.1, 0.5, 0.808, 1.0, 1.5, 1.99}) {
    const double d = f * r;
    EXPECT_NEAR(discOverlapArea(r, r, d), equalLens(r, d), 1e-12 * r * r) << "d / r = " << f;
  }
  EXPECT_NEAR(discOverlapArea(r, r, 0.0), pi * r * r, 1e-15);
}

TEST(DiscOverlapArea, UnequalDiscsMatchAQuadrature) {
  for (double d : {0.0021, 0.004, 0.006, 0.0079}) {
    EXPECT_NEAR(discOverlapArea(0.005, 0.003, d), lensByQuadrature(0.005, 0.003, d), 1e-6 * 0.005 * 0.003) << d;
  }
}

TEST(DiscOverlapArea, IsZeroApartAndTheSmallDiscInside) {
  EXPECT_EQ(discOverlapArea(0.005, 0.003, 0.008), 0.0);
  EXPECT_EQ(discOverlapArea(0.005, 0.003, 0.01), 0.0);
  EXPECT_DOUBLE_EQ(discOverlapArea(0.005, 0.003, 0.002), pi * 0.003 * 0.003);
  EXPECT_EQ(discOverlapArea(0.0, 0.003, 0.0), 0.0);
  // Continuous at both ends of the lens.
  EXPECT_NEAR(discOverlapArea(0.005, 0.003, 0.008 - 1e-12), 0.0, 1e-14);
  EXPECT_NEAR(discOverlapArea(0.005, 0.003, 0.002 + 1e-12), pi * 0.003 * 0.003, 1e-14);
}

TEST(DiscOverlap, MeasuresTheDiscsInTheirCommonTangentPlane) {
  // Two contacts on a face normal to y, one 1 mm higher (the normal offset does not count).
  const PatchDisc a{Vec3(0.004, 0.001, 0.0), Vec3::UnitY(), 0.005};
  const PatchDisc b{Vec3(-0.002, 0.0, 0.0), Vec3::UnitY(), 0.004};
  const DiscOverlap o = discOverlap(a, b);
  EXPECT_NEAR(o.distance, 0.006, 1e-15);
  EXPECT_NEAR(o.depth, 0.003, 1e-15);
  EXPECT_NEAR(o.area, discOverlapArea(0.005, 0.004, 0.006), 1e-18);
  EXPECT_NEAR((o.apart - Vec3::UnitX()).norm(), 0.0, 1e-15);
  EXPECT_EQ(discOverlap(a, {b.centre, b.outward_normal, 0.0}).area, 0.0);  // no patch, no overlap
}

TEST(DiscOverlap, PatchesOnOppositeFacesNeverOverlap) {
  // A pinch: the two contacts face each other through a 1 cm thick tile, one over the other.
  const PatchDisc top{Vec3(0, 0.005, 0), Vec3::UnitY(), 0.006};
  const PatchDisc bottom{Vec3(0.001, -0.005, 0), -Vec3::UnitY(), 0.006};
  EXPECT_EQ(discOverlap(top, bottom).area, 0.0);
  EXPECT_EQ(discOverlap(top, {bottom.centre, Vec3::UnitX(), 0.006}).area, 0.0);  // faces of an edge
}

TEST(PushApartForce, GrowsFromZeroWithTheOverlapDepthAndIsClamped) {
  DiscOverlap o;
  o.apart = Vec3::UnitX();
  o.depth = 0.0;
  EXPECT_EQ(pushApartForce(o, 2000.0, 40.0).norm(), 0.0);  // discs that only touch
  o.depth = 1e-3;
  EXPECT_NEAR((pushApartForce(o, 2000.0, 40.0) - Vec3(2.0, 0, 0)).norm(), 0.0, 1e-12);
  o.depth = 1.0;
  EXPECT_NEAR(pushApartForce(o, 2000.0, 40.0).norm(), 40.0, 1e-12);
}

TEST(MergePatches, CountsCoincidingPointsOnceAndKeepsEveryLoad) {
  ContactSnapshot a, b;
  a.radius = b.radius = 0.005;
  a.point_world = Vec3(0, 0, 0);
  a.point_load.normal = 1.0;
  a.sgos_world = {Vec3(0.005, 0, 0), Vec3(-0.005, 0, 0)};
  a.loads.resize(2);
  a.loads[0].normal = 0.5;
  a.loads[1].normal = 0.25;
  b.point_world = Vec3(0.0052, 0, 0);  // 0.2 mm from a's first SGO: within 0.1 r = 0.5 mm
  b.point_load.normal = 2.0;
  b.sgos_world = {Vec3(0.010, 0, 0)};
  b.loads.resize(1);
  b.loads[0].normal = 0.125;
  std::vector<MergedPoint> merged;
  mergePatches(a, b, 3.0, 1.0, merged);
  ASSERT_EQ(merged.size(), 4u);
  EXPECT_DOUBLE_EQ(merged[1].normal, 2.5);
  EXPECT_DOUBLE_EQ(merged[1].share_a, 0.75);  // split by the presses, 3 : 1
  double total = 0.0;
  for (const MergedPoint& p : merged) total += p.normal;
  EXPECT_DOUBLE_EQ(total, 1.0 + 0.5 + 0.25 + 2.0 + 0.125);
  EXPECT_GE(minPointDistance(merged), 0.1 * 0.005);
}

}  // namespace
}  // namespace gf::sim
