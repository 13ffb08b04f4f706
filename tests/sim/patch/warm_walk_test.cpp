// Warm-started walks (sim/patch/warm_walk.hpp) against walks from the contact point: every bundled
// scene run with World::checkWarmWalks, which computes each step's patches from scratch too;
// every SGO, filled point and path point within 1e-9 m of the from-scratch one, and most walks
// carried, most of them within their slack (no crossing checked).
// Lives in tests/sim: the scene files are read by gf_scene, which the sim tests link.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/patch/warm_walk.hpp"
#include "tests/sim/test_context.hpp"

namespace gf::test_support {
namespace {

// Agreement of a carried walk with the walk from the contact (m).
constexpr double kAgreement = 1e-9;

// The bundled scenes (assets/scenes/*.toml), by name, sorted.
std::vector<std::string> bundledScenes() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(GF_SOURCE_DIR) + "/assets/scenes")) {
    if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Runs `scene` for its duration with every patch checked; returns the world's counters.
sim::WorldCounters runChecked(const sim::SceneDesc& scene) {
  sim::World world(scene);
  world.checkWarmWalks(true);
  std::vector<sim::DeviceTrack> devices = sim::deviceTracks(scene);
  sim::runHapticLoop(world, devices, {scene.world.haptic_rate_hz, scene.duration}, {});
  return world.counters();
}

void expectAgreement(const std::string& what, const sim::WorldCounters& c) {
  std::printf("%s: %ld patches checked, %ld walks carried (%ld within their slack), %ld from the contact, largest "
              "difference %.3g m\n",
              what.c_str(), c.walk_checks, c.warm_walks, c.slack_walks, c.cold_walks, c.walk_check_error);
  EXPECT_EQ(c.walk_checks, c.patch_calls) << what << ": every patch checked";
  EXPECT_LE(c.walk_check_error, kAgreement) << what;
}

TEST(WarmWalks, EveryBundledSceneAgreesWithWalksFromTheContact) {
  const std::vector<std::string> scenes = bundledScenes();
  ASSERT_GE(scenes.size(), 13u) << "the bundled scenes were not found";
  long checked = 0, carried = 0, cold = 0;
  for (const std::string& name : scenes) {
    const sim::SceneDesc scene = TestContext::load(name, kSceneSgo, {});
    // A finger on a soft body presses its surface nodes, with no walk to carry (sim/soft/):
    // those scenes (soft-*) compute no patch, and take most of this test's time for nothing.
    if (std::any_of(scene.bodies.begin(), scene.bodies.end(), [](const sim::BodyDesc& b) { return sim::isSoftShape(b.shape); })) continue;
    const sim::WorldCounters c = runChecked(scene);
    expectAgreement(name, c);
    checked += c.walk_checks, carried += c.warm_walks, cold += c.cold_walks;
    // The held pinch carries nearly every walk (its contact stays on one face), most of them
    // within their slack: both ways of carrying are compared.
    if (name == "fig8-pinch-oscillation") {
      EXPECT_GT(c.warm_walks, 99 * c.cold_walks) << name;
      EXPECT_GT(c.slack_walks, c.warm_walks / 2) << name;
      EXPECT_GT(c.warm_walks - c.slack_walks, c.cold_walks) << name;
    }
  }
  // The comparison is not vacuous: most walks of the scenes were carried. (A walk stopped short
  // at a threshold, as on the puck's rim, a contact moving to another face, as on the
  // tessellated sphere, and edge and vertex contacts are walked from the contact: press-box's
  // box stands still under the finger, whose contact stays on the vertex at its top face's
  // centre; so is a patch sliding under a finger, as overlap-pinch's do for a second: 3 in 4
  // carried in all.)
  EXPECT_GT(checked, 10'000) << "the scenes computed patches";
  EXPECT_GT(carried, 2 * cold);
}

// The pinch at n_SGO 64 with filled patches (points along every path) under both solvers.
TEST(WarmWalks, FilledPinchAtSixtyFourSgosAgrees) {
  for (const char* solver : {"points", "aggregate"}) {
    sim::SceneDesc scene =
        TestContext::load("fig8-pinch-oscillation", 64, {std::string("world.contact_solver=") + solver});
    scene.duration = 8.0;
    for (sim::FingerDesc& f : scene.fingers) f.patch.fill = sim::PatchFill::kFilled;
    const sim::WorldCounters c = runChecked(scene);
    expectAgreement(std::string("fig8 filled 64 ") + solver, c);
    EXPECT_GT(c.slack_walks, c.warm_walks / 2) << solver;
  }
}

}  // namespace
}  // namespace gf::test_support
