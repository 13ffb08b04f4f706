// fem_pad in the World, on the pressed puck (a frictionless table, so the pad alone holds the
// puck sideways and about the vertical): its contacts' forces, as snapshots report them, are
// what changed the puck's momentum; at rest it carries the coupling's force; the model is fixed
// for a session and its settings are checked against the proxy.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim/scene/settings.hpp"
#include "sim/world/world.hpp"
#include "tests/sim/test_context.hpp"

namespace gf::sim {
namespace {

using test_support::kSceneSgo;
using test_support::TestContext;

// The puck's momentum change over the run against the pad's forces (the snapshot after each step
// reports the forces that step put on it), sideways (N s) and about the vertical with the
// scene's torque load (N m s).
TEST(WorldPad, ThePadsForcesAreWhatChangedThePucksMomentum) {
  TestContext ctx("pressed-puck", kSceneSgo, {"fingers.index.contact_model=fem_pad"});
  const int puck = ctx.body("puck");
  const double mass = ctx.scene().bodies[static_cast<std::size_t>(puck)].mass;
  const double inertia_y = ctx.world().bodyInertia(puck).y();
  Snapshot snap;
  Vec3 impulse = Vec3::Zero();
  double angular_impulse = 0.0;
  int pressed_steps = 0;
  ctx.simulate(1.0, [&](const World& w) {
    w.snapshot(snap);
    const Vec3 centre = w.bodyPose(puck).position;
    for (const ContactSnapshot& c : snap.fingers[0].contacts) {
      ASSERT_EQ(c.body, puck);
      ASSERT_EQ(c.sgos_world.size(), c.loads.size());
      for (std::size_t i = 0; i < c.loads.size(); ++i) {
        const Vec3 f = c.loads[i].tangential - c.loads[i].normal * c.outward_normal_world;
        impulse += 0.001 * f;
        angular_impulse += 0.001 * (c.sgos_world[i] - centre).cross(f).y();
      }
      pressed_steps += !c.loads.empty();
    }
    if (w.time() > 0.6 + 1e-9) angular_impulse += 0.001 * 0.04;  // the scene's load, from 0.6 s
  });
  ASSERT_GT(pressed_steps, 500);
  const Vec3 v = ctx.world().bodyLinearVelocity(puck);
  EXPECT_NEAR(mass * v.x(), impulse.x(), 1e-9 + 1e-6 * std::abs(impulse.x()));
  EXPECT_NEAR(mass * v.z(), impulse.z(), 1e-9 + 1e-6 * std::abs(impulse.z()));
  const double spin = inertia_y * ctx.world().bodyAngularVelocity(puck).y();
  EXPECT_GT(spin, 0.005) << "the torque turned the puck";
  EXPECT_NEAR(spin, angular_impulse, 1e-3 * std::abs(angular_impulse));
  EXPECT_EQ(ctx.world().counters().pad_resets, 0);
  EXPECT_EQ(ctx.world().counters().nan_recoveries, 0);
}

// Settled under the press (0.55 s), the pad's normal force on the puck is the coupling's pull,
// its points the pressed skin nodes, its radius that of a disc of their area, and the World's
// queries agree with the snapshot.
TEST(WorldPad, APressedPadCarriesTheCouplingsForce) {
  TestContext ctx("pressed-puck", kSceneSgo, {"fingers.index.contact_model=fem_pad"});
  ctx.simulate(0.55);
  const World& w = ctx.world();
  Snapshot snap;
  w.snapshot(snap);
  const FingerSnapshot& f = snap.fingers[0];
  ASSERT_EQ(f.contacts.size(), 1u);
  const ContactSnapshot& c = f.contacts[0];
  EXPECT_NEAR(-c.force.y(), f.coupling_force.y() * -1.0, 0.01 * std::abs(f.coupling_force.y()));
  EXPECT_GT(c.radius, 0.002);
  EXPECT_LT(c.radius, 0.008);
  EXPECT_GT(c.press_depth, 0.0);
  EXPECT_EQ(w.sgoCount(0), static_cast<int>(c.sgos_world.size()));
  EXPECT_NEAR(w.contactRadius(0), c.radius, 1e-12);
  EXPECT_TRUE(w.touching(0));
  ASSERT_FALSE(f.pad.nodes.empty());
  ASSERT_TRUE(f.pad.skin);
  EXPECT_NEAR(f.pad.bone_radius, 0.008 - 0.003, 1e-15);
}

TEST(WorldPad, AFingerCanNeitherChangeToNorFromFemPad) {
  TestContext pad("pressed-puck", kSceneSgo, {"fingers.index.contact_model=fem_pad"});
  PatchSettings other = pad.scene().fingers[0].patch;
  other.model = ContactModel::kGodFinger;
  EXPECT_THROW(pad.world().setPatchSettings(0, other), DescriptionError);
  TestContext rigid("pressed-puck");
  PatchSettings soft = rigid.scene().fingers[0].patch;
  soft.model = ContactModel::kFemPad;
  try {
    rigid.world().setPatchSettings(0, soft);
    ADD_FAILURE() << "changed to fem_pad";
  } catch (const DescriptionError& e) {
    EXPECT_EQ(e.error().field, "contact_model");
  }
}

// The pad's shape against the proxy: a bone at least as thick as the tissue and deeper than the
// clamp's press, cells within the thickness's range and few enough across the cap.
TEST(WorldPad, PadSettingsThatCannotBeBuiltAreRefusedNamingTheField) {
  const auto field = [](const std::vector<std::string>& set) {
    std::vector<std::string> all = {"fingers.index.contact_model=fem_pad"};
    all.insert(all.end(), set.begin(), set.end());
    try {
      requireValid(TestContext::load("pressed-puck", kSceneSgo, all));
    } catch (const std::exception& e) {  // the scene reader's error names the setting, then why
      const std::string what = e.what(), key = "fingers.index.";
      const std::size_t at = what.rfind(key);
      return at == std::string::npos ? what : what.substr(at + key.size(), what.find(':', at) - at - key.size());
    }
    return std::string();
  };
  EXPECT_EQ(field({}), "");
  EXPECT_EQ(field({"fingers.index.pad_thickness=0.005"}), "pad_thickness");
  EXPECT_EQ(field({"fingers.index.pad_element_size=0.004"}), "pad_element_size");
  EXPECT_EQ(field({"fingers.index.pad_element_size=0.0001"}), "pad_element_size");
  EXPECT_EQ(field({"fingers.index.pad_element_size=0.0007"}), "pad_element_size") << "below a quarter of 3 mm";
  EXPECT_EQ(field({"fingers.index.pad_thickness=0.004", "fingers.index.contact_stiffness=8000"}), "pad_thickness")
      << "a 4 mm bone, 40 N / 8000 N/m = 5 mm deep at the clamp";
  EXPECT_EQ(field({"fingers.index.proxy_radius=0.05", "fingers.index.pad_element_size=0.003"}), "pad_element_size")
      << "more than 16 cells across";
}

}  // namespace
}  // namespace gf::sim
