#include "sim/god_finger.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>

#include "sim/primitives.hpp"

namespace gf::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

PatchSettings settingsWith(int n, double alpha) {
  PatchSettings s;
  s.n_sgo = n;
  s.r_max = 0.010;
  s.d0 = 0.004;
  s.alpha = alpha;
  s.stretch_length = 0.004;
  return s;
}

TEST(Equation1, MatchesHandComputedRadii) {
  // r = r_max (1 - exp(-depth / D'_0)), r_max = 10 mm, D'_0 = 4 mm.
  EXPECT_NEAR(contactRadius(0.004, 0.010, 0.004), 0.006321205588285577, 1e-15);
  EXPECT_NEAR(contactRadius(0.002, 0.010, 0.004), 0.003934693402873666, 1e-15);
  EXPECT_NEAR(contactRadius(1.0, 0.010, 0.004), 0.010, 1e-15);
  EXPECT_EQ(contactRadius(0.0, 0.010, 0.004), 0.0);
  EXPECT_EQ(contactRadius(-0.003, 0.010, 0.004), 0.0);
}

TEST(Equation2, MatchesHandComputedDistances) {
  const PatchSettings s = settingsWith(8, 2.0);
  const Vec3 r = Vec3::UnitX();
  // d = r * 2^(-(v.r)/4mm): v.r = 4 mm halves, -4 mm doubles, 2 mm divides by sqrt(2).
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(0.004, 0, 0), r, s), 0.0025, 1e-15);
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(-0.004, 0, 0), r, s), 0.010, 1e-15);
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(0.002, 0, 0), r, s), 0.005 / std::sqrt(2.0), 1e-15);
  // Orthogonal push leaves the distance unchanged; the exponent is clamped at +-3.
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(0, 0.004, 0.0), r, s), 0.005, 1e-15);
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(0.02, 0, 0), r, s), 0.005 / 8.0, 1e-15);
  PatchSettings off = s;
  off.tangential_stretch = false;
  EXPECT_EQ(stretchedDistance(0.005, Vec3(0.004, 0, 0), r, off), 0.005);
}

TEST(Patch, PressingGivesRadiusAndPullingGivesNone) {
  const Mesh plane = tessellatePlane(1.0, 1);
  const PatchContact c{Vec3(0.1, 0, 0.05), Vec3::UnitY(), -0.001};
  Patch p;
  computePatch(plane, c, Vec3(0, -0.004, 0), settingsWith(8, 2.0), p);  // device below surface
  ASSERT_TRUE(p.valid);
  EXPECT_NEAR(p.press_depth, 0.004, 1e-15);
  EXPECT_NEAR(p.radius, 0.006321205588285577, 1e-15);
  EXPECT_EQ(p.sgos.size(), 8u);
  computePatch(plane, c, Vec3(0, 0.004, 0), settingsWith(8, 2.0), p);  // device above: pulling
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.radius, 0.0);
  EXPECT_TRUE(p.sgos.empty());
}

// Paper Fig. 4b: alpha = 2 and a tangential push give an area longer opposite the push.
TEST(Patch, PlanarFaceDistancesFollowEquation2Exactly) {
  const Mesh plane = tessellatePlane(1.0, 1);
  const PatchContact c{Vec3(0.1, 0, 0.05), Vec3::UnitY(), -0.001};
  const Vec3 v(0.003, -0.004, 0.001);  // pressing 4 mm, pushing towards +x (and a little +z)
  Patch p;
  computePatch(plane, c, v, settingsWith(16, 2.0), p);
  ASSERT_EQ(p.sgos.size(), 16u);
  double longest = 0.0;
  Vec3 longest_dir = Vec3::Zero();
  for (const Sgo& sgo : p.sgos) {
    const Vec3& r = p.radial[sgo.radial];
    const double expected = p.radius * std::pow(2.0, -v.dot(r) / 0.004);
    EXPECT_NEAR(p.d_i[sgo.radial], expected, 1e-15);
    EXPECT_NEAR((sgo.position - c.point_local).norm(), expected, 1e-14);
    EXPECT_NEAR(sgo.position.y(), 0.0, 1e-15);
    EXPECT_EQ(sgo.stop, WalkStop::kDistance);
    if (expected > longest) longest = expected, longest_dir = r;
  }
  const Vec3 push_tangent = Vec3(v.x(), 0, v.z()).normalized();
  EXPECT_LT(longest_dir.dot(push_tangent), -0.95) << "longest radius points against the push";
}

