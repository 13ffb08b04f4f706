// The twist a contact resists and its points' load arrows (render/scene/load_marks.hpp), on made-up
// contacts against hand-worked values: four SGOs 1 cm around a pressed point on a face with
// outward normal +y, each pressing 1 N with 0.1 N of friction turning counter-clockwise about +y
// (seen from above): a moment of 4 x 0.1 N x 1 cm = 0.004 N m about +y on the body.
#include "render/scene/load_marks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/state/contact_load.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

constexpr double kR = 0.01;  // m

sim::ContactSnapshot twisted(double sense) {
  sim::ContactSnapshot c;
  c.outward_normal_world = Vec3::UnitY();
  c.radius = kR;
  c.point_load.normal = 1.0;
  for (const Vec3& p : {Vec3(kR, 0, 0), Vec3(0, 0, kR), Vec3(-kR, 0, 0), Vec3(0, 0, -kR)}) {
    c.sgos_world.push_back(p);
    sim::PointLoad l;
    l.normal = 1.0;
    l.tangential = sense * 0.1 * Vec3::UnitY().cross(p / kR);  // along the turn about +y
    c.loads.push_back(l);
  }
  c.force = Vec3(0, -5, 0);  // the five points' press on the body; their friction cancels
  return c;
}

// The direction (unit) the last arrow head of `list` points: its cone's +y axis.
Vec3 headDirection(const DrawList& list) {
  for (auto it = list.items.rbegin(); it != list.items.rend(); ++it) {
    if (it->shape == DrawShape::kCone) return it->model.block<3, 1>(0, 1).cast<double>().normalized();
  }
  return Vec3::Zero();
}

TEST(LoadMarks, ATwistIsTheMomentOfThePointsFrictionAboutTheNormal) {
  EXPECT_NEAR(contactTorsion(twisted(1.0)), 0.004, 1e-12);
  EXPECT_NEAR(contactTorsion(twisted(-1.0)), -0.004, 1e-12);
  EXPECT_NEAR((pressureCentre(twisted(1.0)) - Vec3::Zero()).norm(), 0.0, 1e-15);
  // A soft finger's one point: the moment it cannot carry is all of its torsion.
  sim::ContactSnapshot soft;
  soft.outward_normal_world = Vec3::UnitY();
  soft.torsion_moment = Vec3(0, -0.003, 0);
  EXPECT_NEAR(contactTorsion(soft), -0.003, 1e-15);
}

TEST(LoadMarks, TheArcTurnsTheWayTheMomentDoesAndGrowsWithIt) {
  for (const double sense : {1.0, -1.0}) {
    const std::optional<TorsionArc> arc = torsionArc(twisted(sense), 1.0, kR);
    ASSERT_TRUE(arc.has_value());
    EXPECT_NEAR(arc->radius, 1.3 * kR, 1e-15);
    // 0.004 N m of mu F_n r = 1 x 5 N x 1 cm: a share of 0.08, so 90 + 0.08 x 180 degrees.
    EXPECT_NEAR(arc->sweep, std::numbers::pi * (0.5 + 0.08), 1e-9);
    DrawList list;
    addTorsionArc(list, *arc, 0.0003, Eigen::Vector3f::Ones(), std::nullopt);
    ASSERT_GT(list.items.size(), 4u);
    // The head at the arc's end points along the turn: n x (end - centre) times the sense.
    const DrawItem& last_tube = list.items[list.items.size() - 3];
    const Vec3 end = last_tube.model.block<3, 1>(0, 3).cast<double>() - arc->centre;
    const Vec3 along = sense * Vec3::UnitY().cross(end).normalized();
    EXPECT_GT(headDirection(list).dot(along), 0.9) << "sense " << sense;
  }
  // Under 5 % of mu F_n r (a pad friction of 2: 0.004 of 0.1 N m is 4 %), or no twist: no arc.
  EXPECT_FALSE(torsionArc(twisted(1.0), 2.0, kR).has_value());
  EXPECT_FALSE(torsionArc(twisted(0.0), 1.0, kR).has_value());
}

TEST(LoadMarks, LoadArrowsSplitEachPointsLoadAtHalfTheRadiusPerMeanLoad) {
  const sim::ContactSnapshot c = twisted(1.0);
  const double m_per_n = loadArrowScale(c, kR);
  EXPECT_NEAR(m_per_n, 0.5 * kR / 1.0, 1e-15);  // the mean point load is 1 N
  DrawList list;
  addLoadArrows(list, c, m_per_n, true, 1e-4, std::nullopt);
  // Five points, a normal arrow each and a friction arrow for the four that have friction (the
  // contact point's is zero, drawn as nothing): 9 arrows of a shaft and a head.
  EXPECT_EQ(list.items.size(), 18u);
  DrawList friction_only;
  addLoadArrows(friction_only, c, m_per_n, false, 1e-4, std::nullopt);
  EXPECT_EQ(friction_only.items.size(), 8u);
}

// On a soft body a god-finger's loads are its pressed nodes alone: the contact point is no point
// of the solver's and does not pull the scale down to zero.
TEST(LoadMarks, AContactPointThatCarriesNoShareIsLeftOutOfTheScale) {
  sim::ContactSnapshot c = twisted(1.0);
  c.point_load = sim::PointLoad{};
  c.point_loaded = false;
  const ContactLoads loads = contactLoads(c);
  ASSERT_TRUE(loads.shown);
  EXPECT_DOUBLE_EQ(loads.mean_normal, 1.0);
  EXPECT_DOUBLE_EQ(loads.min_normal, 1.0);
  EXPECT_DOUBLE_EQ(loads.half_span, kLoadScaleMinHalfSpan);
  c.point_loaded = true;  // the same loads with c_p one of them: it carries nothing
  EXPECT_DOUBLE_EQ(contactLoads(c).min_normal, 0.0);
}

}  // namespace
}  // namespace gf::render
