// Physics of god-finger contacts in Bullet: the paper's claims as measurable checks.
#include "sim/world.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "app/builtin_scenes.hpp"
#include "sim/haptic_loop.hpp"

namespace gf::sim {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

std::vector<DeviceTrack> devicesOf(const SceneDesc& s) {
  std::vector<DeviceTrack> d;
  for (const FingerDesc& f : s.fingers) d.push_back(f.device);
  return d;
}

// Rotation of body `b` from its initial orientation, about the world x axis (deg).
double angleAboutX(const World& w, int b) {
  const Eigen::AngleAxisd aa(w.bodyPose(b).orientation);
  return std::abs(aa.angle() * aa.axis().x()) * kRadToDeg;
}

// Largest rotation of the cylinder about the pinch axis once the lift has started.
double pinchSwing(int n_sgo, double* lifted = nullptr) {
  const SceneDesc scene = app::pinchScene({n_sgo, 6.0});
  World world(scene);
  double swing = 0.0;
  runHapticLoop(world, devicesOf(scene), {1000.0, scene.duration}, [&](const World& w) {
    if (w.time() > 1.0) swing = std::max(swing, angleAboutX(w, 1));
  });
  if (lifted) *lifted = world.bodyPose(1).position.y() - 0.05;
  EXPECT_EQ(world.counters().nan_recoveries, 0);
  return swing;
}

TEST(WorldPinch, GodObjectSwingsAboutThePinchAxis) {
  double lifted = 0.0;
  const double swing = pinchSwing(0, &lifted);
  EXPECT_GT(swing, 20.0);
  std::printf("god-object swing %.2f deg\n", swing);
}

TEST(WorldPinch, GodFingerLiftsAndHoldsWithinTwoDegrees) {
  double lifted = 0.0;
  const double swing = pinchSwing(8, &lifted);
  EXPECT_LT(swing, 2.0);
  EXPECT_NEAR(lifted, 0.05, 0.005) << "lifted with the devices (5 cm)";
  std::printf("god-finger swing %.3f deg, lifted %.4f m\n", swing, lifted);
}

// Spin (rad/s about the contact normal) of the pressed box `after` seconds after an impulse.
double spinAfterTwist(int n_sgo, double after) {
  const SceneDesc scene = app::pressBoxScene({n_sgo, 1.0});
  World world(scene);
  const auto devices = devicesOf(scene);
  runHapticLoop(world, devices, {1000.0, 1.0}, nullptr);  // press and settle
  world.applyTorqueImpulse(1, Vec3(0, 1e-3, 0));          // N m s about the normal (y)
  runHapticLoop(world, devices, {1000.0, after}, nullptr);
  EXPECT_EQ(world.counters().nan_recoveries, 0);
  return std::abs(world.bodyAngularVelocity(1).y());
}

TEST(WorldTwist, GodFingerStopsTheSpinOfAPressedBox) {
  const double god_object = spinAfterTwist(0, 0.05);
  const double god_finger = spinAfterTwist(8, 0.05);
  std::printf("spin 50 ms after the impulse: god-object %.4g rad/s, god-finger %.4g rad/s\n",
              god_object, god_finger);
  EXPECT_GT(god_object, 0.5) << "the impulse must spin the god-object case visibly";
  EXPECT_LT(god_finger, 0.01 * god_object);
}

TEST(WorldStability, ThirtySecondSqueezeStaysBoundedAndFinite) {
  const SceneDesc scene = app::pinchScene({16, 30.0});
  World world(scene);
  double e_min = 1e300, e_max = -1e300, e_late_min = 1e300, e_late_max = -1e300;
  bool finite = true;
  runHapticLoop(world, devicesOf(scene), {1000.0, scene.duration}, [&](const World& w) {
    const double e = w.mechanicalEnergy();
    finite &= std::isfinite(e) && w.bodyPose(1).position.allFinite() && w.proxyPosition(0).allFinite();
    e_min = std::min(e_min, e), e_max = std::max(e_max, e);
    if (w.time() > 10.0) e_late_min = std::min(e_late_min, e), e_late_max = std::max(e_late_max, e);
  });
  EXPECT_TRUE(finite);
  EXPECT_EQ(world.counters().nan_recoveries, 0);
  // Potential energy of a 5 cm lift of 0.15 kg is 0.074 J: the total stays of that order, and
  // once the devices hold still it neither grows nor drains by more than 1 mJ.
  EXPECT_LT(e_max - e_min, 0.2);
  EXPECT_LT(e_late_max - e_late_min, 1e-3);
  std::printf("energy range %.4g J, after 10 s %.3g J\n", e_max - e_min, e_late_max - e_late_min);
}

// Two identical offline runs must agree to the bit at every step.
TEST(WorldDeterminism, TwoOfflineRunsAreBitIdentical) {
  const SceneDesc scene = app::pinchScene({8, 2.0});
  auto trace = [&] {
    World world(scene);
    std::vector<double> out;
    runHapticLoop(world, devicesOf(scene), {1000.0, scene.duration}, [&](const World& w) {
      const BodySnapshot b = w.bodyPose(1);
      out.insert(out.end(), {b.position.x(), b.position.y(), b.position.z(), b.orientation.w(),
                             b.orientation.x(), b.orientation.y(), b.orientation.z(),
                             w.couplingForce(0).x(), w.couplingForce(1).y()});
    });
    return out;
  };
  const std::vector<double> a = trace(), b = trace();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double)));
}

TEST(WorldErrors, BadDescriptionsNameTheBodyOrFinger) {
  SceneDesc scene = app::pinchScene({8, 1.0});
  scene.bodies[1].mass = -1.0;
  try {
    World w(scene);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 'cylinder'"), std::string::npos) << e.what();
  }
  scene = app::pinchScene({8, 1.0});
  scene.fingers[1].patch.n_sgo = 200;
  try {
    World w(scene);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("finger 'right'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gf::sim
