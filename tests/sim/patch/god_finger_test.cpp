#include "sim/patch/god_finger.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <numbers>
#include <utility>
#include <vector>

#include "sim/mesh/primitives.hpp"
#include "tests/sim/angles.hpp"

namespace gf::sim {
namespace {

using gf::test::kDeg;

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
  // Orthogonal push leaves the distance unchanged; d_i stays within [r / 2, 2 r] (max_stretch 2).
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(0, 0.004, 0.0), r, s), 0.005, 1e-15);
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(0.02, 0, 0), r, s), 0.005 / 2.0, 1e-15);
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(-1e300, 0, 0), r, s), 0.010, 1e-15);
  PatchSettings tight = s;
  tight.max_stretch = 1.25;
  EXPECT_NEAR(stretchedDistance(0.005, Vec3(-0.004, 0, 0), r, tight), 0.00625, 1e-15);
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
  auto facesSeen = [&] {
    std::array<int, 3> seen{};
    for (const Sgo& sgo : p_.sgos) {
      for (int a = 0; a < 3; ++a) seen[a] += box_.faceNormal(sgo.face)[a] > 0.99;
    }
    return seen;
  };
  computePatch(box_, {Vec3(0.05, 0.05, 0.05), n, -0.001}, -0.004 * n, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kVertex);
  EXPECT_EQ(p_.sgos.size(), 16u);
  for (int seen : facesSeen()) EXPECT_GT(seen, 0);
  // Below 54.7 degrees the three faces are still the faces the contact lies on (equally well
  // aligned): they always count.
  s_.tau_a = 50 * kDeg;
  computePatch(box_, {Vec3(0.05, 0.05, 0.05), n, -0.001}, -0.004 * n, s_, p_);
  EXPECT_EQ(p_.sgos.size(), 16u);
  // Tilted towards the top, the top is the start face and the sides (beyond 50) drop.
  const Vec3 tilted = Vec3(0.3, 1.0, 0.3).normalized();  // top 23 degrees away, sides 73
  computePatch(box_, {Vec3(0.05, 0.05, 0.05), tilted, -0.001}, -0.004 * tilted, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kVertex);
  const std::array<int, 3> seen = facesSeen();
  EXPECT_EQ(seen[0], 0);
  EXPECT_GT(seen[1], 0);
  EXPECT_EQ(seen[2], 0);
}