// The top face of a 10 cm box, touched 3 mm from its +x edge (the side face is at 90 degrees),
// away from the grid lines at x = 0 and z = 0.
class BoxEdge : public ::testing::Test {
 protected:
  Mesh box_ = tessellateBox(Vec3(0.05, 0.05, 0.05), 2);
  PatchSettings s_ = settingsWith(16, 1.0);
  Patch p_;
  int onSideFace() const {
    int n = 0;
    for (const Sgo& sgo : p_.sgos) n += box_.faceNormal(sgo.face).x() > 0.99;
    return n;
  }
};

TEST_F(BoxEdge, FaceHitSpreadsOverTheEdgeWhenTauAboveTheDihedral) {
  s_.tau_a = 100 * kDeg;
  s_.friction_cone = false;
  computePatch(box_, {Vec3(0.047, 0.05, 0.013), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s_, p_);
  EXPECT_EQ(p_.hit.feature, Feature::kFace);
  EXPECT_GT(onSideFace(), 0);
  for (const Sgo& sgo : p_.sgos) {
    EXPECT_EQ(sgo.stop, WalkStop::kDistance);
    EXPECT_NEAR(sgo.walked, p_.d_i[sgo.radial], 1e-12);
    if (box_.faceNormal(sgo.face).x() > 0.99) {
      // Down the side: the part walked beyond the edge appears as the drop below the top.
      EXPECT_NEAR(sgo.position.x(), 0.05, 1e-12);
      EXPECT_LT(sgo.position.y(), 0.05);
    }
  }
}

TEST_F(BoxEdge, FaceHitStopsAtASharpEdge) {  // paper Fig. 2c
  s_.tau_a = 80 * kDeg;
  s_.friction_cone = false;
  computePatch(box_, {Vec3(0.047, 0.05, 0.013), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s_, p_);
  EXPECT_EQ(onSideFace(), 0);
  int stopped = 0;
  for (const Sgo& sgo : p_.sgos) {
    EXPECT_LE(sgo.position.x(), 0.05 + 1e-15);
    if (sgo.stop == WalkStop::kAngularThreshold) {
      ++stopped;
      EXPECT_NEAR(sgo.position.x(), 0.05, 1e-12) << "stopped on the edge";
      EXPECT_LT(sgo.walked, p_.d_i[sgo.radial]);
    }
  }
  EXPECT_GT(stopped, 0);
}

TEST_F(BoxEdge, FaceHitStopsAtTheFrictionCone) {
  s_.tau_a = 100 * kDeg;
  s_.friction = 1.0;  // cone half-angle 45 degrees < 90
  computePatch(box_, {Vec3(0.047, 0.05, 0.013), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s_, p_);
  EXPECT_EQ(onSideFace(), 0);
  int stopped = 0;
  for (const Sgo& sgo : p_.sgos) stopped += sgo.stop == WalkStop::kFrictionCone;
  EXPECT_GT(stopped, 0);
  s_.friction = 1e6;  // cone half-angle close to 90 degrees, still below the dihedral
  computePatch(box_, {Vec3(0.047, 0.05, 0.013), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s_, p_);
  EXPECT_EQ(onSideFace(), 0);
}

// Paper Fig. 3b: an edge hit with the contact normal tilted 20 degrees towards the side face.
TEST_F(BoxEdge, EdgeHitProjectsOnBothFacesWithinTau) {
  const Vec3 n(std::sin(20 * kDeg), std::cos(20 * kDeg), 0);
  s_.tau_a = 80 * kDeg;  // side face is 70 degrees from n: kept
  s_.friction_cone = false;
  computePatch(box_, {Vec3(0.05, 0.05, 0.01), n, -0.001}, -0.004 * n, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kEdge);
  EXPECT_EQ(p_.sgos.size(), 16u) << "no vector dropped";
  EXPECT_GT(onSideFace(), 0);
  EXPECT_LT(onSideFace(), 16);
  for (const Sgo& sgo : p_.sgos) EXPECT_NEAR(sgo.walked, p_.d_i[sgo.radial], 1e-12);
}

TEST_F(BoxEdge, EdgeHitDropsVectorsOfFacesBeyondTau) {
  const Vec3 n(std::sin(20 * kDeg), std::cos(20 * kDeg), 0);
  s_.tau_a = 45 * kDeg;  // top face is 20 degrees away (kept), side face 70 (dropped)
  s_.friction_cone = false;
  computePatch(box_, {Vec3(0.05, 0.05, 0.01), n, -0.001}, -0.004 * n, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kEdge);
  EXPECT_EQ(onSideFace(), 0);
  int dropped = 0;
  for (WalkStop w : p_.radial_stop) dropped += w == WalkStop::kDropped;
  EXPECT_GT(dropped, 0);
  EXPECT_EQ(p_.sgos.size() + dropped, 16u);
  for (const Sgo& sgo : p_.sgos) EXPECT_NEAR(box_.faceNormal(sgo.face).y(), 1.0, 1e-12);
}

TEST_F(BoxEdge, VertexHitSpreadsOverTheThreeFacesAround) {
  const Vec3 n = Vec3(1, 1, 1).normalized();  // every face 54.7 degrees away
  s_.tau_a = 60 * kDeg;
  s_.friction_cone = false;
  computePatch(box_, {Vec3(0.05, 0.05, 0.05), n, -0.001}, -0.004 * n, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kVertex);
  bool seen[3] = {false, false, false};
  for (const Sgo& sgo : p_.sgos) {
    const Vec3& fn = box_.faceNormal(sgo.face);
    for (int a = 0; a < 3; ++a) seen[a] |= fn[a] > 0.99;
  }
  EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
  s_.tau_a = 50 * kDeg;  // below 54.7: all three faces drop their vectors
  computePatch(box_, {Vec3(0.05, 0.05, 0.05), n, -0.001}, -0.004 * n, s_, p_);
  EXPECT_TRUE(p_.sgos.empty());
}

TEST(Patch, WalkOnFineSphereFollowsGeodesics) {
  const double radius = 0.05;
  const Mesh sphere = tessellateSphere(radius, 6);  // 81920 faces, edges about 1 mm
  PatchSettings s = settingsWith(16, 2.0);
  s.angular_threshold = false;
  s.friction_cone = false;
  const Vec3 n = Vec3(0.3, 0.8, -0.5).normalized();
  const Vec3 v = -0.006 * n + Vec3(0.002, 0, 0.001);
  Patch p;
  computePatch(sphere, {radius * n, n, -0.001}, v, s, p);
  ASSERT_EQ(p.sgos.size(), 16u);
  for (const Sgo& sgo : p.sgos) {
    EXPECT_NEAR(sgo.walked, p.d_i[sgo.radial], 1e-12);
    const double arc = radius * std::acos(std::clamp(sgo.position.normalized().dot(
                                                         p.hit.point.normalized()), -1.0, 1.0));
    EXPECT_NEAR(arc, p.d_i[sgo.radial], 0.02 * p.d_i[sgo.radial]);
    EXPECT_LT(sphere.closestPoint(sgo.position, 0.0).query_distance, 1e-12) << "stays on the surface";
  }
}

}  // namespace
}  // namespace gf::sim
