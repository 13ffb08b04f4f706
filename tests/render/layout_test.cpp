// Where a frame's labels go (render/overlay/layout.hpp), without GL: the corner arithmetic, the
// placement's rules (clear corners first, no jump while clear), and every bundled scene's frames
// from its own camera: the insets' block and the time stamp, placed as the render thread places
// them, cover no body, proxy, force arrow or patch (their screen boxes from the scene's render
// surfaces).
#include "render/overlay/layout.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "render/overlay/labels.hpp"
#include "render/overlay/patch_insets.hpp"
#include "render/scene/geometry.hpp"
#include "tests/render/still_layout.hpp"
#include "sim/world/world.hpp"

namespace gf::render {
namespace {

constexpr int kWidth = 1280, kHeight = 720;
// s of each scene's run looked at: live-view and device-udp hold their devices still for minutes
// after; the sanitizer builds, whose steps are ten times slower, look at the first 2 s (the
// release build checks the rest; the placement is arithmetic, the same in both).
#ifdef GF_UNDER_SANITIZER
constexpr double kLongestRun = 2.0;
#else
constexpr double kLongestRun = 10.0;
#endif

TEST(Layout, CornerBoxesSitTheirMarginInsideThePicture) {
  const ScreenBox br = cornerBox(Corner::kBottomRight, 100, 50, kWidth, kHeight, 10);
  EXPECT_EQ(br.x1, kWidth - 10);
  EXPECT_EQ(br.y1, kHeight - 10);
  EXPECT_EQ(br.x0, kWidth - 110);
  const ScreenBox tl = cornerBox(Corner::kTopLeft, 100, 50, kWidth, kHeight, 10);
  EXPECT_EQ(tl.x0, 10);
  EXPECT_EQ(tl.y0, 10);
  EXPECT_EQ(ScreenBox({0, 0, 10, 10}).overlap({5, 5, 20, 20}), 25.0f);
  EXPECT_EQ(ScreenBox({0, 0, 10, 10}).overlap({10, 0, 20, 10}), 0.0f) << "touching is not covering";
}

TEST(Layout, LabelsGoToClearCornersAndStayWhileClear) {
  LabelSizes sizes;
  sizes.insets_w = 400, sizes.insets_h = 300, sizes.stamp_w = 200, sizes.stamp_h = 40, sizes.margin = 10;
  // Nothing in the way: the defaults, the insets bottom right and the stamp bottom left.
  LabelPlacement p = placeLabels({}, sizes, kWidth, kHeight, {});
  EXPECT_EQ(p.insets, Corner::kBottomRight);
  EXPECT_EQ(p.stamp, Corner::kBottomLeft);
  // A body in the bottom-right corner sends the insets to the next clear corner (bottom left),
  // and the stamp out of their way.
  const std::vector<ScreenBox> body = {{1000, 500, 1200, 700}};
  p = placeLabels(body, sizes, kWidth, kHeight, {});
  EXPECT_EQ(p.insets, Corner::kBottomLeft);
  EXPECT_EQ(p.stamp, Corner::kTopLeft);
  for (const ScreenBox& b : placedBoxes(p, sizes, kWidth, kHeight)) EXPECT_EQ(b.overlap(body[0]), 0.0f);
  // Once the body has left, they stay where they are (a video's labels do not jump back).
  const LabelPlacement kept = placeLabels({}, sizes, kWidth, kHeight, p);
  EXPECT_EQ(kept.insets, p.insets);
  EXPECT_EQ(kept.stamp, p.stamp);
  // Beside the overlay's panel the insets keep to the bottom left, covered or not.
  const LabelPlacement beside = placeLabels({{20, 400, 300, 700}}, sizes, kWidth, kHeight, {}, {false, true, false, false});
  EXPECT_EQ(beside.insets, Corner::kBottomLeft);
  // A subject across the middle that a row touches in every corner: the insets stand in a column
  // at the side.
  LabelSizes with_column = sizes;
  with_column.column_w = 200, with_column.column_h = 600;
  const LabelPlacement column = placeLabels({{250, 100, 1000, 650}}, with_column, kWidth, kHeight, {});
  EXPECT_TRUE(column.column);
  EXPECT_EQ(column.insets, Corner::kBottomRight);
  EXPECT_EQ(placedBoxes(column, with_column, kWidth, kHeight)[0].overlap({250, 100, 1000, 650}), 0.0f);
  // Covered everywhere: the corner that covers least.
  const std::vector<ScreenBox> big = {{0, 0, kWidth, 600}, {0, 600, 700, kHeight}};
  EXPECT_EQ(placeLabels(big, sizes, kWidth, kHeight, {}).insets, Corner::kBottomRight);
}

TEST(Layout, ATopCornersInsetsKeepRoomForTheirCaptions) {
  const std::vector<InsetRect> top = insetRects(kWidth, kHeight, 2, InsetCorner::kTopRight);
  const LabelSizes block = insetBlock(kWidth, kHeight, 2);
  ASSERT_EQ(top.size(), 2u);
  // The block's box, captions included, holds the squares, flush with its bottom.
  const ScreenBox box = cornerBox(Corner::kTopRight, block.insets_w, block.insets_h, kWidth, kHeight, block.margin);
  EXPECT_FLOAT_EQ(static_cast<float>(top[0].y + top[0].size), box.y1);
  EXPECT_FLOAT_EQ(static_cast<float>(top.back().x + top.back().size), box.x1);
  EXPECT_GE(static_cast<float>(top[0].y) - box.y0, insetCaptionReserve(contactLabelPx(top[0].size)) - 1.0f);
}

// The bundled scenes (assets/scenes/*.toml), sorted.
std::vector<std::string> bundledScenes() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(GF_SOURCE_DIR) + "/assets/scenes")) {
    if (e.path().extension() == ".toml") names.push_back(e.path().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Every bundled scene from its default camera, one frame every 0.1 s of its run (up to
// kLongestRun), at its own frame settings: the labels placed as the render thread places them
// (the insets with patch_insets, the stamp without the overlay, the insets beside the overlay's
// panel with it) cover none of the frame's subjects.
TEST(Layout, NoLabelCoversABodyInTheBundledScenesFrames) {
#if defined(__SANITIZE_THREAD__)
  // ThreadSanitizer steps the scenes' physics (the soft bodies' solves above all) past the
  // test's 600 s; this test has no threads of its own, and the release and AddressSanitizer
  // builds run it.
  GTEST_SKIP() << "the scenes' physics is too slow under ThreadSanitizer; release and asan-ubsan run this";
#endif
  const std::vector<std::string> scenes = bundledScenes();
  ASSERT_GE(scenes.size(), 20u);
  int frames = 0;
  for (const std::string& path : scenes) {
    const app::SessionDesc session = app::loadSceneFile(path);
    const sim::SceneDesc& scene = session.scene;
    const FrameOutputSettings settings = app::frameSettings(session, {});
    const std::vector<std::shared_ptr<const sim::Mesh>> surfaces = test::renderSurfaces(scene);
    sim::World world(scene);
    const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(scene);
    std::vector<sim::DeviceSample> samples(devices.size());
    const double dt = 1.0 / scene.world.haptic_rate_hz;
    LabelPlacement placement;
    sim::Snapshot snap;
    for (double next = 0.0; next <= std::min(scene.duration, kLongestRun) + 1e-9; next += 0.1) {
      while (world.time() < next - 0.5 * dt) {
        for (std::size_t i = 0; i < devices.size(); ++i) samples[i] = devices[i].sample(world.time());
        world.step(dt, samples);
      }
      world.snapshot(snap);
      // The subjects and placement as the render thread makes them (tests/render/still_layout.hpp).
      const test::StillLayout layout = test::stillLayout(scene, surfaces, snap, settings, placement);
      placement = layout.placement;
      const std::vector<ScreenBox>& subjects = layout.subjects;
      const std::array<ScreenBox, 2> placed = placedBoxes(placement, layout.sizes, settings.width, settings.height);
      for (int k = 0; k < 2; ++k) {
        if (k == 0 && !settings.patch_insets) continue;
        if (k == 1 && (settings.overlay || !settings.time_stamp)) continue;
        for (const ScreenBox& s : subjects) {
          EXPECT_EQ(placed[k].overlap(s), 0.0f)
              << path << " t = " << snap.time << ": the " << (k == 0 ? "insets" : "stamp") << " [" << placed[k].x0 << ", "
              << placed[k].y0 << ", " << placed[k].x1 << ", " << placed[k].y1 << "] cover a subject [" << s.x0 << ", " << s.y0
              << ", " << s.x1 << ", " << s.y1 << "]";
        }
      }
      ++frames;
    }
  }
  std::printf("%d frames of %zu scenes checked\n", frames, scenes.size());
  EXPECT_GT(frames, kLongestRun > 5.0 ? 500 : 200);
}

}  // namespace
}  // namespace gf::render
