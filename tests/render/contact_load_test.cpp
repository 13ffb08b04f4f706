// How the pictures read a contact's load, without GL: the viridis scale, each point's load on a
// scale centred on the contact's mean point load, the contact's force split along its normal, and the sizes of
// the labels' text and scale bars.
#include "render/state/contact_load.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "render/overlay/labels.hpp"
#include "render/overlay/patch_insets.hpp"

namespace gf::render {
namespace {

// A contact pressing along -y with `n` SGOs, each carrying `each` N, and the contact point `centre` N.
sim::ContactSnapshot pressed(int n, double each, double centre) {
  sim::ContactSnapshot c;
  c.outward_normal_world = sim::Vec3::UnitY();
  c.point_load.normal = centre;
  for (int k = 0; k < n; ++k) {
    c.sgos_world.emplace_back(0.01 * std::cos(k), 0.0, 0.01 * std::sin(k));
    sim::PointLoad l;
    l.normal = each;
    c.loads.push_back(l);
  }
  return c;
}

// Display lightness (Rec. 709 luma of the display values).
double luma(const Eigen::Vector3f& linear) {
  const Eigen::Vector3f d = linear.cwiseSqrt();
  return 0.2126 * d.x() + 0.7152 * d.y() + 0.0722 * d.z();
}

// CIE 1976 Delta-E between two colours as shown: each colour's display value (the square root
// of the linear value the pictures store) read as sRGB, to CIELAB under D65.
double deltaE(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const auto lab = [](const Eigen::Vector3f& linear) {
    Eigen::Vector3d rgb;
    for (int k = 0; k < 3; ++k) {
      const double c = std::sqrt(static_cast<double>(linear[k]));
      rgb[k] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    }
    Eigen::Matrix3d m;
    m << 0.4124, 0.3576, 0.1805, 0.2126, 0.7152, 0.0722, 0.0193, 0.1192, 0.9505;
    const Eigen::Vector3d xyz = (m * rgb).cwiseQuotient(Eigen::Vector3d(0.95047, 1.0, 1.08883));
    const auto f = [](double t) { return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; };
    return Eigen::Vector3d(116.0 * f(xyz.y()) - 16.0, 500.0 * (f(xyz.x()) - f(xyz.y())), 200.0 * (f(xyz.y()) - f(xyz.z())));
  };
  return (lab(a) - lab(b)).norm();
}

TEST(ContactLoad, ViridisRunsFromDarkPurpleToYellowGettingLighterAllTheWay) {
  EXPECT_NEAR(viridis(0.0).cwiseSqrt().x(), 0.267, 1e-3);
  EXPECT_NEAR(viridis(0.0).cwiseSqrt().z(), 0.329, 1e-3);
  EXPECT_NEAR(viridis(1.0).cwiseSqrt().x(), 0.993, 1e-3);
  EXPECT_NEAR(viridis(1.0).cwiseSqrt().y(), 0.906, 1e-3);
  for (int k = 1; k <= 40; ++k) EXPECT_GT(luma(viridis(k / 40.0)), luma(viridis((k - 1) / 40.0))) << k;
  EXPECT_EQ(viridis(-3.0), viridis(0.0));  // clamped
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  EXPECT_EQ(viridis(std::nan("")), viridis(0.0));
}

TEST(ContactLoad, TheScaleIsCentredOnTheMeanAndStretchedToThePointsSpread) {
  const sim::ContactSnapshot uniform = pressed(8, 0.5, 0.5);
  const ContactLoads loads = contactLoads(uniform);
  ASSERT_TRUE(loads.shown);
  EXPECT_NEAR(loads.mean_normal, 0.5, 1e-12);  // 4.5 N over 9 points: 8 SGOs and c_p
  EXPECT_NEAR(loads.share(0.5), 1.0, 1e-12);
  EXPECT_EQ(loads.half_span, kLoadScaleMinHalfSpan) << "no spread: the least half-span";
  EXPECT_EQ(loads.colour(0.5), viridis(0.5));
  EXPECT_NEAR(loads.loadAt(0.0), 0.5 * (1.0 - kLoadScaleMinHalfSpan), 1e-12);
  sim::ContactSnapshot uneven = pressed(8, 0.25, 0.0);
  uneven.loads[0].normal = 1.0;  // 2.75 N over 9 points: mean 0.3056 N; c_p carries nothing
  const ContactLoads u = contactLoads(uneven);
  EXPECT_NEAR(u.share(1.0), 9.0 / 2.75, 1e-12);
  EXPECT_NEAR(u.half_span, 9.0 / 2.75 - 1.0, 1e-12) << "the most loaded point is further off the mean than the least";
  EXPECT_NEAR(u.min_normal, 0.0, 1e-15);
  EXPECT_NEAR(u.max_normal, 1.0, 1e-15);
  EXPECT_NEAR(u.scale(1.0), 1.0, 1e-12) << "the most loaded point: the top";
  EXPECT_NEAR(u.loadAt(1.0), 1.0, 1e-12);
  EXPECT_NEAR(u.scale(u.mean_normal), 0.5, 1e-12);
  EXPECT_GT(u.scale(0.0), 0.0) << "the least is nearer the mean: above the bottom";
}

// The loads of the Fig. 8 close-up (issue 54): the upper SGOs 0.48 N, the lower 0.37 N. On a
// fixed 0..2 x mean scale they were drawn (48,147,126) and (39,117,128), a CIELAB Delta-E of
// 23 (27 for these loads); on the stretched scale they lie at its two ends, 149 apart.
TEST(ContactLoad, AFewPercentSpreadIsSeenInColour) {
  sim::ContactSnapshot c = pressed(8, 0.48, 0.425);
  for (int k = 4; k < 8; ++k) c.loads[static_cast<std::size_t>(k)].normal = 0.37;
  const ContactLoads loads = contactLoads(c);
  ASSERT_TRUE(loads.shown);
  EXPECT_GE(deltaE(loads.colour(0.48), loads.colour(0.37)), 30.0);
  EXPECT_LT(deltaE(viridis(0.48 / loads.mean_normal / 2.0), viridis(0.37 / loads.mean_normal / 2.0)), 30.0) << "the old scale";
}

TEST(ContactLoad, WithoutPerPointLoadsTheDotsAreDrawnUniformly) {
  EXPECT_FALSE(contactLoads(pressed(0, 0.0, 3.0)).shown) << "god-object: no SGOs, no loads";
  EXPECT_FALSE(contactLoads(pressed(8, 0.0, 0.0)).shown) << "loads that press nothing";
  sim::ContactSnapshot missing = pressed(8, 0.5, 0.5);
  missing.loads.pop_back();
  EXPECT_FALSE(contactLoads(missing).shown) << "one load short of the SGOs";
}

TEST(ContactLoad, TheForceSplitsIntoPressAndFrictionOnTheBody) {
  sim::FingerSnapshot finger;
  finger.feedback_force = sim::Vec3(0.3, 2.0, 0.0);  // the device pushed up and along +x
  sim::ContactSnapshot c = pressed(8, 0.25, 0.0);
  // Not filled by the solver: the reaction of the feedback force, on the body.
  ContactForce f = contactForce(finger, c);
  EXPECT_FALSE(f.from_solver);
  EXPECT_NEAR(f.normal, 2.0, 1e-12);
  EXPECT_NEAR((f.tangential - sim::Vec3(-0.3, 0.0, 0.0)).norm(), 0.0, 1e-12);
  c.force = sim::Vec3(0.0, -1.5, 0.2);  // the solver's: pressing 1.5 N, friction 0.2 N along +z
  f = contactForce(finger, c);
  EXPECT_TRUE(f.from_solver);
  EXPECT_NEAR(f.normal, 1.5, 1e-12);
  EXPECT_NEAR((f.tangential - sim::Vec3(0.0, 0.0, 0.2)).norm(), 0.0, 1e-12);
  c.force = sim::Vec3(0.0, 1.0, 0.0);  // pulling: no press
  EXPECT_EQ(contactForce(finger, c).normal, 0.0);
}

TEST(Labels, TextIsNeverSmallerThan13PixelsAndGrowsWithTheView) {
  // The insets of a 640x360 frame (the goldens, the README) and of a comparison's panels.
  for (const auto& [w, h] : {std::pair{640, 360}, std::pair{426, 240}, std::pair{320, 180}, std::pair{1280, 720}}) {
    const int side = insetRects(w, h, 2, InsetCorner::kBottomRight).front().size;
    EXPECT_GE(contactLabelPx(side), 13.0f) << w << "x" << h;
    EXPECT_GE(stampLabelPx(h), 13.0f) << w << "x" << h;
  }
  EXPECT_GT(contactLabelPx(480), contactLabelPx(216));
  EXPECT_LE(contactLabelPx(2000), 18.0f);
  EXPECT_GT(stampLabelPx(1080), stampLabelPx(720));
}

TEST(Labels, TheScaleBarIsARoundLengthUpToAThirdOfTheView) {
  EXPECT_DOUBLE_EQ(scaleBarMetres(0.030), 0.005);   // a 3 cm inset: 5 mm
  EXPECT_DOUBLE_EQ(scaleBarMetres(0.0334), 0.01);   // 10 mm fits 30 % of 33.4 mm
  EXPECT_DOUBLE_EQ(scaleBarMetres(0.004), 0.001);   // 4 mm: 1 mm
  EXPECT_DOUBLE_EQ(scaleBarMetres(1.0), 0.2);
  for (double view = 0.001; view < 2.0; view *= 1.37) {
    const double bar = scaleBarMetres(view);
    EXPECT_LE(bar, 0.3 * view + 1e-15) << view;
    EXPECT_GT(bar, 0.3 * view / 2.5 - 1e-15) << view;  // the next round length would not fit
  }
}

}  // namespace
}  // namespace gf::render
