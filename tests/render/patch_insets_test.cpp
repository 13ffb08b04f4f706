// The patch_insets effect's geometry, without GL: where each finger's inset goes in a frame, and
// the close-up view of one finger's contact (its contacts alone, the camera down the normal).
#include "render/overlay/patch_insets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "sim/world/world.hpp"

namespace gf::render {
namespace {

TEST(PatchInsets, SquaresSitInABottomCornerInFingerOrderWithoutOverlapping) {
  for (const InsetCorner corner : {InsetCorner::kBottomRight, InsetCorner::kBottomLeft}) {
    for (const auto& [w, h, n] : {std::tuple{1280, 720, 2}, std::tuple{640, 360, 1}, std::tuple{640, 360, 4},
                                 std::tuple{200, 720, 3}}) {
      const std::vector<InsetRect> r = insetRects(w, h, n, corner);
      ASSERT_EQ(r.size(), static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        EXPECT_GE(r[i].x, 0);
        EXPECT_LE(r[i].x + r[i].size, w);
        EXPECT_EQ(r[i].y + r[i].size + std::max(2, static_cast<int>(std::lround(0.015 * h))), h);  // the margin
        EXPECT_LE(r[i].size, static_cast<int>(std::lround(0.3 * h)));
        if (i > 0) {
          EXPECT_GT(r[i].x, r[i - 1].x + r[i - 1].size);
        }
      }
      const bool right = corner == InsetCorner::kBottomRight;
      EXPECT_EQ(right ? w - (r.back().x + r.back().size) : r.front().x, std::max(2, static_cast<int>(std::lround(0.015 * h))));
    }
  }
  EXPECT_EQ(insetRects(1280, 720, 2, InsetCorner::kBottomRight)[0].size, 216);
  EXPECT_TRUE(insetRects(1280, 720, 0, InsetCorner::kBottomRight).empty());
}

TEST(PatchInsets, TheCloseUpLooksDownTheNormalAtOneFingersContact) {
  const app::SessionDesc session = app::loadSceneFile(app::resolveScenePath("fig8-pinch-oscillation"));
  sim::World world(session.scene);
  const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(session.scene);
  std::vector<sim::DeviceSample> samples(devices.size());
  sim::Snapshot before;
  world.snapshot(before);
  sim::Snapshot only;
  view::Camera camera;
  EXPECT_FALSE(contactCloseUp(session.scene, before, 0, only, camera)) << "nothing touched at t = 0";
  for (int k = 0; k < 800; ++k) {  // squeezing
    for (std::size_t i = 0; i < devices.size(); ++i) samples[i] = devices[i].sample(world.time());
    world.step(0.001, samples);
  }
  sim::Snapshot snap;
  world.snapshot(snap);
  for (std::size_t f = 0; f < 2; ++f) {
    ASSERT_TRUE(contactCloseUp(session.scene, snap, f, only, camera)) << f;
    const sim::ContactSnapshot& c = snap.fingers[f].contacts.front();
    EXPECT_EQ(only.fingers[f].contacts.size(), snap.fingers[f].contacts.size());
    EXPECT_TRUE(only.fingers[1 - f].contacts.empty());
    EXPECT_LT((camera.target - c.point_world).norm(), 1e-12);
    EXPECT_GT((camera.position - camera.target).normalized().dot(c.outward_normal_world), 1.0 - 1e-9);
    // The view holds r_max with a margin: half its height at the target is at least 1.5 r_max.
    const double half = (camera.position - camera.target).norm() * std::tan(0.5 * camera.fov_deg * M_PI / 180.0);
    EXPECT_GE(half, 1.5 * session.scene.fingers[f].patch.r_max);
  }
}

}  // namespace
}  // namespace gf::render
