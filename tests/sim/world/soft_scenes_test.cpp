// Soft bodies in bundled scenes: the Fig. 8 contrast on a soft ball (two fingers pinch it under
// its centre and lift it: the god-finger's pads hold it still, the god-objects' points let it
// turn about the pinch axis), torsion on a soft disc (a pressing god-finger holds a torque that
// spins it under a god-object), and a sponge pressed to rest, by a flat or a round pad; on a
// soft plate, walk_fill's points along the walks. The sanitizer builds, about 20 times slower in
// the sparse solves, run each scene's first 0.3 s and check it stays finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/scene/settings.hpp"
#include "tests/scratch.hpp"
#include "tests/sim/angles.hpp"
#include "tests/sim/test_context.hpp"

namespace gf::test_support {
namespace {

#ifdef GF_UNDER_SANITIZER
constexpr bool kUnderSanitizer = true;
#else
constexpr bool kUnderSanitizer = false;
#endif

// Under the sanitizers: scene `name`'s first 0.3 s stays finite, no step undone or rolled back.
void checkStart(const std::string& name) {
  TestContext ctx(name);
  ctx.simulate(0.3);
  EXPECT_EQ(ctx.world().counters().nan_recoveries, 0);
  EXPECT_EQ(ctx.world().counters().soft_resets, 0);
  for (std::size_t b = 0; b < ctx.scene().bodies.size(); ++b) EXPECT_TRUE(ctx.world().bodyPose(static_cast<int>(b)).position.allFinite());
}

struct Pinch {
  double lift = 0.0;      // m: the ball's centre at the end above where it started
  double rotation = 0.0;  // deg: the largest turn from its orientation at 1 s (the grasp closed)
};

Pinch pinchBall(int n_sgo) {
  Pinch out;
  TestContext ctx("soft-ball-pinch", n_sgo);
  const int ball = indexOf(ctx.scene().bodies, "ball");
  double start = 0.0;
  Eigen::Quaterniond grasped = Eigen::Quaterniond::Identity();
  ctx.simulate(ctx.scene().duration, [&](const sim::World& w) {
    const sim::Pose p = w.bodyPose(ball);
    if (w.counters().steps == 1) start = p.position.y();
    if (std::abs(w.time() - 1.0) < 5e-4) grasped = p.orientation;
    if (w.time() > 1.0) out.rotation = std::max(out.rotation, Eigen::AngleAxisd(p.orientation * grasped.inverse()).angle() / test::kDeg);
    out.lift = p.position.y() - start;
  });
  std::printf("soft-ball-pinch n_sgo=%d: lifted %.4f m, turned at most %.2f deg\n", n_sgo, out.lift, out.rotation);
  return out;
}

TEST(SoftScenes, ASoftBallPinchedUnderItsCentreIsHeldByGodFingersAndTurnsUnderGodObjects) {
  if (kUnderSanitizer) return checkStart("soft-ball-pinch");
  const Pinch god_finger = pinchBall(8), god_object = pinchBall(0);
  EXPECT_GT(god_finger.lift, 0.045) << "the devices lift 5 cm";
  EXPECT_LT(god_finger.rotation, 2.0) << "the pads' friction holds the ball's weight's torque";
  EXPECT_GT(god_object.rotation, 45.0) << "two points: nothing holds a turn about the pinch axis";
}

// The disc's largest turn about the vertical from its orientation when the torque starts (deg).
double twist(int n_sgo) {
  TestContext ctx("soft-cylinder-twist", n_sgo);
  const int disc = indexOf(ctx.scene().bodies, "cylinder");
  Eigen::Quaterniond start = Eigen::Quaterniond::Identity();
  double turned = 0.0;
  ctx.simulate(ctx.scene().duration, [&](const sim::World& w) {
    const sim::Pose p = w.bodyPose(disc);
    if (std::abs(w.time() - 0.6) < 5e-4) start = p.orientation;
    if (w.time() > 0.6) turned = std::max(turned, Eigen::AngleAxisd(p.orientation * start.inverse()).angle() / test::kDeg);
  });
  std::printf("soft-cylinder-twist n_sgo=%d: turned at most %.2f deg\n", n_sgo, turned);
  return turned;
}

TEST(SoftScenes, APressingGodFingerHoldsATwistThatSpinsASoftDiscUnderAGodObject) {
  if (kUnderSanitizer) return checkStart("soft-cylinder-twist");
  EXPECT_LT(twist(8), 5.0) << "the pad's nodes' friction holds 4 mN m";
  EXPECT_GT(twist(0), 90.0) << "one point holds no torque about its normal";
}

// The sponge pressed and held: the surface under the finger sank, the pad presses nodes, the
// coupling pushes with more than 1 N, every step finite and none undone. (It does not come to
// rest: its nodes' friction on the table chatters; docs/soft-bodies.md, "Limits found".)
TEST(SoftScenes, APressedSpongeIndentsUnderThePadAndStaysFinite) {
  if (kUnderSanitizer) return checkStart("soft-sponge-press");
  TestContext ctx("soft-sponge-press");
  ctx.simulate(ctx.scene().duration);
  sim::Snapshot snap;
  ctx.world().snapshot(snap);
  ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
  const sim::ContactSnapshot& c = snap.fingers[0].contacts[0];
  const double pushed = -ctx.world().couplingForce(0).y();  // the coupling pushes the proxy down
  std::printf("soft-sponge-press: coupling %.4f N, contact %.4f N, indentation %.5f m, %zu nodes\n", pushed, -c.force.y(), c.indentation,
              c.sgos_world.size());
  EXPECT_GT(pushed, 1.0);
  EXPECT_GT(c.indentation, 0.001) << "the surface under the finger sank";
  EXPECT_GE(c.sgos_world.size(), 1u) << "the pad presses nodes";
  EXPECT_EQ(ctx.world().counters().soft_resets, 0);
  EXPECT_EQ(ctx.world().counters().nan_recoveries, 0);
}

// The pad's imprint: pressed at 1.5 s, the sponge's nodes that carry a load lie on the flat
// pad's plane (through the proxy's lowest point across the contact normal) with `imprint` flat,
// on the proxy's sphere with `imprint` round, each to within 0.3 mm (the contacts' springs give
// under their loads); the round dent is a bowl, its loaded nodes spread over more than 0.3 mm
// in depth (a round pad leaves the patch's rim untouched: its nodes carry nothing).
TEST(SoftScenes, AFlatImprintPressesThePadsPlaneARoundOneTheProxysSphere) {
  if (kUnderSanitizer) GTEST_SKIP() << "3 s of the sponge; its start is checked by APressedSpongeIndents...";
  for (const std::string imprint : {"flat", "round"}) {
    TestContext ctx("soft-sponge-press", kSceneSgo, {"fingers.index.imprint=" + imprint});
    ctx.simulate(1.5);
    sim::Snapshot snap;
    ctx.world().snapshot(snap);
    ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
    const sim::ContactSnapshot& c = snap.fingers[0].contacts[0];
    ASSERT_EQ(c.loads.size(), c.sgos_world.size());
    const sim::Vec3 centre = snap.fingers[0].proxy, n = c.outward_normal_world;
    const double radius = ctx.scene().fingers[0].proxy.radius;
    double off_plane = 0.0, off_sphere = 0.0, lowest = 1.0, highest = -1.0;
    int loaded = 0;
    for (std::size_t k = 0; k < c.sgos_world.size(); ++k) {
      if (!(c.loads[k].normal > 0.0)) continue;
      const sim::Vec3& p = c.sgos_world[k];
      const double height = (p - centre).dot(n) + radius;  // above the pad's plane
      off_plane = std::max(off_plane, std::abs(height));
      off_sphere = std::max(off_sphere, std::abs((p - centre).norm() - radius));
      lowest = std::min(lowest, height);
      highest = std::max(highest, height);
      ++loaded;
    }
    std::printf("soft-sponge-press imprint=%s: %d of %zu nodes loaded, off the plane %.5f m, off the sphere %.5f m, depths spread %.5f m\n",
                imprint.c_str(), loaded, c.sgos_world.size(), off_plane, off_sphere, highest - lowest);
    ASSERT_GE(loaded, 3) << imprint;
    if (imprint == "flat") {
      EXPECT_LT(off_plane, 3e-4);
    } else {
      EXPECT_LT(off_sphere, 3e-4);
      EXPECT_GT(highest - lowest, 3e-4) << "a round pad's dent is a bowl";
    }
    EXPECT_EQ(ctx.world().counters().soft_resets, 0);
  }
}

// walk_fill (Sec. 4.4's "new sub-god-objects regularly during the local geometry search"): a
// finger with four walks pressing a soft plate of 3 mm elements (pinned underneath); with
// walk_fill 1 mm the faces along each walk join the pad's, so it presses more of the surface
// under the patch than the walks' ends alone reach, every node within a fifth more of the
// walks' longest reach.
TEST(SoftScenes, WalkFillPressesMoreOfTheSurfaceUnderThePatch) {
  if (kUnderSanitizer) GTEST_SKIP() << "1.6 s of a 1 200-tetrahedron plate: about a minute under a sanitizer";
  const std::filesystem::path dir = gf::test::scratchRoot() / "soft_walk_fill";
  std::filesystem::create_directories(dir);
  const std::string scene = (dir / "plate.toml").string();
  std::ofstream(scene) << R"(name = "walk-fill-plate"
duration = 1.0
haptic_rate = 1000
effects = ["friction", "god_finger", "tangential_stretch", "angular_threshold", "friction_cone", "force_feedback"]
[bodies.plate]
shape = "soft_box"
half_extents = [0.015, 0.003, 0.015]
element_size = 0.003
young = 5e4
poisson = 0.3
mass = 0.005
friction = 1.0
pinned = [{ min = [-0.02, -0.004, -0.02], max = [0.02, -0.0029, 0.02] }]
position = [0.0, 0.003, 0.0]
[fingers.index]
n_sgo = 4
r_max = 0.009
d0 = 0.0005
friction = 1.0
[fingers.index.device]
interpolation = "smooth"
keyframes = [{ t = 0.0, p = [0.0, 0.02, 0.0] }, { t = 0.5, p = [0.0, 0.011, 0.0] }]
)";
  std::size_t pressed[2] = {0, 0};
  for (const int fill : {0, 1}) {
    TestContext ctx(scene, kSceneSgo, {fill ? "fingers.index.walk_fill=0.001" : "fingers.index.walk_fill=0"});
    ctx.simulate(0.8);
    sim::Snapshot snap;
    ctx.world().snapshot(snap);
    ASSERT_EQ(snap.fingers[0].contacts.size(), 1u);
    const sim::ContactSnapshot& c = snap.fingers[0].contacts[0];
    const sim::Vec3 n = c.outward_normal_world;
    const auto lateral = [&](const sim::Vec3& p) { return ((p - c.point_world) - (p - c.point_world).dot(n) * n).norm(); };
    double reach = 0.0;
    for (const sim::Vec3& p : c.path_points_world) reach = std::max(reach, lateral(p));
    pressed[fill] = c.sgos_world.size();
    for (const sim::Vec3& p : c.sgos_world) EXPECT_LE(lateral(p), 1.2 * reach + 1e-9) << "walk_fill " << fill;
    EXPECT_EQ(ctx.world().counters().soft_resets, 0);
    EXPECT_EQ(ctx.world().counters().nan_recoveries, 0);
  }
  std::printf("walk-fill-plate, 4 walks: %zu nodes pressed, %zu with walk_fill 1 mm\n", pressed[0], pressed[1]);
  EXPECT_GT(pressed[1], pressed[0]);
}

// What a scene may give a soft body is what it can take: a density outside its material's range
// is refused naming `mass`, a walk_fill below 0.1 mm naming `walk_fill`; a file's nodes that no
// tetrahedron uses (second-order elements' mid-edge nodes) are dropped, so the solve has none
// without mass or stiffness.
TEST(SoftDescriptions, DensityWalkFillAndUnusedNodes) {
  sim::BodyDesc b;
  b.name = "block";
  b.shape = sim::ShapeKind::kSoftBox;
  b.half_extents = sim::Vec3(0.01, 0.01, 0.01);
  b.soft.element_size = 0.01;
  b.soft.tets = sim::softMesh(b);
  b.mass = 0.1;  // 12 500 kg/m³ over 8 cm³
  const std::optional<sim::FieldError> heavy = sim::validateBody(b);
  ASSERT_TRUE(heavy.has_value());
  EXPECT_EQ(heavy->field, "mass");
  b.mass = 0.01;
  EXPECT_FALSE(sim::validateBody(b).has_value());
  sim::FingerDesc f;
  f.soft_walk_fill = 1e-9;
  const std::optional<sim::FieldError> fill = sim::validateFinger(f);
  ASSERT_TRUE(fill.has_value());
  EXPECT_EQ(fill->field, "walk_fill");
  f.soft_walk_fill = 0.0;
  const std::optional<sim::FieldError> off = sim::validateFinger(f);
  EXPECT_TRUE(!off || off->field != "walk_fill");

  const std::filesystem::path dir = gf::test::scratchRoot() / "soft_unused_nodes";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "t.node") << "5 3 0 0\n0 0 0 0\n1 0.01 0 0\n2 0 0.01 0\n3 0 0 0.01\n4 0.5 0.5 0.5\n";
  std::ofstream(dir / "t.ele") << "1 4 0\n0 0 1 2 3\n";
  sim::BodyDesc m;
  m.shape = sim::ShapeKind::kSoftMesh;
  m.soft.tet_path = (dir / "t.node").string();
  const std::shared_ptr<const sim::TetMesh> mesh = sim::softMesh(m);
  EXPECT_EQ(mesh->nodes.size(), 4u) << "the node no tetrahedron uses is dropped";
  EXPECT_EQ(mesh->surface.size(), 4u);
}

}  // namespace
}  // namespace gf::test_support
