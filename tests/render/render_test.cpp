// PNG encoding, snapshot interpolation and the frame stream of a session.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <fstream>

#include "app/scene_file.hpp"
#include "app/screenshots.hpp"
#include "app/session.hpp"
#include "render/context.hpp"
#include "render/gpu.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "sim/snapshot.hpp"

namespace gf {
namespace {

namespace fs = std::filesystem;

TEST(Png, RoundTripsExactly) {
  render::Image image{37, 11, {}};
  for (int i = 0; i < 37 * 11 * 3; ++i) image.rgb.push_back(static_cast<std::uint8_t>((i * 7919) % 251));
  const fs::path path = fs::temp_directory_path() / "gf_png_roundtrip.png";
  render::writePng(path.string(), image);
  const render::Image back = render::readPng(path.string());
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.rgb, image.rgb);
}

TEST(Png, ReadingAMissingFileNamesIt) {
  try {
    render::readPng("/nonexistent/golden.png");
    FAIL() << "no error";
  } catch (const render::ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/golden.png"), std::string::npos);
  }
}

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
  c.point = sim::Vec3(3, 0, 0);  // 1 m from the body centre along x, in b's pose
  sim::interpolateSnapshot(a, b, 1.5, out);
  EXPECT_DOUBLE_EQ(out.time, 1.5);
  EXPECT_NEAR(out.bodies[0].position.x(), 1.0, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(out.bodies[0].orientation).angle(), 0.5, 1e-12);
  EXPECT_NEAR(out.fingers[0].proxy.y(), 2.0, 1e-12);
  // Body frame: R(-1) (1, 0, 0); carried to the halfway pose: centre + R(0.5) R(-1) (1, 0, 0).
  const sim::Vec3 expected = sim::Vec3(1, 0, 0) + Eigen::AngleAxisd(-0.5, sim::Vec3::UnitY()) * sim::Vec3(1, 0, 0);
  EXPECT_NEAR((out.fingers[0].contacts[0].point - expected).norm(), 0.0, 1e-12);
}

// A 0.5 s offline session gives a frame at every 1/60 s (t = 0 included), close-ups beside
// the contact JSON, and the overlay's scripted clicks change the running simulation.
TEST(Session, WritesEveryFrameAndAppliesScriptedInput) {
  const std::vector<std::string> overrides = {"duration=0.6", "record.contacts=[0.4]", "render.width=320",
      "render.height=180",
      "render.actions=[{t = 0.3, widget = \"left/god_finger\", value = \"off\"}]"};
  app::SessionDesc s =
      app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/overlay-demo.toml", overrides);
  const fs::path out = fs::temp_directory_path() / "gf_render_session";
  fs::remove_all(out);
  app::SessionOptions options;
  options.out_dir = out.string();
  options.progress = false;
  options.frames = true;
  app::runSession(s, options);
  int frames = 0;
  for (const auto& e : fs::directory_iterator(out / "frames")) frames += e.path().extension() == ".png";
  EXPECT_EQ(frames, 37);  // k / 60 s for k = 0..36
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400.json"));
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400-left.png"));
  EXPECT_TRUE(fs::exists(out / "contacts" / "t0.400-right.png"));
  const render::Image frame = render::readPng((out / "frames" / "000036.png").string());
  EXPECT_EQ(frame.width, 320);
  EXPECT_EQ(frame.height, 180);
  std::ifstream in(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  ASSERT_EQ(summary["overlay_changes"].size(), 1u);
  EXPECT_EQ(summary["overlay_changes"][0]["finger"], "left");
  EXPECT_EQ(summary["overlay_changes"][0]["n_sgo"], 0);
  // The click lands on the frame after the press: (ceil(0.3 * 60) + 2) / 60 s.
  EXPECT_NEAR(summary["overlay_changes"][0]["t"].get<double>(), 20.0 / 60.0, 1e-3);
}

// Frames of fig8 at t = 4 s, 320 x 180, drawn by one renderer into framebuffers of each kind.
class Frames : public ::testing::Test {
 protected:
  Frames()
      : session_(app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml")),
        snapshot_(app::snapshotAt(session_, 4.0)),
        settings_(app::frameSettings(session_, {})),
        renderer_(session_.scene, settings_.scene) {}

  render::Image draw(render::Framebuffer& frame, const render::Camera& camera) {
    frame.bind();
    frame.resolve(renderer_.draw(snapshot_, camera, frame.width(), frame.height()));
    render::Image image;
    frame.read(image);
    return image;
  }
  render::Image draw(render::Antialiasing aa) {
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
  const render::Image none = draw(render::Antialiasing::kNone);
  for (const render::Antialiasing aa : {render::Antialiasing::kFxaa, render::Antialiasing::kMsaa}) {
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
    EXPECT_GT(share, 0.002) << render::antialiasingName(aa);
    EXPECT_LT(share, 0.08) << render::antialiasingName(aa);
    EXPECT_EQ(changed_corner, 0) << render::antialiasingName(aa);
  }
}

// The backdrop is cached per camera: drawing again gives the same frame, and a frame after a
// different camera's frame is the same as before (the cache was rebuilt for each view).
TEST_F(Frames, CachedBackdropFollowsTheCamera) {
  render::Framebuffer frame(kWidth, kHeight, render::Antialiasing::kFxaa);
  const render::Image first = draw(frame, settings_.camera);
  EXPECT_EQ(draw(frame, settings_.camera).rgb, first.rgb);
  render::Camera other = settings_.camera;
  other.position += sim::Vec3(0.05, 0.02, 0.0);
  const render::Image moved = draw(frame, other);
  EXPECT_NE(moved.rgb, first.rgb);
  EXPECT_EQ(draw(frame, settings_.camera).rgb, first.rgb);
}

}  // namespace
}  // namespace gf