// Two 10 cm squares meeting at x = 0.05 with a 40-degree turn: a face hit spreads over the
// turn while tau_a and the cone allow 40 degrees (exactly 40 is a tie and spreads too).
class Hinge : public ::testing::Test {
 protected:
  static Mesh make() {
    const double c = std::cos(40 * kDeg), s = std::sin(40 * kDeg);
    const std::vector<Vec3> v = {{-0.05, 0, -0.05}, {-0.05, 0, 0.05}, {0.05, 0, 0.05}, {0.05, 0, -0.05},
                                 {0.05 + 0.1 * c, -0.1 * s, 0.05}, {0.05 + 0.1 * c, -0.1 * s, -0.05}};
    return buildMesh(v, {{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {3, 4, 5}});
  }
  int onSlope() const {
    int n = 0;
    for (const Sgo& sgo : p_.sgos) n += mesh_.faceNormal(sgo.face).x() > 0.1;
    return n;
  }
  void compute() {
    computePatch(mesh_, {Vec3(0.047, 0, 0.013), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s_, p_);
  }
  Mesh mesh_ = make();
  PatchSettings s_ = settingsWith(16, 1.0);
  Patch p_;
};

TEST_F(Hinge, FaceHitSpreadsOverTheTurnWhenTauAboveIt) {
  s_.tau_a = 60 * kDeg;
  compute();
  EXPECT_EQ(p_.hit.feature, Feature::kFace);
  EXPECT_GT(onSlope(), 0);
  for (const Sgo& sgo : p_.sgos) {
    EXPECT_EQ(sgo.stop, WalkStop::kDistance);
    EXPECT_NEAR(sgo.walked, p_.d_i[sgo.radial], 1e-12);
    if (mesh_.faceNormal(sgo.face).x() > 0.1) {
      EXPECT_LT(sgo.position.y(), 0.0) << "down the slope";
    }
  }
}

TEST_F(Hinge, ExactTiesOfTauAndTheConeKeepTheFace) {
  s_.tau_a = 40 * kDeg;
  compute();
  EXPECT_GT(onSlope(), 0) << "tau_a equal to the turn";
  s_.tau_a = 60 * kDeg;
  s_.friction = std::tan(40 * kDeg);
  compute();
  EXPECT_GT(onSlope(), 0) << "cone equal to the turn";
  s_.friction = std::tan(39.9 * kDeg);
  compute();
  EXPECT_EQ(onSlope(), 0);
  int cone = 0;
  for (const Sgo& sgo : p_.sgos) cone += sgo.stop == WalkStop::kFrictionCone;
  EXPECT_GT(cone, 0);
}

TEST_F(Hinge, TauBelowTheTurnStopsAtIt) {
  s_.tau_a = 30 * kDeg;
  compute();
  EXPECT_EQ(onSlope(), 0);
  int stopped = 0;
  for (const Sgo& sgo : p_.sgos) stopped += sgo.stop == WalkStop::kAngularThreshold;
  EXPECT_GT(stopped, 0);
}

// The face the contact lies on always counts: tau_a 0 or friction 0 on a flat face give the full
// patch (coplanar neighbours are a tie at 0 degrees), not a god-object.
TEST(PatchTies, ZeroThresholdsKeepTheFlatPatch) {
  const Mesh plane = tessellatePlane(0.1, 8);
  for (const auto& [tau, friction] : {std::pair{0.0, 1.0}, std::pair{30 * kDeg, 0.0}, std::pair{0.0, 0.0}}) {
    PatchSettings s = settingsWith(8, 1.0);
    s.tau_a = tau;
    s.friction = friction;
    Patch p;
    computePatch(plane, {Vec3(0.0031, 0, 0.0047), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s, p);
    ASSERT_EQ(p.sgos.size(), 8u) << "tau " << tau << " friction " << friction;
    for (const Sgo& sgo : p.sgos) {
      EXPECT_EQ(sgo.stop, WalkStop::kDistance);
      EXPECT_NEAR(sgo.walked, p.radius, 1e-12);
    }
  }
}

// A 45-degree normal on a 90-degree edge with friction 1 (a 45-degree cone): both faces tie at
// the limit and keep their vectors; under a pure press nothing is stretched.
TEST_F(BoxEdge, FortyFiveDegreeEdgeHitWithFrictionOneKeepsBothFaces) {
  const Vec3 n = Vec3(1, 1, 0).normalized();
  s_ = settingsWith(16, 2.0);  // stretch on: a pure press must not stretch
  s_.friction = 1.0;
  s_.tau_a = 60 * kDeg;
  computePatch(box_, {Vec3(0.05, 0.05, 0.013), n, -0.001}, -0.004 * n, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kEdge);
  EXPECT_EQ(p_.sgos.size(), 16u);
  EXPECT_GT(onSideFace(), 0);
  EXPECT_LT(onSideFace(), 16);
  for (const Sgo& sgo : p_.sgos) EXPECT_NEAR(p_.d_i[sgo.radial], p_.radius, 1e-15) << "no tangential force";
  s_.friction = std::tan(44.9 * kDeg);  // below the tie: both faces are still the start faces
  computePatch(box_, {Vec3(0.05, 0.05, 0.013), n, -0.001}, -0.004 * n, s_, p_);
  EXPECT_EQ(p_.sgos.size(), 16u);
}

// Radial vectors along the hit edge enter both faces at 0: they go to the face that keeps them,
// so the patch is the mirror image of itself across the plane normal to the edge.
TEST_F(BoxEdge, VectorsAlongTheEdgeAreKeptSymmetrically) {
  const Vec3 n(std::sin(20 * kDeg), std::cos(20 * kDeg), 0);
  s_.tau_a = 45 * kDeg;  // top kept, side (70 degrees) dropped
  s_.friction_cone = false;
  PatchContact c{Vec3(0.05, 0.05, 0.01), n, -0.001};
  c.ring_reference_local = Vec3::UnitZ();  // radial 0 and 8 run along the edge (z)
  computePatch(box_, c, -0.004 * n, s_, p_);
  ASSERT_EQ(p_.hit.feature, Feature::kEdge);
  ASSERT_EQ(p_.radial_stop.size(), 16u);
  EXPECT_NE(p_.radial_stop[0], WalkStop::kDropped);
  EXPECT_NE(p_.radial_stop[8], WalkStop::kDropped);
  for (int i = 0; i < 16; ++i) {  // radial i at angle a mirrors radial 8 - i at pi - a
    EXPECT_EQ(p_.radial_stop[i] == WalkStop::kDropped, p_.radial_stop[(24 - i) % 16] == WalkStop::kDropped) << i;
  }
  for (const Sgo& sgo : p_.sgos) {
    if (sgo.radial == 0 || sgo.radial == 8) {
      EXPECT_NEAR(sgo.position.x(), 0.05, 1e-12) << "along the edge";
      EXPECT_NEAR(sgo.position.y(), 0.05, 1e-12);
      EXPECT_NEAR(sgo.walked, p_.d_i[sgo.radial], 1e-12);
    }
  }
}

// An SGO on a face turned 90 degrees or more from the normal could not push along it: with the
// thresholds at their widest (tau_a 90, no cone) and r_max 1 m on a 3 cm ball, every walk stops
// before the equator.
TEST(Patch, NoSgoOnFacesTurnedAwayFromThePress) {
  const Mesh ball = tessellateSphere(0.015, 4);
  PatchSettings s = settingsWith(8, 1.0);
  s.r_max = 1.0;
  s.tau_a = 90 * kDeg;
  s.friction_cone = false;
  for (const bool threshold : {true, false}) {  // tau_a 90 stops there too; off, nothing else does
    s.angular_threshold = threshold;
    Patch p;
    computePatch(ball, {Vec3(0, 0.015, 0), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s, p);
    ASSERT_EQ(p.sgos.size(), 8u);
    for (const Sgo& sgo : p.sgos) {
      EXPECT_GT(ball.faceNormal(sgo.face).y(), 0.0);
      if (threshold) {
        EXPECT_TRUE(sgo.stop == WalkStop::kFacingAway || sgo.stop == WalkStop::kAngularThreshold);
      } else {
        EXPECT_EQ(sgo.stop, WalkStop::kFacingAway);
      }
      EXPECT_LT(sgo.walked, 0.5 * std::numbers::pi * 0.015 + 1e-9) << "a quarter of the circumference at most";
    }
  }
}

// Eq. 2 stretches at most max_stretch, and the SGOs' load shares keep the load's centre at the
// contact whatever the stretch.
TEST(Patch, StretchIsBoundedAndTheLoadCentreStaysAtTheContact) {
  const Mesh plane = tessellatePlane(1.0, 1);
  const PatchContact c{Vec3(0.1, 0, 0.05), Vec3::UnitY(), -0.001};
  for (const double push : {0.0, 0.002, 0.004, 0.05, 10.0}) {
    const Vec3 v(push, -0.004, 0.3 * push);
    for (const int n : {3, 8, 13, 64}) {
      Patch p;
      computePatch(plane, c, v, settingsWith(n, 2.0), p);
      ASSERT_EQ(p.sgos.size(), static_cast<std::size_t>(n));
      Vec3 centre = p.centre_share * p.hit.point;
      double total = p.centre_share;
      EXPECT_DOUBLE_EQ(p.centre_share, 1.0 / (n + 1));
      for (const Sgo& sgo : p.sgos) {
        EXPECT_LE(p.d_i[sgo.radial], 2.0 * p.radius * (1 + 1e-12));
        EXPECT_GE(p.d_i[sgo.radial], 0.5 * p.radius * (1 - 1e-12));
        centre += sgo.load_share * sgo.position;
        total += sgo.load_share;
      }
      EXPECT_NEAR(total, 1.0, 1e-12);
      EXPECT_LT((centre - p.hit.point).norm(), 1e-12) << "push " << push << " n " << n;
    }
  }
}

// The ring follows a reference direction: radial 0 is its projection on the tangent plane, so a
// normal wobbling about +x (the sign of its z flipping) does not turn the ring.
TEST(Patch, RingFollowsItsReferenceAcrossNormalWobble) {
  const Mesh box = tessellateBox(Vec3(0.05, 0.05, 0.05), 2);
  PatchSettings s = settingsWith(8, 1.0);
  Patch p;
  Vec3 reference = Vec3::Zero();
  Vec3 first = Vec3::Zero();
  for (int step = 0; step < 20; ++step) {
    const double wobble = (step % 2 ? 1e-9 : -1e-9);
    const Vec3 n = Vec3(1.0, 0.0, wobble).normalized();
    PatchContact c{Vec3(0.05, 0.011, 0.013), n, -0.001};
    c.ring_reference_local = reference;
    computePatch(box, c, -0.004 * n, s, p);
    ASSERT_EQ(p.sgos.size(), 8u);
    ASSERT_EQ(p.sgos[0].radial, 0);
    const Vec3 dir = (p.sgos[0].position - p.hit.point).normalized();
    if (step == 0) first = dir;
    EXPECT_GT(dir.dot(first), 1.0 - 1e-9) << "step " << step;
    EXPECT_NEAR(p.ring_tangent.dot(n), 0.0, 1e-15);
    reference = p.ring_tangent;
  }
}

// The walk's crossing budget grows with r over the local edge length: on a 100 352-face grid
// (98 um squares) every walk covers the full 10 mm radius.
TEST(Patch, FineMeshKeepsTheFullRadius) {
  const Mesh plane = tessellatePlane(0.011, 224);
  ASSERT_EQ(plane.faceCount(), 100352);
  PatchSettings s = settingsWith(8, 1.0);
  s.d0 = 1e-4;  // a deep press: r = r_max
  Patch p;
  computePatch(plane, {Vec3(0.00013, 0, -0.00021), Vec3::UnitY(), -0.001}, Vec3(0, -0.004, 0), s, p);
  ASSERT_EQ(p.sgos.size(), 8u);
  EXPECT_NEAR(p.radius, 0.010, 1e-12);
  for (const Sgo& sgo : p.sgos) {
    EXPECT_EQ(sgo.stop, WalkStop::kDistance);
    EXPECT_NEAR(sgo.walked, 0.010, 1e-12);
  }
}

// A box's collision margin rounds its edges and corners: a contact on the rounding, with a
// normal between the faces', is an edge or vertex hit snapped onto the feature; on the flat
// part (the face's normal) it stays a face hit.
TEST(ContactFeature, RoundedEdgesAndCornersAreEdgeAndVertexHits) {
  const Mesh box = tessellateBox(Vec3(0.02, 0.02, 0.02), 4);
  const double m = 0.0005;
  // On the rounded top-front edge (inner edge at y = z = 0.0195), 21.5 degrees from the front.
  const double a = 21.5 * kDeg;
  const Vec3 n(0, std::sin(a), std::cos(a));
  const Vec3 on_edge_rounding = Vec3(0.0013, 0.02 - m, 0.02 - m) + m * n;
  SurfacePoint hit = contactFeature(box, {on_edge_rounding, n, -1e-4, m}, 1e-7);
  ASSERT_EQ(hit.feature, Feature::kEdge);
  EXPECT_NEAR(hit.point.y(), 0.02, 1e-15);
  EXPECT_NEAR(hit.point.z(), 0.02, 1e-15);
  EXPECT_NEAR(hit.point.x(), 0.0013, 1e-15);
  // The same point reported by a sharp shape is a face hit.
  EXPECT_EQ(contactFeature(box, {on_edge_rounding, n, -1e-4, 0.0}, 1e-7).feature, Feature::kFace);
  // On the flat front face 0.3 mm below the edge: the face's normal, a face hit.
  EXPECT_EQ(contactFeature(box, {Vec3(0.0013, 0.0197, 0.02), Vec3::UnitZ(), -1e-4, m}, 1e-7).feature,
            Feature::kFace);
  // On the rounded corner, the normal inside the three faces' normals.
  const Vec3 d = Vec3(1, 2, 3).normalized();
  hit = contactFeature(box, {Vec3::Constant(0.02 - m) + m * d, d, -1e-4, m}, 1e-7);
  ASSERT_EQ(hit.feature, Feature::kVertex);
  EXPECT_LT((hit.point - Vec3::Constant(0.02)).norm(), 1e-15);
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

namespace gf::sim {
namespace {

// The filled patch's areas: the sum over its points and the contact's disc.
double filledArea(const Patch& p) {
  double a = p.centre_area;
  for (const Sgo& s : p.sgos) a += s.area;
  for (const Sgo& s : p.inner) a += s.area;
  return a;
}

// On a plane, each point stands for its ring's annular sector and the patch for the whole disc;
// the shares are the areas over the disc's.
TEST(FilledPatch, WeightsAreAnnularSectorsSummingToTheDisc) {
  const Mesh plane = tessellatePlane(1.0, 1);
  const PatchContact c{Vec3(0.1, 0, 0.05), Vec3::UnitY(), -0.001};
  for (const int n : {3, 8, 16}) {
    for (const int rings : {1, 3, 8}) {
      PatchSettings s = settingsWith(n, 1.0);
      s.fill = PatchFill::kFilled;
      s.rings = rings;
      Patch p;
      computePatch(plane, c, Vec3(0, -0.004, 0), s, p);
      ASSERT_EQ(p.sgos.size(), static_cast<std::size_t>(n));
      ASSERT_EQ(p.inner.size(), static_cast<std::size_t>(n * (rings - 1)));
      const double r = p.radius, sector = 2.0 * std::numbers::pi / n, step = r / rings;
      EXPECT_NEAR(p.centre_area, n * 0.5 * sector * 0.25 * step * step, 1e-15);
      for (const Sgo& g : p.inner) {
        EXPECT_NEAR((g.position - c.point_local).norm(), g.ring * step, 1e-12);
        const double a = (g.ring - 0.5) * step, b = (g.ring + 0.5) * step;
        EXPECT_NEAR(g.area, 0.5 * sector * (b * b - a * a), 1e-15);
      }
      for (const Sgo& g : p.sgos) {
        EXPECT_EQ(g.ring, rings);
        const double a = (rings - 0.5) * step;
        EXPECT_NEAR(g.area, 0.5 * sector * (r * r - a * a), 1e-15);
      }
      EXPECT_NEAR(filledArea(p), std::numbers::pi * r * r, 1e-14) << "n " << n << " rings " << rings;
      double shares = p.centre_share;
      for (const Sgo& g : p.sgos) shares += g.load_share;
      for (const Sgo& g : p.inner) shares += g.load_share;
      EXPECT_NEAR(shares, 1.0, 1e-12);
      EXPECT_NEAR(p.centre_share, p.centre_area / filledArea(p), 1e-12);
    }
  }
}

// Where walks stop short (a box edge beyond tau_a) or vectors are dropped, only what was walked
// counts: each direction's sectors reach its walked length.
TEST(FilledPatch, WhatTheWalksDidNotReachIsNotCounted) {
  const Mesh box = tessellateBox(Vec3(0.05, 0.05, 0.05), 2);
  PatchSettings s = settingsWith(8, 1.0);
  s.fill = PatchFill::kFilled;
  s.rings = 3;
  // 3 mm from the +x edge of the top face: the walks towards +x stop at the edge (90 degrees).
  const PatchContact c{Vec3(0.047, 0.05, 0.0), Vec3::UnitY(), -0.001};
  Patch p;
  computePatch(box, c, Vec3(0, -0.004, 0), s, p);
  ASSERT_EQ(p.sgos.size(), 8u);
  const double sector = 2.0 * std::numbers::pi / 8;
  double expected = 0.0;
  int stopped = 0;
  for (const Sgo& g : p.sgos) {
    expected += 0.5 * sector * g.walked * g.walked;
    stopped += g.stop == WalkStop::kAngularThreshold;
  }
  EXPECT_EQ(stopped, 3) << "the three vectors towards +x stop at the edge";
  EXPECT_NEAR(filledArea(p), expected, 1e-14);
  EXPECT_LT(filledArea(p), std::numbers::pi * p.radius * p.radius * 0.9);
}

}  // namespace
}  // namespace gf::sim
