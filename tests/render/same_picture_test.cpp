// Frames that draw what the frame before drew: which snapshot changes count
// (render/state/same_picture.hpp), and that a kept bodies' layer, shadow map or whole picture
// gives the frame a fresh draw gives.
#include "render/state/same_picture.hpp"
#include "render/state/view_layers.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "app/compare/screenshots.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "render/frames/image.hpp"
#include "render/frames/image_compare.hpp"
#include "render/gl/context.hpp"
#include "render/gl/gpu.hpp"
#include "render/render_thread.hpp"
#include "render/state/contact_load.hpp"
#include "render/scene/scene_renderer.hpp"
#include "tests/scratch.hpp"

namespace gf {
namespace {

// The Fig. 8 pinch held at 4 s: two contacts with eight SGOs each and their loads.
class SamePicture : public ::testing::Test {
 protected:
  SamePicture()
      : session_(app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml")),
        snapshot_(app::snapshotAt(session_, 4.0)) {}
  sim::ContactSnapshot& contact(sim::Snapshot& s) { return s.fingers.front().contacts.front(); }

  app::SessionDesc session_;
  sim::Snapshot snapshot_;
};

TEST_F(SamePicture, TheHeldPinchHasLoadsToCompare) {
  ASSERT_EQ(snapshot_.fingers.size(), 2u);
  const sim::ContactSnapshot& c = snapshot_.fingers.front().contacts.front();
  ASSERT_EQ(c.sgos_world.size(), 8u);
  ASSERT_EQ(c.loads.size(), 8u);
}

// What the labels draw (time, step) and what nothing draws (velocities, timings) do not count.
TEST_F(SamePicture, TimeStepVelocitiesAndTimingsDoNotCount) {
  sim::Snapshot later = snapshot_;
  later.time += 1.0;
  later.step += 1000;
  later.nan_recoveries += 1;
  later.timings.step_median_us = 99.0;
  later.timings.late_steps = 7;
  for (auto& v : later.body_velocities) v.first += sim::Vec3(1.0, 0.0, 0.0);
  EXPECT_TRUE(render::drawsTheSame(snapshot_, later, false));
  EXPECT_TRUE(render::drawsTheSame(snapshot_, later, true));
  EXPECT_TRUE(render::samePlaces(snapshot_, later));
}

// A body, a proxy or an SGO moved by twice the tolerance is a new picture and, but for the SGO,
// new places (the shadow map and the bodies' layer); half the tolerance is not.
TEST_F(SamePicture, AMoveBeyondANanometreCounts) {
  const double tol = render::kSamePictureTolerance;
  for (const double step : {0.5 * tol, 2.0 * tol}) {
    const bool same = step < tol;
    sim::Snapshot body = snapshot_, proxy = snapshot_, sgo = snapshot_;
    body.bodies.back().position.y() += step;
    proxy.fingers.back().proxy.x() += step;
    contact(sgo).sgos_world[3].z() += step;
    EXPECT_EQ(render::drawsTheSame(snapshot_, body, false), same) << step;
    EXPECT_EQ(render::samePlaces(snapshot_, body), same) << step;
    EXPECT_EQ(render::drawsTheSame(snapshot_, proxy, false), same) << step;
    EXPECT_EQ(render::samePlaces(snapshot_, proxy), same) << step;
    EXPECT_EQ(render::drawsTheSame(snapshot_, sgo, false), same) << step;
    EXPECT_TRUE(render::samePlaces(snapshot_, sgo)) << step;
  }
  sim::Snapshot turned = snapshot_;
  turned.bodies.back().orientation =
      turned.bodies.back().orientation * sim::Quat(Eigen::AngleAxisd(1e-6, sim::Vec3::UnitY()));
  EXPECT_FALSE(render::drawsTheSame(snapshot_, turned, false));
  EXPECT_FALSE(render::samePlaces(snapshot_, turned));
}

// Loads count relative to their size: 1e-5 of an SGO's normal load does not, 1e-4 does; so does
// the coupling force (the arrow) and a contact the other finger lost.
TEST_F(SamePicture, LoadsCountRelativeToTheirSize) {
  for (const double share : {0.25 * render::kSameLoadShare, 2.5 * render::kSameLoadShare}) {
    const bool same = share < render::kSameLoadShare;
    sim::Snapshot pressed = snapshot_, arrow = snapshot_;
    contact(pressed).loads[2].normal *= 1.0 + share;
    arrow.fingers.front().feedback_force *= 1.0 + share;
    EXPECT_EQ(render::drawsTheSame(snapshot_, pressed, false), same) << share;
    EXPECT_EQ(render::drawsTheSame(snapshot_, arrow, false), same) << share;
    EXPECT_TRUE(render::samePlaces(snapshot_, pressed));
  }
  sim::Snapshot lost = snapshot_;
  lost.fingers.back().contacts.clear();
  EXPECT_FALSE(render::drawsTheSame(snapshot_, lost, false));
  EXPECT_TRUE(render::samePlaces(snapshot_, lost));
  sim::Snapshot slipping = snapshot_;
  contact(slipping).loads[0].slipping = !contact(slipping).loads[0].slipping;
  EXPECT_FALSE(render::drawsTheSame(snapshot_, slipping, false));
}

// Without load arrows a point's friction is seen only through the torsion arc: friction along
// the SGO's lever from the centre of pressure turns nothing and draws the same; friction across
// it changes the torsion and does not. With load arrows both count.
TEST_F(SamePicture, FrictionCountsThroughTheTorsionWithoutLoadArrows) {
  sim::Snapshot along = snapshot_, across = snapshot_;
  sim::ContactSnapshot& a = contact(along);
  const sim::Vec3 n = a.outward_normal_world;
  const sim::Vec3 lever = a.sgos_world[1] - render::pressureCentre(a);
  const sim::Vec3 radial = (lever - lever.dot(n) * n).normalized();
  a.loads[1].tangential += 0.05 * radial;
  contact(across).loads[1].tangential += 0.05 * n.cross(radial);
  EXPECT_NEAR(render::contactTorsion(a), render::contactTorsion(contact(snapshot_)), 1e-15);
  EXPECT_TRUE(render::drawsTheSame(snapshot_, along, false));
  EXPECT_FALSE(render::drawsTheSame(snapshot_, along, true));
  EXPECT_FALSE(render::drawsTheSame(snapshot_, across, false));
  EXPECT_FALSE(render::drawsTheSame(snapshot_, across, true));
}

// Not a number is never the same: a frame of a state gone bad is drawn again.
TEST_F(SamePicture, NotANumberIsNeverTheSame) {
  sim::Snapshot bad = snapshot_;
  bad.bodies.back().position.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(render::drawsTheSame(bad, bad, false));
  EXPECT_FALSE(render::samePlaces(bad, bad));
}

// The renderer keeps the shadow map and the bodies' layer while nothing moves: the second and
// third draws of a held state (reusing them) equal the first, and a state in which everything
// then moved is drawn anew: as a renderer that drew the held state once (kept nothing) draws it.
// (A renderer that drew nothing before differs from both by one level in 22 of the 57 600
// pixels: a renderer's earlier draws leave traces of their own, reuse or not.)
TEST_F(SamePicture, KeptLayersDrawWhatAFreshDrawDraws) {
  render::GlContext context;
  const render::FrameOutputSettings settings = app::frameSettings(session_, {});
  const auto draw = [&](render::SceneRenderer& renderer, const sim::Snapshot& s) {
    render::Framebuffer frame(320, 180, settings.antialiasing);
    frame.bind();
    frame.resolve(renderer.draw(s, settings.camera, 320, 180));
    render::Image image;
    frame.read(image);
    return image;
  };
  render::SceneRenderer kept(session_.scene, settings.scene);
  const render::Image first = draw(kept, snapshot_);
  sim::Snapshot later = snapshot_;
  later.time += 0.5;
  later.step += 500;
  EXPECT_EQ(draw(kept, later).rgb, first.rgb);  // layer kept from this draw
  EXPECT_EQ(draw(kept, later).rgb, first.rgb);  // layer restored
  sim::Snapshot moved = later;
  for (sim::Pose& p : moved.bodies) p.position.x() += 0.004;
  for (sim::FingerSnapshot& f : moved.fingers) {
    f.proxy.x() += 0.004;
    f.device.x() += 0.004;
    for (sim::ContactSnapshot& c : f.contacts) {
      c.point_world.x() += 0.004;
      for (sim::Vec3& p : c.sgos_world) p.x() += 0.004;
      for (sim::Vec3& p : c.path_points_world) p.x() += 0.004;
    }
  }
  const render::Image after = draw(kept, moved);
  EXPECT_NE(after.rgb, first.rgb);
  render::SceneRenderer once(session_.scene, settings.scene);
  draw(once, snapshot_);
  const render::ImageDifference d = render::compareImages(after, draw(once, moved), 0);
  EXPECT_EQ(d.differing_share, 0.0) << d.max_channel_difference;
}

// Each view keeps its own slot: two insets of one size with different cameras, the frame and a
// close-up, each drawn again with its camera (or one moved by solver jitter, 1e-12 m) finds its
// slot as it left it; a fifth view takes the least recently used slot of its size.
TEST(ViewLayers, EachViewKeepsItsSlot) {
  render::GlContext context;
  render::ViewLayers layers;
  view::Camera frame, inset_a, inset_b, close_up;
  inset_a.position = sim::Vec3(0.1, 0.0, 0.0);
  inset_b.position = sim::Vec3(-0.1, 0.0, 0.0);
  close_up.position = sim::Vec3(0.0, 0.2, 0.0);
  bool stale = false;
  render::ViewSlot* a = &layers.slotFor(inset_a, 216, 216, 1, false, stale);
  EXPECT_TRUE(stale);
  render::ViewSlot* f = &layers.slotFor(frame, 1280, 720, 1, true, stale);
  EXPECT_TRUE(stale);
  render::ViewSlot* b = &layers.slotFor(inset_b, 216, 216, 1, false, stale);
  EXPECT_TRUE(stale);
  EXPECT_NE(a, b);
  render::ViewSlot* c = &layers.slotFor(close_up, 480, 480, 1, false, stale);
  EXPECT_TRUE(stale);
  for (int round = 0; round < 3; ++round) {
    view::Camera jittered = inset_a;
    jittered.target.x() += 1e-12;
    EXPECT_EQ(&layers.slotFor(jittered, 216, 216, 1, false, stale), a);
    EXPECT_FALSE(stale);
    EXPECT_EQ(&layers.slotFor(frame, 1280, 720, 1, true, stale), f);
    EXPECT_FALSE(stale);
    EXPECT_EQ(&layers.slotFor(inset_b, 216, 216, 1, false, stale), b);
    EXPECT_FALSE(stale);
    EXPECT_EQ(&layers.slotFor(close_up, 480, 480, 1, false, stale), c);
    EXPECT_FALSE(stale);
  }
  view::Camera moved = inset_a;
  moved.position.y() += 0.001;  // inset A's contact moved: A's slot, the older of the two
  EXPECT_EQ(&layers.slotFor(inset_b, 216, 216, 1, false, stale), b);
  EXPECT_EQ(&layers.slotFor(moved, 216, 216, 1, false, stale), a);
  EXPECT_TRUE(stale);
}

// A whole frame (insets, labels, stamp) of a held state equals the frame renderStill draws of
// it, whether the render thread drew the scene or reused its picture: a run's frames 2 and 3 of
// the same state against a still of each.
TEST_F(SamePicture, AReusedPictureGivesTheFrameAStillGives) {
  render::FrameOutputSettings settings = app::frameSettings(session_, {});
  settings.width = 480;
  settings.height = 270;
  struct Keep : render::FrameTap {
    std::vector<render::Image> frames;
    void frame(const render::Image& image, const sim::Snapshot&, float) noexcept override { frames.push_back(image); }
  } tap;
  settings.tap = &tap;
  std::vector<sim::Snapshot> states(3, snapshot_);
  for (int k = 0; k < 3; ++k) states[k].time = 4.0 + k / 60.0;
  render::RenderStats stats;
  {
    render::RenderThread thread(session_.scene, settings);
    for (const sim::Snapshot& s : states) thread.submitFrame(s, false);
    stats = thread.finish();
  }
  EXPECT_EQ(stats.pictures_reused, 1);  // the second frame keeps the picture, the third reuses it
  ASSERT_EQ(tap.frames.size(), 3u);
  settings.tap = nullptr;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(tap.frames[k].rgb, render::renderStill(session_.scene, states[k], settings).rgb) << "frame " << k;
  }
}

// Counts the frames a render thread hands to it.
struct CountingTap : render::FrameTap {
  int frames = 0;
  void frame(const render::Image&, const sim::Snapshot&, float) noexcept override { ++frames; }
};

// releaseFrames returns once the frames queued before it are drawn, keeps the count of reused
// pictures, and no frame may follow: one submitted after it fails with an error rather than
// waiting for a reply that never comes.
TEST_F(SamePicture, ReleasedFramesAreDrawnFirstAndNoneMayFollow) {
  render::FrameOutputSettings settings = app::frameSettings(session_, {});
  settings.width = 320;
  settings.height = 180;
  CountingTap tap;
  settings.tap = &tap;
  std::vector<sim::Snapshot> states(3, snapshot_);
  for (int k = 0; k < 3; ++k) states[k].time = 4.0 + k / 60.0;
  render::RenderThread thread(session_.scene, settings);
  for (const sim::Snapshot& s : states) thread.submitFrame(s, false);
  thread.releaseFrames();
  EXPECT_EQ(tap.frames, 3);
  EXPECT_THROW(thread.submitFrame(states.back(), true), render::GlError);
  try {
    thread.finish();
    FAIL() << "finish() did not report the frame after the release";
  } catch (const render::GlError& e) {
    EXPECT_NE(std::string(e.what()).find("released"), std::string::npos) << e.what();
  }
}

std::string pngBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// An offline run drawing frames keeps its close-ups until the frames' GL memory is given back
// (releaseFrames) or the thread finishes, and draws them then in a context of their own: the
// same bytes as close-ups drawn at once by a thread that draws no frames.
TEST_F(SamePicture, CloseUpsAmongFramesAreDrawnAfterTheFramesAsTheyWouldBeAtOnce) {
  const std::filesystem::path dir = test::scratchRoot() / "same_picture_close_ups";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  render::FrameOutputSettings settings = app::frameSettings(session_, {});
  {
    render::RenderThread alone(session_.scene, settings);  // no frames: drawn at once
    alone.submitCloseUps(snapshot_, (dir / "alone").string());
    alone.finish();
  }
  const std::string left = session_.scene.fingers.front().name;
  const std::string expected = pngBytes(dir / ("alone-" + left + ".png"));
  ASSERT_GT(expected.size(), 1000u);

  settings.width = 320;
  settings.height = 180;
  CountingTap tap;
  settings.tap = &tap;
  for (const bool release : {true, false}) {
    const std::string stem = release ? "released" : "finished";
    render::RenderThread thread(session_.scene, settings);
    thread.submitFrame(snapshot_, false);
    thread.submitCloseUps(snapshot_, (dir / stem).string());
    thread.submitFrame(snapshot_, true);  // drawn after the close-up job was taken
    EXPECT_FALSE(std::filesystem::exists(dir / (stem + "-" + left + ".png"))) << stem;
    if (release) {
      thread.releaseFrames();
    } else {
      thread.finish();
    }
    for (const sim::FingerDesc& f : session_.scene.fingers) {
      EXPECT_EQ(pngBytes(dir / (stem + "-" + f.name + ".png")), pngBytes(dir / ("alone-" + f.name + ".png")))
          << stem << " " << f.name;
    }
  }
  EXPECT_EQ(tap.frames, 4);
}

// Close-ups drawn among the frames (as realtime runs draw them; close_ups_after_frames off here)
// draw a shadow map of their own, without the fingers, and leave none behind: the frame of their
// instant keeps the fingers' shadows, the frame a thread without close-ups draws.
TEST_F(SamePicture, ACloseUpAmongFramesLeavesTheFrameOfItsInstantItsShadows) {
  const std::filesystem::path dir = test::scratchRoot() / "same_picture_close_up_among";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  render::FrameOutputSettings settings = app::frameSettings(session_, {});
  settings.width = 320;
  settings.height = 180;
  settings.close_ups_after_frames = false;
  struct Keep : render::FrameTap {
    std::vector<std::vector<std::uint8_t>> frames;
    void frame(const render::Image& image, const sim::Snapshot&, float) noexcept override {
      frames.push_back(image.rgb);
    }
  };
  Keep plain, with_close_up;
  for (Keep* tap : {&plain, &with_close_up}) {
    settings.tap = tap;
    render::RenderThread thread(session_.scene, settings);
    if (tap == &with_close_up) thread.submitCloseUps(snapshot_, (dir / "among").string());
    thread.submitFrame(snapshot_, true);  // as a session does: the close-up, then the frame
    thread.submitFrame(snapshot_, true);
    const std::string left = session_.scene.fingers.front().name;
    // Drawn when it came: on disk before the frames are released.
    if (tap == &with_close_up) {
      EXPECT_TRUE(std::filesystem::exists(dir / ("among-" + left + ".png")));
    }
    thread.finish();
  }
  ASSERT_EQ(plain.frames.size(), 2u);
  ASSERT_EQ(with_close_up.frames.size(), 2u);
  EXPECT_TRUE(plain.frames[0] == with_close_up.frames[0]) << "a close-up changed the frame of its instant";
  EXPECT_TRUE(plain.frames[1] == with_close_up.frames[1]) << "a close-up changed the frame after";
}

}  // namespace
}  // namespace gf
