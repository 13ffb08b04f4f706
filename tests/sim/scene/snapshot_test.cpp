// Snapshots: interpolation between two haptic steps for frames at exact times.
#include "sim/scene/snapshot.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace gf {
namespace {

// Halfway between two states: positions halfway, orientation the half rotation, and a patch
// point rides along with its body.
TEST(Snapshot, InterpolatesPosesAndCarriesPatches) {
  sim::Snapshot a, b, out;
  a.time = 1.0;
  b.time = 2.0;
  a.bodies.resize(1);
  b.bodies.resize(1);
  b.bodies[0].position = sim::Vec3(2, 0, 0);
  b.bodies[0].orientation = Eigen::AngleAxisd(1.0, sim::Vec3::UnitY());
  a.fingers.resize(1);
  b.fingers.resize(1);
  b.fingers[0].proxy = sim::Vec3(0, 4, 0);
  sim::ContactSnapshot& c = b.fingers[0].contacts.emplace_back();
  c.body = 0;
  c.point_world = sim::Vec3(3, 0, 0);  // 1 m from the body centre along x, in b's pose
  sim::interpolateSnapshot(a, b, 1.5, out);
  EXPECT_DOUBLE_EQ(out.time, 1.5);
  EXPECT_NEAR(out.bodies[0].position.x(), 1.0, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(out.bodies[0].orientation).angle(), 0.5, 1e-12);
  EXPECT_NEAR(out.fingers[0].proxy.y(), 2.0, 1e-12);
  // Body frame: R(-1) (1, 0, 0); carried to the halfway pose: centre + R(0.5) R(-1) (1, 0, 0).
  const sim::Vec3 expected = sim::Vec3(1, 0, 0) + Eigen::AngleAxisd(-0.5, sim::Vec3::UnitY()) * sim::Vec3(1, 0, 0);
  EXPECT_NEAR((out.fingers[0].contacts[0].point_world - expected).norm(), 0.0, 1e-12);
}

// A device's orientation is slerped: a third of the way from flat to 90 degrees about x is 30
// degrees about x.
TEST(Snapshot, SlerpsTheDeviceOrientation) {
  sim::Snapshot a, b, out;
  a.time = 0.0;
  b.time = 3.0;
  a.fingers.resize(1);
  b.fingers.resize(1);
  b.fingers[0].device_orientation = Eigen::AngleAxisd(0.5 * std::numbers::pi, sim::Vec3::UnitX());
  sim::interpolateSnapshot(a, b, 1.0, out);
  const Eigen::AngleAxisd turn(out.fingers[0].device_orientation);
  EXPECT_NEAR(turn.angle(), std::numbers::pi / 6.0, 1e-12);
  EXPECT_NEAR((turn.axis() - sim::Vec3::UnitX()).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace gf
