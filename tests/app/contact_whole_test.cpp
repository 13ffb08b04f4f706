// Whether a finger's contact lies whole on the face it presses: closed-form outlines on a turned
// box's face and on a cylinder's cap, with and without Eq. 2's stretch.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "app/measures/contact_whole.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

constexpr double kTol = 1e-12;  // m

// A point contact on a box turned 90 degrees about y (local x along world -z, local z along
// world x): its overhang is the farther of |x| - hx and |z| - hz in the box's frame.
TEST(ContactWhole, PointOnATurnedBoxFace) {
  sim::BodyDesc box;
  box.shape = sim::ShapeKind::kBox;
  box.half_extents = Vec3(0.05, 0.02, 0.03);
  PressState s;
  s.body.orientation = sim::Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()));
  s.proxy = Vec3(0.02, 0.028, 0.045);  // local x -0.045, z 0.02
  s.device = s.proxy - Vec3(0.0, 0.005, 0.0);
  const sim::PatchSettings patch;
  EXPECT_NEAR(*contactOverhang(box, patch, Vec3::UnitY(), s), -0.005, kTol);
  s.proxy.z() = 0.052;  // local x -0.052: 2 mm over the edge
  EXPECT_NEAR(*contactOverhang(box, patch, Vec3::UnitY(), s), 0.002, kTol);
  // Pressed from below, the bottom face has the same outline.
  s.proxy.y() = -0.028;
  EXPECT_NEAR(*contactOverhang(box, patch, Vec3::UnitY(), s), 0.002, kTol);
}

// A patch on a cylinder's cap, the device 4 mm ahead of the proxy along +x: Eq. 2 stretches it
// to max_stretch r = 2 r behind (-x) and r / 2 ahead, so its outline reaches x = c - 2 r. With
// the stretch off it is a disc of radius r. Pressed on its curved side, no face is pressed.
TEST(ContactWhole, StretchedPatchOnACylinderCap) {
  sim::BodyDesc puck;
  puck.shape = sim::ShapeKind::kCylinder;
  puck.radius = 0.04;
  puck.half_height = 0.02;
  PressState s;
  s.proxy = Vec3(-0.02, 0.028, 0.0);
  s.device = s.proxy + Vec3(0.004, -0.005, 0.0);
  s.patch_radius = 0.0075;
  sim::PatchSettings patch;  // alpha 2, stretch_length 4 mm, max_stretch 2
  EXPECT_NEAR(*contactOverhang(puck, patch, Vec3::UnitY(), s), 0.035 - 0.04, 1e-9);
  patch.tangential_stretch = false;
  EXPECT_NEAR(*contactOverhang(puck, patch, Vec3::UnitY(), s), 0.0275 - 0.04, 1e-9);
  s.proxy = Vec3(0.048, 0.0, 0.0);
  EXPECT_FALSE(contactOverhang(puck, patch, Vec3::UnitX(), s).has_value());
  EXPECT_TRUE(hasFlatFaces(sim::ShapeKind::kBox));
  EXPECT_FALSE(hasFlatFaces(sim::ShapeKind::kSphere));
}

}  // namespace
}  // namespace gf::app
