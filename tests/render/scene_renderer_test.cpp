// Frames drawn by the scene renderer: anti-aliasing and the cached backdrop.
#include "render/scene_renderer.hpp"

#include <gtest/gtest.h>

#include "app/scene/scene_file.hpp"
#include "app/session/screenshots.hpp"
#include "app/session/session.hpp"
#include "render/context.hpp"
#include "render/gpu.hpp"
#include "render/image.hpp"

namespace gf {
namespace {

// Frames of fig8 at t = 4 s, 320 x 180, drawn by one renderer into framebuffers of each kind.
class Frames : public ::testing::Test {
 protected:
  Frames()
      : session_(app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml")),
        snapshot_(app::snapshotAt(session_, 4.0)),
        settings_(app::frameSettings(session_, {})),
        renderer_(session_.scene, settings_.scene) {}

  render::Image draw(render::Framebuffer& frame, const sim::Camera& camera) {
    frame.bind();
    frame.resolve(renderer_.draw(snapshot_, camera, frame.width(), frame.height()));
    render::Image image;
    frame.read(image);
    return image;
  }
  render::Image draw(sim::Antialiasing aa) {
    render::Framebuffer frame(kWidth, kHeight, aa);
    return draw(frame, settings_.camera);
  }

  static constexpr int kWidth = 320, kHeight = 180;
  render::GlContext context_;
  app::SessionDesc session_;
  sim::Snapshot snapshot_;
  render::FrameOutputSettings settings_;
  render::SceneRenderer renderer_;
};

// Anti-aliasing only touches pixels at edges: a few percent of the frame change, and none in
// the top-left corner (sky and far ground, where the frame has no geometric edge).
TEST_F(Frames, AntialiasingChangesOnlyEdgePixels) {
  const render::Image none = draw(sim::Antialiasing::kNone);
  for (const sim::Antialiasing aa : {sim::Antialiasing::kFxaa, sim::Antialiasing::kMsaa}) {
    const render::Image smooth = draw(aa);
    ASSERT_EQ(smooth.rgb.size(), none.rgb.size());
    int changed = 0, changed_corner = 0;
    for (std::size_t i = 0; i < none.rgb.size(); i += 3) {
      const bool differs = std::abs(int(none.rgb[i]) - int(smooth.rgb[i])) > 2 ||
                           std::abs(int(none.rgb[i + 1]) - int(smooth.rgb[i + 1])) > 2 ||
                           std::abs(int(none.rgb[i + 2]) - int(smooth.rgb[i + 2])) > 2;
      changed += differs;
      const std::size_t x = i / 3 % kWidth, y = i / 3 / kWidth;
      changed_corner += differs && x < kWidth / 4 && y < kHeight / 2;
    }
    const double share = double(changed) / (kWidth * kHeight);
    EXPECT_GT(share, 0.002) << sim::antialiasingName(aa);
    EXPECT_LT(share, 0.08) << sim::antialiasingName(aa);
    EXPECT_EQ(changed_corner, 0) << sim::antialiasingName(aa);
  }
}

// The backdrop is cached per camera: drawing again gives the same frame, and a frame after a
// different camera's frame is the same as before (the cache was rebuilt for each view).
TEST_F(Frames, CachedBackdropFollowsTheCamera) {
  render::Framebuffer frame(kWidth, kHeight, sim::Antialiasing::kFxaa);
  const render::Image first = draw(frame, settings_.camera);
  EXPECT_EQ(draw(frame, settings_.camera).rgb, first.rgb);
  sim::Camera other = settings_.camera;
  other.position += sim::Vec3(0.05, 0.02, 0.0);
  const render::Image moved = draw(frame, other);
  EXPECT_NE(moved.rgb, first.rgb);
  EXPECT_EQ(draw(frame, settings_.camera).rgb, first.rgb);
}

}  // namespace
}  // namespace gf
