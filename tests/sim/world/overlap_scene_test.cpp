// The overlap-pinch scene under each world.overlap mode (docs/overlap.md): ignore measures the
// overlap the paper leaves, push_apart keeps its peak under a fifth of ignore's and still lifts
// the tile, merge counts every load once (the merged patch's loads add up to the two fingers'
// presses within 1 %, no two of its points closer than 0.1 r); "ignore" changes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/world/overlap.hpp"
#include "sim/scene/snapshot.hpp"
#include "tests/sim/test_context.hpp"

namespace gf::test_support {
namespace {

struct PinchRun {
  double peak_mm2 = 0.0;
  double integral_mm2_s = 0.0;
  double tile_rise = 0.0;  // m: the tile's height at the end over its start
};

PinchRun runPinch(const std::string& mode, const std::vector<std::string>& more = {}) {
  std::vector<std::string> overrides = {"world.overlap=" + mode};
  overrides.insert(overrides.end(), more.begin(), more.end());
  TestContext ctx("overlap-pinch", kSceneSgo, overrides);
  const int tile = ctx.body("tile");
  const double start = ctx.world().bodyPose(tile).position.y();
  ctx.simulate(ctx.scene().duration);
  const sim::OverlapStats o = ctx.world().overlap(0);
  return {o.peak * 1e6, o.integral * 1e6, ctx.world().bodyPose(tile).position.y() - start};
}

TEST(OverlapPinch, IgnoreOverlapsByAboutHalfAPatchAndLifts) {
  const PinchRun r = runPinch("ignore");
  EXPECT_GT(r.peak_mm2, 30.0);
  EXPECT_GT(r.tile_rise, 0.02);
}

TEST(OverlapPinch, PushApartKeepsThePeakUnderAFifthOfIgnoresAndLifts) {
  const PinchRun ignore = runPinch("ignore");
  const PinchRun push = runPinch("push_apart");
  EXPECT_LE(push.peak_mm2, 0.2 * ignore.peak_mm2);
  EXPECT_LT(push.integral_mm2_s, 0.2 * ignore.integral_mm2_s);
  EXPECT_GT(push.tile_rise, 0.02);
}

// The ends of overlap_stiffness's range hold: the softest (10 N/m) and the stiffest the
// default proxies allow at 1 kHz ((0.1 x 1000^2 - 800) / 2 N/m) stay finite and lift.
TEST(OverlapPinch, PushApartHoldsAtBothEndsOfItsStiffnessRange) {
  for (const char* k : {"10", "49600"}) {
    const PinchRun r = runPinch("push_apart", {std::string("world.overlap_stiffness=") + k});
    EXPECT_TRUE(std::isfinite(r.peak_mm2)) << k;
    EXPECT_GT(r.tile_rise, 0.02) << k;
  }
}

TEST(OverlapPinch, MergeCountsEachLoadOnceAndSumsToThePresses) {
  TestContext ctx("overlap-pinch", kSceneSgo, {"world.overlap=merge"});
  sim::Snapshot snap;
  std::vector<sim::MergedPoint> merged;
  int checked = 0;
  std::size_t coinciding = 0;  // points merged into another over the checks
  const auto check = [&](double until) {
    ctx.simulate(until - ctx.world().time());
    ctx.world().snapshot(snap);
    const sim::FingerSnapshot& a = snap.fingers[0];
    const sim::FingerSnapshot& b = snap.fingers[1];
    ASSERT_EQ(a.contacts.size(), 1u);
    ASSERT_EQ(b.contacts.size(), 1u);
    const sim::ContactSnapshot& ca = a.contacts[0];
    const sim::ContactSnapshot& cb = b.contacts[0];
    const double press_a = -a.coupling_force.dot(ca.outward_normal_world);
    const double press_b = -b.coupling_force.dot(cb.outward_normal_world);
    sim::mergePatches(ca, cb, press_a, press_b, merged);
    coinciding += 2 + ca.sgos_world.size() + cb.sgos_world.size() - merged.size();
    double load = 0.0;
    for (const sim::MergedPoint& p : merged) load += p.normal;
    EXPECT_NEAR(load, press_a + press_b, 0.01 * (press_a + press_b)) << "t = " << until;
    EXPECT_GE(sim::minPointDistance(merged), 0.1 * std::min(ca.radius, cb.radius)) << "t = " << until;
    EXPECT_GT(sim::discOverlap({ca.point_world, ca.outward_normal_world, ca.radius},
                               {cb.point_world, cb.outward_normal_world, cb.radius}).area, 0.0);
    ++checked;
  };
  for (double t : {1.7, 1.8, 1.9, 2.0, 3.3, 3.6, 4.0}) check(t);
  EXPECT_EQ(checked, 7);
  EXPECT_GT(coinciding, 7u) << "the filled patches overlap: some of their points coincide";
}

// "ignore" is the paper's behaviour: the same steps, bit for bit, as a scene that does not
// name world.overlap, whatever the stiffness says.
TEST(OverlapPinch, IgnoreIsTheSceneWithoutOverlapHandling) {
  TestContext a("fig7-lift-two-fingers");
  TestContext b("fig7-lift-two-fingers", kSceneSgo, {"world.overlap=ignore", "world.overlap_stiffness=5000"});
  a.simulate(2.0);
  b.simulate(2.0);
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(a.world().proxyPosition(f), b.world().proxyPosition(f));
    EXPECT_EQ(a.world().couplingForce(f), b.world().couplingForce(f));
  }
  EXPECT_EQ(a.world().bodyPose(a.body("tile")).position, b.world().bodyPose(b.body("tile")).position);
}

}  // namespace
}  // namespace gf::test_support
